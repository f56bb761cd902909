// SPDX-License-Identifier: MIT
// Bad input, row by row of the table in docs/robustness.md: every validated parameter is refused
// with gimlet::invalid_parameter, and the message names the parameter and its valid range.
// Numerical trouble during a run stops it with gimlet::numerical_error naming the particle,
// where it is and the step.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

using Catch::Matchers::Contains;
using S = gimlet::space<2>;
using elastic = gimlet::elastic_material;
using elastic_scene = gimlet::scene::scene<S, elastic>;
using elastic_solver = gimlet::solver<S, gimlet::shape::ugimp, elastic>;
using hmx = gimlet::presets::hmx_material<>;
using hmx_scene = gimlet::scene::scene<S, hmx>;
using hmx_solver = gimlet::solver<S, gimlet::shape::ugimp, hmx>;

namespace {

const double not_a_number = std::numeric_limits<double>::quiet_NaN();
const double infinity = std::numeric_limits<double>::infinity();

/// One row of the bad-input table: building `build` must throw invalid_parameter whose message
/// contains `name` (the parameter as the user spells it) and `range` (its valid range).
struct bad_input {
    std::string row;
    std::function<void()> build;
    std::string name;
    std::string range;
};

void check_refused(const std::vector<bad_input>& table) {
    for (const auto& r : table) {
        INFO("row: " << r.row);
        CHECK_THROWS_AS(r.build(), gimlet::invalid_parameter);
        CHECK_THROWS_WITH(r.build(), Contains(r.name) && Contains(r.range));
    }
}

gimlet::grid_spec<S> unit_grid(gimlet::boundary bc = gimlet::boundary::slip) {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Ones();
    gs.cell = 0.1;
    gs.bc = {bc, bc};
    return gs;
}

elastic soft() { return gimlet::make_elastic_material(1000.0, 1e6, 0.3); }

gimlet::scene::box<S> square(double lo, double hi) { return {S::vector(lo, lo), S::vector(hi, hi)}; }

/// A scene with one elastic block in the middle of the unit grid.
elastic_scene one_block(const gimlet::grid_spec<S>& gs = unit_grid(), S::vector v = S::vector::Zero()) {
    elastic_scene sc(gs);
    sc.add_body(square(0.3, 0.7), soft(), v, 2, "block");
    return sc;
}

/// Solver construction with these options on the one-block scene.
std::function<void()> with_options(const std::function<void(gimlet::solver_options<S>&)>& set) {
    return [set] {
        gimlet::solver_options<S> opt;
        set(opt);
        elastic_solver sol(one_block(), opt);
    };
}

/// Solver construction on the one-block scene over this grid.
std::function<void()> with_grid(const std::function<void(gimlet::grid_spec<S>&)>& set) {
    return [set] {
        auto gs = unit_grid();
        set(gs);
        elastic_scene sc(gs);
        sc.add_body(square(0.0, 0.1), soft(), S::vector::Zero());
        elastic_solver sol(sc);
    };
}

/// make_hmx with one constant changed.
std::function<void()> with_hmx(const std::function<void(gimlet::presets::hmx_constants&)>& set) {
    return [set] {
        gimlet::presets::hmx_constants c;
        set(c);
        (void)gimlet::presets::make_hmx(c);
    };
}

/// A user region whose bounding box is not finite.
struct broken_region {
    [[nodiscard]] bool contains(const S::vector&) const { return true; }
    [[nodiscard]] S::vector lower() const { return S::vector(0.1, 0.1); }
    [[nodiscard]] S::vector upper() const { return S::vector(not_a_number, 0.5); }
};
static_assert(gimlet::scene::Region<broken_region, S>);

}  // namespace

