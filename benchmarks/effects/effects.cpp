// SPDX-License-Identifier: MIT
// The cost of each effect: the two-block HMX scene (touching, so contact acts from the first
// step) with heating, artificial viscosity, plasticity and multi-field contact switched on and
// off one at a time. An effect is switched off by its `none` policy (or linear_elastic for
// plasticity, single_field for contact): its fields are not stored and its code is not
// compiled, so "off" is the build without it. Prints CSV: variant, bytes stored per particle,
// median wall time, particle-updates per second.
// Flags: --cell MM (1), --steps N (300), --repeats R (5), --threads T (1).
#include "common/bench.hpp"

#include <cstdio>
#include <exception>

namespace {

using S = bench::S2;
using mg = gimlet::eos::mie_gruneisen<>;
using heating = gimlet::thermal::isentrope_temperature;  // make_hmx()'s default

struct hmx_parts {
    gimlet::presets::hmx_constants c;
    double shear = gimlet::elastic_moduli::from_young_poisson(c.young, c.poisson).shear;
    [[nodiscard]] gimlet::strength::von_mises plastic() const { return {shear, c.yield_stress, c.hardening}; }
    [[nodiscard]] gimlet::strength::linear_elastic elastic() const { return gimlet::strength::linear_elastic{shear}; }
    [[nodiscard]] mg eos() const { return {c.density, c.sound_speed, c.slope, c.gruneisen}; }
    [[nodiscard]] heating heat() const {
        return {c.density, c.sound_speed, c.slope, c.gruneisen, c.specific_heat, c.temperature};
    }
};

// A variant's name: the CSV row's first field, written unquoted, so a comma in it would shift
// the row's columns. Checked where the name is written in the source: a name with a comma does
// not compile.
struct variant_name {
    const char* text;
    consteval variant_name(const char* s) : text(s) {  // NOLINT: implicit, from a string literal
        for (const char* c = s; *c != '\0'; ++c)
            if (*c == ',') throw "a variant name holds a comma (the CSV's first field, written unquoted)";
    }
};

template <class Contact, class M, class Part = gimlet::multi_field::by_body>
void run(variant_name name, const M& mat, double cell, int steps, int repeats, int threads,
         gimlet::solver_options<S> opt = {}, bool self_contact = true) {
    using solver = gimlet::solver<S, gimlet::shape::ugimp, M, Contact, gimlet::field_list<>, Part>;
    opt.threads = threads;
    std::vector<double> seconds;
    std::size_t particles = 0, bytes = 0;
    for (int k = 0; k < repeats; ++k) {
        Part part;
        if constexpr (requires { part.enabled; }) part.enabled = self_contact;
        solver sol(bench::two_blocks(mat, cell, 0.0), opt, Contact{}, part);
        particles = sol.particles().size();
        bytes = 0;
        sol.particles().for_each_column([&](auto, const auto& column) { bytes += sizeof(column[0]); });
        const auto t0 = std::chrono::steady_clock::now();
        for (int n = 0; n < steps; ++n) sol.step(bench::reference_dt(cell));
        seconds.push_back(bench::seconds_since(t0));
    }
    const double med = bench::median(seconds);
    std::printf("%s,%zu,%zu,%d,%d,%.4f,%.3f\n", name.text, bytes, particles, steps, threads, med,
                double(particles) * steps / med * 1e-6);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) try {
    bench::flags f(argc, argv);
    const double cell = 1e-3 * f.number("cell", 1.0);
    const int steps = static_cast<int>(f.number("steps", 300));
    const int repeats = static_cast<int>(f.number("repeats", 5));
    const int threads = static_cast<int>(f.number("threads", 1));
    f.finish();
    using namespace gimlet;
    const hmx_parts h;
    std::printf("variant,bytes_per_particle,particles,steps,threads,median_s,mups\n");
    run<contact::distance>("full HMX: plasticity + heating + viscosity + distance contact", presets::make_hmx(), cell, steps,
                           repeats, threads);
    run<contact::distance>("heating off", material<strength::von_mises, mg, thermal::none, viscosity::bulk>{
                                              h.c.density, h.plastic(), h.eos(), {}, viscosity::bulk{}},
                           cell, steps, repeats, threads);
    run<contact::distance>("viscosity off", material<strength::von_mises, mg, heating, viscosity::none>{
                                                h.c.density, h.plastic(), h.eos(), h.heat(), {}},
                           cell, steps, repeats, threads);
    run<contact::distance>("plasticity off", material<strength::linear_elastic, mg, heating, viscosity::bulk>{
                                                 h.c.density, h.elastic(), h.eos(), h.heat(), viscosity::bulk{}},
                           cell, steps, repeats, threads);
    run<contact::distance>("paper's Walsh-Christian heating (instead of the isentrope temperature)",
                           presets::make_hmx<eos::energy_reference::internal_energy, presets::paper_temperature>(),
                           cell, steps, repeats, threads);
    auto options = [](auto&& set) {
        solver_options<S> opt;
        set(opt);
        return opt;
    };
    run<contact::distance>("volumetric average on (solver_options)", presets::make_hmx(), cell, steps, repeats, threads,
                           options([](auto& o) { o.volumetric_average = true; }));
    // The particle-scale options of docs/equations.md: each adds passes over the particles and nodes.
    run<contact::distance>("consistent-mass accelerations with k = 1 (solver_options)", presets::make_hmx(), cell, steps,
                           repeats, threads, options([](auto& o) { o.consistent_mass_iterations = 1; }));
    run<contact::distance>("consistent-mass accelerations with k = 4 (solver_options)", presets::make_hmx(), cell, steps,
                           repeats, threads, options([](auto& o) { o.consistent_mass_iterations = 4; }));
    run<contact::distance>("volume filter with k = 4 (solver_options)", presets::make_hmx(), cell, steps, repeats,
                           threads, options([](auto& o) {
                               o.consistent_mass_iterations = 4;
                               o.volume_filter = true;
                           }));
    // Self-contact costs what its per-step passes cost even where no void closes (here none).
    run<contact::distance, presets::hmx_material<>, multi_field::self_contact>(
        "self-contact on (multi_field::self_contact; no void in this scene)", presets::make_hmx(), cell, steps,
        repeats, threads);
    run<contact::distance, presets::hmx_material<>, multi_field::self_contact>(
        "self-contact compiled in but enabled = false", presets::make_hmx(), cell, steps, repeats, threads, {},
        false);
    run<contact::single_field>("single-field contact (instead of distance)", presets::make_hmx(), cell, steps, repeats, threads);
    run<contact::bardenhagen>("Bardenhagen contact (instead of distance)", presets::make_hmx(), cell, steps, repeats, threads);
    run<contact::single_field>("all off: elastic + Mie-Grueneisen + single field",
                               material<strength::linear_elastic, mg>{h.c.density, h.elastic(), h.eos(), {}, {}}, cell,
                               steps, repeats, threads);
    run<contact::single_field>("reference physics: linear elastic + linear EOS + single field", bench::reference_material(), cell, steps,
                               repeats, threads);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "bench_effects: %s\n", e.what());
    return 1;
}
