// SPDX-License-Identifier: MIT
// Must not compile: the surface observers on an axisymmetric solver whose particles keep no
// domain half-width (the linear shape's point particles): a ring's spacing is read from it, and
// its volume per radian does not give it. The observers' static_assert names the field.
// GIMLET_FAILTEST_EXPECT: need the particles' spacing, fields::domain_half_width
#include <gimlet/gimlet.hpp>

using A = gimlet::axisymmetric_space<double>;
#ifdef GIMLET_FAILTEST_OK
using chosen = gimlet::shape::ugimp;
#else
using chosen = gimlet::shape::linear;
#endif

int main() {
    gimlet::grid_spec<A> gs;
    gs.upper = A::vector(1.0, 1.0);
    gimlet::scene::scene<A, gimlet::elastic_material> sc(gs);
    sc.add_body(gimlet::scene::box<A>(A::vector(0.0, 0.2), A::vector(0.5, 0.5)), gimlet::make_elastic_material(1, 1, 0),
                A::vector::Zero());
    gimlet::solver<A, chosen, gimlet::elastic_material> sol(sc, {});
    const auto chord = gimlet::diagnostics::void_chord(sol, 0, 1, A::vector(0.1, 0.3), 0.05, 0.01);
    return chord.open ? 1 : 0;
}