TEST_CASE("bad material constants are refused, naming the constant and its range", "[robustness][bad_input]") {
    using gimlet::make_elastic_material;
    using mg = gimlet::eos::mie_gruneisen<>;
    using heating = gimlet::thermal::hugoniot_heating<>;
    check_refused({
        {"density", [] { (void)make_elastic_material(0.0, 1e6, 0.3); }, "density rho0 (kg/m^3)", "finite and > 0"},
        {"density", [] { (void)make_elastic_material(not_a_number, 1e6, 0.3); }, "density rho0 (kg/m^3)", "finite and > 0"},
        {"density", [] {  // an aggregate-built material is checked when its body is added
             elastic_scene sc(unit_grid());
             sc.add_body(square(0.3, 0.7), elastic{-1.0, gimlet::strength::linear_elastic{1e6}, gimlet::eos::linear{1e6}},
                         S::vector::Zero());
         }, "density rho0 (kg/m^3)", "finite and > 0"},
        {"density", with_hmx([](auto& c) { c.density = 0; }), "density rho0 (kg/m^3)", "finite and > 0"},
        {"Young's modulus", [] { (void)make_elastic_material(1000.0, 0.0, 0.3); }, "Young's modulus E (Pa)", "finite and > 0"},
        {"Young's modulus", [] { (void)make_elastic_material(1000.0, infinity, 0.3); }, "Young's modulus E (Pa)", "finite and > 0"},
        {"Young's modulus", with_hmx([](auto& c) { c.young = -1; }), "Young's modulus E (Pa)", "finite and > 0"},
        {"Poisson's ratio", [] { (void)make_elastic_material(1000.0, 1e6, 0.5); }, "Poisson's ratio nu", "(-1, 0.5)"},
        {"Poisson's ratio", [] { (void)make_elastic_material(1000.0, 1e6, -1.0); }, "Poisson's ratio nu", "(-1, 0.5)"},
        {"Poisson's ratio", [] { (void)make_elastic_material(1000.0, 1e6, not_a_number); }, "Poisson's ratio nu", "(-1, 0.5)"},
        {"Poisson's ratio", with_hmx([](auto& c) { c.poisson = 0.6; }), "Poisson's ratio nu", "(-1, 0.5)"},
        {"shear modulus", [] { gimlet::strength::linear_elastic g(0.0); }, "shear modulus G (Pa)", "finite and > 0"},
        {"shear modulus", [] { gimlet::strength::von_mises vm(-1.0, 1e8); }, "shear modulus G (Pa)", "finite and > 0"},
        {"bulk modulus", [] { gimlet::eos::linear k(0.0); }, "bulk modulus K (Pa)", "finite and > 0"},
        {"bulk modulus", [] { gimlet::eos::linear k(not_a_number); }, "bulk modulus K (Pa)", "finite and > 0"},
        {"yield stress", [] { gimlet::strength::von_mises vm(1e9, 0.0); }, "yield stress Y0 (Pa)", "finite and > 0"},
        {"yield stress", with_hmx([](auto& c) { c.yield_stress = -1e8; }), "yield stress Y0 (Pa)", "finite and > 0"},
        {"hardening modulus", [] { gimlet::strength::von_mises vm(1e9, 1e8, -1.0); }, "hardening modulus H (Pa)",
         "finite and >= 0"},
        {"hardening modulus", with_hmx([](auto& c) { c.hardening = infinity; }), "hardening modulus H (Pa)", "finite and >= 0"},
        {"EOS rho0", [] { mg e(0.0, 2740, 2.6, 1.1); }, "Mie-Grueneisen reference density rho0 (kg/m^3)", "finite and > 0"},
        {"EOS c0", [] { mg e(1900, -1.0, 2.6, 1.1); }, "Mie-Grueneisen bulk sound speed c0 (m/s)", "finite and > 0"},
        {"EOS c0", with_hmx([](auto& c) { c.sound_speed = 0; }), "Mie-Grueneisen bulk sound speed c0 (m/s)",
         "finite and > 0"},
        {"EOS s", [] { mg e(1900, 2740, 1.0, 1.1); }, "Mie-Grueneisen Hugoniot slope s", "(1, 20]"},
        {"EOS s", with_hmx([](auto& c) { c.slope = not_a_number; }), "Mie-Grueneisen Hugoniot slope s", "(1, 20]"},
        // s = 2^1019 is "> 1", but the isentrope's table would divide by log(0).
        {"EOS s", with_hmx([](auto& c) { c.slope = 0x1p1019; }), "Mie-Grueneisen Hugoniot slope s", "(1, 20]"},
        {"EOS Gamma", [] { mg e(1900, 2740, 2.6, -0.1); }, "Grueneisen parameter Gamma", "[0, 20]"},
        {"EOS Gamma", [] { mg e(1900, 2740, 2.6, 1e300); }, "Grueneisen parameter Gamma", "[0, 20]"},
        {"EOS singularity margin", [] { mg e(1900, 2740, 2.6, 1.1, 0.0); }, "Mie-Grueneisen singularity_margin", "(0, 1)"},
        {"EOS singularity margin", [] { mg e(1900, 2740, 2.6, 1.1, 1.0); }, "Mie-Grueneisen singularity_margin", "(0, 1)"},
        {"EOS rho0 = material rho0", [] {
             hmx m = gimlet::presets::make_hmx();
             m.eos = mg(1800.0, 2740, 2.6, 1.1);
             hmx_scene sc(unit_grid());
             sc.add_body(square(0.3, 0.7), m, S::vector::Zero());
         }, "EOS reference density rho0 (kg/m^3) = 1800", "equal to the material density rho0 = 1900 kg/m^3"},
        {"thermal constants = the EOS's", [] {
             hmx m = gimlet::presets::make_hmx();
             m.thermal = gimlet::thermal::isentrope_temperature(1900, 2740, 2.6, 1.3, 1250, 300);  // another Gamma
             hmx_scene sc(unit_grid());
             sc.add_body(square(0.3, 0.7), m, S::vector::Zero());
         }, "thermal Grueneisen parameter Gamma = 1.3", "equal to the EOS's 1.1"},
        {"thermal constants = the EOS's", [] {
             hmx m = gimlet::presets::make_hmx();
             m.thermal = gimlet::thermal::isentrope_temperature(1900, 2800, 2.6, 1.1, 1250, 300);  // another c0
             hmx_scene sc(unit_grid());
             sc.add_body(square(0.3, 0.7), m, S::vector::Zero());
         }, "thermal bulk sound speed c0 (m/s) = 2800", "equal to the EOS's 2740"},
        {"thermal rho0", [] { heating h(-1, 2740, 2.6, 1.1, 1250, 300); }, "thermal reference density rho0 (kg/m^3)",
         "finite and > 0"},
        {"thermal c0", [] { heating h(1900, 0, 2.6, 1.1, 1250, 300); }, "thermal bulk sound speed c0 (m/s)", "finite and > 0"},
        {"thermal s", [] { heating h(1900, 2740, 0.5, 1.1, 1250, 300); }, "thermal Hugoniot slope s", "(1, 20]"},
        {"thermal s", [] { heating h(1900, 2740, 25.0, 1.1, 1250, 300); }, "thermal Hugoniot slope s", "(1, 20]"},
        {"thermal Gamma", [] { heating h(1900, 2740, 2.6, not_a_number, 1250, 300); }, "thermal Grueneisen parameter Gamma",
         "[0, 20]"},
        {"specific heat", with_hmx([](auto& c) { c.specific_heat = 0; }), "specific heat c_v (J/(kg K))", "finite and > 0"},
        {"initial temperature", with_hmx([](auto& c) { c.temperature = -5; }), "initial temperature T0 (K)",
         "finite and > 0"},
        {"viscosity b2", [] { gimlet::viscosity::bulk q(-1.2); }, "artificial viscosity quadratic coefficient b2",
         "finite and >= 0"},
        {"viscosity b1", [] { gimlet::viscosity::bulk q(1.2, not_a_number); }, "artificial viscosity linear coefficient b1",
         "finite and >= 0"},
    });
}

