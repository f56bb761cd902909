// SPDX-License-Identifier: MIT
// Throughput in particle-updates per second (particles x steps / wall seconds, the median of
// repeated runs) of one scene:
//   --scene reference  two linear-elastic blocks 40 mm x 50 mm, 4 mm apart, +-300 m/s, uGIMP,
//                      single field (bench::two_blocks; at --cell 0.5: 64,000 particles)
//   --scene hmx        the same blocks in the paper's HMX (von Mises + Mie-Grueneisen + viscosity
//                      + heating) with the distance-switched contact, touching from the start
//                      so every timed step resolves contact, and the flagship's defaults:
//                      self-contact on (multi_field::self_contact; no void here, so what a
//                      user pays for having it), FLIP, no volumetric averaging, the examples'
//                      consistent mass (4 iterations) and bulk viscosity (b1, b2) = (0.12, 2.4)
//                      (examples/common/hmx_defaults.hpp)
// Flags: --cell MM (0.5), --steps N (1000 at 0.5 mm; scaled by particle count if omitted),
//        --repeats R (3), --threads T (2), --scheme musl|usl|usf (musl), --phases 1 (print
//        the share of each phase of the step, from solver::timings(), on stderr, and of
//        P2G's parts: the weights, the slabs and the rest),
//        --consistent-mass K (solver_options::consistent_mass_iterations, at most 5 at the
//        default Courant number; 0 for the reference scene and under USL, 4 for the hmx scene),
//        --volume-filter 1 (solver_options::volume_filter; the hmx scene only, with
//        --consistent-mass 1 or more).
// Prints one CSV row (header with --header 1).
#include "common/bench.hpp"
#include "common/hmx_defaults.hpp"

#include <cstdio>
#include <exception>

namespace {

struct row {
    std::size_t particles = 0;
    int steps = 0;
    std::vector<double> seconds;
    gimlet::step_timings phases;  // of the last repeat
};

template <class Solver>
row time_scene(const auto& make, double dt, int steps, int repeats) {
    row r;
    r.steps = steps;
    for (int k = 0; k < repeats; ++k) {
        Solver sol = make();
        r.particles = sol.particles().size();
        const auto t0 = std::chrono::steady_clock::now();
        for (int n = 0; n < steps; ++n) sol.step(dt);
        r.seconds.push_back(bench::seconds_since(t0));
        r.phases = sol.timings();
    }
    return r;
}

}  // namespace

int main(int argc, char** argv) try {
    bench::flags f(argc, argv);
    const std::string scene = f.text("scene", "reference");
    const double cell = 1e-3 * f.number("cell", 0.5);
    const int repeats = static_cast<int>(f.number("repeats", 3));
    const int threads = static_cast<int>(f.number("threads", 2));
    const std::string scheme = f.text("scheme", "musl");
    // The same particle-steps at every size (1000 steps at 64,000 particles), at least 20 steps.
    const double default_steps = std::max(20.0, std::round(1000.0 * (cell / 0.5e-3) * (cell / 0.5e-3)));
    const int steps = static_cast<int>(f.number("steps", std::min(1000.0, default_steps)));
    const bool header = f.number("header", 0) != 0;
    const bool phases = f.number("phases", 0) != 0;
    // USL refuses the consistent mass (solver_options), so the hmx scene under USL is lumped.
    const int consistent_mass = static_cast<int>(
        f.number("consistent-mass", scene == "hmx" && scheme != "usl" ? example::hmx_defaults::consistent_mass : 0));
    const bool volume_filter = f.number("volume-filter", 0) != 0;
    f.finish();

    gimlet::solver_options<bench::S2> opt;
    opt.threads = threads;
    opt.scheme = bench::parse_scheme(scheme);
    opt.consistent_mass_iterations = consistent_mass;
    opt.volume_filter = volume_filter;
    const double dt = bench::reference_dt(cell);
    row r;
    if (scene == "reference") {
        using solver = gimlet::solver<bench::S2, gimlet::shape::ugimp, gimlet::elastic_material>;
        r = time_scene<solver>([&] { return solver(bench::two_blocks(bench::reference_material(), cell, 4e-3), opt); },
                               dt, steps, repeats);
    } else if (scene == "hmx") {
        using material = gimlet::presets::hmx_material<>;
        using solver = gimlet::solver<bench::S2, gimlet::shape::ugimp, material, gimlet::contact::distance,
                                      gimlet::field_list<>, gimlet::multi_field::self_contact>;
        const auto hmx = gimlet::presets::make_hmx({}, gimlet::viscosity::bulk(example::hmx_defaults::viscosity_quadratic,
                                                                                 example::hmx_defaults::viscosity_linear));
        r = time_scene<solver>([&] { return solver(bench::two_blocks(hmx, cell, 0.0), opt); }, dt, steps, repeats);
    } else {
        throw std::invalid_argument("--scene must be reference or hmx");
    }
    const double med = bench::median(r.seconds);
    const double best = *std::min_element(r.seconds.begin(), r.seconds.end());
    if (header)
        std::printf("scene,scheme,cell_mm,particles,steps,threads,repeats,median_s,min_s,mups_median,mups_best,consistent_mass\n");
    const double updates = double(r.particles) * r.steps;
    std::printf("%s,%s,%g,%zu,%d,%d,%d,%.4f,%.4f,%.3f,%.3f,%d\n", scene.c_str(), scheme.c_str(), cell * 1e3, r.particles,
                r.steps, threads, repeats, med, best, updates / med * 1e-6, updates / best * 1e-6, consistent_mass);
    if (phases) {
        const auto& p = r.phases;
        const double t = p.total();
        std::fprintf(stderr, "phases (share of %.3f s): sort %.3f, P2G %.3f, grid %.3f, contact %.3f, G2P %.3f, material %.3f\n",
                     t, p.sort / t, p.particle_to_grid / t, p.grid_update / t, p.contact / t, p.grid_to_particle / t,
                     p.material_update / t);
        std::fprintf(stderr, "P2G's parts (share of the step): weights %.3f, slabs %.3f, the rest (clearing, scatters) %.3f\n",
                     p.weights / t, p.slabs / t, (p.particle_to_grid - p.weights - p.slabs) / t);
    }
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "bench_throughput: %s\n", e.what());
    return 1;
}
