// SPDX-License-Identifier: MIT
// The impact_1d scene: symmetric impact of two HMX slabs in uniaxial strain, against the
// elastic-plastic Rankine-Hugoniot state computed from the same EOS and strength parameters.
#include "impact_1d/impact_1d.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <utility>

namespace {

impact_1d::result check_impact(double v, double length = 20e-3, double end_time = 3e-6) {
    impact_1d::settings s;  // 0.1 mm cells, 20 mm slabs, 3 us, USF
    s.velocity = v;
    s.length = length;
    s.end_time = end_time;
    const auto r = impact_1d::run(s);
    std::printf("impact_1d v = %.0f m/s: sigma_yy %.4e Pa (RH %.4e, %+.2f %%), shock speed %.1f m/s "
                "(RH %.1f, c0 + s v %.1f, %s), energy error %.2e, plateau T - T0 %.2f K (RH %.2f K), "
                "plastic work %.2f K (uniaxial %.2f K), front rise %.2f cells, peak eta %+.1f %% over the plateau\n",
                v, r.plateau_sigma_yy, r.rh.sigma_yy, 100 * (r.plateau_sigma_yy / r.rh.sigma_yy - 1), r.shock_speed,
                r.rh.shock_speed, 2740 + 2.6 * v, r.rh.two_wave ? "two-wave" : "single wave", r.energy_error,
                r.plateau_temperature - 300.0, r.rh_temperature - 300.0, r.plateau_plastic_heat, r.rh_plastic_heat,
                r.rise_cells, 100 * (r.front_peak_eta / r.plateau_eta - 1));
    // Plateau within 3 % of Rankine-Hugoniot.
    CHECK(std::abs(r.plateau_sigma_yy / r.rh.sigma_yy - 1) < 0.03);
    CHECK(r.all_finite);
    CHECK(r.min_det_f > 0);
    // The temperature rise within 3 % of the Rankine-Hugoniot state's on the EOS's own
    // thermodynamics (the isentrope temperature, the shear energy excluded from heat).
    CHECK(std::abs((r.plateau_temperature - 300.0) / (r.rh_temperature - 300.0) - 1) < 0.03);
    CHECK(r.max_temperature < 1000.0);
    if (!r.rh.two_wave) {
        // Single wave: U_s within 3 % of c0 + s v and of the elastic-plastic
        // Rankine-Hugoniot speed; the front rises (10-90 % of sigma_yy) within 4 cells.
        CHECK(std::abs(r.shock_speed / (2740.0 + 2.6 * v) - 1) < 0.03);
        CHECK(std::abs(r.shock_speed / r.rh.shock_speed - 1) < 0.03);
        CHECK(r.rise_cells > 0.5);  // a shock spread over the grid, not a measurement artefact
        CHECK(r.rise_cells < 4.0);
    }
    return r;
}

}  // namespace

// Total energy (kinetic + internal, heat and viscous work included) within 1 % at 150 and
// 300 m/s. At 500 and 700 m/s it is not asserted: the shock rings at the default viscosity and
// USF gains 1.1 and 1.7 % (docs/equations.md, viscosity::bulk; the particle-scale mode control
// that should close it is open work).
TEST_CASE("impact_1d at 300 m/s: single shock on the Rankine-Hugoniot state", "[examples][verification]") {
    const auto r = check_impact(300.0);
    CHECK(std::abs(r.energy_error) < 0.01);
}

// 10 mm slabs to 1.5 us (a quarter of the cost; the plateau still spans 16 cells): the same
// run as 20 mm slabs to 3 us at 0.2 mm cells, to every printed digit, since nothing in the
// model has a length of its own but the cell. Measured: sigma_yy +1.29 / +1.89 %, T - T0 +1.9 /
// +2.7 % of the Rankine-Hugoniot rise.
TEST_CASE("impact_1d at 500 and 700 m/s: the shocked state's temperature", "[examples][verification]") {
    check_impact(500.0, 10e-3, 1.5e-6);
    check_impact(700.0, 10e-3, 1.5e-6);
}