TEST_CASE("bad contact parameters are refused", "[robustness][bad_input]") {
    check_refused({
        {"friction", [] { gimlet::contact::bardenhagen c(-0.1); }, "contact friction coefficient mu", ">= 0"},
        {"friction", [] { gimlet::contact::bardenhagen c(not_a_number); }, "contact friction coefficient mu", ">= 0"},
        {"friction", [] { gimlet::contact::distance c(-1.0); }, "contact friction coefficient mu", ">= 0"},
        {"switching distance", [] { gimlet::contact::distance c(0.0, 0.0); }, "contact switching distance (cells)", "(0, 2]"},
        {"switching distance", [] { gimlet::contact::distance c(0.0, 2.5); }, "contact switching distance (cells)", "(0, 2]"},
        {"switching distance", [] { gimlet::contact::distance c(0.0, not_a_number); }, "contact switching distance (cells)", "(0, 2]"},
    });
    // Infinite friction is documented as no slip, and accepted.
    CHECK_NOTHROW(gimlet::contact::bardenhagen(infinity));
}

TEST_CASE("a bad grid is refused when the solver is built", "[robustness][bad_input]") {
    check_refused({
        {"cell size", with_grid([](auto& g) { g.cell = 0; }), "grid cell size h (m)", "finite and > 0"},
        {"cell size", with_grid([](auto& g) { g.cell = -0.1; }), "grid cell size h (m)", "finite and > 0"},
        {"cell size", with_grid([](auto& g) { g.cell = not_a_number; }), "grid cell size h (m)", "finite and > 0"},
        {"grid bounds", with_grid([](auto& g) { g.lower[0] = not_a_number; }), "grid lower bound x (m)", "finite"},
        {"wall friction", with_grid([](auto& g) { g.wall_friction[1] = -0.1; }), "wall friction mu along y", "finite and >= 0"},
        {"wall friction", with_grid([](auto& g) { g.wall_friction[0] = 0.3; }), "wall friction mu along x",
         "0 unless that axis is a one-sided wall (boundary::wall)"},
        {"grid bounds", with_grid([](auto& g) { g.upper[1] = infinity; }), "grid upper bound y (m)", "finite"},
        {"grid extent", with_grid([](auto& g) { g.upper[1] = -1; }), "grid extent along y (upper - lower, m)", "> 0"},
        {"grid extent in cells", with_grid([](auto& g) { g.cell = 0.3; }),
         "grid extent along x in cells ((upper - lower) / h)", "a whole number >= 1"},
        {"periodic cells", with_grid([](auto& g) {
             g.cell = 0.5;
             g.bc = {gimlet::boundary::periodic, gimlet::boundary::slip};
         }), "periodic grid cells along x", ">= 3 (the shape stencil width)"},
    });
}

