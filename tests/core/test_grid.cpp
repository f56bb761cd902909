// SPDX-License-Identifier: MIT
// core/grid.hpp: the default boundaries, and what they do to a body that reaches the grid's end;
// the periodic wrap; a node's layer along the last axis.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <string>

using Catch::Matchers::Contains;

TEST_CASE("grid: the boundaries default to free, and a body reaching the end stops the run", "[core]") {
    using S = gimlet::space<2>;
    gimlet::grid_spec<S> gs;
    for (const auto b : gs.bc) CHECK(b == gimlet::boundary::free);
    CHECK(gimlet::grid_spec<gimlet::space<3>>{}.bc[2] == gimlet::boundary::free);
    // A block flying at the grid's right end: with the default it is not wrapped round to the
    // left side (a periodic axis would do that silently); the particle that leaves is named.
    gs.upper = S::vector(10e-3, 4e-3);
    gs.cell = 1e-3;
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    sc.add_body(gimlet::scene::box<S>(S::vector(6e-3, 1e-3), S::vector(9e-3, 3e-3)),
                gimlet::make_elastic_material(1900.0, 10e9, 0.3), S::vector(500.0, 0.0), 2, "block");
    gimlet::solver_options<S> opt;
    opt.threads = 1;
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material> sol(sc, opt);
    std::string message;
    try {
        sol.run_until(10e-6);  // 5 mm of travel
    } catch (const gimlet::numerical_error& e) {
        message = e.what();
    }
    CHECK_THAT(message, Contains("particle") && Contains("left the grid through a non-periodic boundary"));
}

// A periodic axis wraps any finite position into [lower, upper): one just outside by one
// period, and one far away (at 7e21 m a shift by whole periods rounds off by more than a
// period, and the weights' cell index would overflow an int).
TEST_CASE("grid: a periodic axis wraps near and far positions into the domain", "[core]") {
    using S = gimlet::space<2>;
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector(-1e-3, 0.0);
    gs.upper = S::vector(0.5e-3, 1.5e-3);
    gs.cell = 0.5e-3;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::periodic};
    const gimlet::grid<S> g(gs, 3);
    for (const double x : {-1.2e-3, 0.7e-3, 0.5e-3, 12.34, -7.05e21, 4.4e300, -1.7e308}) {
        S::vector p(x, x);
        g.wrap(p);
        INFO("x = " << x << " -> " << p.transpose());
        CHECK(p[0] >= gs.lower[0]);
        CHECK(p[0] < gs.upper[0]);
        CHECK(p[1] >= gs.lower[1]);
        CHECK(p[1] < gs.upper[1]);
    }
    S::vector p(0.7e-3, -0.2e-3);  // one period out: shifted by exactly one period
    g.wrap(p);
    CHECK(p[0] == 0.7e-3 - 1.5e-3);
    CHECK(p[1] == -0.2e-3 + 1.5e-3);
}

// layer(index), which the contact's reach pass uses to find the slabs it must visit, is the
// node's storage index along the last axis, in 2-D and 3-D, with and without periodic axes.
TEST_CASE("grid: a node's layer is its storage index along the last axis", "[core]") {
    auto check = [](const auto& g) {
        for (std::size_t n = 0; n < g.size(); ++n) {
            const auto idx = g.unflatten(n);
            REQUIRE(g.layer(n) == idx.back());
        }
    };
    using S2 = gimlet::space<2>;
    gimlet::grid_spec<S2> g2;
    g2.upper = S2::vector(5e-3, 3e-3);
    g2.cell = 1e-3;
    check(gimlet::grid<S2>(g2, 3));
    g2.bc = {gimlet::boundary::free, gimlet::boundary::periodic};
    check(gimlet::grid<S2>(g2, 3));
    using S3 = gimlet::space<3>;
    gimlet::grid_spec<S3> g3;
    g3.upper = S3::vector(4e-3, 3e-3, 5e-3);
    g3.cell = 1e-3;
    check(gimlet::grid<S3>(g3, 4));
    g3.bc = {gimlet::boundary::periodic, gimlet::boundary::free, gimlet::boundary::periodic};
    const gimlet::grid<S3> periodic3(g3, 4);
    check(periodic3);
    CHECK(periodic3.layer(periodic3.size() - 1) == periodic3.nodes(2) - 1);
}
