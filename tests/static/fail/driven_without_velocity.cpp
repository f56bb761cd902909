// SPDX-License-Identifier: MIT
// Must not compile: a solver whose particles carry fields::driven without fields::driven_velocity;
// the solver's static_assert says they go together.
// GIMLET_FAILTEST_EXPECT: fields::driven and fields::driven_velocity go together
#include <gimlet/gimlet.hpp>

using S = gimlet::space<2>;
#ifdef GIMLET_FAILTEST_OK
using extra = gimlet::field_list<gimlet::fields::driven, gimlet::fields::driven_velocity>;
#else
using extra = gimlet::field_list<gimlet::fields::driven>;
#endif

int main() {
    gimlet::grid_spec<S> gs;
    gs.upper = S::vector(1.0, 1.0);
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    sc.add_body(gimlet::scene::box<S>(S::vector(0.2, 0.2), S::vector(0.5, 0.5)), gimlet::make_elastic_material(1, 1, 0),
                S::vector::Zero());
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, gimlet::contact::single_field, extra> sol(sc, {});
    sol.step();
    return 0;
}
