// SPDX-License-Identifier: MIT
// The reference paper's contact validation: two HMX blocks with a 4 mm gap collide; pressure
// along the vertical centre line for the three contact policies (single field, Bardenhagen et
// al. 2000, the paper's distance-switched contact). The paper reports a spurious pressure peak
// at the interface for the first two and none for its own.
//
//   contact_validation [--velocity 300] [--cell 0.5] [--time-us 14] [--consistent-mass 4]
//                      [--viscosity-linear 0.12] [--viscosity-quadratic 2.4] [--cfl 0.4] [--threads 0]
//                      [--output results/contact_validation]
//
// The mass matrix and the viscosity default to the HMX examples' pair, as in cavity_collapse
// (common/hmx_defaults.hpp); --consistent-mass 0 --viscosity-linear 0.06
// --viscosity-quadratic 1.2 gives the library's.
//
// Writes OUTPUT/profile_<policy>.csv (y_mm, pressure_Pa; y from the bottom of the lower block),
// OUTPUT/summary.csv (policy, interface_peak_over_plateau, ...) and, where python3 with
// matplotlib is available, OUTPUT/profiles.png.
// Built with MPI (gimlet::mpi, where the toolchain has it), it runs on many processes too,
// `mpirun -np 2 contact_validation --threads 1`: the same files, bit for bit, written by the
// first process.
#include "common/cli.hpp"
#include "common/hmx_flags.hpp"
#include "common/processes.hpp"
#include "contact_validation/contact_validation.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

int main(int argc, char** argv) {
    const example::run_processes procs(argc, argv);
    const bool writer = procs.writer();  // one process writes, prints and plots
    try {
    example::cli args(argc, argv,
                      "usage: contact_validation [--velocity V_m_s] [--cell H_mm] [--time-us T] [--consistent-mass K] "
                      "[--viscosity-linear B1] [--viscosity-quadratic B2] [--cfl C] [--threads N] [--output DIR]");
    contact_validation::settings s;
    s.velocity = args.real("velocity", 300.0, 0.0, 1000.0);
    s.cell = 1e-3 * args.real("cell", 0.5, 0.0, 4.0);
    s.time = 1e-6 * args.real("time-us", 14.0, 0.0, 40.0);
    const auto mv = example::read_numerics(args);
    s.consistent_mass = mv.consistent_mass;
    s.viscosity_linear = mv.viscosity_linear;
    s.viscosity_quadratic = mv.viscosity_quadratic;
    s.cfl = mv.cfl;
    s.threads = args.integer("threads", 0, 0, 256);
    // The writer creates and probes the directory; the others only take the flag. Where it
    // cannot, every process stops (together).
    std::filesystem::path out;
    const auto output = [&] {
        out = writer ? args.directory("output", "results/contact_validation") : std::filesystem::path(args.path("output"));
    };
    procs.together(output);
    s.processes = [&procs] { return procs.for_solver(); };
    args.finish();

    const std::vector<contact_validation::result> results{
        contact_validation::run<gimlet::contact::single_field>(s, "single"),
        contact_validation::run<gimlet::contact::bardenhagen>(s, "bardenhagen"),
        contact_validation::run<gimlet::contact::distance>(s, "distance"),
    };
    if (!writer) return 0;

    std::ofstream summary(out / "summary.csv");
    gimlet::io::exact_numbers(summary);
    summary << "policy,interface_peak_over_plateau,particle_peak_over_plateau,interface_peak_Pa,plateau_Pa,"
               "velocity_m_s,cell_mm,time_us,max_eta,consistent_mass,viscosity_linear,viscosity_quadratic,cfl";
    for (const char* name : gimlet::health_events::names) summary << ",events_" << name;
    summary << '\n';
    std::printf("contact_validation: HMX blocks at +-%.0f m/s, cell %.3f mm, t = %.2f us, consistent mass %d, "
                "viscosity (%g, %g)\n",
                s.velocity, s.cell * 1e3, s.time * 1e6, s.consistent_mass, s.viscosity_linear, s.viscosity_quadratic);
    std::printf("  %-12s %12s %18s %14s %14s\n", "policy", "peak/plateau", "(particle values)", "peak (Pa)",
                "plateau (Pa)");
    for (const auto& r : results) {
        std::ofstream prof(out / ("profile_" + r.policy + ".csv"));
        gimlet::io::exact_numbers(prof);
        prof << "y_mm,pressure_Pa\n";
        for (const auto& [y, p] : r.profile) prof << (y + r.interface_y) * 1e3 << ',' << p << '\n';
        summary << r.policy << ',' << r.peak_over_plateau << ',' << r.particle_peak_over_plateau << ','
                << r.interface_peak << ',' << r.plateau << ',' << s.velocity << ',' << s.cell * 1e3 << ','
                << s.time * 1e6 << ',' << r.max_eta << ',' << s.consistent_mass << ',' << s.viscosity_linear << ','
                << s.viscosity_quadratic << ',' << s.cfl;
        for (const auto n : r.health.count) summary << ',' << n;
        summary << '\n';
        for (std::size_t k = 0; k < gimlet::health_events::kinds; ++k)
            if (r.health.count[k] > 0)
                std::printf("  %s: health event %s: %llu, first %s\n", r.policy.c_str(), gimlet::health_events::names[k],
                            static_cast<unsigned long long>(r.health.count[k]), r.health.first[k].c_str());
        std::printf("  %-12s %12.3f %18.3f %14.4e %14.4e\n", r.policy.c_str(), r.peak_over_plateau,
                    r.particle_peak_over_plateau, r.interface_peak, r.plateau);
    }
    summary.close();
    // Debian's python3 carries matplotlib from the system packages; prefer it over another on PATH.
    const std::string python = std::system("test -x /usr/bin/python3") == 0 ? "/usr/bin/python3" : "python3";
    const std::string plot = python + " \"" + GIMLET_EXAMPLE_DIR + "/plot.py\" \"" + out.string() + "\"";
    if (std::system((plot + " 2>/dev/null").c_str()) == 0)
        std::printf("  plot: %s\n", (out / "profiles.png").string().c_str());
    else
        std::printf("  (no plot: needs python3 with matplotlib; run %s)\n", plot.c_str());
    std::printf("  summary: %s\n", (out / "summary.csv").string().c_str());
    return 0;
    } catch (const std::exception& e) {
        if (writer) std::cerr << "contact_validation: " << e.what() << '\n';
        return 1;
    }
}
