// SPDX-License-Identifier: MIT
// The reference paper's cavity collapse: two HMX blocks with a circular cavity each collide.
// Secondary impact under weak shocks, jetting and hot spots under strong ones.
//
//   cavity_collapse [--velocity 300] [--radius 10] [--cell 0.5] [--contact distance]
//                   [--end-us 40] [--sample-every-us 0.1] [--snapshot-every-us 4]
//                   [--hot-spot-radius 0.5] [--threads 0] [--quiet]
//                   [--output results/cavity_collapse]
//
// Writes OUTPUT/series.csv (one row per sample), OUTPUT/summary.csv (one row: D_max, secondary
// impact, maximum relative wall velocity, hot spot, collapse mode), particle snapshots
// OUTPUT/snapshots/map_NNNN.csv and, where python3 with matplotlib is available, PNG maps of
// pressure and temperature and a plot of the series. docs/reproduction.md defines each quantity.
#include "cavity_collapse/cavity_collapse.hpp"
#include "common/cli.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace {

using namespace cavity_collapse;

void write_header(std::ostream& os) {
    os << "time_us,time_after_contact_us,D_mm,kinetic_energy,internal_energy,max_temperature_K,"
          "hotspot_temperature_K,hotspot_x_mm,hotspot_y_mm,wall_relative_velocity_m_s,"
          "lower_cavity_open,lower_axial_chord_mm,lower_lateral_chord_mm,lower_closing_speed_m_s,"
          "upper_cavity_open,upper_axial_chord_mm,upper_lateral_chord_mm,upper_closing_speed_m_s\n";
}

void write_row(std::ostream& os, const sample& r, const settings& s) {
    os << r.time * 1e6 << ',' << (r.time - contact_time(s)) * 1e6 << ',' << r.D * 1e3 << ',' << r.kinetic << ','
       << r.internal << ',' << r.max_temperature << ',' << r.hot_spot << ',' << r.hot_spot_centre[0] * 1e3 << ','
       << r.hot_spot_centre[1] * 1e3 << ',' << r.wall_relative_velocity();
    for (const auto& c : r.cavity)
        os << ',' << int(c.open) << ',' << c.axial_chord * 1e3 << ',' << c.lateral_chord * 1e3 << ','
           << c.closing_speed;
    os << '\n';
}

// Particle map for the PNG figures: position, pressure, temperature (single precision is
// plenty for a picture).
template <class Solver>
void write_map(const std::filesystem::path& file, const Solver& sol) {
    std::ofstream os(file);
    os.precision(7);
    os << "x_mm,y_mm,pressure_MPa,temperature_K,body\n";
    const auto& ps = sol.particles();
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const auto p = ps[i];
        const auto& x = p.template get<gimlet::fields::position>();
        os << x[0] * 1e3 << ',' << x[1] * 1e3 << ',' << gimlet::mean_pressure(p) * 1e-6 << ','
           << p.template get<gimlet::fields::temperature>() << ',' << p.template get<gimlet::fields::body>() << '\n';
    }
    if (!os) throw std::runtime_error("could not write " + file.string());
}

template <class Contact>
int run(const settings& s, const std::filesystem::path& out, bool quiet) {
    gimlet::solver_options<S> opt;
    opt.threads = s.threads;
    gimlet::solver<S, gimlet::shape::ugimp, material, Contact> sol(make_scene(s), opt, Contact{});
    std::printf("cavity_collapse: HMX blocks at +-%.0f m/s, cavity radius %.2f mm, cell %.3f mm, %s contact, "
                "%zu particles, to %.2f us\n",
                s.velocity, s.radius * 1e3, s.cell * 1e3, name_of(s.contact).c_str(), sol.particles().size(),
                s.end * 1e6);
    std::fflush(stdout);

    std::ofstream series(out / "series.csv");
    series.precision(10);
    write_header(series);
    monitor mon(s);
    summary sum;
    auto sampler = gimlet::diagnostics::every_time(s.sample_every, [&](const auto& so) {
        const sample r = mon.measure(so);
        write_row(series, r, s);
        sum.add(r, s);
    });
    std::filesystem::create_directories(out / "snapshots");
    int snapshot = 0;
    std::ofstream times(out / "snapshots" / "times.csv");
    times << "index,time_us,time_after_contact_us\n";
    auto snapshots = gimlet::diagnostics::every_time(s.snapshot_every > 0 ? s.snapshot_every : 2 * s.end,
                                                     [&](const auto& so) {
        if (s.snapshot_every <= 0) return;
        char name[32];
        std::snprintf(name, sizeof name, "map_%04d.csv", snapshot);
        write_map(out / "snapshots" / name, so);
        times << snapshot << ',' << double(so.time()) * 1e6 << ',' << (double(so.time()) - contact_time(s)) * 1e6
              << '\n';
        ++snapshot;
    });
    gimlet::diagnostics::progress bar(std::cerr, s.end);
    const auto start = std::chrono::steady_clock::now();
    if (quiet) sol.run_until(s.end, sampler, snapshots);
    else sol.run_until(s.end, sampler, snapshots, bar);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    series.close();
    times.close();
    if (!series || !times) throw std::runtime_error("could not write the series in " + out.string());

    std::ofstream su(out / "summary.csv");
    su << "velocity_m_s,radius_mm,cell_mm,contact,end_us,particles,steps,wall_s,first_contact_us,separation_us,"
          "D_max_mm,t_D_max_us,secondary_impact_us,max_wall_relative_velocity_m_s,max_hotspot_temperature_K,"
          "t_hotspot_us,final_hotspot_temperature_K,max_temperature_K,lower_closure_us,lower_asymmetric,upper_closure_us,upper_asymmetric\n";
    auto us = [](double t) { return t < 0 ? -1.0 : t * 1e6; };
    su << s.velocity << ',' << s.radius * 1e3 << ',' << s.cell * 1e3 << ',' << name_of(s.contact) << ','
       << s.end * 1e6 << ',' << sol.particles().size() << ',' << sol.steps() << ',' << wall << ','
       << us(sum.first_contact) << ',' << us(sum.separation) << ',' << sum.D_max * 1e3 << ',' << us(sum.t_D_max)
       << ',' << us(sum.secondary_impact) << ',' << sum.max_wall_relative_velocity << ',' << sum.max_hot_spot << ','
       << us(sum.t_hot_spot) << ',' << sum.final_hot_spot << ',' << sum.max_temperature << ',' << us(sum.closure[0]) << ','
       << int(sum.asymmetric[0]) << ',' << us(sum.closure[1]) << ',' << int(sum.asymmetric[1]) << '\n';
    su.close();
    if (!su) throw std::runtime_error("could not write " + (out / "summary.csv").string());

    std::printf("  %llu steps in %.1f s\n", static_cast<unsigned long long>(sol.steps()), wall);
    std::printf("  D_max %.3f mm at %.2f us; secondary impact at %.2f us\n", sum.D_max * 1e3, us(sum.t_D_max),
                us(sum.secondary_impact));
    std::printf("  max relative wall velocity %.0f m/s; hot spot peak %.1f K, at the end %.1f K (hottest particle %.1f K)\n",
                sum.max_wall_relative_velocity, sum.max_hot_spot, sum.final_hot_spot, sum.max_temperature);
    if (s.radius > 0)
        for (int b = 0; b < 2; ++b)
            std::printf("  %s cavity: %s\n", b == 0 ? "lower" : "upper",
                        sum.closure[b] < 0 ? "open at the end"
                                           : (sum.asymmetric[b] ? "closed asymmetrically (jet)" : "closed evenly"));
    return 0;
}

}  // namespace