TEST_CASE("bad regions and bodies are refused when given", "[robustness][bad_input]") {
    using gimlet::scene::ball;
    using gimlet::scene::box;
    using gimlet::scene::difference;
    check_refused({
        {"box extent", [] { box<S> b(S::vector(0.5, 0.5), S::vector(0.4, 0.9)); }, "box extent along axis 0 (hi - lo, m)",
         "finite and > 0"},
        {"box extent", [] { box<S> b(S::vector(0.1, 0.1), S::vector(0.4, not_a_number)); }, "box extent along axis 1 (hi - lo, m)",
         "finite and > 0"},
        {"ball radius", [] { ball<S> b(S::vector(0.5, 0.5), 0.0); }, "ball radius (m)", "finite and > 0"},
        {"ball radius", [] { ball<S> b(S::vector(0.5, 0.5), -0.1); }, "ball radius (m)", "finite and > 0"},
        {"ball centre", [] { ball<S> b(S::vector(not_a_number, 0.5), 0.1); }, "ball centre coordinate (m)", "finite"},
        {"cavity outside its block", [] { difference d(square(0.2, 0.6), ball<S>(S::vector(0.9, 0.6), 0.2)); },
         "cavity (ball) radius (m) = 0.2", "> 0.3, the distance from its centre (0.9, 0.6) m to the block"},
        {"removed region outside", [] { difference d(square(0.2, 0.6), square(0.7, 0.9)); },
         "removed region's extent along x", "overlapping the region it is removed from, [0.2, 0.6]"},
        {"region bounding box", [] {
             elastic_scene sc(unit_grid());
             sc.add_body(broken_region{}, soft(), S::vector::Zero(), 2, "slab");
         }, "bounding box of slab along x (upper - lower, m)", "finite and > 0"},
        {"particles per cell", [] { one_block().add_body(square(0.0, 0.1), soft(), S::vector::Zero(), 0); },
         "particles_per_cell", "1 to 8 (per axis)"},
        {"particles per cell", [] { one_block().add_body(square(0.0, 0.1), soft(), S::vector::Zero(), 9); },
         "particles_per_cell", "1 to 8 (per axis)"},
        {"initial velocity", [] { one_block().add_body(square(0.0, 0.1), soft(), S::vector(not_a_number, 0.0)); },
         "initial velocity component (m/s)", "finite"},
        {"initial velocity", [] { one_block().add_body(square(0.0, 0.1), soft(), S::vector(0.0, -infinity)); },
         "initial velocity component (m/s)", "finite"},
    });
    // A cavity that pokes out of its block (a notch) is allowed.
    CHECK_NOTHROW(difference(square(0.2, 0.6), ball<S>(S::vector(0.6, 0.4), 0.1)));
}