impact_1d::settings blended(double v) {
    impact_1d::settings s;  // 0.1 mm cells, 20 mm slabs, 3 us, USF
    s.velocity = v;
    s.pic_fraction = 0.5;
    return s;
}

// The PIC blend (solver_options::pic_fraction, alpha = 0.5) with its heat: the velocity part of
// the ringing goes, and with it the reverse yielding. Measured (sigma_yy, T - T0, plastic work,
// energy): 300 m/s -0.02 %, +1.9 %, +2.4 %, +0.03 %; 500 m/s +0.07 %, +0.2 %, +3.7 %, +0.19 %;
// 700 m/s +0.45 %, -0.3 %, +4.3 %, +0.37 % (FLIP: plastic work +46, +126, +172 %, energy up to
// +1.7 %). Not asserted because they fail: the front rises over 6.6 cells at 300 m/s (3.8 and
// 3.0 at 500 and 700; FLIP 3.6, 2.2, 1.5), and the largest particle eta behind the front is
// 3.9 / 6.3 / 9.9 % over the plateau mean: the particle rows alternate by about that much all
// through the plateau (docs/equations.md, "Does the viscosity set the answer?").
TEST_CASE("impact_1d with the PIC blend: plateau, temperature, plastic work and energy",
          "[examples][verification][long]") {
    for (const double v : {300.0, 500.0, 700.0}) {
        const auto r = impact_1d::run(blended(v));
        std::printf("impact_1d v = %.0f m/s, PIC blend 0.5: sigma_yy %+.2f %%, T - T0 %+.2f %%, plastic work %.2f K "
                    "(uniaxial %.2f K), energy %+.2e, rise %.2f cells, peak eta %+.1f %%\n",
                    v, 100 * (r.plateau_sigma_yy / r.rh.sigma_yy - 1),
                    100 * ((r.plateau_temperature - 300.0) / (r.rh_temperature - 300.0) - 1), r.plateau_plastic_heat,
                    r.rh_plastic_heat, r.energy_error, r.rise_cells, 100 * (r.front_peak_eta / r.plateau_eta - 1));
        CHECK(std::abs(r.plateau_sigma_yy / r.rh.sigma_yy - 1) < 0.01);
        CHECK(std::abs((r.plateau_temperature - 300.0) / (r.rh_temperature - 300.0) - 1) < 0.03);
        CHECK(std::abs(r.plateau_plastic_heat / r.rh_plastic_heat - 1) < 0.25);
        CHECK(std::abs(r.energy_error) < 0.01);
        CHECK(r.health.total() == 0);
    }
}

// With the PIC blend the viscosity does not set the answer: doubling (b1, b2) from Abaqus's
// (0.06, 1.2) moves sigma_yy by 0.12 / 0.10 / 0.10 % and T - T0 by 0.14 / 0.18 / 0.11 K at
// 300 / 500 / 700 m/s; halving them, by 0.18 / 0.06 / 0.02 % and 0.07 / 0.20 / 0.06 K. (FLIP:
// doubling moves sigma_yy by 1.05 % at 500 m/s and halves the plastic work.)
TEST_CASE("impact_1d with the PIC blend: the viscosity does not set the answer", "[examples][verification][long]") {
    for (const double v : {300.0, 500.0, 700.0}) {
        const auto s = blended(v);
        const auto base = impact_1d::run(s);
        const auto doubled = impact_1d::run(s, gimlet::presets::make_hmx({}, gimlet::viscosity::bulk(2.4, 0.12)));
        const auto halved = impact_1d::run(s, gimlet::presets::make_hmx({}, gimlet::viscosity::bulk(0.6, 0.03)));
        std::printf("impact_1d v = %.0f m/s, PIC blend 0.5: doubling the viscosity moves sigma_yy %+.2f %% and T %+.2f K; "
                    "halving it, %+.2f %% and %+.2f K\n",
                    v, 100 * (doubled.plateau_sigma_yy / base.plateau_sigma_yy - 1),
                    doubled.plateau_temperature - base.plateau_temperature,
                    100 * (halved.plateau_sigma_yy / base.plateau_sigma_yy - 1),
                    halved.plateau_temperature - base.plateau_temperature);
        CHECK(std::abs(doubled.plateau_sigma_yy / base.plateau_sigma_yy - 1) < 0.005);
        CHECK(std::abs(doubled.plateau_temperature - base.plateau_temperature) < 1.0);
    }
}