int main(int argc, char** argv) try {
    // --quiet is a switch without a value; the other flags are name-value pairs.
    std::vector<char*> rest{argv[0]};
    bool quiet = false;
    for (int i = 1; i < argc; ++i) {
        if (std::string(argv[i]) == "--quiet") quiet = true;
        else rest.push_back(argv[i]);
    }
    example::cli args(static_cast<int>(rest.size()), rest.data(),
                      "usage: cavity_collapse [--velocity V_m_s] [--radius R_mm] [--cell H_mm] "
                      "[--contact single|bardenhagen|distance] [--end-us T] [--sample-every-us T] "
                      "[--snapshot-every-us T] [--hot-spot-radius R_mm] [--threads N] [--quiet] [--output DIR]");
    settings s;
    s.velocity = args.real("velocity", 300.0, 0.0, 2000.0);
    s.radius = 1e-3 * args.real("radius", 10.0, 0.0, max_radius * 1e3, true);
    s.cell = 1e-3 * args.real("cell", 0.5, 0.0, 4.0);
    const std::string contact = args.choice("contact", "distance", {"single", "bardenhagen", "distance"});
    s.contact = contact == "single" ? contact_kind::single
                                    : (contact == "bardenhagen" ? contact_kind::bardenhagen : contact_kind::distance);
    s.end = 1e-6 * args.real("end-us", 40.0, 0.0, 1000.0);
    s.sample_every = 1e-6 * args.real("sample-every-us", 0.1, 0.0, 100.0);
    s.snapshot_every = 1e-6 * args.real("snapshot-every-us", 4.0, 0.0, 1000.0, true);
    s.hot_spot_radius = 1e-3 * args.real("hot-spot-radius", 0.5, 0.0, 10.0);
    s.threads = static_cast<int>(args.real("threads", 0.0, 0.0, 256.0, true));
    const auto out = args.directory("output", "results/cavity_collapse");
    args.finish();
    validate(s);

    int rc = 0;
    switch (s.contact) {
        case contact_kind::single: rc = run<gimlet::contact::single_field>(s, out, quiet); break;
        case contact_kind::bardenhagen: rc = run<gimlet::contact::bardenhagen>(s, out, quiet); break;
        case contact_kind::distance: rc = run<gimlet::contact::distance>(s, out, quiet); break;
    }
    // Debian's python3 carries matplotlib from the system packages; prefer it over another on PATH.
    const std::string python = std::system("test -x /usr/bin/python3") == 0 ? "/usr/bin/python3" : "python3";
    const std::string plot = python + " \"" + GIMLET_EXAMPLE_DIR + "/plot.py\" \"" + out.string() + "\"";
    if (std::system((plot + " 2>/dev/null").c_str()) == 0)
        std::printf("  figures: %s (series.png, map_*.png)\n", out.string().c_str());
    else
        std::printf("  (no figures: needs python3 with matplotlib; run %s)\n", plot.c_str());
    std::printf("  series: %s\n", (out / "series.csv").string().c_str());
    return rc;
} catch (const std::exception& e) {
    std::cerr << "cavity_collapse: " << e.what() << '\n';
    return 1;
}