TEST_CASE("scenes the solver cannot fill are refused", "[robustness][bad_input]") {
    check_refused({
        {"no bodies", [] { elastic_solver sol{elastic_scene(unit_grid())}; }, "number of bodies", ">= 1"},
        {"body outside the grid", [] {
             elastic_scene sc(unit_grid());
             sc.add_body(gimlet::scene::box<S>(S::vector(0.5, 0.5), S::vector(1.5, 0.9)), soft(), S::vector::Zero(), 2,
                         "big block");
             elastic_solver sol(sc);
         }, "extent of big block along x", "inside the grid [0, 1]"},
        {"overlapping bodies", [] {
             elastic_scene sc(unit_grid());
             sc.add_body(square(0.1, 0.5), soft(), S::vector::Zero(), 2, "first");
             sc.add_body(gimlet::scene::ball<S>(S::vector(0.5, 0.5), 0.2), soft(), S::vector::Zero(), 2, "second");
             elastic_solver sol(sc);
         }, "bodies = second and first", "non-overlapping"},
        {"no particles: cavity larger than its block", [] {
             elastic_scene sc(unit_grid());
             sc.add_body(gimlet::scene::difference(square(0.4, 0.6), gimlet::scene::ball<S>(S::vector(0.5, 0.5), 0.3)),
                         soft(), S::vector::Zero(), 2, "hollow");
             elastic_solver sol(sc);
         }, "particle count of hollow", ">= 1"},
        {"no particles: region smaller than the particle spacing", [] {
             elastic_scene sc(unit_grid());
             sc.add_body(gimlet::scene::box<S>(S::vector(0.51, 0.51), S::vector(0.52, 0.52)), soft(), S::vector::Zero(), 2,
                         "speck");
             elastic_solver sol(sc);
         }, "particle count of speck", ">= 1"},
    });
}

