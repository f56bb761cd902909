// SPDX-License-Identifier: MIT
// Bad input is refused at construction with a message naming the parameter and its valid
// range; numerical trouble stops the run naming the particle, its position and the step.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <limits>
#include <string>

using Catch::Matchers::Contains;
using S = gimlet::space<2>;
using elastic_solver = gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material>;

namespace {

gimlet::grid_spec<S> unit_grid(gimlet::boundary bc = gimlet::boundary::periodic) {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Ones();
    gs.cell = 0.1;
    gs.bc = {bc, bc};
    return gs;
}

gimlet::scene::scene<S, gimlet::elastic_material> one_block(gimlet::boundary bc, S::vector v = S::vector::Zero()) {
    gimlet::scene::scene<S, gimlet::elastic_material> sc(unit_grid(bc));
    sc.add_body(gimlet::scene::box<S>(S::vector(0.3, 0.3), S::vector(0.7, 0.7)),
                gimlet::make_elastic_material(1000.0, 1e6, 0.3), v, 2, "block");
    return sc;
}

}  // namespace

TEST_CASE("material parameters are validated with their names and ranges", "[core][errors]") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH(gimlet::make_elastic_material(-1.0, 1e6, 0.3), Contains("density") && Contains("> 0"));
    CHECK_THROWS_WITH(gimlet::make_elastic_material(1000.0, 0.0, 0.3), Contains("Young's modulus") && Contains("> 0"));
    CHECK_THROWS_WITH(gimlet::make_elastic_material(1000.0, 1e6, 0.5), Contains("Poisson's ratio") && Contains("(-1, 0.5)"));
    CHECK_THROWS_WITH(gimlet::make_elastic_material(1000.0, 1e6, -1.0), Contains("Poisson's ratio"));
    CHECK_THROWS_WITH(gimlet::make_elastic_material(1000.0, nan, 0.3), Contains("Young's modulus"));
    CHECK_THROWS_WITH(gimlet::strength::linear_elastic(-5.0), Contains("shear modulus") && Contains("> 0"));
    CHECK_THROWS_WITH(gimlet::eos::linear(0.0), Contains("bulk modulus") && Contains("> 0"));
    CHECK_THROWS_AS(gimlet::eos::linear(0.0), gimlet::invalid_parameter);
}

TEST_CASE("grid and scene are validated", "[core][errors]") {
    auto gs = unit_grid();
    gs.cell = 0.0;
    CHECK_THROWS_WITH((gimlet::grid<S>(gs, 3)), Contains("cell size") && Contains("> 0"));
    gs = unit_grid();
    gs.cell = 0.3;  // 1 / 0.3 is not whole
    CHECK_THROWS_WITH((gimlet::grid<S>(gs, 3)), Contains("whole number"));
    gs = unit_grid();
    gs.upper[1] = -1.0;
    CHECK_THROWS_WITH((gimlet::grid<S>(gs, 3)), Contains("grid extent along y") && Contains("> 0"));
    // More nodes than int node indices hold is refused before anything is allocated.
    gs = unit_grid();
    gs.cell = 1e-10;  // 1e10 cells along each axis
    CHECK_THROWS_WITH((gimlet::grid<S>(gs, 3)), Contains("grid extent along x in cells") && Contains("node indices are int"));
    gs = unit_grid();
    gs.cell = 1e-5;  // 1e5 x 1e5 nodes
    CHECK_THROWS_WITH((gimlet::grid<S>(gs, 3)), Contains("grid node count") && Contains("2147483647"));

    const auto mat = gimlet::make_elastic_material(1000.0, 1e6, 0.3);
    gimlet::scene::scene<S, gimlet::elastic_material> sc(unit_grid());
    const gimlet::scene::box<S> block(S::vector(0.2, 0.2), S::vector(0.5, 0.5));
    CHECK_THROWS_WITH(sc.add_body(block, mat, S::vector::Zero(), 0), Contains("particles_per_cell") && Contains("1 to 8"));
    CHECK_THROWS_WITH(sc.add_body(block, mat, S::vector(std::numeric_limits<double>::infinity(), 0.0)),
                      Contains("velocity") && Contains("finite"));
    CHECK_THROWS_WITH(gimlet::scene::ball<S>(S::vector(0.5, 0.5), -0.1), Contains("radius") && Contains("> 0"));
    CHECK_THROWS_WITH(gimlet::scene::box<S>(S::vector(0.5, 0.5), S::vector(0.4, 0.9)), Contains("box extent"));
}