// The coarse twin of the two `long` tests above (docs/testing.md): 10 mm slabs to 1.5 us, the
// same run as 20 mm to 3 us at 0.2 mm cells. Measured: sigma_yy -0.04 / +0.29 %, T - T0 +0.6 /
// -0.3 %, plastic work +3.5 / +4.1 %, energy +0.10 / +0.28 % at 500 / 700 m/s; doubling the
// viscosity moves sigma_yy by +0.13 / -0.01 % and T by +0.52 / +0.33 K.
TEST_CASE("impact_1d with the PIC blend, 10 mm slabs: the shocked state does not depend on the viscosity",
          "[examples][verification]") {
    for (const double v : {500.0, 700.0}) {
        auto s = blended(v);
        s.length = 10e-3;
        s.end_time = 1.5e-6;
        const auto r = impact_1d::run(s);
        const auto doubled = impact_1d::run(s, gimlet::presets::make_hmx({}, gimlet::viscosity::bulk(2.4, 0.12)));
        std::printf("impact_1d v = %.0f m/s, 10 mm, PIC blend 0.5: sigma_yy %+.2f %%, T - T0 %+.2f %%, plastic work "
                    "%+.1f %%, energy %+.2e; doubled viscosity: sigma_yy %+.2f %%, T %+.2f K\n",
                    v, 100 * (r.plateau_sigma_yy / r.rh.sigma_yy - 1),
                    100 * ((r.plateau_temperature - 300.0) / (r.rh_temperature - 300.0) - 1),
                    100 * (r.plateau_plastic_heat / r.rh_plastic_heat - 1), r.energy_error,
                    100 * (doubled.plateau_sigma_yy / r.plateau_sigma_yy - 1),
                    doubled.plateau_temperature - r.plateau_temperature);
        CHECK(std::abs(r.plateau_sigma_yy / r.rh.sigma_yy - 1) < 0.01);
        CHECK(std::abs((r.plateau_temperature - 300.0) / (r.rh_temperature - 300.0) - 1) < 0.03);
        CHECK(std::abs(r.plateau_plastic_heat / r.rh_plastic_heat - 1) < 0.25);
        CHECK(std::abs(r.energy_error) < 0.01);
        CHECK(std::abs(doubled.plateau_sigma_yy / r.plateau_sigma_yy - 1) < 0.005);
        CHECK(std::abs(doubled.plateau_temperature - r.plateau_temperature) < 1.0);
    }
}

