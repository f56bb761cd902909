// SPDX-License-Identifier: MIT
// A slot closing inside one HMX block (multi_field::self_contact) at the examples' settings,
// against two independent references:
// - the wall layer: the hottest cell-thick layer of material at the landing plane, 1 us after
//   the faces meet, is at most 1.15 times the first cell of a 1-D Lagrangian hydrocode
//   (tests/examples/lagrangian_1d.hpp) run with the same strength and viscosity. The excess
//   heating at a plane where two shocked bodies meet is the wall heating of artificial-viscosity
//   shock capturing (Noh 1987, J. Comput. Phys. 72), which the reference has too: the bound says
//   that the slot's landing adds little to it;
// - the plateau: sigma_yy behind the shock within 1 % of the elastic-plastic Rankine-Hugoniot
//   state of the symmetric impact at +-dv/2 (examples/common/hugoniot.hpp), 2 us after the faces
//   meet.
// Both under USF and MUSL: asserted at a closing speed dv of 1000 m/s on a 40 x 20 mm block;
// printed at 3000 m/s on a 40 x 40 mm block, whose free faces' releases reach the plateau after
// the reading but whose slot ends' waves reach it before (that case says by how much). The 1-D
// reference's own plateau is checked against Rankine-Hugoniot first (docs/equations.md,
// "Self-contact").
#include "../examples/lagrangian_1d.hpp"
#include "common/hugoniot.hpp"

#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace {

using S = gimlet::space<2>;
using vec = S::vector;
using hmx = gimlet::presets::hmx_material<>;
using solver_type = gimlet::solver<S, gimlet::shape::ugimp, hmx, gimlet::contact::distance, gimlet::field_list<>,
                                   gimlet::multi_field::self_contact>;

constexpr double cell = 0.25e-3;                      // m
constexpr double slot_length = 30e-3, gap = 0.5e-3;   // m, the slot at the block's centre
constexpr double band = 1e-3;                         // m: the readings take |x| < band (the slot's middle)
constexpr double temperature0 = 300.0;                // K, hmx_constants' T0

// The examples' viscosity (examples/common/hmx_defaults.hpp): twice Abaqus/Explicit's, b1 = 0.12,
// b2 = 2.4 (viscosity::bulk takes b2 first).
gimlet::viscosity::bulk viscosity() { return gimlet::viscosity::bulk(2.4, 0.12); }

// A block of HMX 40 mm wide (periodic along x) and `height` tall with a slot 30 x 0.5 mm at its
// centre, whose ends are joined to the block; the material above the slot moves at -dv/2 along
// y, below it at +dv/2, so the slot closes at dv. The examples' settings: 0.25 mm cells, 2 x 2
// particles per cell, four consistent-mass iterations, the viscosity above, FLIP (PIC blend 0),
// the distance contact, the default Courant number. The grid has 4 mm of room above and below,
// and a node on the plane where the faces meet (y = 0) and on each face.
solver_type closing_slot(double dv, double height, gimlet::update_scheme scheme) {
    const double width = 40e-3, margin = 4e-3;
    gimlet::grid_spec<S> gs;
    gs.lower = vec(-width / 2, -height / 2 - margin);
    gs.upper = vec(width / 2, height / 2 + margin);
    gs.cell = cell;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
    gimlet::scene::scene<S, hmx> sc(gs);
    using box = gimlet::scene::box<S>;
    sc.add_body(gimlet::scene::difference(box(vec(-width / 2, -height / 2), vec(width / 2, height / 2)),
                                          box(vec(-slot_length / 2, -gap / 2), vec(slot_length / 2, gap / 2))),
                gimlet::presets::make_hmx({}, viscosity()), vec::Zero(), 2, "slotted block");
    gimlet::solver_options<S> opt;
    opt.threads = 1;
    opt.scheme = scheme;
    opt.pic_fraction = 0;
    opt.consistent_mass_iterations = 4;
    solver_type sol(sc, opt);
    auto& ps = sol.particles();
    auto& v = ps.column<gimlet::fields::velocity>();
    const auto& x = ps.column<gimlet::fields::position>();
    for (std::size_t i = 0; i < ps.size(); ++i) v[i] = vec(0, x[i][1] < 0 ? dv / 2 : -dv / 2);
    return sol;
}

