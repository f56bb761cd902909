// SPDX-License-Identifier: MIT
// solver_options::consistent_mass_iterations: the grid accelerations of the consistent mass
// matrix, approximated by k iterations (docs/equations.md, "Consistent-mass accelerations").
// What it must do: keep momentum, leave a uniform acceleration alone, converge in k, and make
// the grid's waves run closer to the continuum's speed (the lumped mass's dispersion is what
// makes a shock ring).
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace {

using S = gimlet::space<2>;
using elastic = gimlet::elastic_material;
using single = gimlet::solver<S, gimlet::shape::ugimp, elastic>;
using two_field = gimlet::solver<S, gimlet::shape::ugimp, elastic, gimlet::contact::distance>;

constexpr double pi = 3.141592653589793;

// A standing compression wave of `cells_per_wave` cells in a doubly periodic strip two
// wavelengths long (rho = 1, E = 1, nu = 0: the longitudinal speed is c = 1 m/s), 2 x 2
// particles per cell. Returns omega_measured / omega_continuum - 1 from the zero crossings of
// the mode's amplitude over two and a half periods.
double frequency_error(int cells_per_wave, int iterations) {
    const double h = 1.0 / 64, v0 = 1e-4, length = 2 * cells_per_wave * h;
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector(length, 4 * h);
    gs.cell = h;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::periodic};
    gimlet::scene::scene<S, elastic> sc(gs);
    sc.add_body(gimlet::scene::box<S>(S::vector::Zero(), gs.upper), gimlet::make_elastic_material(1.0, 1.0, 0.0),
                S::vector::Zero(), 2, "bar");
    gimlet::solver_options<S> opt;
    opt.threads = 1;
    opt.cfl = 0.3;
    opt.consistent_mass_iterations = iterations;
    single sol(sc, opt);
    const double k = 2 * pi / (cells_per_wave * h);
    auto& x = sol.particles().template column<gimlet::fields::position>();
    auto& v = sol.particles().template column<gimlet::fields::velocity>();
    const auto& m = sol.particles().template column<gimlet::fields::mass>();
    for (std::size_t p = 0; p < x.size(); ++p) v[p] = S::vector(v0 * std::sin(k * x[p][0]), 0.0);
    auto amplitude = [&] {
        double a = 0;
        for (std::size_t p = 0; p < x.size(); ++p) a += m[p] * v[p][0] * std::sin(k * x[p][0]);
        return a;
    };
    const double period = cells_per_wave * h;  // lambda / c
    std::vector<double> crossings;
    double a_old = amplitude(), t_old = 0;
    while (crossings.size() < 6) {
        sol.step();
        const double t = double(sol.time()), a = amplitude();
        if ((a_old > 0) != (a > 0)) crossings.push_back(t_old + (t - t_old) * a_old / (a_old - a));
        a_old = a;
        t_old = t;
        REQUIRE(t < 4 * period);
    }
    const double measured = 2 * (crossings.back() - crossings.front()) / double(crossings.size() - 1);
    return period / measured - 1;
}

// Two elastic blocks in their own velocity fields (distance contact) or in one, their
// velocities scrambled, one of them far lighter (its nodes are light nodes), doubly periodic.
template <class Solver = two_field>
Solver cloud(int iterations, double mass_cutoff = 1e-12) {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector(16e-3, 10e-3);
    gs.cell = 1e-3;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::periodic};
    gimlet::scene::scene<S, elastic> sc(gs);
    const auto mat = gimlet::make_elastic_material(1900.0, 10e9, 0.3);
    sc.add_body(gimlet::scene::box<S>(S::vector(4e-3, 1e-3), S::vector(9e-3, 4e-3)), mat, S::vector(40.0, 10.0), 2, "lower");
    sc.add_body(gimlet::scene::box<S>(S::vector(6e-3, 4.5e-3), S::vector(12e-3, 8e-3)), mat, S::vector(-20.0, -60.0), 2,
                "upper");
    sc.add_body(gimlet::scene::box<S>(S::vector(0.0, 8e-3), S::vector(2e-3, 9.5e-3)),
                gimlet::make_elastic_material(1900.0e-14, 10e-5, 0.3), S::vector(-30.0, 10.0), 2, "light");
    gimlet::solver_options<S> opt;
    opt.threads = 1;
    opt.consistent_mass_iterations = iterations;
    opt.mass_cutoff = mass_cutoff;
    Solver sol(sc, opt);
    auto& v = sol.particles().template column<gimlet::fields::velocity>();
    for (std::size_t i = 0; i < v.size(); ++i) v[i] += S::vector(5.0 * std::sin(1.7 * double(i)), 3.0 * std::cos(2.3 * double(i)));
    return sol;
}

template <class Solver>
S::vector momentum(const Solver& sol) {
    S::vector p = S::vector::Zero();
    const auto& m = sol.particles().template column<gimlet::fields::mass>();
    const auto& v = sol.particles().template column<gimlet::fields::velocity>();
    for (std::size_t i = 0; i < m.size(); ++i) p += m[i] * v[i];
    return p;
}

}  // namespace

