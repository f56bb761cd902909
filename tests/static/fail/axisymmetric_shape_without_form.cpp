// SPDX-License-Identifier: MIT
// Must not compile: an axisymmetric solver with a shape whose r-weighted radial factors do not
// exist (the quadratic B-spline); the solver's static_assert names the shapes it takes.
// GIMLET_FAILTEST_EXPECT: must be shape::ugimp or shape::linear
#include <gimlet/gimlet.hpp>

using A = gimlet::axisymmetric_space<double>;
#ifdef GIMLET_FAILTEST_OK
using chosen = gimlet::shape::ugimp;
#else
using chosen = gimlet::shape::bspline_quadratic;
#endif

int main() {
    gimlet::grid_spec<A> gs;
    gs.upper = A::vector(1.0, 1.0);
    gimlet::scene::scene<A, gimlet::elastic_material> sc(gs);
    sc.add_body(gimlet::scene::box<A>(A::vector(0.0, 0.0), A::vector(0.5, 0.5)), gimlet::make_elastic_material(1, 1, 0),
                A::vector::Zero());
    gimlet::solver<A, chosen, gimlet::elastic_material> sol(sc, {});
    sol.step();
    return 0;
}
