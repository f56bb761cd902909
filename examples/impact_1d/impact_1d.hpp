// SPDX-License-Identifier: MIT
#pragma once
// The scene of the impact_1d example, its measurements, and the elastic-plastic
// Rankine-Hugoniot state they are compared with. Shared by the example and its test.
//
// Two HMX slabs in uniaxial strain (a narrow strip, periodic across it) hit each other
// symmetrically at +-v along y: the interface stays at rest and a compressive wave runs into
// each slab. Below about 210 m/s an elastic precursor runs ahead of the plastic shock.

#include "common/hugoniot.hpp"

#include <gimlet/gimlet.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace impact_1d {

using S = gimlet::space<2>;
using material = gimlet::presets::hmx_material<>;
template <class M = material, class C = gimlet::contact::single_field>
using solver_for = gimlet::solver<S, gimlet::shape::ugimp, M, C>;
using solver = solver_for<>;

struct settings {
    double velocity = 300.0;   // m/s, each slab
    double cell = 0.1e-3;      // m
    double length = 20e-3;     // m, each slab
    double end_time = 3e-6;    // s
    gimlet::update_scheme scheme = gimlet::update_scheme::usf;
    bool volumetric_average = false;  // solver_options::volumetric_average
    double pic_fraction = 0;   // solver_options::pic_fraction (the damping transfer's blend)
    int consistent_mass = 0;   // solver_options::consistent_mass_iterations (0: the lumped mass)
    bool volume_filter = false;// solver_options::volume_filter (needs consistent_mass >= 1)
    double cfl = gimlet::solver_options<gimlet::space<2>>{}.cfl;  // solver_options::cfl, the Courant number
    double margin = 0;         // m of empty grid beyond each free end (0: 10 cells); room to fly off
    int threads = 0;
};

// ---- the Rankine-Hugoniot state (examples/common/hugoniot.hpp) ---------------------------

using example::hugoniot_state;
using example::hugoniot_temperature;
using example::model_sigma;
using example::rankine_hugoniot;
using example::solve_shock;
using example::uniaxial_plastic_heat;

// ---- the scene and the measurements --------------------------------------------------------

template <class M = material, class C = gimlet::contact::single_field>
solver_for<M, C> make_solver(const settings& s, const M& mat = gimlet::presets::make_hmx()) {
    gimlet::require(std::isfinite(s.velocity) && s.velocity > 0 && s.velocity <= 1000, "velocity (m/s)", s.velocity,
                    "(0, 1000]");
    gimlet::require(std::isfinite(s.cell) && s.cell > 0 && s.cell <= 1e-3, "cell size (m)", s.cell, "(0, 1e-3]");
    const double width = 4 * s.cell;  // periodic strip, the uGIMP stencil wide
    gimlet::grid_spec<S> gs;
    const double margin = s.margin > 0 ? s.margin : 10 * s.cell;
    gs.lower = S::vector(0.0, -s.length - margin);
    gs.upper = S::vector(width, s.length + margin);
    gs.cell = s.cell;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
    gimlet::scene::scene<S, M> scene(gs);
    scene.add_body(gimlet::scene::box<S>(S::vector(0.0, 0.0), S::vector(width, s.length)), mat,
                   S::vector(0.0, -s.velocity), 2, "upper slab");
    scene.add_body(gimlet::scene::box<S>(S::vector(0.0, -s.length), S::vector(width, 0.0)), mat,
                   S::vector(0.0, s.velocity), 2, "lower slab");
    gimlet::solver_options<S> opt;
    opt.scheme = s.scheme;
    opt.threads = s.threads;
    opt.volumetric_average = s.volumetric_average;
    opt.pic_fraction = s.pic_fraction;
    opt.consistent_mass_iterations = s.consistent_mass;
    opt.cfl = s.cfl;
    opt.volume_filter = s.volume_filter;
    return solver_for<M, C>(scene, opt);
}

// The leading edge of a wave running towards larger coordinates: the largest coordinate in
// [lo, hi] where the profile reaches `level`, interpolated linearly to the next larger coordinate
// (particles at one coordinate are averaged); lo if none reaches it.
inline double leading_crossing(const std::vector<std::pair<double, double>>& prof, double level, double lo, double hi) {
    struct row {
        double x, sum;
        int count;
    };
    std::vector<row> rows;  // increasing coordinate
    for (const auto& [x, v] : prof) {
        if (x < lo || x > hi) continue;
        if (!rows.empty() && x - rows.back().x <= 1e-12 * (1.0 + std::abs(x))) rows.back().sum += v, ++rows.back().count;
        else rows.push_back({x, v, 1});
    }
    auto mean = [&](std::size_t k) { return rows[k].sum / rows[k].count; };
    for (std::size_t k = rows.size(); k-- > 0;) {
        if (mean(k) < level) continue;
        if (k + 1 == rows.size()) return rows[k].x;
        return rows[k].x + (rows[k + 1].x - rows[k].x) * (mean(k) - level) / (mean(k) - mean(k + 1));
    }
    return lo;
}

