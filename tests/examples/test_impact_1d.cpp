// SPDX-License-Identifier: MIT
// The impact_1d scene: symmetric impact of two HMX slabs in uniaxial strain, against the
// elastic-plastic Rankine-Hugoniot state computed from the same EOS and strength parameters.
#include "impact_1d/impact_1d.hpp"

#include <catch2/catch.hpp>

#include <cstdio>

namespace {

void check_impact(double v) {
    impact_1d::settings s;  // 0.1 mm cells, 20 mm slabs, 3 us, USF
    s.velocity = v;
    const auto r = impact_1d::run(s);
    std::printf("impact_1d v = %.0f m/s: sigma_yy %.4e Pa (RH %.4e, %+.2f %%), shock speed %.1f m/s "
                "(RH %.1f, c0 + s v %.1f, %s), energy error %.2e, plateau T %.1f K\n",
                v, r.plateau_sigma_yy, r.rh.sigma_yy, 100 * (r.plateau_sigma_yy / r.rh.sigma_yy - 1), r.shock_speed,
                r.rh.shock_speed, 2740 + 2.6 * v, r.rh.two_wave ? "two-wave" : "single wave", r.energy_error,
                r.plateau_temperature);
    // The bounds: plateau within 3 % of Rankine-Hugoniot; total energy (kinetic +
    // internal, heat and viscous work included) within 1 %.
    CHECK(std::abs(r.plateau_sigma_yy / r.rh.sigma_yy - 1) < 0.03);
    CHECK(std::abs(r.energy_error) < 0.01);
    CHECK(r.all_finite);
    CHECK(r.min_det_f > 0);
    // The material did heat up (shock and plastic work) and stayed far from anything absurd.
    CHECK(r.plateau_temperature > 300.0);
    CHECK(r.max_temperature < 1000.0);
    if (!r.rh.two_wave) {
        // Single wave: U_s within 3 % of c0 + s v (the bound) and of the elastic-plastic
        // Rankine-Hugoniot speed.
        CHECK(std::abs(r.shock_speed / (2740.0 + 2.6 * v) - 1) < 0.03);
        CHECK(std::abs(r.shock_speed / r.rh.shock_speed - 1) < 0.03);
    }
}

}  // namespace

TEST_CASE("impact_1d at 300 m/s: single shock on the Rankine-Hugoniot state", "[examples][verification]") {
    check_impact(300.0);
}

TEST_CASE("impact_1d at 150 m/s: two-wave structure, plateau on the Rankine-Hugoniot state", "[examples][verification]") {
    const auto rh = impact_1d::rankine_hugoniot(gimlet::materials::make_hmx(), 150.0);
    CHECK(rh.two_wave);  // the paper's material has an elastic precursor below ~210 m/s
    check_impact(150.0);
}

TEST_CASE("Rankine-Hugoniot helper: hydrodynamic limit", "[examples]") {
    // With a vanishing yield stress the state is the hydrodynamic one: U_s = c0 + s v with
    // Gamma corrections only through e - e_H = 0 on the Hugoniot, so U_s = c0 + s v exactly.
    gimlet::materials::hmx_constants c;
    c.yield_stress = 1.0;  // Pa
    const auto rh = impact_1d::rankine_hugoniot(gimlet::materials::make_hmx(c), 300.0);
    CHECK(rh.shock_speed == Approx(2740.0 + 2.6 * 300.0).epsilon(1e-4));
    CHECK(rh.sigma_yy == Approx(1900.0 * (2740.0 + 2.6 * 300.0) * 300.0).epsilon(1e-4));
}