// The consistent-mass accelerations (solver_options::consistent_mass_iterations, 4 iterations)
// at 300 m/s, 10 mm slabs to 1.5 us: the lumped mass's dispersion is what trails the shock with
// ringing, so with the consistent mass the front overshoots less and rises sooner, at the
// Abaqus viscosity and at twice it, each against the lumped mass at the same viscosity.
// Measured (rise in cells, largest particle eta over the plateau mean, plastic work over the
// uniaxial value): Abaqus viscosity, lumped 3.76, +24.0 %, +49.5 %, consistent 2.65, +17.7 %,
// +16.4 %; twice it, lumped 4.40, +11.3 %, +10.2 %, consistent 3.60, +7.1 %, +3.0 % (20 mm
// slabs to 3 us: peaks +22.7 and +15.0 %, +8.9 and +6.3 %). What the doubled run still misses
// of the thermodynamics work's front criteria is the front peak (at most 5 %): what is left is
// no longer a coherent overshoot but the particle rows alternating in eta (docs/equations.md,
// "Consistent-mass accelerations").
TEST_CASE("impact_1d with the consistent mass: less ringing, a sharper front", "[examples][verification]") {
    impact_1d::settings s;  // 0.1 mm cells, USF
    s.velocity = 300.0;
    s.length = 10e-3;
    s.end_time = 1.5e-6;
    auto show = [](const char* what, const impact_1d::result& r) {
        std::printf("impact_1d 300 m/s, 10 mm, %s: sigma_yy %+.2f %%, T - T0 %+.2f %%, plastic work %+.1f %%, energy %+.2e, "
                    "rise %.2f cells, peak eta %+.1f %%\n",
                    what, 100 * (r.plateau_sigma_yy / r.rh.sigma_yy - 1),
                    100 * ((r.plateau_temperature - 300.0) / (r.rh_temperature - 300.0) - 1),
                    100 * (r.plateau_plastic_heat / r.rh_plastic_heat - 1), r.energy_error, r.rise_cells,
                    100 * (r.front_peak_eta / r.plateau_eta - 1));
    };
    auto peak = [](const impact_1d::result& r) { return r.front_peak_eta / r.plateau_eta - 1; };
    for (const double scale : {1.0, 2.0}) {
        const auto mat = gimlet::presets::make_hmx({}, gimlet::viscosity::bulk(1.2 * scale, 0.06 * scale));
        s.consistent_mass = 0;
        const auto lumped = impact_1d::run(s, mat);
        s.consistent_mass = 4;
        const auto consistent = impact_1d::run(s, mat);
        show(scale == 1 ? "Abaqus viscosity, lumped" : "twice the Abaqus viscosity, lumped", lumped);
        show(scale == 1 ? "Abaqus viscosity, consistent mass" : "twice the Abaqus viscosity, consistent mass", consistent);
        CHECK(std::abs(consistent.plateau_sigma_yy / consistent.rh.sigma_yy - 1) < 0.01);
        CHECK(std::abs((consistent.plateau_temperature - 300.0) / (consistent.rh_temperature - 300.0) - 1) < 0.03);
        CHECK(std::abs(consistent.plateau_plastic_heat / consistent.rh_plastic_heat - 1) < 0.25);
        CHECK(std::abs(consistent.energy_error) < 0.01);
        CHECK(consistent.rise_cells < 4.0);
        CHECK(consistent.health.total() == 0);
        // Against the lumped mass at the same viscosity: less overshoot, a sharper front, and
        // less of the ringing's reverse yielding.
        CHECK(peak(consistent) < 0.8 * peak(lumped));
        CHECK(consistent.rise_cells < lumped.rise_cells);
        CHECK(consistent.plateau_plastic_heat < lumped.plateau_plastic_heat);
    }
}