struct result {
    hugoniot_state rh;              // what the jump conditions predict, for the paper's HMX (make_hmx()) whatever the run's material
    double rh_temperature = 0;      // K, hugoniot_temperature(rh)
    double rh_plastic_heat = 0;     // K, uniaxial_plastic_heat(rh)
    double plateau_sigma_yy = 0;    // Pa, compression positive
    double plateau_pressure = 0;    // Pa
    double plateau_eta = 0;         // mean 1 - J over the plateau
    double plateau_plastic_heat = 0;// K, mean plastic work / c_v over the plateau
    double front_peak_eta = 0;      // largest 1 - J between the plateau and the front
    double front_peak_eta_layers = 0;  // the same over cell-thick layers at rest: the largest layer mean of 1 - J
    double row_alternation = 0;     // the plateau's particle rows' alternation in 1 - J, relative to its mean
    double rise_cells = 0;          // 10-90 % rise of sigma_yy at the front, in cells
    gimlet::health_events health;   // the silent guards that acted (solver::health)
    double shock_speed = 0;         // m/s, relative to the material ahead of it
    double energy_error = 0;        // (E - E0) / E0, E = kinetic + internal (incl. heat)
    double max_temperature = 0;     // K
    double plateau_temperature = 0; // K
    double min_det_f = 1;
    bool all_finite = true;
    std::vector<double> times, fronts;  // (s, m): the plastic front in the upper slab
};

