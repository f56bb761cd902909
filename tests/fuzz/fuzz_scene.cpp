// SPDX-License-Identifier: MIT
// libFuzzer harness: a scene built from fuzzed parameters and run for a few steps. The grid
// (bounds, cell, boundaries), one to three HMX boxes (bounds, velocity, particles per cell,
// material constants), the contact (single field or distance), the update scheme and the solver
// options are each either drawn in a physical range or taken as any double (NaN, infinities,
// huge, negative): the library must refuse what is invalid by name, and run what is valid
// without a crash or a silent NaN (a step ends in a state of finite numbers, or in a named error).
//
// Limits, so that no input hangs (docs/robustness.md, "Fuzzing"): the harness skips scenes whose
// grid would have more than 4096 nodes or whose bodies more than 4096 particles (estimated from
// the parameters before anything is built), and runs at most 5 steps. The library itself
// refuses a grid whose node count its int node offsets cannot hold.
#include "fuzz_common.hpp"

#include <gimlet/gimlet.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using S = gimlet::space<2>;
using V = S::vector;
using hmx = gimlet::presets::hmx_material<>;
namespace f = gimlet::fields;

constexpr double max_nodes = 4096, max_particles = 4096;
constexpr int max_steps = 5;

struct body_params {
    V lower, upper, velocity;
    int ppc;
    gimlet::presets::hmx_constants c;
};

template <class Contact>
void run(const gimlet::scene::scene<S, hmx>& sc, const gimlet::solver_options<S>& opt) {
    gimlet::solver<S, gimlet::shape::ugimp, hmx, Contact> sol(sc, opt);
    for (int k = 0; k < max_steps; ++k) {
        sol.step();
        if (!fuzz::finite_state(sol)) fuzz::finding("step " + std::to_string(k) + " left a non-finite value without an error");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::bytes in(data, size);
    const std::uint32_t raw = in.u32();  // bit k: parameter k taken as any double
    int bit = 0;
    auto pick = [&](double lo, double hi) { return (raw >> (bit++ % 32)) & 1 ? in.f64() : in.in(lo, hi); };

    gimlet::grid_spec<S> gs;
    const double h = pick(1e-4, 1e-2);
    for (int d = 0; d < 2; ++d) {
        gs.lower[d] = pick(-0.05, 0.05);
        gs.upper[d] = (raw >> 31) & 1 ? in.f64() : gs.lower[d] + h * double(1 + in.u8() % 40);
    }
    gs.cell = h;
    for (int d = 0; d < 2; ++d) gs.bc[d] = static_cast<gimlet::boundary>(in.u8() % 5);
    // The harness's limit on the grid, from the parameters alone. A grid the library refuses
    // (non-finite, empty, not a whole number of cells) costs nothing and is left to it.
    const bool grid_valid = std::isfinite(h) && h > 0 && gs.lower.allFinite() && gs.upper.allFinite() &&
                            gs.upper[0] > gs.lower[0] && gs.upper[1] > gs.lower[1];
    double nodes = 1;
    for (int d = 0; d < 2; ++d) nodes *= (double(gs.upper[d]) - double(gs.lower[d])) / h + 7;
    if (grid_valid && !(nodes <= max_nodes)) return 0;

    std::vector<body_params> bodies(1 + in.u8() % 3);
    double particles = 0;
    for (auto& b : bodies) {
        for (int d = 0; d < 2; ++d) {
            const double span = double(gs.upper[d]) - double(gs.lower[d]);
            b.lower[d] = pick(gs.lower[d] - 0.1 * span, gs.upper[d]);
            b.upper[d] = pick(b.lower[d], gs.upper[d] + 0.1 * span);
            b.velocity[d] = pick(-3000, 3000);
        }
        b.ppc = in.u8() % 10;  // 0 and 9 are out of range
        b.c.density = pick(500, 20000);
        b.c.young = pick(1e6, 1e12);
        b.c.poisson = pick(0, 0.49);
        b.c.yield_stress = pick(1e5, 1e10);
        b.c.sound_speed = pick(500, 8000);
        b.c.slope = pick(1, 4);
        b.c.gruneisen = pick(0, 3);
        b.c.specific_heat = pick(100, 5000);
        b.c.hardening = pick(0, 1e9);
        // Particles inside the grid (the library refuses a body reaching outside it, and a
        // body with a non-finite bound).
        double count = 1;
        for (int d = 0; d < 2; ++d) {
            const double lo = b.lower[d], hi = b.upper[d];
            const double extent = std::isfinite(lo) && std::isfinite(hi)
                                      ? std::max(0.0, std::min(hi, double(gs.upper[d])) - std::max(lo, double(gs.lower[d])))
                                      : 0.0;
            count *= (extent / h + 1) * double(b.ppc);
        }
        particles += count;
    }
    if (grid_valid && !(particles <= max_particles)) return 0;

    gimlet::solver_options<S> opt;
    opt.threads = 1;
    opt.scheme = static_cast<gimlet::update_scheme>(in.u8() % 3);
    opt.cfl = pick(0.05, 1);
    opt.pic_fraction = pick(0, 1);
    opt.mass_cutoff = pick(0, 1e-6);
    opt.volumetric_average = in.u8() & 1;
    opt.body_force = V(pick(-1e6, 1e6), pick(-1e6, 1e6));
    const bool distance = in.u8() & 1;
    opt.light_particle_ratio = pick(0, 0.5);
    // Drawn last, so the committed corpus (shorter inputs) keeps the lumped mass (0).
    opt.consistent_mass_iterations = in.u8() % 4;
    opt.volume_filter = in.u8() & 1;  // after it, for the same reason (refused where k = 0)

    if (std::getenv("GIMLET_FUZZ_VERBOSE")) {  // to read a finding's parameters
        std::fprintf(stderr,
                     "grid [%a, %a] x [%a, %a], h %a, bc %d %d; scheme %d cfl %a pic %a cutoff %a light %a va %d cm %d vf %d b (%a, %a) %s\n",
                     gs.lower[0], gs.upper[0], gs.lower[1], gs.upper[1], h, int(gs.bc[0]), int(gs.bc[1]),
                     int(opt.scheme), opt.cfl, opt.pic_fraction, opt.mass_cutoff, opt.light_particle_ratio,
                     int(opt.volumetric_average), opt.consistent_mass_iterations, int(opt.volume_filter),
                     opt.body_force[0], opt.body_force[1], distance ? "distance" : "single");
        for (const auto& b : bodies)
            std::fprintf(stderr,
                         "  body [%a, %a] x [%a, %a] v (%a, %a) ppc %d rho %a E %a nu %a Y %a c0 %a s %a G %a cv %a H %a\n",
                         b.lower[0], b.upper[0], b.lower[1], b.upper[1], b.velocity[0], b.velocity[1], b.ppc,
                         b.c.density, b.c.young, b.c.poisson, b.c.yield_stress, b.c.sound_speed, b.c.slope,
                         b.c.gruneisen, b.c.specific_heat, b.c.hardening);
    }
    fuzz::expect_clean([&] {
        gimlet::scene::scene<S, hmx> sc(gs);
        for (const auto& b : bodies)
            sc.add_body(gimlet::scene::box<S>(b.lower, b.upper), gimlet::presets::make_hmx(b.c), b.velocity, b.ppc);
        if (distance) run<gimlet::contact::distance>(sc, opt);
        else run<gimlet::contact::single_field>(sc, opt);
    });
    return 0;
}