// Runs to `t` (s) as the examples do (run_until: the solver's own steps, so the contact's step
// acts, solver_options::contact_closure), keeping the largest number of split nodes met.
void advance_to(solver_type& sol, double t, std::size_t& split) {
    auto watch = gimlet::diagnostics::every_steps(1, [&](const auto& s) { split = std::max(split, s.partition().split_nodes()); });
    sol.run_until(t, watch);
}

// The wall layers: the slot's middle particles (initial |x| < band), binned by their initial
// distance from their face, d = |y0| - gap / 2, into cell-thick layers (two particle rows) on
// each side; each layer's mass-weighted mean T - T0 (K), the rise above T0. layers[side][k]:
// side 0 below the slot, 1 above; k = 0 at the face.
struct wall_layers {
    static constexpr int count = 6;
    double rise[2][count] = {};
    // The hottest of the three layers nearest the landing plane on either side (the material the
    // 1-D reference's first three cells hold).
    [[nodiscard]] double hottest() const {
        double most = -1e300;
        for (const auto& side : rise) most = std::max({most, side[0], side[1], side[2]});
        return most;
    }
};

wall_layers read_layers(const solver_type& sol, const std::vector<vec>& initial) {
    const auto& ps = sol.particles();
    double mass[2][wall_layers::count] = {}, heat[2][wall_layers::count] = {};
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const vec& x0 = initial[i];
        if (std::abs(x0[0]) >= band) continue;
        const auto k = static_cast<int>(std::floor((std::abs(x0[1]) - gap / 2) / cell));
        if (k < 0 || k >= wall_layers::count) continue;
        const int side = x0[1] > 0;
        const double m = ps[i].get<gimlet::fields::mass>();
        mass[side][k] += m;
        heat[side][k] += m * (ps[i].get<gimlet::fields::temperature>() - temperature0);
    }
    wall_layers w;
    for (int side = 0; side < 2; ++side)
        for (int k = 0; k < wall_layers::count; ++k) w.rise[side][k] = heat[side][k] / mass[side][k];
    return w;
}

// The plateau's sigma_yy (Pa, compression positive): the mean over the slot's middle particles
// (current |x| < band) from 3 cells off the landing plane (y = 0) to half-way to the shock front,
// on each side. The front on a side is the farthest of those particles from the plane whose
// sigma_yy reaches half the Rankine-Hugoniot value (the precursor's, if any, plus the plateau's,
// halved, as impact_1d reads it).
struct plateau_reading {
    double sigma_yy = 0;
    double front[2] = {0, 0};  // m from the plane, below and above
    int particles = 0;
};

plateau_reading read_plateau(const solver_type& sol, const example::hugoniot_state& rh) {
    const auto& ps = sol.particles();
    const double threshold = 0.5 * (rh.precursor_sigma + rh.sigma_yy);
    auto sigma_yy = [&](std::size_t i) { return -double(ps[i].get<gimlet::fields::stress>()(1, 1)); };
    auto middle = [&](std::size_t i) { return std::abs(double(ps[i].get<gimlet::fields::position>()[0])) < band; };
    auto y_of = [&](std::size_t i) { return double(ps[i].get<gimlet::fields::position>()[1]); };
    plateau_reading r;
    for (std::size_t i = 0; i < ps.size(); ++i)
        if (middle(i) && sigma_yy(i) >= threshold) {
            const int side = y_of(i) > 0;
            r.front[side] = std::max(r.front[side], std::abs(y_of(i)));
        }
    double sum = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        if (!middle(i)) continue;
        const double d = std::abs(y_of(i));
        if (d >= 3 * cell && d <= 0.5 * r.front[y_of(i) > 0]) sum += sigma_yy(i), ++r.particles;
    }
    r.sigma_yy = sum / r.particles;
    return r;
}

// The 1-D Lagrangian reference: two 20 mm slabs at +-dv/2 on 0.25 mm cells, with the von Mises
// strength and the library's bulk viscosity at the MPM's coefficients; every cell's state at
// `after` (s) after impact.
lagrangian_1d::profile reference(double dv, double after) {
    lagrangian_1d::settings s;
    s.velocity = dv / 2;
    s.length = 20e-3;
    s.cells = static_cast<int>(std::lround(s.length / cell));
    s.strength = true;
    s.bulk = viscosity();
    std::vector<lagrangian_1d::profile> out;
    lagrangian_1d::run(s, {after}, {}, &out);
    return out.front();
}

