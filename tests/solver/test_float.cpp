// SPDX-License-Identifier: MIT
// The solver in single precision (space<2, float>): it builds and runs the elastic two-disk
// collision and an HMX impact with every physics policy on, and conserves what it should to
// float's round-off.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

namespace {
using F = gimlet::space<2, float>;

/// Two elastic disks in a unit square with slip walls, meeting at 0.1 sqrt(2) m/s each.
gimlet::scene::scene<F, gimlet::elastic_material> two_disks() {
    gimlet::grid_spec<F> gs;
    gs.upper = F::vector(1.0f, 1.0f);
    gs.cell = 0.05f;
    gs.bc = {gimlet::boundary::slip, gimlet::boundary::slip};
    gimlet::scene::scene<F, gimlet::elastic_material> sc(gs);
    const auto mat = gimlet::make_elastic_material(1000.0, 1000.0, 0.3);
    sc.add_body(gimlet::scene::ball<F>(F::vector(0.25f, 0.25f), 0.2f), mat, F::vector(0.1f, 0.1f), 2);
    sc.add_body(gimlet::scene::ball<F>(F::vector(0.75f, 0.75f), 0.2f), mat, F::vector(-0.1f, -0.1f), 2);
    return sc;
}
}  // namespace

TEST_CASE("float: two elastic disks collide and part", "[core][float]") {
    const auto sc = two_disks();
    gimlet::solver_options<F> opt;
    opt.threads = 1;
    gimlet::solver<F, gimlet::shape::ugimp, gimlet::elastic_material> sol(sc, opt);
    const auto first = gimlet::diagnostics::sample_conservation(sol);
    double min_kinetic = 1, worst_dp = 0, worst_de = 0;
    const double body_momentum = 0.5 * first.mass * 0.1 * std::sqrt(2.0);
    gimlet::diagnostics::every_steps watch(1, [&](const auto& s) {
        const auto c = gimlet::diagnostics::sample_conservation(s);
        min_kinetic = std::min(min_kinetic, c.kinetic / first.kinetic);
        worst_dp = std::max(worst_dp, double((c.momentum - first.momentum).norm()) / body_momentum);
        worst_de = std::max(worst_de, std::abs(c.total_energy() / first.total_energy() - 1));
    });
    sol.run_until(2.4f, watch);
    std::printf("float two disks: min KE %.3f of the start, momentum %.1e of a disk's, energy within %.3f\n",
                min_kinetic, worst_dp, worst_de);
    CHECK(min_kinetic < 0.2);    // they collided
    CHECK(worst_dp < 1e-5);      // float round-off over ~300 steps and 1000 particles
    CHECK(worst_de < 0.06);      // the double-precision bound (tests/solver/test_conservation.cpp)
}

TEST_CASE("float: light particles return their momentum exactly", "[core][float]") {
    // The two disks with a small third one between them, of a thousandth of their density and
    // stiffness (the same wave speed): its particles are light (solver_options::
    // light_particle_ratio) once the disks reach it. The momentum they change goes back to the
    // disks' particles over the non-light mass, summed (not m_i less the light mass, whose
    // rounding in float would be of the light mass's size).
    auto sc = two_disks();
    sc.add_body(gimlet::scene::ball<F>(F::vector(0.5f, 0.5f), 0.06f), gimlet::make_elastic_material(1.0, 1.0, 0.3), F::vector(0.0f, 0.0f), 2);
    gimlet::solver_options<F> opt;
    opt.threads = 1;
    gimlet::solver<F, gimlet::shape::ugimp, gimlet::elastic_material> sol(sc, opt);
    const auto first = gimlet::diagnostics::sample_conservation(sol);
    double worst_dp = 0, fastest = 0;
    std::size_t light = 0;
    const double body_momentum = 0.5 * first.mass * 0.1 * std::sqrt(2.0);
    gimlet::diagnostics::every_steps watch(1, [&](const auto& s) {
        const auto c = gimlet::diagnostics::sample_conservation(s);
        worst_dp = std::max(worst_dp, double((c.momentum - first.momentum).norm()) / body_momentum);
        for (const auto& v : s.particles().template column<gimlet::fields::velocity>()) fastest = std::max(fastest, double(v.norm()));
        light = std::max(light, s.light_particles());
    });
    sol.run_until(1.2f, watch);
    std::printf("float light particles: up to %zu light, momentum %.1e of a disk's, fastest %.3f m/s\n", light, worst_dp, fastest);
    CHECK(light > 0);
    CHECK(worst_dp < 1e-5);  // as the two disks alone
}

TEST_CASE("float: an HMX impact with plasticity, the EOS, viscosity and temperature", "[core][float]") {
    using hmx = gimlet::presets::hmx_material<>;
    gimlet::grid_spec<F> gs;
    gs.lower = F::vector(0.0f, -6e-3f);
    gs.upper = F::vector(2e-3f, 6e-3f);
    gs.cell = 0.5e-3f;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
    gimlet::scene::scene<F, hmx> sc(gs);
    const auto m = gimlet::presets::make_hmx();
    sc.add_body(gimlet::scene::box<F>(F::vector(0.0f, 0.0f), F::vector(2e-3f, 4e-3f)), m, F::vector(0.0f, -300.0f), 2);
    sc.add_body(gimlet::scene::box<F>(F::vector(0.0f, -4e-3f), F::vector(2e-3f, 0.0f)), m, F::vector(0.0f, 300.0f), 2);
    gimlet::solver_options<F> opt;
    opt.threads = 1;
    gimlet::solver<F, gimlet::shape::ugimp, hmx, gimlet::contact::distance> sol(sc, opt);
    sol.run_until(0.6e-6f);
    float hottest = 0, max_eta = 0;
    for (std::size_t i = 0; i < sol.particles().size(); ++i) {
        const auto p = sol.particles()[i];
        hottest = std::max(hottest, p.get<gimlet::fields::temperature>());
        max_eta = std::max(max_eta, 1.0f - p.get<gimlet::fields::deformation_gradient>().determinant());
    }
    std::printf("float HMX at 300 m/s: hottest %.1f K, largest eta %.4f, %llu steps\n", hottest, max_eta,
                static_cast<unsigned long long>(sol.steps()));
    // Shocked: about 337 K and eta 0.084 on the Rankine-Hugoniot state; finite and bounded here.
    CHECK(hottest > 320.0f);
    CHECK(hottest < 500.0f);
    CHECK(max_eta > 0.06f);
    CHECK(max_eta < 0.2f);
    CHECK(sol.health().total() == 0);
}