TEST_CASE("scenes that cannot be built are refused", "[core][errors]") {
    const auto mat = gimlet::make_elastic_material(1000.0, 1e6, 0.3);
    SECTION("no bodies") {
        gimlet::scene::scene<S, gimlet::elastic_material> sc(unit_grid());
        CHECK_THROWS_WITH(elastic_solver(sc), Contains("number of bodies"));
    }
    SECTION("a body outside the grid") {
        gimlet::scene::scene<S, gimlet::elastic_material> sc(unit_grid());
        sc.add_body(gimlet::scene::box<S>(S::vector(0.5, 0.5), S::vector(1.5, 0.9)), mat, S::vector::Zero(), 2, "big block");
        CHECK_THROWS_WITH(elastic_solver(sc), Contains("big block") && Contains("inside the grid"));
    }
    SECTION("overlapping bodies") {
        gimlet::scene::scene<S, gimlet::elastic_material> sc(unit_grid());
        sc.add_body(gimlet::scene::box<S>(S::vector(0.1, 0.1), S::vector(0.5, 0.5)), mat, S::vector::Zero(), 2, "first");
        sc.add_body(gimlet::scene::ball<S>(S::vector(0.5, 0.5), 0.2), mat, S::vector::Zero(), 2, "second");
        CHECK_THROWS_WITH(elastic_solver(sc), Contains("first") && Contains("second") && Contains("non-overlapping"));
    }
    SECTION("a cavity that removes the whole block") {
        gimlet::scene::scene<S, gimlet::elastic_material> sc(unit_grid());
        sc.add_body(gimlet::scene::difference(gimlet::scene::box<S>(S::vector(0.4, 0.4), S::vector(0.6, 0.6)),
                                              gimlet::scene::ball<S>(S::vector(0.5, 0.5), 0.3)),
                    mat, S::vector::Zero(), 2, "hollow");
        CHECK_THROWS_WITH(elastic_solver(sc), Contains("hollow") && Contains("particle count"));
    }
    SECTION("solver options") {
        const auto sc = one_block(gimlet::boundary::periodic);
        gimlet::solver_options<S> opt;
        opt.cfl = 1.5;
        CHECK_THROWS_WITH(elastic_solver(sc, opt), Contains("cfl") && Contains("(0, 1]"));
        opt = {};
        opt.pic_fraction = -0.1;
        CHECK_THROWS_WITH(elastic_solver(sc, opt), Contains("pic_fraction") && Contains("[0, 1]"));
        elastic_solver sol(sc);
        CHECK_THROWS_WITH(sol.step(-1.0), Contains("time step") && Contains("> 0"));
    }
}

