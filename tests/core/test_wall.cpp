// SPDX-License-Identifier: MIT
// boundary::wall: a rigid one-sided wall resists penetration only, so an elastic bar that hits
// it rebounds with its speed and leaves it.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>

namespace {

using S = gimlet::space<2>;
constexpr double fine = 0.125e-3, length = 10e-3, speed = 10.0;

struct rebound {
    double peak_energy = 0;  // the largest (KE + IE) over KE at the start, at any step
    double velocity = 0;  // the bar's mean velocity along y at the end (m/s)
    double sideways = 0;  // ... and along x
    double clearance = 0; // the lowest particle domain's distance above the wall at the end (m)
    double energy = 0;    // (KE + IE) at the end over KE at the start
};

// An elastic bar (nu = 0, so the bar speed is sqrt(E / rho) = 1000 m/s) in a strip periodic
// across, falling at 10 m/s onto the wall at y = 0 from half a cell above it. Contact lasts
// 2 L / c = 20 us; the run ends 45 us after first contact.
rebound drop(gimlet::boundary wall, double friction = 0.0,
             gimlet::update_scheme scheme = gimlet::update_scheme::musl, double sideways = 0.0, double cell = fine) {
    gimlet::grid_spec<S> gs;
    gs.upper = S::vector(4 * cell, length + 10 * cell);
    gs.cell = cell;
    gs.bc = {gimlet::boundary::periodic, wall};
    gs.wall_friction = {0.0, friction};
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    sc.add_body(gimlet::scene::box<S>(S::vector(0.0, 0.5 * cell), S::vector(4 * cell, 0.5 * cell + length)),
                gimlet::make_elastic_material(1000.0, 1e9, 0.0), S::vector(sideways, -speed), 2, "bar");
    gimlet::solver_options<S> opt;
    opt.threads = 1;
    opt.scheme = scheme;
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material> sol(sc, opt);
    const double e0 = gimlet::diagnostics::kinetic_energy(sol);
    rebound r;
    gimlet::diagnostics::every_steps watch(1, [&](const auto& s) {
        r.peak_energy = std::max(r.peak_energy,
                                 (gimlet::diagnostics::kinetic_energy(s) + gimlet::diagnostics::internal_energy(s)) / e0);
    });
    sol.run_until(0.5 * cell / speed + 45e-6, watch);
    r.velocity = gimlet::diagnostics::linear_momentum(sol)[1] / gimlet::diagnostics::total_mass(sol);
    r.sideways = gimlet::diagnostics::linear_momentum(sol)[0] / gimlet::diagnostics::total_mass(sol);
    double lowest = 1e9;
    for (const auto& x : sol.particles().column<gimlet::fields::position>()) lowest = std::min(lowest, double(x[1]));
    r.clearance = lowest - 0.25 * cell;  // a particle's domain reaches h/4 below its centre
    r.energy = (gimlet::diagnostics::kinetic_energy(sol) + gimlet::diagnostics::internal_energy(sol)) / e0;
    return r;
}

}  // namespace

TEST_CASE("one-sided wall: an elastic bar rebounds with its speed and leaves", "[core][verification]") {
    const auto wall = drop(gimlet::boundary::wall);
    const auto slip = drop(gimlet::boundary::slip, 0.0, gimlet::update_scheme::musl, 0.0, 2 * fine);
    const auto usl = drop(gimlet::boundary::wall, 0.0, gimlet::update_scheme::usl);
    std::printf("bar on a one-sided wall: rebound %.3f m/s (of %.0f), clearance %.3f mm, energy %.4f of the start "
                "(USL: %.3f m/s, energy %.4f); on a slip wall: %.3f m/s, clearance %.3f mm\n",
                wall.velocity, speed, wall.clearance * 1e3, wall.energy, usl.velocity, usl.energy, slip.velocity,
                slip.clearance * 1e3);
    // MUSL and USL: the rebound speed within 2 % (measured -1.35 % and -1.39 %; MUSL at 0.25 mm
    // cells -2.0 %, at 0.5 mm -3.0 %: the loss is the release's, and falls with h), and the bar
    // leaves. USF gains energy here (+8 % at 0.25 mm), so the solver refuses a one-sided wall
    // with USF (below).
    for (const auto& r : {wall, usl}) {
        CHECK(r.velocity == Approx(speed).epsilon(0.02));
        CHECK(r.clearance > 0.1e-3);  // it left: 25 us at 10 m/s is 0.25 mm
        CHECK(r.peak_energy < 1.0 + 1e-6);  // the wall takes energy or keeps it, never gives, at any step
    }
    // A slip wall holds the normal velocity both ways: the bar leaves at a fraction of its speed
    // (measured 5.6 m/s at these 0.25 mm cells, 0.3 m/s at 0.125 mm).
    CHECK(slip.velocity < 0.7 * speed);
}

TEST_CASE("one-sided wall: refused with USF, naming the axis", "[core][robustness]") {
    CHECK_THROWS_WITH(drop(gimlet::boundary::wall, 0.0, gimlet::update_scheme::usf, 0.0, 2 * fine),
                      Catch::Matchers::Contains("update scheme with a one-sided wall (boundary::wall) along y = usf") &&
                          Catch::Matchers::Contains("musl or usl"));
}

TEST_CASE("one-sided wall: Coulomb friction slows the sliding, within mu times the normal impulse", "[core]") {
    // The bar arrives sliding at 5 m/s along the wall. Frictionless, nothing acts along it; with
    // mu = 0.1 the wall takes at most mu times the normal velocity change (10 + the rebound) off it.
    // (0.25 mm cells: the rebound there is -2.0 %, not what this case is about.)
    const auto free = drop(gimlet::boundary::wall, 0.0, gimlet::update_scheme::musl, 5.0, 2 * fine);
    const auto rough = drop(gimlet::boundary::wall, 0.1, gimlet::update_scheme::musl, 5.0, 2 * fine);
    std::printf("sliding bar: frictionless %.4f m/s along the wall after the rebound, mu = 0.1 %.4f m/s "
                "(bound %.4f)\n", free.sideways, rough.sideways, 5.0 - 0.1 * (speed + rough.velocity));
    CHECK(free.sideways == Approx(5.0).epsilon(1e-9));
    CHECK(rough.sideways < 5.0 - 0.2);  // friction acted
    CHECK(rough.sideways >= 5.0 - 0.1 * (speed + rough.velocity) * (1 + 1e-6));  // at most mu dv_n
    CHECK(rough.velocity == Approx(speed).epsilon(0.03));
}
