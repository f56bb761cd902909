// SPDX-License-Identifier: MIT
#pragma once
// The reference paper's contact validation run (its section 3, docs/physics.md section 8): two HMX
// blocks 40 mm x 50 mm, one above the other with a 4 mm gap, no cavity, each moving towards the
// other at v; periodic in x, free in y. Pressure along the vertical centre line at a given time,
// for each contact policy. Shared by the example and its test.

#include <gimlet/gimlet.hpp>

#include "common/processes.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace contact_validation {

using S = gimlet::space<2>;
using material = gimlet::presets::hmx_material<>;

struct settings {
    double velocity = 300.0;  // m/s, each block
    double cell = 0.5e-3;     // m
    double time = 14e-6;      // s
    int threads = 0;
    // The library's defaults here (the tests build on them); the example's command line runs the
    // HMX examples' pair, four consistent-mass iterations with (0.12, 2.4) (docs/equations.md,
    // "The examples' defaults").
    int consistent_mass = 0;           // solver_options::consistent_mass_iterations
    double viscosity_linear = 0.06;    // viscosity::bulk's b1
    double viscosity_quadratic = 1.2;  // viscosity::bulk's b2
    double cfl = gimlet::solver_options<gimlet::space<2>>{}.cfl;  // solver_options::cfl
    // On many processes: each run's processes (solver_options::processes; one object a solver),
    // taken where the example is built with MPI (example::solver is then a distributed_solver).
    std::function<std::shared_ptr<gimlet::processes>()> processes;
};

constexpr double width = 40e-3, height = 50e-3, gap = 4e-3;

struct result {
    std::string policy;
    std::vector<std::pair<double, double>> profile;  // (y - interface (m), pressure (Pa)) of the centre-line particles
    std::vector<std::pair<double, double>> cells;    // the same, averaged per grid cell (cell centre, mean)
    double interface_peak = 0;  // Pa: largest cell-averaged pressure within two cells of the interface
    double plateau = 0;         // Pa: mean pressure of the shocked region away from the interface
    double peak_over_plateau = 0;
    double particle_peak_over_plateau = 0;  // the same with the largest single-particle pressure
    double interface_y = 0;     // m: the interface (the centre of the gap; the impact is symmetric)
    double max_eta = 0;         // the largest particle compression 1 - det F at the end
    gimlet::health_events health;  // the silent guards that acted (solver::health)
};

// The particle profile averaged per grid cell. The two particle rows of a cell oscillate
// against each other in a shocked plateau (about +-10 % here: a sub-cell mode the grid does not
// see), so the cell mean is the resolved pressure; a contact spike spans whole cells and stays.
inline std::vector<std::pair<double, double>> cell_means(const std::vector<std::pair<double, double>>& prof,
                                                         double h) {
    std::vector<std::pair<double, double>> out;
    std::size_t i = 0;
    while (i < prof.size()) {
        const double k = std::floor(prof[i].first / h);
        double sum = 0;
        std::size_t n = 0;
        for (; i < prof.size() && std::floor(prof[i].first / h) == k; ++i) sum += prof[i].second, ++n;
        out.emplace_back((k + 0.5) * h, sum / double(n));
    }
    return out;
}