// The consistent mass beside multi-field contact: the slabs in their own velocity fields with the
// distance contact, k = 4 at (0.12, 2.4), 0.5 mm cells, 1.5 us after the impact. The first cell
// behind the contact plane (its two particle rows) carries the plateau's sigma_yy, because the
// nodes shared by two fields keep their lumped accelerations: iterated, they would couple each
// field's edge node, whose velocity the contact then sets, to the cell behind it, which would
// read 37 % under the plateau under MUSL and 33 % under USF (24 % at k = 1; docs/equations.md,
// "Consistent-mass accelerations"). Measured: -2.6 % (MUSL) and +1.9 % (USF), -2.0 % at k = 1;
// with the lumped mass -1.9 % and +3.1 %.
TEST_CASE("impact_1d with the consistent mass and the distance contact: no pressure dip at the contact plane",
          "[examples][verification][contact]") {
    using M = gimlet::presets::hmx_material<>;
    const auto mat = gimlet::presets::make_hmx({}, gimlet::viscosity::bulk(2.4, 0.12));
    using enum gimlet::update_scheme;
    const std::pair<gimlet::update_scheme, int> runs[] = {{musl, 0}, {musl, 1}, {musl, 4}, {usf, 0}, {usf, 4}};
    for (const auto& [scheme, k] : runs) {
        impact_1d::settings s;
        s.velocity = 300.0;
        s.cell = 0.5e-3;
        s.length = 10e-3;
        s.end_time = 1.5e-6;  // the front 9-10 cells from the contact plane
        s.scheme = scheme;
        s.consistent_mass = k;
        auto sol = impact_1d::make_solver<M, gimlet::contact::distance>(s, mat);
        sol.run_until(s.end_time);
        // The upper slab's sigma_yy, averaged over the first cell and over 2-6 cells behind the plane.
        double first = 0, plateau = 0;
        int n_first = 0, n_plateau = 0;
        for (std::size_t i = 0; i < sol.particles().size(); ++i) {
            const auto p = sol.particles()[i];
            if (p.template get<gimlet::fields::body>() != 0u) continue;
            const double y = p.template get<gimlet::fields::position>()[1] / s.cell;
            const double syy = -p.template get<gimlet::fields::stress>()(1, 1);
            if (y < 1.0) first += syy, ++n_first;
            else if (y >= 2.0 && y <= 6.0) plateau += syy, ++n_plateau;
        }
        REQUIRE(n_first > 0);
        REQUIRE(n_plateau > 0);
        first /= n_first;
        plateau /= n_plateau;
        std::printf("impact_1d 300 m/s, 0.5 mm, distance contact, k = %d, %s: the first cell's sigma_yy %+.2f %% of the "
                    "plateau's (%.4e Pa)\n",
                    k, scheme == musl ? "MUSL" : "USF", 100 * (first / plateau - 1), plateau);
        CHECK(std::abs(first / plateau - 1) < 0.05);
        CHECK(sol.health().total() == 0);
    }
}

