// SPDX-License-Identifier: MIT
// Two elastic disks collide and rebound: the classic first test of an MPM code, after Sulsky,
// Chen & Schreyer (1994, section 5.1). Their material, disk radius (0.2), speed and cell, but the
// disks centred at 0.25 and 0.75 of the unit square, where theirs sit at 0.2 and 0.8 and so
// touch its walls: here nothing meets a wall before the disks part. Writes the conserved quantities over time to
// OUTPUT/energy.csv and prints a summary.
//
//   sulsky_disks [--cell 0.05] [--end-time 3.0] [--velocity 0.1] [--threads N] [--output results/sulsky_disks]
//
// Built with MPI (gimlet::mpi, where the toolchain has it), it runs on many processes too, the
// grid's slabs split between them, with the same bits as on one:
//
//   mpirun -np 2 sulsky_disks --cell 0.005
#include "common/cli.hpp"
#include "common/processes.hpp"

#include <gimlet/gimlet.hpp>

#include <cstdio>
#include <fstream>
#include <iostream>

int main(int argc, char** argv) {
    const example::run_processes procs(argc, argv);
    const bool writer = procs.writer();  // one process writes and prints
    try {
    example::cli args(argc, argv,
                      "usage: sulsky_disks [--cell H_m] [--end-time T_s] [--velocity V_m_s] [--threads N] [--output DIR]");
    const double cell = args.real("cell", 0.05, 0.0, 0.2);
    const double end = args.real("end-time", 3.0, 0.0, 100.0);
    const double speed = args.real("velocity", 0.1, 0.0, 10.0);
    const int threads = args.integer("threads", 0, 0, 1024);
    // The writer creates and probes the directory; the others only take the flag. Where it
    // cannot, every process stops (together), none waits for it in the run's exchanges.
    std::filesystem::path out;
    const auto output = [&] {
        out = writer ? args.directory("output", "results/sulsky_disks") : std::filesystem::path(args.path("output"));
    };
    procs.together(output);
    args.finish();

    using S = gimlet::space<2>;
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Ones();
    gs.cell = cell;
    gs.bc = {gimlet::boundary::slip, gimlet::boundary::slip};
    gimlet::scene::scene<S, gimlet::elastic_material> scene(gs);
    const auto mat = gimlet::make_elastic_material(1000.0, 1000.0, 0.3);  // Sulsky et al.'s values
    scene.add_body(gimlet::scene::ball<S>(S::vector(0.25, 0.25), 0.2), mat, S::vector(speed, speed), 2, "lower disk");
    scene.add_body(gimlet::scene::ball<S>(S::vector(0.75, 0.75), 0.2), mat, S::vector(-speed, -speed), 2, "upper disk");
    gimlet::solver_options<S> options;
    options.threads = threads;
    options.processes = procs.for_solver();
    example::solver<S, gimlet::shape::ugimp, gimlet::elastic_material> sol(scene, options);

    std::ofstream csv;
    if (writer) csv.open(out / "energy.csv");
    gimlet::io::exact_numbers(csv);
    csv << "time_s,mass_kg,momentum_x,momentum_y,kinetic_J,internal_J,total_J\n";
    gimlet::diagnostics::conservation_sample<2> first{}, last{};
    bool have_first = false;
    gimlet::diagnostics::every_time observer(end / 200, [&](const auto& s) {
        last = gimlet::diagnostics::sample_conservation(s);
        if (!have_first) first = last, have_first = true;
        csv << last.time << ',' << last.mass << ',' << last.momentum[0] << ',' << last.momentum[1] << ','
            << last.kinetic << ',' << last.internal << ',' << last.total_energy() << '\n';
    });
    sol.run_until(end, observer);
    const auto particles = std::size_t(procs.sum(sol.particles().size()));
    if (!writer) return 0;

    std::printf("sulsky_disks: %zu particles, %llu steps to t = %.3f s\n", particles,
                static_cast<unsigned long long>(sol.steps()), double(sol.time()));
    std::printf("  mass change        %.2e (relative)\n", (last.mass - first.mass) / first.mass);
    std::printf("  momentum change    %.2e kg m/s (each disk carries %.3f)\n", (last.momentum - first.momentum).norm(),
                0.5 * first.mass * speed * std::sqrt(2.0));
    std::printf("  energy: initial %.5f J, final %.5f J (%+.2f %%)\n", first.total_energy(), last.total_energy(),
                100.0 * (last.total_energy() / first.total_energy() - 1.0));
    std::printf("  time series: %s\n", (out / "energy.csv").string().c_str());
    return 0;
    } catch (const std::exception& e) {
        if (writer) std::cerr << "sulsky_disks: " << e.what() << '\n';
        return 1;
    }
}
