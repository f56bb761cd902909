// SPDX-License-Identifier: MIT
// A strengthless slab released after the symmetric impact keeps its entropy: theta = T / T_s(J)
// is constant along an isentrope (constant Gamma and c_v), so after the free-surface release and
// the slabs' parting the median theta stays at the Hugoniot's, and the median T - T0 rings about
// the isentropic release's (19.6 K at 500 m/s, 47.0 K at 700 m/s). Checked first on a 1-D
// Lagrangian reference (lagrangian_1d.hpp), which shows how long that holds: the tension where
// the release fans cross, and the freed slab's ringing, steepen into weak shocks that raise theta
// slowly over 10-20 us (about 0.07 % at 500 m/s, 0.2 % at 700 m/s) and faster later (0.38 and
// 0.68 % at 30 us). Then the MPM run against the same numbers, over 10 to 20 us
// (docs/equations.md, "Release keeps the entropy").
#include "impact_1d/impact_1d.hpp"
#include "lagrangian_1d.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace {

// Samples every 0.25 us from 10 to 20 us.
std::vector<double> window() {
    std::vector<double> t;
    for (int k = 0; k <= 40; ++k) t.push_back((10.0 + 0.25 * k) * 1e-6);
    return t;
}

struct window_stats {
    double largest_theta_error = 0;  // max |theta / theta_H - 1|
    double mean_heating = 0;         // mean of the median T - T0 (K)
};

template <class Samples>
window_stats summarise(const Samples& samples, double theta_h) {
    window_stats w;
    for (const auto& s : samples) {
        w.largest_theta_error = std::max(w.largest_theta_error, std::abs(s.theta / theta_h - 1));
        w.mean_heating += s.heating / double(samples.size());
    }
    return w;
}

using strengthless = gimlet::material<gimlet::strength::none, gimlet::eos::mie_gruneisen<>,
                                      gimlet::thermal::isentrope_temperature, gimlet::viscosity::bulk>;

strengthless make_strengthless(const gimlet::viscosity::bulk& viscosity) {
    const gimlet::materials::hmx_constants c{};
    return {c.density,
            gimlet::strength::none{},
            gimlet::eos::mie_gruneisen<>{c.density, c.sound_speed, c.slope, c.gruneisen},
            gimlet::thermal::isentrope_temperature{c.density, c.sound_speed, c.slope, c.gruneisen, c.specific_heat,
                                                   c.temperature},
            viscosity};
}

// The MPM run: impact_1d's strip, 10 mm slabs with room to fly apart, the distance contact,
// USF with the consistent mass (k = 4) and twice the Abaqus viscosity, (b1, b2) = (0.12, 2.4),
// the setting that meets the shocked state's criteria (test_impact_1d.cpp). The medians skip
// the particles within 5 cells of either face of the upper slab.
std::vector<lagrangian_1d::sample> mpm_release(double v, double cell) {
    impact_1d::settings s;
    s.velocity = v;
    s.cell = cell;
    s.length = 10e-3;
    s.margin = 8e-3;
    s.consistent_mass = 4;
    const auto mat = make_strengthless(gimlet::viscosity::bulk(2.4, 0.12));
    auto sol = impact_1d::make_solver<strengthless, gimlet::contact::distance>(s, mat);
    const auto& th = mat.thermal;
    std::vector<lagrangian_1d::sample> out;
    std::vector<double> theta, heating;
    for (const double t : window()) {
        sol.run_until(t);
        const auto& ps = sol.particles();
        double lo = 1e9, hi = -1e9;
        for (std::size_t i = 0; i < ps.size(); ++i) {
            if (ps[i].get<gimlet::fields::body>() != 0u) continue;
            const double y = ps[i].get<gimlet::fields::position>()(1);
            lo = std::min(lo, y), hi = std::max(hi, y);
        }
        theta.clear();
        heating.clear();
        for (std::size_t i = 0; i < ps.size(); ++i) {
            const auto p = ps[i];
            const double y = p.get<gimlet::fields::position>()(1);
            if (p.get<gimlet::fields::body>() != 0u || y < lo + 5 * cell || y > hi - 5 * cell) continue;
            const double temperature = p.get<gimlet::fields::temperature>();
            theta.push_back(temperature / th.isentrope(p.get<gimlet::fields::deformation_gradient>().determinant()));
            heating.push_back(temperature - th.initial_temperature());
        }
        auto median = [](std::vector<double>& x) {
            std::nth_element(x.begin(), x.begin() + x.size() / 2, x.end());
            return x[x.size() / 2];
        };
        out.push_back({t, median(theta), median(heating), lo});
        REQUIRE(sol.health().total() == 0);
    }
    return out;
}