const char* name(gimlet::update_scheme scheme) { return scheme == gimlet::update_scheme::usf ? "USF" : "MUSL"; }

struct slot_run {
    wall_layers layers;           // at 1 us after the faces meet
    plateau_reading early;        // at 1 us after
    plateau_reading plateau;      // at 2 us after
    std::size_t split = 0;        // the largest number of split nodes
    std::uint64_t health = 0;     // the silent guards that acted
};

// Runs the slot closing at dv on a block `height` tall: the wall layers and the plateau at 1 us
// after the faces meet, the plateau again at 2 us.
slot_run run_slot(double dv, double height, gimlet::update_scheme scheme) {
    auto sol = closing_slot(dv, height, scheme);
    const auto& x = sol.particles().column<gimlet::fields::position>();
    std::vector<vec> initial;
    for (std::size_t i = 0; i < sol.particles().size(); ++i) initial.push_back(x[i]);
    const double meet = gap / dv;
    slot_run r;
    const auto rh = example::rankine_hugoniot(gimlet::presets::make_hmx(), dv / 2);
    advance_to(sol, meet + 1e-6, r.split);
    r.layers = read_layers(sol, initial);
    r.early = read_plateau(sol, rh);
    advance_to(sol, meet + 2e-6, r.split);
    r.plateau = read_plateau(sol, rh);
    r.health = sol.health().total();
    return r;
}

// Prints the wall layers against the reference's first cells; returns the ratio of the rises.
double report_layers(const char* scheme, double dv, const wall_layers& w, const lagrangian_1d::profile& ref) {
    const double mpm = w.hottest(), first = ref.heating[0];
    std::printf("slot %s, %.0f m/s, 1 us after the faces meet: layer T - T0 by initial distance from the face "
                "(cells 1-6), below %.1f %.1f %.1f %.1f %.1f %.1f K, above %.1f %.1f %.1f %.1f %.1f %.1f K\n",
                scheme, dv, w.rise[0][0], w.rise[0][1], w.rise[0][2], w.rise[0][3], w.rise[0][4], w.rise[0][5],
                w.rise[1][0], w.rise[1][1], w.rise[1][2], w.rise[1][3], w.rise[1][4], w.rise[1][5]);
    std::printf("slot %s, %.0f m/s: hottest wall layer T - T0 %.1f K against the 1-D reference's first cell %.1f K "
                "(cells 2, 3: %.1f, %.1f K): ratio of the rises %.3f, of T %.3f\n",
                scheme, dv, mpm, first, ref.heating[1], ref.heating[2], mpm / first,
                (temperature0 + mpm) / (temperature0 + first));
    return mpm / first;
}

double report_plateau(const char* scheme, double dv, double height, const slot_run& r) {
    const auto rh = example::rankine_hugoniot(gimlet::presets::make_hmx(), dv / 2);
    const double error = r.plateau.sigma_yy / rh.sigma_yy - 1;
    std::printf("slot %s, %.0f m/s, %.0f mm block, 2 us after the faces meet: plateau sigma_yy %.4f GPa (%d particles, "
                "fronts %.2f / %.2f mm) against Rankine-Hugoniot %.4f GPa: %+.3f %% (1 us after: %+.3f %%); largest "
                "split nodes %zu, guards %llu\n",
                scheme, dv, height * 1e3, r.plateau.sigma_yy / 1e9, r.plateau.particles, r.plateau.front[0] * 1e3,
                r.plateau.front[1] * 1e3, rh.sigma_yy / 1e9, 100 * error, 100 * (r.early.sigma_yy / rh.sigma_yy - 1),
                r.split, static_cast<unsigned long long>(r.health));
    return error;
}

}  // namespace