TEST_CASE("consistent mass: the grid's waves run closer to the continuum's speed, at second order",
          "[core][verification]") {
    // The lumped mass makes the grid a lattice whose short waves run slow; that lag is what
    // trails a shock as ringing. Measured (frequency against c k): lumped -7.88 % at 8 cells a
    // wavelength and -2.02 % at 16; 1, 2, 4, 8 iterations -2.93, -2.40, -2.335, -2.334 % at 8
    // cells and -0.63, -0.59, -0.585, -0.585 % at 16. Both are second order (error ratio 3.9
    // and 4.0 from 8 to 16 cells; 4.7 after one iteration, not yet converged); the consistent
    // mass's coefficient is 3.4 times smaller. With
    // GIMP's stiffness the consistent mass still lags (linear finite elements would lead).
    std::vector<double> e8, e16;
    for (const int k : {0, 1, 2, 4, 8}) {
        e8.push_back(frequency_error(8, k));
        e16.push_back(frequency_error(16, k));
        std::printf("consistent mass k = %d: frequency error %+.3f %% (8 cells a wave), %+.3f %% (16)\n", k, 100 * e8.back(),
                    100 * e16.back());
    }
    for (std::size_t i = 0; i < e8.size(); ++i) {
        // Slow waves, second order in h; one iteration is not yet converged and keeps part of
        // the lumped lag, which falls faster (ratio 4.7).
        CHECK(e8[i] < 0);
        CHECK(e8[i] / e16[i] > 3.5);
        if (i != 1) CHECK(e8[i] / e16[i] < 4.5);
    }
    for (std::size_t i = 1; i < e8.size(); ++i) {
        if (i <= 3) CHECK(e8[i] > e8[i - 1]);  // 1, 2, 4 iterations: each brings the wave closer to c
        CHECK(std::abs(e8[i]) < 0.4 * std::abs(e8[0]));  // and leaves at most 0.4 of the lumped lag
    }
    CHECK(std::abs(e8[4] - e8[3]) < 1e-3 * std::abs(e8[3]));  // converged by 4 iterations (8 reads the same)
    CHECK(std::abs(e8[4]) < std::abs(e8[0]) / 3);
    CHECK(std::abs(e16[4]) < std::abs(e16[0]) / 3);
}

// With the largest mass cut-off (1e-3 of the heaviest particle) the blocks' edge nodes are
// light too, inside the stencils of particles that also reach heavy nodes: each particle's share
// of M a is spread over its heavy nodes alone, or momentum leaks there (6e-7 to 1e-6 of
// sum m |v| over 200 steps in one field without that renormalisation).
TEMPLATE_TEST_CASE("consistent mass: momentum is kept, with light nodes beside heavy ones", "[core][conservation]", two_field,
                   single) {
    for (const double cutoff : {1e-12, 1e-3}) {
        auto lumped = cloud<TestType>(0, cutoff);
        for (int s = 0; s < 60; ++s) lumped.step();
        for (const int k : {1, 4}) {
            auto sol = cloud<TestType>(k, cutoff);
            const S::vector p0 = momentum(sol);
            double scale = 0;  // sum m |v|
            const auto& m = sol.particles().template column<gimlet::fields::mass>();
            const auto& v = sol.particles().template column<gimlet::fields::velocity>();
            for (std::size_t i = 0; i < m.size(); ++i) scale += m[i] * v[i].norm();
            for (int s = 0; s < 60; ++s) sol.step();
            const S::vector p1 = momentum(sol);
            INFO("iterations " << k << ", mass cut-off " << cutoff << ": momentum change " << (p1 - p0).norm() / scale);
            CHECK((p1 - p0).norm() <= 1e-12 * scale);
            // The correction acted: the blocks met, and the velocities differ from the lumped run's.
            double differ = 0;
            for (std::size_t i = 0; i < m.size(); ++i)
                differ = std::max(differ, (v[i] - lumped.particles().template column<gimlet::fields::velocity>()[i]).norm());
            CHECK(differ > 1.0);
        }
    }
}

TEST_CASE("consistent mass: a uniform acceleration is left as it is", "[core][verification]") {
    // A free block under gravity: every node's acceleration is g, and the consistent mass
    // changes nothing (M g = m g row by row), so the block falls as one, to rounding.
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector(20e-3, 20e-3);
    gs.cell = 1e-3;
    gimlet::scene::scene<S, elastic> sc(gs);
    sc.add_body(gimlet::scene::box<S>(S::vector(5e-3, 10e-3), S::vector(12e-3, 16e-3)),
                gimlet::make_elastic_material(1900.0, 10e9, 0.3), S::vector(3.0, 0.0), 2, "block");
    gimlet::solver_options<S> opt;
    opt.threads = 1;
    opt.consistent_mass_iterations = 4;
    opt.body_force = S::vector(0.0, -1e6);  // 1e6 m/s^2: a visible fall in 100 steps
    single sol(sc, opt);
    for (int s = 0; s < 100; ++s) sol.step(2e-8);
    const double t = double(sol.time());
    const S::vector expected(3.0, -1e6 * t);
    double worst = 0, worst_stress = 0;
    for (std::size_t i = 0; i < sol.particles().size(); ++i) {
        worst = std::max(worst, (sol.particles().template column<gimlet::fields::velocity>()[i] - expected).norm());
        worst_stress = std::max(worst_stress, sol.particles().template column<gimlet::fields::stress>()[i].norm());
    }
    INFO("largest velocity error " << worst << " m/s of " << expected.norm() << ", largest stress " << worst_stress << " Pa");
    CHECK(worst <= 1e-12 * expected.norm());
    CHECK(worst_stress <= 1e-3);  // a rigid fall strains nothing (E = 10 GPa: 1e-3 Pa is a strain of 1e-13)
}