TEST_CASE("bad solver options and run controls are refused", "[robustness][bad_input]") {
    check_refused({
        {"PIC fraction", with_options([](auto& o) { o.pic_fraction = 1.5; }), "pic_fraction", "[0, 1]"},
        {"PIC fraction", with_options([](auto& o) { o.pic_fraction = not_a_number; }), "pic_fraction", "[0, 1]"},
        {"CFL", with_options([](auto& o) { o.cfl = 0.0; }), "cfl (Courant number)", "(0, 1]"},
        {"CFL", with_options([](auto& o) { o.cfl = 1.5; }), "cfl (Courant number)", "(0, 1]"},
        {"CFL", with_options([](auto& o) { o.cfl = not_a_number; }), "cfl (Courant number)", "(0, 1]"},
        {"CFL with USL", with_options([](auto& o) { o.scheme = gimlet::update_scheme::usl, o.cfl = 0.75; }),
         "cfl (Courant number) with the USL scheme", "(0, 0.7]"},
        {"mass cut-off", with_options([](auto& o) { o.mass_cutoff = 0.1; }), "mass_cutoff", "[0, 1e-3]"},
        {"light particle ratio", with_options([](auto& o) { o.light_particle_ratio = 0.6; }), "light_particle_ratio", "[0, 0.5]"},
        {"light particle ratio", with_options([](auto& o) { o.light_particle_ratio = not_a_number; }), "light_particle_ratio",
         "[0, 0.5]"},
        {"consistent mass", with_options([](auto& o) { o.consistent_mass_iterations = -1; }), "consistent_mass_iterations",
         "[0, 8]"},
        {"consistent mass", with_options([](auto& o) { o.consistent_mass_iterations = 9; }), "consistent_mass_iterations",
         "[0, 8]"},
        {"consistent mass with USL", with_options([](auto& o) { o.consistent_mass_iterations = 1, o.scheme = gimlet::update_scheme::usl; }),
         "consistent_mass_iterations with the USL scheme", "use MUSL or USF"},
        {"CFL with the consistent mass", with_options([](auto& o) { o.consistent_mass_iterations = 4, o.cfl = 0.5; }),
         "cfl (Courant number, with consistent_mass_iterations = 4)", "1/sqrt(consistent_mass_iterations + 1)"},
        {"volume filter without the consistent mass", with_options([](auto& o) { o.volume_filter = true; }),
         "volume_filter (with consistent_mass_iterations = 0)", "consistent_mass_iterations in [1, 8]"},
        {"volume filter on a material without the reference isentrope",
         with_options([](auto& o) { o.volume_filter = true, o.consistent_mass_iterations = 1; }), "volume_filter",
         "thermal::isentrope_temperature"},
        {"contact's step", with_options([](auto& o) { o.contact_closure = -0.1; }), "contact_closure (cells a step)", "[0, 1]"},
        {"contact's step", with_options([](auto& o) { o.contact_closure = 1.5; }), "contact_closure (cells a step)", "[0, 1]"},
        {"contact's step", with_options([](auto& o) { o.contact_closure = not_a_number; }), "contact_closure (cells a step)",
         "[0, 1]"},
        {"maximum time step", with_options([](auto& o) { o.max_time_step = 0.0; }), "max_time_step (s)", "> 0"},
        {"maximum time step", with_options([](auto& o) { o.max_time_step = not_a_number; }), "max_time_step (s)", "> 0"},
        {"body force", with_options([](auto& o) { o.body_force = S::vector(0.0, not_a_number); }), "body_force component (m/s^2)",
         "finite"},
        {"threads", with_options([](auto& o) { o.threads = -1; }), "threads", ">= 0"},
        {"sort interval", with_options([](auto& o) { o.sort_interval = -1; }), "sort_interval (steps)", ">= 0"},
        {"time step", [] { elastic_solver(one_block()).step(0.0); }, "time step dt (s)", "finite and > 0"},
        {"largest time step", [] { elastic_solver(one_block()).step_at_most(-1.0); }, "largest time step dt_max (s)",
         "finite and > 0"},
        {"time step", [] { elastic_solver(one_block()).step(not_a_number); }, "time step dt (s)", "finite and > 0"},
        {"end time", [] { elastic_solver(one_block()).run_until(not_a_number); }, "end time (s)", "finite"},
        {"end time",
         [] {
             elastic_solver sol(one_block());
             sol.resume_at(2.0, 10);
             sol.run_until(1.0);
         },
         "end time (s)", "finite and >= the current time 2"},
        {"resume time", [] { elastic_solver(one_block()).resume_at(-1.0, 0); }, "resume time (s)", "finite and >= 0"},
        {"observer interval", [] { gimlet::diagnostics::every_time o(0.0, [](const auto&) {}); }, "observer interval (s)",
         "finite and > 0"},
        {"observer steps", [] { gimlet::diagnostics::every_steps o(0, [](const auto&) {}); }, "observer step interval",
         ">= 1"},
        {"hook steps", [] { gimlet::diagnostics::between_steps o(0, [](auto&) {}); }, "hook step interval", ">= 1"},
    });
}

TEST_CASE("invalid_parameter carries the parameter's name", "[robustness][bad_input]") {
    try {
        (void)gimlet::make_elastic_material(1000.0, 1e6, 0.7);
        FAIL("accepted");
    } catch (const gimlet::invalid_parameter& e) {
        CHECK(e.parameter() == "Poisson's ratio nu");
        CHECK(std::string(e.what()) == "Poisson's ratio nu = 0.7 is invalid; valid range: (-1, 0.5)");
    }
}

// ---- numerical trouble ------------------------------------------------------------------