TEST_CASE("numerical trouble names particle, position and step", "[core][errors]") {
    SECTION("a particle leaving a non-periodic grid") {
        elastic_solver sol(one_block(gimlet::boundary::free, S::vector(40.0, 0.0)));
        try {
            for (int i = 0; i < 10000; ++i) sol.step();
            FAIL("no error");
        } catch (const gimlet::numerical_error& e) {
            const std::string m = e.what();
            CHECK_THAT(m, Contains("left the grid") && Contains("particle") && Contains("step"));
            CHECK_THAT(m, Contains("body 0") && Contains(") m"));
        }
    }
    SECTION("a non-finite velocity") {
        elastic_solver sol(one_block(gimlet::boundary::periodic));
        sol.particles().column<gimlet::fields::velocity>()[7] = S::vector(std::numeric_limits<double>::quiet_NaN(), 0.0);
        CHECK_THROWS_AS(sol.step(1e-6), gimlet::numerical_error);
        elastic_solver sol2(one_block(gimlet::boundary::periodic));
        sol2.particles().column<gimlet::fields::velocity>()[7] = S::vector(std::numeric_limits<double>::quiet_NaN(), 0.0);
        CHECK_THROWS_WITH(sol2.step(1e-6), Contains("step 0") && Contains("particle 7 ") && Contains("velocity is not finite"));
    }
    SECTION("a mass or initial volume set to zero or NaN between steps") {
        // Both divide (densities, volumes, and the light particles' reference density m / V0).
        for (const double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
            elastic_solver sol(one_block(gimlet::boundary::periodic));
            sol.particles().column<gimlet::fields::mass>()[5] = bad;
            CHECK_THROWS_WITH(sol.step(1e-6), Contains("particle 5 ") && Contains("mass = ") && Contains("not finite and > 0"));
            elastic_solver sol2(one_block(gimlet::boundary::periodic));
            sol2.particles().column<gimlet::fields::volume0>()[3] = bad;
            CHECK_THROWS_WITH(sol2.step(1e-6), Contains("particle 3 ") && Contains("volume0") && Contains("not finite and > 0"));
        }
    }
    SECTION("an inverted particle (time step far beyond the CFL limit)") {
        gimlet::scene::scene<S, gimlet::elastic_material> sc(unit_grid());
        const auto mat = gimlet::make_elastic_material(1000.0, 1e6, 0.3);
        sc.add_body(gimlet::scene::box<S>(S::vector(0.2, 0.2), S::vector(0.5, 0.8)), mat, S::vector(50.0, 0.0), 2, "left");
        sc.add_body(gimlet::scene::box<S>(S::vector(0.5, 0.2), S::vector(0.8, 0.8)), mat, S::vector(-50.0, 0.0), 2, "right");
        elastic_solver sol(sc);
        CHECK_THROWS_WITH(sol.step(0.01), Contains("det F") && Contains("inverted") && Contains("particle") && Contains("at ("));
    }
    SECTION("a policy's own field going non-finite (found by fuzzing)") {
        // A specific heat of 1.5e-315 J/(kg K) is positive and finite, so it is accepted, and the
        // first step's heating makes the temperature infinite while every core field stays finite.
        using hmx = gimlet::presets::hmx_material<>;
        gimlet::grid_spec<S> gs;
        gs.lower = S::vector(-0x1.999999999999ap-5, -0x1.2fd2c96c6306p-5);
        gs.upper = S::vector(-0x1.98c7e28240b78p-5, -0x1.2f0112550a23ep-5);
        gs.cell = 0x1.a36e2eb1c432dp-14;
        gs.bc = {gimlet::boundary::wall, gimlet::boundary::wall};
        gimlet::presets::hmx_constants c;
        c.density = 0x1.b0b8787878788p+12;
        c.young = 1e6;
        c.poisson = 0;
        c.yield_stress = 1e5;
        c.sound_speed = 0x1.f943ad43ad43bp+8;
        c.slope = 0x1.00c000c000cp+0;
        c.gruneisen = 0;
        c.specific_heat = 0x0.0000001p-1022;
        gimlet::scene::scene<S, hmx> sc(gs);
        sc.add_body(gimlet::scene::box<S>(S::vector(-0x1.996294a23b814p-5, -0x1.2f9bc47504edap-5),
                                          S::vector(-0x1.9928b6b640514p-5, -0x1.2f61e68909bdap-5)),
                    gimlet::presets::make_hmx(c), S::vector(-0x1.ffc3c3c3c3c3cp+9, -0x1.ffc3c3c3c3c3cp+9), 4);
        gimlet::solver_options<S> opt;
        opt.cfl = 0x1.999999999999ap-5;
        opt.mass_cutoff = 0;
        opt.body_force = S::vector(-1e6, -1e6);
        gimlet::solver<S, gimlet::shape::ugimp, hmx, gimlet::contact::single_field> sol(sc, opt);
        CHECK_THROWS_WITH(sol.step(), Contains("temperature is not finite") && Contains("particle 0") && Contains("step"));
    }
}

TEST_CASE("a stable run stays finite with det F > 0", "[core][errors]") {
    elastic_solver sol(one_block(gimlet::boundary::periodic, S::vector(1.0, 0.5)));
    CHECK(sol.stable_time_step() > 0);
    for (int i = 0; i < 50; ++i) CHECK_NOTHROW(sol.step());
}