inline gimlet::scene::scene<S, material> make_scene(const settings& s) {
    gimlet::require(std::isfinite(s.velocity) && s.velocity > 0 && s.velocity <= 1000, "velocity (m/s)", s.velocity,
                    "(0, 1000]");
    gimlet::require(std::isfinite(s.cell) && s.cell > 0 && s.cell <= 4e-3, "cell size (m)", s.cell, "(0, 4e-3]");
    gimlet::require(std::isfinite(s.time) && s.time > 0 && s.time <= 40e-6, "time (s)", s.time, "(0, 40e-6]");
    const double cells_x = width / s.cell;
    gimlet::require(std::abs(cells_x - std::round(cells_x)) < 1e-9 * cells_x && std::fmod(gap / s.cell, 1.0) < 1e-9,
                    "cell size (m)", s.cell, "a divisor of the block width 40 mm and the gap 4 mm");
    gimlet::grid_spec<S> gs;
    const double margin = 10e-3;  // room for the free ends to move
    gs.lower = S::vector(0.0, -margin);
    gs.upper = S::vector(width, 2 * height + gap + margin);
    gs.cell = s.cell;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
    gimlet::scene::scene<S, material> scene(gs);
    const auto hmx =
        gimlet::presets::make_hmx({}, gimlet::viscosity::bulk(s.viscosity_quadratic, s.viscosity_linear));
    scene.add_body(gimlet::scene::box<S>(S::vector(0.0, 0.0), S::vector(width, height)), hmx,
                   S::vector(0.0, s.velocity), 2, "lower block");
    scene.add_body(gimlet::scene::box<S>(S::vector(0.0, height + gap), S::vector(width, 2 * height + gap)), hmx,
                   S::vector(0.0, -s.velocity), 2, "upper block");
    return scene;
}

// Runs one policy. The centre line is the particle column nearest x = width / 2; the
// interface peak is the largest cell-averaged pressure within two cells of the interface. The plateau
// is the mean pressure between 4 cells from the interface and half-way to the shock front
// (where the pressure first falls below half the mean of the 4-8 cell band), on both sides.
template <class Contact>
result run(const settings& s, const std::string& name, const Contact& contact = Contact{}) {
    gimlet::solver_options<S> opt;
    opt.threads = s.threads;
    opt.consistent_mass_iterations = s.consistent_mass;
    opt.cfl = s.cfl;
    if (s.processes) opt.processes = s.processes();
    example::solver<S, gimlet::shape::ugimp, material, Contact> sol(make_scene(s), opt, contact);
    sol.run_until(s.time);
    result r;
    r.policy = name;
    r.interface_y = height + 0.5 * gap;
    const double quarter = 0.25 * s.cell;  // 2x2 particles per cell sit at quarter-cells
    const double centre = 0.5 * width - quarter;
    auto on_line = [&](const auto& p) {
        return std::abs(p.template get<gimlet::fields::position>()[0] - centre) < quarter;
    };
    auto pressure = [](const auto& p) { return gimlet::mean_pressure(p); };
    r.profile = gimlet::diagnostics::profile(sol, 1, pressure, on_line);
    for (auto& [y, pres] : r.profile) y -= r.interface_y;
    const double h = s.cell;
    r.cells = cell_means(r.profile, h);  // the interface lies on a grid line, so cells do not straddle it
    double particle_peak = 0;
    for (const auto& [y, pres] : r.profile)
        if (std::abs(y) <= 2 * h) particle_peak = std::max(particle_peak, pres);
    for (const auto& [y, pres] : r.cells)
        if (std::abs(y) <= 2 * h) r.interface_peak = std::max(r.interface_peak, pres);
    // Both sides folded onto the distance from the interface.
    std::vector<std::pair<double, double>> folded;
    for (const auto& [y, pres] : r.profile) folded.emplace_back(std::abs(y), pres);
    std::sort(folded.begin(), folded.end());
    const double band = gimlet::diagnostics::mean_between(folded, 4 * h, 8 * h);
    const double front = gimlet::diagnostics::front_position(folded, 0.5 * band, 0.0, height);
    r.plateau = gimlet::diagnostics::mean_between(folded, 4 * h, std::max(8 * h, 0.5 * front));
    r.peak_over_plateau = r.interface_peak / r.plateau;
    r.particle_peak_over_plateau = particle_peak / r.plateau;
    for (const auto& f : sol.particles().template column<gimlet::fields::deformation_gradient>())
        r.max_eta = std::max(r.max_eta, 1.0 - double(f.determinant()));
    if (gimlet::processes* many = sol.processes()) r.max_eta = many->max(r.max_eta);  // exact: a maximum
    r.health = sol.health();
    return r;
}

}  // namespace contact_validation