namespace {

/// Steps (of size dt, or the stable step if dt = 0) until the run stops; returns the message
/// (empty if it never stopped).
template <class Solver>
std::string stop_message(Solver& sol, double dt = 0, int max_steps = 2000) {
    try {
        for (int i = 0; i < max_steps; ++i) dt > 0 ? sol.step(dt) : sol.step();
    } catch (const gimlet::numerical_error& e) {
        return e.what();
    }
    return {};
}

/// The message names the step, the particle, its body and its position.
void check_names_particle(const std::string& m, std::size_t particle, const std::string& step) {
    INFO(m);
    CHECK_THAT(m, Contains("gimlet: step " + step + " (t = "));
    CHECK_THAT(m, Contains("particle " + std::to_string(particle) + " (body 0) at ("));
    CHECK_THAT(m, Contains(") m: "));
}

/// A strength law that turns one particle's stress into NaN at one step (a broken user law).
struct nan_at_step {
    using required_fields = gimlet::field_list<>;
    std::size_t step = 3, particle = 11;
    template <class Real, class P>
    Real update(const gimlet::point_step<Real>& st, Eigen::Matrix<Real, 3, 3>& s, const P& p) const {
        s += st.dt * Real(2e6) * gimlet::strength::deviator(st.D);
        if (st.step == step && p.index() == particle) s(0, 1) = s(1, 0) = std::numeric_limits<Real>::quiet_NaN();
        return Real(0);
    }
    template <class Real, class P>
    Real shear_modulus(const gimlet::point_state<Real>&, const P&) const { return Real(1e6); }
};

/// An EOS that returns NaN once compressed beyond J = 0.999 (a broken user EOS).
struct nan_eos {
    using required_fields = gimlet::field_list<>;
    template <class Real, class P>
    Real pressure(const gimlet::point_step<Real>& st, const P&) const {
        return st.J < Real(0.999) ? std::numeric_limits<Real>::quiet_NaN() : Real(1e6) * (1 - st.J);
    }
    template <class Real, class P>
    Real bulk_modulus(const gimlet::point_state<Real>& st, const P&) const { return Real(1e6) * st.J; }
};

}  // namespace