// Runs the scene to s.end_time. The plateau is the mean over the upper slab between 10 cells
// from the interface and half-way to the plastic front at the end; the front is where
// sigma_yy first exceeds the mid-point between the precursor (0 for a single wave) and the
// predicted plateau; its speed is a least-squares fit over the second half of the run, plus
// the velocity of the material ahead of it.
template <class M = material, class C = gimlet::contact::single_field>
result run(const settings& s, const M& mat = gimlet::presets::make_hmx()) {
    auto sol = make_solver<M, C>(s, mat);
    result r;
    r.rh = rankine_hugoniot(gimlet::presets::make_hmx(), s.velocity);
    r.rh_temperature = hugoniot_temperature(r.rh);
    r.rh_plastic_heat = uniaxial_plastic_heat(r.rh);
    const double e0 = gimlet::diagnostics::kinetic_energy(sol) + gimlet::diagnostics::internal_energy(sol);
    const double threshold = 0.5 * (r.rh.precursor_sigma + r.rh.sigma_yy);
    auto sigma_yy = [](const auto& p) { return -p.template get<gimlet::fields::stress>()(1, 1); };
    auto upper = [](const auto& p) { return p.template get<gimlet::fields::body>() == 0u; };
    const int samples = 20;
    for (int k = 1; k <= samples; ++k) {
        const double t = s.end_time * k / samples;
        sol.run_until(t);
        if (2 * k >= samples) {
            const auto prof = gimlet::diagnostics::profile(sol, 1, sigma_yy, upper);
            r.times.push_back(t);
            r.fronts.push_back(gimlet::diagnostics::front_position(prof, threshold, 0.0, s.length));
        }
    }
    const auto& ps = sol.particles();
    const double front = r.fronts.back();
    const double lo = 10 * s.cell, hi = 0.5 * front;
    using store = typename solver_for<M, C>::store_type;
    double n = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const auto p = ps[i];
        const double y = p.template get<gimlet::fields::position>()[1];
        const double j = p.template get<gimlet::fields::deformation_gradient>().determinant();
        r.min_det_f = std::min(r.min_det_f, j);
        r.all_finite = r.all_finite && p.template get<gimlet::fields::stress>().allFinite() && std::isfinite(j);
        if constexpr (store::template has<gimlet::fields::temperature>)
            r.max_temperature = std::max(r.max_temperature, double(p.template get<gimlet::fields::temperature>()));
        if (upper(p) && y > hi) r.front_peak_eta = std::max(r.front_peak_eta, 1.0 - j);
        if (upper(p) && y >= lo && y <= hi) {
            r.plateau_sigma_yy += sigma_yy(p);
            r.plateau_pressure += gimlet::mean_pressure(p);
            r.plateau_eta += 1.0 - j;
            if constexpr (store::template has<gimlet::fields::temperature>)
                r.plateau_temperature += p.template get<gimlet::fields::temperature>();
            if constexpr (store::template has<gimlet::fields::plastic_work>)
                r.plateau_plastic_heat += p.template get<gimlet::fields::plastic_work>() /
                                          gimlet::presets::hmx_constants{}.specific_heat;
            n += 1;
        }
    }
    // The front peak read on single particles (above; the test's reading) and on the material
    // of one cell at rest, as a Lagrangian hydrocode's zone holds it: the upper slab's particles
    // past `hi`, in order of y, taken a layer at a time (its particles per cell-thick layer),
    // each layer's mean 1 - J. The particle rows alternate in J all through the plateau
    // (docs/equations.md); a layer holds two rows.
    {
        const auto eta = gimlet::diagnostics::profile(
            sol, 1, [](const auto& p) { return 1.0 - p.template get<gimlet::fields::deformation_gradient>().determinant(); },
            upper);
        const auto per_layer = static_cast<std::size_t>(std::llround(double(eta.size()) * s.cell / s.length));
        std::size_t k = 0;
        while (k < eta.size() && eta[k].first <= hi) ++k;
        for (; per_layer > 0 && k + per_layer <= eta.size(); k += per_layer) {
            double sum = 0;
            for (std::size_t q = k; q < k + per_layer; ++q) sum += eta[q].second;
            r.front_peak_eta_layers = std::max(r.front_peak_eta_layers, sum / double(per_layer));
        }
        // The rows' alternation over the plateau: with rows of means eta_k = eta + a (-1)^k,
        // eta_k - (eta_{k-1} + eta_{k+1}) / 2 = 2 a (-1)^k, so a is half the mean of its size
        // over the inner rows (a layer holds two rows, of per_layer / 2 particles each).
        const std::size_t per_row = per_layer / 2;
        std::vector<double> rows;
        std::size_t q = 0;
        while (q < eta.size() && eta[q].first < lo) ++q;
        for (; per_row > 0 && q + per_row <= eta.size() && eta[q + per_row - 1].first <= hi; q += per_row) {
            double sum = 0;
            for (std::size_t u = q; u < q + per_row; ++u) sum += eta[u].second;
            rows.push_back(sum / double(per_row));
        }
        double swing = 0;
        for (std::size_t k = 1; k + 1 < rows.size(); ++k) swing += std::abs(rows[k] - 0.5 * (rows[k - 1] + rows[k + 1]));
        if (rows.size() > 2) r.row_alternation = 0.5 * swing / double(rows.size() - 2);
    }
    r.plateau_sigma_yy /= n;
    r.plateau_pressure /= n;
    r.plateau_eta /= n;
    r.plateau_temperature /= n;
    r.plateau_plastic_heat /= n;
    r.row_alternation /= r.plateau_eta;
    // The front's 10-90 % rise, from the level ahead of it (the precursor's, or 0) to the plateau.
    {
        const auto prof = gimlet::diagnostics::profile(sol, 1, sigma_yy, upper);
        const double ahead = r.rh.precursor_sigma, jump = r.plateau_sigma_yy - ahead;
        const double y10 = leading_crossing(prof, ahead + 0.1 * jump, hi, s.length);
        const double y90 = leading_crossing(prof, ahead + 0.9 * jump, hi, s.length);
        r.rise_cells = (y10 - y90) / s.cell;
    }
    // Least-squares slope of front(t): the lab-frame speed of the plastic front.
    double st = 0, sf = 0, stt = 0, stf = 0;
    const double m = double(r.times.size());
    for (std::size_t i = 0; i < r.times.size(); ++i) {
        st += r.times[i], sf += r.fronts[i], stt += r.times[i] * r.times[i], stf += r.times[i] * r.fronts[i];
    }
    const double lab = (m * stf - st * sf) / (m * stt - st * st);
    // The material ahead of the plastic front moves at -(v - v_precursor) towards it.
    r.shock_speed = lab + (s.velocity - r.rh.precursor_velocity);
    r.health = sol.health();
    const double e1 = gimlet::diagnostics::kinetic_energy(sol) + gimlet::diagnostics::internal_energy(sol);
    r.energy_error = (e1 - e0) / e0;
    return r;
}

}  // namespace impact_1d