// The reference holds the Rankine-Hugoniot state that the MPM plateau is compared with: with the
// strength and the library's viscosity its plateau (cells 3 off the wall to half-way to the
// front, 2 us after impact) reads sigma_yy within 0.25 % of it. Measured: -0.09 % at +-500 m/s,
// -0.02 % at +-1500 m/s.
TEST_CASE("1-D Lagrangian reference with the von Mises strength and the library's viscosity: its plateau at "
          "the elastic-plastic Rankine-Hugoniot sigma_yy",
          "[multi_field][self_contact]") {
    for (const double dv : {1000.0, 3000.0}) {
        const auto rh = example::rankine_hugoniot(gimlet::presets::make_hmx(), dv / 2);
        const auto ref = reference(dv, 2e-6);
        const double threshold = 0.5 * (rh.precursor_sigma + rh.sigma_yy);
        std::size_t front = 0;
        for (std::size_t k = 0; k < ref.sigma_yy.size(); ++k)
            if (ref.sigma_yy[k] >= threshold) front = k;
        double sigma = 0, rise = 0;
        std::size_t n = 0;
        for (std::size_t k = 3; 2 * k <= front; ++k) sigma += ref.sigma_yy[k], rise += ref.heating[k], ++n;
        sigma /= double(n);
        rise /= double(n);
        const double rh_rise = example::hugoniot_temperature(rh) - temperature0;
        std::printf("1-D reference, %.0f m/s, 2 us: plateau (cells 3 to %zu) sigma_yy %.4f GPa against Rankine-Hugoniot "
                    "%.4f GPa: %+.3f %%; T - T0 %.1f K against %.1f K; first cells' T - T0 %.1f, %.1f, %.1f K\n",
                    dv, front / 2, sigma / 1e9, rh.sigma_yy / 1e9, 100 * (sigma / rh.sigma_yy - 1), rise, rh_rise,
                    ref.heating[0], ref.heating[1], ref.heating[2]);
        CHECK(n >= 4);
        CHECK(std::abs(sigma / rh.sigma_yy - 1) <= 2.5e-3);
    }
}

namespace {

// The slot closing at dv on a block `height` tall under USF and MUSL: the faces land in separate
// fields; the wall layer against the reference's first cell and the plateau's sigma_yy against
// Rankine-Hugoniot are printed, and where `asserted`, held to 1.15 times and 1 %.
void slot_under_both_schemes(double dv, double height, bool asserted) {
    const auto ref = reference(dv, 1e-6);
    for (const auto scheme : {gimlet::update_scheme::usf, gimlet::update_scheme::musl}) {
        const auto r = run_slot(dv, height, scheme);
        const double ratio = report_layers(name(scheme), dv, r.layers, ref);
        const double error = report_plateau(name(scheme), dv, height, r);
        CHECK(r.split > 0);  // the faces met in separate fields
        if (asserted) {
            CHECK(ratio <= 1.15);
            CHECK(std::abs(error) <= 0.01);
        }
    }
}

}  // namespace

// Measured (0.25 mm cells, 1 us after the faces meet for the layers, 2 us for the plateau): the
// hottest wall layer 115.1 K (USF) and 109.1 K (MUSL) above T0 against the reference's first cell
// 130.5 K (its second and third cells 82.7 and 76.5 K): 0.882 and 0.836 times; sigma_yy +0.29 %
// (USF) and -0.33 % (MUSL) of Rankine-Hugoniot's 3.863 GPa, as two slabs meeting across the whole
// width read (+0.31 and -0.34 %): the slot's ends do not reach the plateau by then.
TEST_CASE("slot closing in one block at 1000 m/s, USF and MUSL: the wall layer within 1.15 times the 1-D "
          "reference's first cell, the plateau's sigma_yy within 1 % of Rankine-Hugoniot",
          "[multi_field][self_contact][long]") {
    slot_under_both_schemes(1000, 20e-3, true);
}

// At 3000 m/s the faces land in separate fields; the wall layer and the plateau are printed, not
// asserted. Measured: the hottest wall layer 1076 K (USF) and 985 K (MUSL) above T0 against the
// reference's first cell 1225 K (0.878 and 0.804 times); sigma_yy +7.6 % (USF) and +7.5 % (MUSL)
// of Rankine-Hugoniot's 18.94 GPa at 2 us (+1.9 and +1.0 % at 1 us), where 1 % is the
// criterion. Two causes:
// - the waves from the slot's ends, 15 mm from its middle, reach the plateau between 1 and
//   1.5 us after the faces meet (a 70 mm slot in an 80 mm block reads +2.9 % at 2 us under USF);
// - the MPM plateau itself at these settings: two slabs meeting across the whole width (no slot
//   ends) read +2.8 % (USF) and +2.0 % (MUSL) at 2 us, where the 1-D reference reads -0.02 %.
TEST_CASE("slot closing in one block at 3000 m/s on a 40 mm block, USF and MUSL: the faces land in separate "
          "fields, the wall layer and the plateau's sigma_yy printed against their references",
          "[multi_field][self_contact][long]") {
    slot_under_both_schemes(3000, 40e-3, false);
}