// The volume filter (solver_options::volume_filter, with the consistent mass, k = 4, at twice the
// Abaqus viscosity, (b1, b2) = (0.12, 2.4)): the particle rows' pattern behind the front goes,
// and with it the front peak (docs/equations.md, "Particle-scale state filters", (D)). Measured on
// 20 mm slabs to 3 us at 300 / 500 / 700 m/s: sigma_yy -0.25 / -0.08 / +0.11 %, T - T0 +0.57 /
// -0.50 / -0.75 %, plastic work +4.3 / +4.5 / +6.9 %, rise 3.95 / 2.62 / 2.48 cells, energy
// -0.15 / -0.17 / -0.22 %. Twice that viscosity moves sigma_yy by 0.10 / 0.19 / 0.39 % and
// T - T0 by 0.28 / 0.09 / 0.15 K; half of it, the Abaqus viscosity, leaves the 500 m/s front
// ringing (peak +14.3 %, plastic work +31 %).
//
// The front peak is read on cell-thick layers at rest (impact_1d::result::front_peak_eta_layers),
// what a Lagrangian hydrocode's zone holds, and gated at 5 % over the plateau under USF and MUSL;
// the single particle's peak and the rows' alternation are printed beside it. Measured, layers /
// single particle / rows' alternation, 300 / 500 / 700 m/s: USF +3.0 / +2.3 / +1.3 %, +3.5 /
// +3.0 / +2.2 %, +-0.04 / 0.05 / 0.02 %; MUSL +2.6 / +2.8 / +1.2 %, +3.5 / +5.5 / +2.0 %,
// +-0.04 / 0.04 / 0.02 %. MUSL's 300 m/s front rises over 4.05 cells, so its rise is printed,
// not held to USF's 4 cells.
namespace {
impact_1d::result filtered(double v, double scale, bool filter, double length, double end_time,
                           gimlet::update_scheme scheme = gimlet::update_scheme::usf) {
    impact_1d::settings s;  // 0.1 mm cells
    s.velocity = v;
    s.length = length;
    s.end_time = end_time;
    s.scheme = scheme;
    s.consistent_mass = 4;
    s.volume_filter = filter;
    const auto r = impact_1d::run(s, gimlet::presets::make_hmx({}, gimlet::viscosity::bulk(2.4 * scale, 0.12 * scale)));
    std::printf("impact_1d %s %.0f m/s, %.0f mm, consistent mass, (%.2f, %.1f)%s: sigma_yy %+.2f %%, T - T0 %+.2f %%, "
                "plastic work %+.1f %%, energy %+.2e, rise %.2f cells, front peak eta by layers %+.2f %% (single particle "
                "%+.2f %%), rows alternate by +-%.2f %%\n",
                scheme == gimlet::update_scheme::musl ? "MUSL" : "USF", v, length * 1e3, 0.12 * scale, 2.4 * scale,
                filter ? ", volume filter" : "", 100 * (r.plateau_sigma_yy / r.rh.sigma_yy - 1),
                100 * ((r.plateau_temperature - 300.0) / (r.rh_temperature - 300.0) - 1),
                100 * (r.plateau_plastic_heat / r.rh_plastic_heat - 1), r.energy_error, r.rise_cells,
                100 * (r.front_peak_eta_layers / r.plateau_eta - 1), 100 * (r.front_peak_eta / r.plateau_eta - 1),
                100 * r.row_alternation);
    return r;
}
// The shocked state and its front peak, read on cell-thick layers.
void check_shocked_state(const impact_1d::result& r) {
    CHECK(std::abs(r.plateau_sigma_yy / r.rh.sigma_yy - 1) < 0.01);
    CHECK(std::abs((r.plateau_temperature - 300.0) / (r.rh_temperature - 300.0) - 1) < 0.03);
    CHECK(std::abs(r.plateau_plastic_heat / r.rh_plastic_heat - 1) < 0.25);
    CHECK(std::abs(r.energy_error) < 0.01);
    CHECK(r.front_peak_eta_layers / r.plateau_eta - 1 <= 0.05);
    // A layer's mean is never above its largest particle's.
    CHECK(r.front_peak_eta_layers > 0);
    CHECK(r.front_peak_eta_layers <= r.front_peak_eta);
    CHECK(r.health.total() == 0);
}
// The thermodynamics criteria for the shocked state and its front: the above, and a front that
// rises within 4 cells.
void check_front_criteria(const impact_1d::result& r) {
    check_shocked_state(r);
    CHECK(r.rise_cells < 4.0);
}
}  // namespace

TEST_CASE("impact_1d with the volume filter: the front criteria at 300, 500 and 700 m/s under USF and MUSL",
          "[examples][verification][long]") {
    for (const double v : {300.0, 500.0, 700.0}) {
        const auto r = filtered(v, 1.0, true, 20e-3, 3e-6);
        check_front_criteria(r);
        if (v != 500.0) {
            // The viscosity does not set the answer: doubling it moves the plateau little.
            const auto twice = filtered(v, 2.0, true, 20e-3, 3e-6);
            CHECK(std::abs(twice.plateau_sigma_yy / r.plateau_sigma_yy - 1) < 0.005);
            CHECK(std::abs(twice.plateau_temperature - r.plateau_temperature) < 1.0);
        }
        check_shocked_state(filtered(v, 1.0, true, 20e-3, 3e-6, gimlet::update_scheme::musl));
    }
}

// At impact_1d's defaults (no volume filter) the particle rows alternate behind the front; the
// layers hold their mean. Measured, layers / single particle / rows' alternation, 300 / 500 /
// 700 m/s: USF +1.8 / +2.3 / +3.9 %, +6.3 / +7.8 / +9.5 %, +-2.8 / 4.0 / 4.8 %; MUSL +2.3 /
// +5.2 / +4.5 %, +6.6 / +9.3 / +10.7 %, +-3.2 / 4.6 / 5.5 %: under MUSL, at 500 m/s, the
// layers read above the 5 % the volume filter meets, so this gates USF and prints MUSL.
TEST_CASE("impact_1d at the defaults: the front peak by layers within 5 % under USF", "[examples][verification][long]") {
    for (const double v : {300.0, 500.0, 700.0}) {
        const auto usf = filtered(v, 1.0, false, 20e-3, 3e-6);
        CHECK(usf.front_peak_eta_layers / usf.plateau_eta - 1 <= 0.05);
        // The layers read the rows' mean: their peak stands below the single particle's by
        // about the rows' alternation.
        CHECK(usf.row_alternation > 0.01);
        CHECK(usf.front_peak_eta_layers < usf.front_peak_eta);
        const auto musl = filtered(v, 1.0, false, 20e-3, 3e-6, gimlet::update_scheme::musl);
        CHECK(musl.health.total() == 0);
    }
}