TEST_CASE("numerical trouble stops the run, naming particle, position and step", "[robustness][numerical]") {
    SECTION("non-finite position, velocity, stress or energy set between steps") {
        for (int what = 0; what < 4; ++what) {
            elastic_solver sol(one_block());
            sol.step();
            auto& ps = sol.particles();
            if (what == 0) ps.column<gimlet::fields::position>()[5][0] = not_a_number;
            if (what == 1) ps.column<gimlet::fields::velocity>()[5][1] = infinity;
            if (what == 2) ps.column<gimlet::fields::stress>()[5](0, 0) = not_a_number;
            if (what == 3) ps.column<gimlet::fields::specific_internal_energy>()[5] = not_a_number;
            // An explicit step size: the stable one would see the infinite speed first (below).
            const std::string m = stop_message(sol, 1e-6);
            check_names_particle(m, 5, "1");
            const char* expected[] = {"position is not finite", "velocity is not finite", "stress is not finite",
                                      "internal energy is not finite"};
            CHECK_THAT(m, Contains(expected[what]));
        }
    }
    SECTION("the volume filter projecting a particle beyond the isentrope's singular compression") {
        // Half an HMX block at J = 0.62 (just above 1 - 1/s = 0.615), half at rest: the L2
        // projection undershoots next to the jump (to J = 0.58), which the reference isentrope
        // refuses. The filter checks every particle before it changes any.
        using M = gimlet::presets::hmx_material<>;
        gimlet::grid_spec<S> gs;
        gs.lower = S::vector::Zero();
        gs.upper = S::vector(8e-3, 8e-3);
        gs.cell = 1e-3;
        gs.bc = {gimlet::boundary::periodic, gimlet::boundary::periodic};
        gimlet::scene::scene<S, M> sc(gs);
        const auto hmx = gimlet::presets::make_hmx();
        sc.add_body(gimlet::scene::box<S>(gs.lower, gs.upper), hmx, S::vector::Zero(), 2, "block");
        gimlet::solver_options<S> opt;
        opt.consistent_mass_iterations = 4;
        opt.volume_filter = true;
        gimlet::solver<S, gimlet::shape::ugimp, M> sol(sc, opt);
        auto& ps = sol.particles();
        auto& F = ps.column<gimlet::fields::deformation_gradient>();
        auto& e = ps.column<gimlet::fields::specific_internal_energy>();
        for (std::size_t i = 0; i < ps.size(); ++i) {
            const double j = ps.column<gimlet::fields::position>()[i][0] < 4e-3 ? 0.62 : 1.0;
            F[i] = std::sqrt(j) * S::matrix::Identity();
            e[i] = hmx.thermal.reference_energy(j) + 100.0;
        }
        const auto before = F;
        const std::string m = stop_message(sol, 1e-12, 1);
        check_names_particle(m, 2, "0");
        CHECK_THAT(m, Contains("the volume filter projected J = 0.62 to 0.58") &&
                          Contains("which the reference isentrope refuses (J = V/V0 of the reference isentrope"));
        bool unchanged = true;
        for (std::size_t i = 0; i < ps.size(); ++i) unchanged = unchanged && F[i] == before[i];
        CHECK(unchanged);  // nothing was changed before the stop
    }
    SECTION("a user law that produces a non-finite stress") {
        using M = gimlet::material<nan_at_step, gimlet::eos::linear>;
        gimlet::scene::scene<S, M> sc(unit_grid());
        sc.add_body(square(0.3, 0.7), M{1000.0, nan_at_step{}, gimlet::eos::linear{1e6}}, S::vector(0.5, 0.0));
        gimlet::solver<S, gimlet::shape::ugimp, M> sol(sc);
        const std::string m = stop_message(sol);
        // The law broke in step 3 (the fourth); the check after that step reports it.
        check_names_particle(m, 11, "4");
        CHECK_THAT(m, Contains("stress is not finite"));
    }
    SECTION("an EOS that returns a non-finite pressure") {
        using M = gimlet::material<gimlet::strength::linear_elastic, nan_eos>;
        gimlet::scene::scene<S, M> sc(unit_grid());
        sc.add_body(square(0.3, 0.5), M{1000.0, gimlet::strength::linear_elastic{1e6}, nan_eos{}}, S::vector(1.0, 0.0));
        sc.add_body(square(0.5, 0.7), M{1000.0, gimlet::strength::linear_elastic{1e6}, nan_eos{}}, S::vector(-1.0, 0.0));
        gimlet::solver<S, gimlet::shape::ugimp, M> sol(sc);
        const std::string m = stop_message(sol);
        INFO(m);
        CHECK_THAT(m, Contains("gimlet: step ") && Contains(" particle ") && Contains(") m: the EOS returned a non-finite pressure"));
    }
    SECTION("an inverted particle") {
        elastic_solver sol(one_block());
        sol.step();
        sol.particles().column<gimlet::fields::deformation_gradient>()[9] = S::matrix{{-1.0, 0.0}, {0.0, 1.0}};
        const std::string m = stop_message(sol);
        check_names_particle(m, 9, "1");
        CHECK_THAT(m, Contains("det F = -1 <= 0 (inverted particle)"));
    }
    SECTION("a particle leaving the grid through a free boundary") {
        elastic_solver sol(one_block(unit_grid(gimlet::boundary::free), S::vector(0.0, -40.0)));
        const std::string m = stop_message(sol);
        INFO(m);
        CHECK_THAT(m, Contains("gimlet: step ") && Contains("(body 0) at (") && Contains("left the grid through a non-periodic boundary"));
        CHECK_THAT(m, !Contains("gimlet: step 0 "));
    }
    SECTION("the Mie-Grueneisen singularity") {
        hmx_scene sc(unit_grid());
        sc.add_body(square(0.3, 0.7), gimlet::presets::make_hmx(), S::vector::Zero());
        hmx_solver sol(sc);
        sol.step();
        // 1 - s eta = 1 - 2.6 * 0.38 = 0.012, inside the default margin 0.05.
        sol.particles().column<gimlet::fields::deformation_gradient>()[6] = S::matrix{{1.0, 0.0}, {0.0, 0.62}};
        const std::string m = stop_message(sol);
        check_names_particle(m, 6, "1");
        CHECK_THAT(m, Contains("compression eta = 1 - V/V0 = ") && Contains("reached the Mie-Grueneisen limit") &&
                          Contains("singular at eta = 1/s"));
    }
}

// An infinite velocity would make the stable time step zero: the particles changed between steps
// are checked before the time step is computed, so the error names the particle, not dt.
TEST_CASE("an infinite velocity set between steps is blamed on its particle", "[robustness][numerical]") {
    elastic_solver sol(one_block());
    sol.step();
    sol.particles().column<gimlet::fields::velocity>()[5][1] = infinity;
    CHECK_THROWS_AS(sol.step(), gimlet::numerical_error);
    CHECK_THROWS_WITH(sol.step(), Contains("particle 5 (body 0)") && Contains("velocity is not finite"));
}