// The criteria over the window: theta within 0.3 % of the Hugoniot's, the median T - T0
// within 10 % of the isentropic release's on average (it rings by +-40 % about it).
void check_release(double v, double cell, double isentropic_heating) {
    const double theta_h = lagrangian_1d::hugoniot_theta(v);
    const auto w = summarise(mpm_release(v, cell), theta_h);
    std::printf("release, MPM, %.0f m/s, %.2f mm cells: largest |theta / theta_H - 1| over 10-20 us %.3f %%, mean "
                "median T - T0 %.2f K (isentropic %.1f K)\n",
                v, cell * 1e3, 100 * w.largest_theta_error, w.mean_heating, isentropic_heating);
    CHECK(w.largest_theta_error < 0.003);
    CHECK(std::abs(w.mean_heating / isentropic_heating - 1) < 0.10);
}

}  // namespace

// Measured (800 cells; 400 cells): over 10-20 us theta at most 0.111 % (0.156 %) above the
// Hugoniot's at 500 m/s and 0.267 % (0.330 %) at 700 m/s, first-order convergent (to about
// 0.07 and 0.20 %); the median T - T0 averaging 20.6 and 47.9 K (it swings over 12-28 K and
// 29-67 K); at 30 us theta +0.38 and +0.68 %.
TEST_CASE("release reference (1-D Lagrangian): theta kept until the freed slab's ringing steepens into shocks",
          "[examples][verification]") {
    for (const auto& [v, isentropic] : {std::pair{500.0, 19.6}, std::pair{700.0, 47.0}}) {
        const double theta_h = lagrangian_1d::hugoniot_theta(v);
        auto times = window();
        times.push_back(30e-6);
        std::vector<lagrangian_1d::sample> runs[2];
        for (int r = 0; r < 2; ++r) {
            lagrangian_1d::settings s;
            s.velocity = v;
            s.cells = 400 << r;
            runs[r] = lagrangian_1d::run(s, times);
        }
        const auto& fine = runs[1];
        const std::vector<lagrangian_1d::sample> in_window(fine.begin(), fine.end() - 1);
        const auto w = summarise(in_window, theta_h);
        const double late = fine.back().theta / theta_h - 1;
        std::printf("release reference, %.0f m/s: theta_H %.5f, largest |theta / theta_H - 1| over 10-20 us %.3f %%, "
                    "mean median T - T0 %.2f K (isentropic %.1f K), theta at 30 us %+.3f %%\n",
                    v, theta_h, 100 * w.largest_theta_error, w.mean_heating, isentropic, 100 * late);
        CHECK(fine.front().lower_face > 0);  // the slabs have parted by 10 us
        CHECK(w.largest_theta_error < 0.003);  // the criterion the MPM run is held to holds here
        CHECK(std::abs(w.mean_heating / isentropic - 1) < 0.10);
        // Converged: 400 and 800 cells agree.
        for (std::size_t k = 0; k < fine.size(); ++k) CHECK(std::abs(runs[0][k].theta / fine[k].theta - 1) < 1e-3);
        // Later the ringing's shocks raise theta more: a criterion on theta must end before them.
        CHECK(late > 0.003);
    }
}

// Measured: 0.19 % and 20.8 K (USF; MUSL 0.17 %, 20.6 K). Not met at 700 m/s: 0.40 % and 47.3 K
// (the reference: 0.27 %); with the volume filter 2.5 % and 4.6 %: it turns the freed slab's
// ringing into heat (docs/equations.md).
TEST_CASE("impact_1d release, strength off, 500 m/s: theta within 0.3 % of the Hugoniot's from 10 to 20 us",
          "[examples][verification][long]") {
    check_release(500.0, 0.1e-3, 19.6);
}

// The coarse twin (0.2 mm cells, 8 times less work): measured 0.23 % and 21.3 K.
TEST_CASE("impact_1d release, strength off, 500 m/s, 0.2 mm cells: theta within 0.3 % of the Hugoniot's",
          "[examples][verification]") {
    check_release(500.0, 0.2e-3, 19.6);
}