// The coarse twin (10 mm slabs to 1.5 us, 500 m/s; 4 times less work): measured +3.3 % against
// +8.4 % without the filter, rise 2.73 cells; the rows' alternation goes with the filter.
TEST_CASE("impact_1d with the volume filter, 10 mm slabs: the rows' pattern goes", "[examples][verification]") {
    const auto with = filtered(500.0, 1.0, true, 10e-3, 1.5e-6);
    const auto without = filtered(500.0, 1.0, false, 10e-3, 1.5e-6);
    check_front_criteria(with);
    CHECK(with.front_peak_eta / with.plateau_eta - 1 < 0.5 * (without.front_peak_eta / without.plateau_eta - 1));
    CHECK(with.row_alternation < 0.1 * without.row_alternation);
}

TEST_CASE("impact_1d at 150 m/s: two-wave structure, plateau on the Rankine-Hugoniot state", "[examples][verification]") {
    const auto rh = impact_1d::rankine_hugoniot(gimlet::presets::make_hmx(), 150.0);
    CHECK(rh.two_wave);  // the paper's material has an elastic precursor below ~210 m/s
    const auto r = check_impact(150.0);
    CHECK(std::abs(r.energy_error) < 0.01);
}

TEST_CASE("Rankine-Hugoniot helper: the oracle values of the shock-thermodynamics work", "[examples]") {
    // The elastic-plastic jump conditions on the same EOS and strength: sigma_yy, the temperature
    // rise T(V, e_th) on the reference isentrope (e_th = e - Y^2 / (6 G rho)), and the uniaxial
    // plastic work 2 Y (eta - eta_HEL) / (3 rho0 c_v) at 300, 500 and 700 m/s, against values
    // computed independently from the EOS and quoted to 0.1 K and 0.01 K (so within those).
    const auto hmx = gimlet::presets::make_hmx();
    const double sigma[] = {2.034e9, 3.863e9, 6.087e9}, rise[] = {37.0, 71.9, 122.1}, work[] = {2.07, 3.16, 4.00};
    int k = 0;
    for (const double v : {300.0, 500.0, 700.0}) {
        const auto rh = impact_1d::rankine_hugoniot(hmx, v);
        CHECK(rh.sigma_yy == Approx(sigma[k]).epsilon(5e-4));
        CHECK(impact_1d::hugoniot_temperature(rh) - 300.0 == Approx(rise[k]).margin(0.1));
        CHECK(impact_1d::uniaxial_plastic_heat(rh) == Approx(work[k]).margin(0.01));
        ++k;
    }
}

TEST_CASE("Rankine-Hugoniot helper: hydrodynamic limit", "[examples]") {
    // With a vanishing yield stress the state is the hydrodynamic one: U_s = c0 + s v with
    // Gamma corrections only through e - e_H = 0 on the Hugoniot, so U_s = c0 + s v exactly.
    gimlet::presets::hmx_constants c;
    c.yield_stress = 1.0;  // Pa
    const auto rh = impact_1d::rankine_hugoniot(gimlet::presets::make_hmx(c), 300.0);
    CHECK(rh.shock_speed == Approx(2740.0 + 2.6 * 300.0).epsilon(1e-4));
    CHECK(rh.sigma_yy == Approx(1900.0 * (2740.0 + 2.6 * 300.0) * 300.0).epsilon(1e-4));
}
