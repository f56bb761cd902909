// SPDX-License-Identifier: MIT
// The reference paper's cavity collapse: two HMX blocks with a circular cavity each collide.
// Secondary impact under weak shocks, jetting and hot spots under strong ones.
//
//   cavity_collapse [--velocity 300] [--radius 10] [--cell 0.5] [--contact distance]
//                   [--self-contact on|off (on with distance or bardenhagen contact)]
//                   [--end-us 40] [--sample-every-us 0.1] [--snapshot-every-us 4]
//                   [--snapshots-after-contact-us 4,8,14]
//                   [--hot-spot-radius 0.75] [--volumetric-average off] [--pic-fraction 0]
//                   [--consistent-mass 4] [--volume-filter off|on] [--viscosity-linear 0.12]
//                   [--viscosity-quadratic 2.4] [--cfl 0.4]
//                   [--temperature isentrope|paper] [--threads 0]
//                   [--geometry plane|axisymmetric|3d] [--side array|free]
//                   [--quiet] [--no-figures]
//                   [--output results/cavity_collapse]
//                   [--checkpoint FILE --checkpoint-at-us T] [--restart FILE]
//
// Writes OUTPUT/series.csv (one row per sample), OUTPUT/summary.csv (one row: D_max, secondary
// impact, maximum relative wall velocity, hot spot, largest particle compression, collapse
// mode), particle snapshots for
// ParaView (OUTPUT/snapshots/particles.pvd and particles_NNNNNN.vtp) and for the figures
// (OUTPUT/snapshots/map_NNNN.csv) and, where python3 with matplotlib is available, PNG maps of
// pressure and temperature and a plot of the series (plot.py: the maps are drawn while the run
// goes on, from processor time it leaves idle, the rest when it ends; --no-figures skips them).
// docs/reproduction.md defines each quantity.
// --checkpoint writes the run's state at --checkpoint-at-us; --restart resumes from it (give
// the original run's other flags, --end-us included: the grid is sized for it) and continues
// the same outputs. Exit status: 0 done, 1 bad
// input or I/O error, 3 stopped by the library (numerical trouble; the outputs so far are
// written and summary.csv's status says why).
// Built with MPI (gimlet::mpi, where the toolchain has it), it runs on many processes too,
// `mpirun -np 2 cavity_collapse --threads 1 ...`: the same files, bit for bit (summary.csv's
// ranks column aside, and its wall time), written by the first process, which alone prints and
// draws, except the ParaView snapshots: each is particles_NNNNNN.pvtp, one piece a process
// (particles_NNNNNN_<rank>.vtp), whose particles, put in the order of their `ordinal` array,
// are one process's bit for bit;
// a checkpoint resumes on any number of processes.
#include "cavity_collapse/cavity_collapse.hpp"
#include "cavity_collapse/flags.hpp"
#include "common/cli.hpp"
#include "common/particle_map.hpp"
#include "common/plotter.hpp"
#include "common/processes.hpp"
#include "common/restart.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <optional>
#include <type_traits>
#include <utility>
#include <string>
#include <vector>

namespace {

using namespace cavity_collapse;
using example::keep_lines;
using example::plotter;
using example::shell_word;

// The units of the sums over the particles: per metre of depth in the plane, the whole body's
// axisymmetric and in 3-D.
const char* mass_unit(const settings& s) { return s.geometry == geometry_kind::plane ? "kg_m" : "kg"; }

void write_header(std::ostream& os, const settings& s) {
    os << "time_us,time_after_contact_us,D_mm,kinetic_energy,internal_energy,max_temperature_K,max_eta,"
          "hotspot_temperature_K,"
       << (s.geometry == geometry_kind::plane          ? "hotspot_x_mm,hotspot_y_mm"
           : s.geometry == geometry_kind::axisymmetric ? "hotspot_r_mm,hotspot_z_mm"
                                                       : "hotspot_x_mm,hotspot_y_mm,hotspot_z_mm")
       << ",wall_relative_velocity_m_s,"
          "lower_cavity_open,lower_axial_chord_mm,lower_lateral_chord_mm,lower_closing_speed_m_s,"
          "lower_upstream_wall_speed_m_s,upper_cavity_open,upper_axial_chord_mm,upper_lateral_chord_mm,"
          "upper_closing_speed_m_s,upper_upstream_wall_speed_m_s";
    for (double excess : hot_excess) os << ",hot_mass_above_TEP_plus_" << int(excess) << "K_" << mass_unit(s);
    if (s.geometry == geometry_kind::plane)
        for (double excess : hot_excess) os << ",hot_area_above_TEP_plus_" << int(excess) << "K_mm2";
    else
        for (double excess : hot_excess) os << ",hot_volume_above_TEP_plus_" << int(excess) << "K_mm3";
    os << '\n';
}

template <class Vector>
void write_row(std::ostream& os, const sample_of<Vector>& r, const settings& s) {
    os << r.time * 1e6 << ',' << (r.time - contact_time(s)) * 1e6 << ',' << r.D * 1e3 << ',' << r.kinetic << ','
       << r.internal << ',' << r.max_temperature << ',' << r.max_eta << ',' << r.hot_spot;
    for (int d = 0; d < int(Vector::RowsAtCompileTime); ++d) os << ',' << r.hot_spot_centre[d] * 1e3;
    os << ',' << r.wall_relative_velocity();
    for (const auto& c : r.cavity)
        os << ',' << int(c.open) << ',' << c.axial_chord * 1e3 << ',' << c.lateral_chord * 1e3 << ','
           << c.closing_speed << ',' << c.upstream_speed;
    for (double m : r.hot_mass) os << ',' << m;
    const double to_mm = s.geometry == geometry_kind::plane ? 1e6 : 1e9;  // mm^2, or mm^3 for whole bodies
    for (double a : r.hot_area) os << ',' << a * to_mm;
    os << '\n';
}

// Takes the checkpoint at the first step at or after the requested time, after that step's
// outputs (it is the last observer but the progress line), so a resumed run starts exactly
// where they stop.
struct checkpointer {
    std::function<void(double)> save;
    double at;
    bool done;
    template <class Solver>
    void maybe_call(const Solver& so) {
        if (done || double(so.time()) < at) return;
        done = true;
        save(double(so.time()));
    }
};

// Calls f at the first step at or after each listed time (s), once per step.
template <class F>
struct listed_times {
    std::vector<double> at;
    std::size_t next;
    F f;
    template <class Solver>
    void maybe_call(const Solver& so) {
        if (next >= at.size() || double(so.time()) < at[next]) return;
        while (next < at.size() && double(so.time()) >= at[next]) ++next;
        f(so);
    }
};
// Aggregate deduction (C++20, P1816) is not in clang 14: the guide says it.
template <class F>
listed_times(std::vector<double>, std::size_t, F) -> listed_times<F>;

// Where a run writes, and whether it checkpoints or resumes.
struct run_files {
    std::filesystem::path out;
    std::filesystem::path checkpoint;  // empty: none
    double checkpoint_at = 0;          // s
    std::filesystem::path restart;     // empty: a fresh run
    bool quiet = false;
    plotter* figures = nullptr;  // none: no figures
    // On many processes: theirs (solver_options::processes; built with MPI, where example::solver
    // is a distributed_solver); only the first one writes, prints and draws (`writer`).
    std::shared_ptr<gimlet::processes> processes;
    bool writer = true;
};

double value_of(const gimlet::io::checkpoint_values& v, const std::string& key, const std::filesystem::path& file) {
    const auto it = v.find(key);
    if (it == v.end())
        throw std::runtime_error(file.string() + " is not a cavity_collapse checkpoint (no value '" + key + "')");
    return it->second;
}

// The settings a resumed run must share with the checkpointed one (the grid is sized for the
// end time); a checkpoint records them and a restart compares. The geometry only where it is
// not the plane: a checkpoint without it is a plane run's.
gimlet::io::checkpoint_values fixed_on_restart(const settings& s) {
    gimlet::io::checkpoint_values v = {{"velocity_m_s", s.velocity},        {"radius_m", s.radius},
            {"cell_m", s.cell},                  {"contact", double(int(s.contact))},
            {"sample_every_s", s.sample_every},  {"snapshot_every_s", s.snapshot_every},
            {"hot_spot_radius_m", s.hot_spot_radius}, {"end_s", s.end},
            {"volumetric_average", s.volumetric_average ? 1.0 : 0.0}, {"pic_fraction", s.pic_fraction},
            {"paper_temperature", s.paper_temperature ? 1.0 : 0.0}, {"self_contact", s.self_contact ? 1.0 : 0.0},
            {"consistent_mass", double(s.consistent_mass)}, {"viscosity_linear", s.viscosity_linear},
            {"viscosity_quadratic", s.viscosity_quadratic}, {"volume_filter", s.volume_filter ? 1.0 : 0.0},
            {"cfl", s.cfl}};
    if (s.geometry != geometry_kind::plane) v["geometry"] = double(int(s.geometry));
    if (s.geometry != geometry_kind::plane) v["free_side"] = s.free_side() ? 1.0 : 0.0;
    return v;
}

// Where each output stands: the series' rows and the snapshots written, and the next time of
// each schedule. A checkpoint saves it; a restart gives it back.
struct output_state {
    std::size_t rows = 0, snapshot = 0, listed_next = 0;
    double next_sample = 0, next_snapshot = 0, last_sample = -1;
};

// A restart: the particles from the checkpoint, whose flags must be this run's; where each
// output stood, the monitor and the summary so far. (The writer cuts the series and the
// snapshots' list back to the checkpoint's rows when it opens them: the interrupted run may have
// written more after it.)
template <class Solver>
output_state resume_from(const std::filesystem::path& checkpoint, const settings& s, Solver& sol,
                         monitor_of<typename Solver::vector>& mon,
                         summary& sum) {
    auto v = gimlet::io::load_checkpoint(checkpoint, sol);
    // A checkpoint without these keys ran with the lumped mass, viscosity (0.06, 1.2), no volume
    // filter and the Courant number 0.4.
    v.try_emplace("consistent_mass", 0.0);
    v.try_emplace("viscosity_linear", 0.06);
    v.try_emplace("viscosity_quadratic", 1.2);
    v.try_emplace("volume_filter", 0.0);
    v.try_emplace("cfl", 0.4);
    if (s.geometry != geometry_kind::plane) v.try_emplace("geometry", double(int(geometry_kind::plane)));
    // Nor did it keep the hot spot's disc compression: a restart reports it only if the peak
    // moves after it (-1 otherwise).
    v.try_emplace("summary.hot_spot_eta", -1.0);
    for (const auto& [key, mine] : fixed_on_restart(s))
        if (value_of(v, key, checkpoint) != mine)
            throw std::invalid_argument("--restart " + checkpoint.string() + ": the checkpoint's " + key + " is " +
                                        std::to_string(value_of(v, key, checkpoint)) + ", this run's is " +
                                        std::to_string(mine) + "; restart with the original run's flags");
    output_state at;
    at.rows = std::size_t(value_of(v, "series_rows", checkpoint));
    at.snapshot = std::size_t(value_of(v, "snapshots", checkpoint));
    at.next_sample = value_of(v, "next_sample_s", checkpoint);
    at.next_snapshot = value_of(v, "next_snapshot_s", checkpoint);
    at.last_sample = value_of(v, "last_sample_s", checkpoint);
    at.listed_next = std::size_t(value_of(v, "next_listed_snapshot", checkpoint));
    mon.visit([&](const std::string& k, auto& x) {
        x = static_cast<std::remove_reference_t<decltype(x)>>(value_of(v, "monitor." + k, checkpoint));
    });
    sum.visit([&](const std::string& k, auto& x) {
        x = static_cast<std::remove_reference_t<decltype(x)>>(value_of(v, "summary." + k, checkpoint));
    });
    return at;
}

// The Rankine-Hugoniot compression of a planar symmetric landing at half the largest relative
// wall velocity (examples/common/hugoniot.hpp), the reference beside the hot spot's disc-mean
// compression; -1 when no wall moved.
inline double landing_eta(const summary& sum) {
    const double v = 0.5 * sum.max_wall_relative_velocity;
    return v > 0 ? example::rankine_hugoniot(gimlet::presets::make_hmx(), v).eta : -1.0;
}

// summary.csv: the run's settings, its peaks and times, the health events and how it ended.
// `particles`: the whole run's; `ranks`: the processes it ran on.
template <class Solver>
void write_summary(const std::filesystem::path& file, const settings& s, const Solver& sol, const summary& sum,
                   const monitor_of<typename Solver::vector>& mon, double wall, const std::string& status,
                   std::uint64_t particles, int ranks) {
    std::ofstream su(file);
    gimlet::io::exact_numbers(su);
    su << "velocity_m_s,radius_mm,cell_mm,contact,end_us,particles,steps,wall_s,first_contact_us,separation_us,"
          "D_max_mm,t_D_max_us,secondary_impact_us,max_wall_relative_velocity_m_s,max_upstream_wall_speed_m_s,max_hotspot_temperature_K,"
          "t_hotspot_us,final_hotspot_temperature_K,settled_hotspot_temperature_K,max_temperature_K,max_eta,lower_closure_us,lower_asymmetric,"
          "upper_closure_us,upper_asymmetric,lower_collapse_us,upper_collapse_us,lower_aspect_at_collapse,"
          "upper_aspect_at_collapse,volumetric_average,pic_fraction,temperature,self_contact,bulk_shock_temperature_K,"
          "consistent_mass,viscosity_linear,viscosity_quadratic,volume_filter,cfl,hotspot_eta,landing_eta";
    for (double excess : hot_excess) su << ",max_hot_mass_above_TEP_plus_" << int(excess) << "K_" << mass_unit(s);
    for (const char* name : gimlet::health_events::names) su << ",events_" << name;
    su << ",geometry,side,ranks,status\n";
    auto us = [](double t) { return t < 0 ? -1.0 : t * 1e6; };
    su << s.velocity << ',' << s.radius * 1e3 << ',' << s.cell * 1e3 << ',' << name_of(s.contact) << ','
       << s.end * 1e6 << ',' << particles << ',' << sol.steps() << ',' << wall << ','
       << us(sum.first_contact) << ',' << us(sum.separation) << ',' << sum.D_max * 1e3 << ',' << us(sum.t_D_max)
       << ',' << us(sum.secondary_impact) << ',' << sum.max_wall_relative_velocity << ',' << sum.max_upstream_speed << ',' << sum.max_hot_spot << ','
       << us(sum.t_hot_spot) << ',' << sum.final_hot_spot << ',' << sum.settled_hot_spot << ',' << sum.max_temperature << ','
       << sum.max_eta << ',' << us(sum.closure[0]) << ',' << int(sum.asymmetric[0]) << ',' << us(sum.closure[1]) << ','
       << int(sum.asymmetric[1]) << ',' << us(sum.collapse[0]) << ',' << us(sum.collapse[1]) << ',' << sum.aspect[0] << ','
       << sum.aspect[1] << ',' << (s.volumetric_average ? "on" : "off") << ',' << s.pic_fraction << ','
       << (s.paper_temperature ? "paper" : "isentrope") << ',' << (s.self_contact ? "on" : "off") << ','
       << mon.bulk_shock_temperature() << ',' << s.consistent_mass << ',' << s.viscosity_linear << ','
       << s.viscosity_quadratic << ',' << (s.volume_filter ? "on" : "off") << ',' << s.cfl << ',' << sum.hot_spot_eta
       << ',' << landing_eta(sum);
    for (double m : sum.max_hot_mass) su << ',' << m;
    for (const auto n : sol.health().count) su << ',' << n;
    su << ',' << name_of(s.geometry) << ','
       << (s.geometry == geometry_kind::plane ? "periodic" : s.free_side() ? "free" : "array") << ',' << ranks << ','
       << status << '\n';
    su.close();
    if (!su) throw std::runtime_error("could not write " + file.string());

}

// The run's report on standard output: where the time went and the summary's main figures.
template <class Solver>
void print_report(const settings& s, const Solver& sol, const summary& sum, const monitor_of<typename Solver::vector>& mon,
                  double wall) {
    // Where the time went: the solver's phases (solver::timings()), and the rest of the run
    // (the time step's choice, the observers, the files), which scales differently with threads.
    const auto& ph = sol.timings();
    std::printf("  %llu steps in %.1f s: steps %.2f s (P2G %.2f, grid %.2f, contact %.2f, G2P %.2f, material %.2f), "
                "time steps, observers and files %.2f s\n",
                static_cast<unsigned long long>(sol.steps()), wall, ph.total(), ph.particle_to_grid + ph.sort,
                ph.grid_update, ph.contact, ph.grid_to_particle, ph.material_update, wall - ph.total());
    // A time or value the run never reached reads "none" here (summary.csv keeps -1 there).
    auto at_us = [](double t, const char* fmt) {
        char text[64] = "none";
        if (t >= 0) std::snprintf(text, sizeof text, fmt, t * 1e6);
        return std::string(text);
    };
    auto kelvin = [](double t) {
        char text[64] = "none";
        if (t >= 0) std::snprintf(text, sizeof text, "%.1f K", t);
        return std::string(text);
    };
    std::printf("  D_max %.3f mm at %s; secondary impact at %s\n", sum.D_max * 1e3, at_us(sum.t_D_max, "%.2f us").c_str(),
                at_us(sum.secondary_impact, "%.2f us").c_str());
    std::printf("  max relative wall velocity %.0f m/s; hot spot: peak %.1f K, 5 us after it %s, at the end "
                "%.1f K (hottest particle %.1f K)\n",
                sum.max_wall_relative_velocity, sum.max_hot_spot, kelvin(sum.settled_hot_spot).c_str(),
                sum.final_hot_spot, sum.max_temperature);
    std::printf("  largest particle compression eta = 1 - det F: %.4f; the hot spot's disc at its peak: %.4f (a "
                "planar landing at half the largest relative wall velocity: %.4f)\n",
                sum.max_eta, sum.hot_spot_eta, landing_eta(sum));
    std::printf("  hot material, largest mass above T_EP = %.1f K plus", mon.bulk_shock_temperature());
    const char* grams = s.geometry == geometry_kind::plane ? "g/m" : "g";  // the whole body's: kg
    for (std::size_t k = 0; k < hot_levels; ++k)
        std::printf("%s %.0f K: %.3g %s", k ? "," : "", hot_excess[k], sum.max_hot_mass[k] * 1e3, grams);
    std::printf("\n");
    // The silent numerical guards that acted (solver::health): counts, and the first of each.
    std::printf("  health events: %llu\n", static_cast<unsigned long long>(sol.health().total()));
    for (std::size_t k = 0; k < gimlet::health_events::kinds; ++k)
        if (sol.health().count[k] > 0)
            std::printf("    %s: %llu, first %s\n", gimlet::health_events::names[k],
                        static_cast<unsigned long long>(sol.health().count[k]), sol.health().first[k].c_str());
    if (s.radius > 0)
        for (int b = 0; b < 2; ++b)
            std::printf("  %s cavity: %s\n", b == 0 ? "lower" : "upper",
                        sum.collapse[b] < 0 ? "not collapsed (axial chord above R)"
                                            : (sum.asymmetric[b] ? "collapsed asymmetrically (jet)" : "collapsed evenly"));
}

template <class Space, class Contact>
int run(const settings& s, const run_files& io, const Contact& contact) {
    gimlet::solver_options<Space> opt;
    opt.threads = s.threads;
    opt.volumetric_average = s.volumetric_average;
    opt.pic_fraction = s.pic_fraction;
    opt.consistent_mass_iterations = s.consistent_mass;
    opt.cfl = s.cfl;
    opt.volume_filter = s.volume_filter;
    opt.processes = io.processes;
    // Self-contact needs several fields per body, so a multi-field contact; off, its partition
    // keeps one field per body and the results are those of multi_field::by_body.
    using partition = std::conditional_t<std::is_same_v<Contact, gimlet::contact::single_field>,
                                         gimlet::multi_field::by_body, gimlet::multi_field::self_contact>;
    partition part;
    if constexpr (std::is_same_v<partition, gimlet::multi_field::self_contact>) part.enabled = s.self_contact;
    auto scene = [&] {
        if constexpr (gimlet::is_axisymmetric_v<Space>) return make_axisymmetric_scene<run_material>(s);
        else if constexpr (Space::dim == 3) return make_3d_scene<run_material>(s);
        else return make_scene<run_material>(s);
    };
    example::solver<Space, gimlet::shape::ugimp, run_material, Contact, gimlet::field_list<>, partition> sol(
        scene(), opt, contact, part);
    const auto& out = io.out;
    monitor_of<typename Space::vector> mon(s);
    summary sum;
    std::ofstream series, times;
    gimlet::io::vtp_writer_for<decltype(sol)> vtp;
    vtp.add("pressure", [](const auto& p) { return gimlet::mean_pressure(p); })
        .template add_field<gimlet::fields::temperature>()
        .template add_field<gimlet::fields::velocity>()
        .template add_field<gimlet::fields::plastic_strain>()
        .template add_field<gimlet::fields::body>();
    const auto pvd_path = out / "snapshots" / "particles.pvd";
    std::optional<gimlet::io::pvd_writer> pvd;
    output_state at;

    // What a checkpoint keeps besides the particles: where each output stands, the summary so
    // far, and the flags that must not change on a restart.
    auto save_values = [&] {
        gimlet::io::checkpoint_values v = fixed_on_restart(s);
        v["series_rows"] = double(at.rows);
        v["snapshots"] = double(at.snapshot);
        mon.visit([&](const std::string& k, auto& x) { v["monitor." + k] = double(x); });
        sum.visit([&](const std::string& k, auto& x) { v["summary." + k] = double(x); });
        return v;
    };

    if (!io.restart.empty()) at = resume_from(io.restart, s, sol, mon, sum);
    // The writer's files; a failure to open them stops every process (together).
    auto open_files = [&] {
        if (!io.writer) return;
        if (io.restart.empty()) {
            series.open(out / "series.csv", std::ios::trunc);
            write_header(series, s);
            times.open(out / "snapshots" / "times.csv", std::ios::trunc);
            times << "index,time_us,time_after_contact_us\n";
        } else {
            keep_lines(out / "series.csv", at.rows + 1);
            keep_lines(out / "snapshots" / "times.csv", at.snapshot + 1);
            series.open(out / "series.csv", std::ios::app);
            times.open(out / "snapshots" / "times.csv", std::ios::app);
        }
        // Exact numbers: a resumed run's rows match the uninterrupted run's.
        gimlet::io::exact_numbers(series);
        gimlet::io::exact_numbers(times);
        if (!series || !times) throw std::runtime_error("cannot write the series in " + out.string());
    };
    if (io.processes) io.processes->together(open_files);
    else open_files();
    // The snapshots' series, on every process (on many, the first writes the .pvd and each
    // snapshot is one piece a process).
    if (io.restart.empty()) pvd.emplace(pvd_path, io.processes);
    else pvd.emplace(gimlet::io::pvd_writer::resume(pvd_path, double(sol.time()), io.processes));
    // The whole run's particles (collective).
    const auto whole_count = [&] {
        const std::uint64_t mine = sol.particles().size();
        return io.processes ? io.processes->sum(mine) : mine;
    };
    const std::uint64_t particles = whole_count();
    if (io.writer) std::printf("cavity_collapse: HMX blocks at +-%.0f m/s, %s %.2f mm, cell %.3f mm, %s contact, "
                "self-contact %s, %zu particles, %s %.2f us to %.2f us\n",
                s.velocity,
                s.geometry == geometry_kind::plane          ? "cavity radius"
                : s.geometry == geometry_kind::axisymmetric
                    ? (s.free_side() ? "axisymmetric, spherical pore radius"
                                     : "axisymmetric, side held (the array's cell), spherical pore radius")
                : s.free_side() ? "3-D (a quarter of the cylinders), spherical pore radius"
                                : "3-D (the square array's cell), spherical pore radius",
                s.radius * 1e3, s.cell * 1e3, name_of(s.contact).c_str(), s.self_contact ? "on" : "off",
                static_cast<std::size_t>(particles),
                io.restart.empty() ? "from" : "resumed at", double(sol.time()) * 1e6, s.end * 1e6);
    std::fflush(stdout);

    // The last sample and its step: the per-step tracking below takes its peaks from it at that
    // step instead of searching the hot spot a second time.
    sample_of<typename Space::vector> sampled;
    std::uint64_t sampled_step = std::numeric_limits<std::uint64_t>::max();
    auto take_sample = [&](const auto& so) {
        const auto r = mon.measure(so);
        if (io.writer) write_row(series, r, s);
        sum.add(r, s);
        ++at.rows;
        at.last_sample = double(so.time());
        sampled = r, sampled_step = so.steps();
    };
    auto samples = gimlet::diagnostics::every_time(s.sample_every, take_sample);
    // The hot spot's peak and the hot material every step: a jet's landing can be shorter than
    // a sample interval (0.1 us at 0.25 mm cells). Called after the samples (run_until below).
    auto peaks = gimlet::diagnostics::every_steps(1, [&](const auto& so) {
        sum.track(so.steps() == sampled_step ? sampled : mon.peaks(so, sum.max_hot_spot));
    });
    // Without periodic snapshots, the one at or after the last listed time is the run's last.
    const double last_listed = s.snapshots_after_contact.empty()
                                   ? std::numeric_limits<double>::infinity()
                                   : contact_time(s) + *std::max_element(s.snapshots_after_contact.begin(),
                                                                         s.snapshots_after_contact.end());
    auto write_snapshot = [&](const auto& so) {
        char name[32];
        std::snprintf(name, sizeof name, "map_%04zu.csv", at.snapshot);
        example::write_particle_map(out / "snapshots" / name, so, cavity_collapse::parallel_from, axis_coordinate(s));
        pvd->write(vtp, so);  // collective on many processes: a failure on any stops all
        const double after_contact_us = (double(so.time()) - contact_time(s)) * 1e6;
        if (io.writer) times << at.snapshot << ',' << double(so.time()) * 1e6 << ',' << after_contact_us << '\n';
        if (io.figures) io.figures->map(at.snapshot, after_contact_us, s.snapshot_every <= 0 && double(so.time()) >= last_listed);
        ++at.snapshot;
    };
    auto snapshots = gimlet::diagnostics::every_time(s.snapshot_every > 0 ? s.snapshot_every : 2 * s.end,
                                                     [&](const auto& so) {
        if (s.snapshot_every > 0) write_snapshot(so);
    });
    listed_times listed{{}, at.listed_next, write_snapshot};
    for (double t : s.snapshots_after_contact) listed.at.push_back(contact_time(s) + t);
    if (!io.restart.empty()) samples.resume(at.next_sample), snapshots.resume(at.next_snapshot);
    checkpointer ckpt{[&](double t) {
                          series.flush(), times.flush();
                          auto v = save_values();
                          v["next_sample_s"] = samples.next();
                          v["next_snapshot_s"] = snapshots.next();
                          v["last_sample_s"] = at.last_sample;
                          v["next_listed_snapshot"] = double(listed.next);
                          v["listed_snapshots"] = double(listed.at.size());
                          gimlet::io::save_checkpoint(io.checkpoint, sol, v);
                          if (io.writer) std::printf("  checkpoint at %.3f us: %s\n", t * 1e6, io.checkpoint.string().c_str());
                          std::fflush(stdout);
                      },
                      io.checkpoint_at, io.checkpoint.empty() || double(sol.time()) >= io.checkpoint_at};
    gimlet::diagnostics::progress bar(std::cerr, s.end);
    const auto start = std::chrono::steady_clock::now();
    // A run the library stops (EOS singularity, inverted particle, ...) still leaves its series
    // and a summary that says where it stopped; the exit status tells scripts it did not finish.
    std::string status = "completed";
    try {
        if (io.quiet || !io.writer) sol.run_until(s.end, samples, peaks, snapshots, listed, ckpt);
        else sol.run_until(s.end, samples, peaks, snapshots, listed, ckpt, bar);
    } catch (const gimlet::numerical_error& e) {
        status = std::string("stopped: ") + e.what();
        std::replace(status.begin(), status.end(), ',', ';');  // one CSV cell
        if (io.writer) std::fprintf(stderr, "cavity_collapse: %s\n", e.what());
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (at.last_sample < double(sol.time())) take_sample(sol);  // the series always ends at the end time
    if (!io.writer) return status == "completed" ? 0 : 3;
    series.close();
    times.close();
    if (!series || !times) throw std::runtime_error("could not write the series in " + out.string());

    write_summary(out / "summary.csv", s, sol, sum, mon, wall, status, particles,
                  io.processes ? io.processes->size() : 1);
    print_report(s, sol, sum, mon, wall);
    return status == "completed" ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
    const example::run_processes procs(argc, argv);
    const bool writer = procs.writer();  // one process writes, prints and draws
    try {
    // --quiet is a switch without a value; the other flags are name-value pairs.
    std::vector<char*> rest{argv[0]};
    bool quiet = false, figures_on = true;
    for (int i = 1; i < argc; ++i) {
        if (std::string(argv[i]) == "--quiet") quiet = true;
        else if (std::string(argv[i]) == "--no-figures") figures_on = false;
        else rest.push_back(argv[i]);
    }
    example::cli args(static_cast<int>(rest.size()), rest.data(), cavity_collapse::usage);
    settings s = cavity_collapse::read_settings(args);
    run_files io;
    io.quiet = quiet;
    io.writer = writer;
    // The writer creates the directories and probes them; the others only take the flag. Where it
    // cannot, every process stops (together), none waits for it in the run's exchanges.
    const auto output = [&] {
        io.out = writer ? args.directory("output", "results/cavity_collapse") : std::filesystem::path(args.path("output"));
        if (io.out.empty()) io.out = "results/cavity_collapse";
        if (writer) std::filesystem::create_directories(io.out / "snapshots");
    };
    procs.together(output);
    io.processes = procs.for_solver();
    io.checkpoint = args.path("checkpoint");
    io.checkpoint_at = 1e-6 * args.real("checkpoint-at-us", 0.0, 0.0, 1000.0, true);
    io.restart = args.path("restart");
    args.finish();
    validate(s);
    if (!io.checkpoint.empty() && io.checkpoint_at >= s.end)
        throw std::invalid_argument("--checkpoint-at-us = " + std::to_string(io.checkpoint_at * 1e6) +
                                    " is invalid; valid range: [0, --end-us) so the run reaches it");

    std::string plot;  // the command that draws the figures after the run
    std::optional<plotter> figures;
    const auto log = io.out / "plot.log";  // the plotter's errors
    if (figures_on && writer) {
        // Debian's python3 carries matplotlib from the system packages; prefer it over another on PATH.
        const std::string python = std::system("test -x /usr/bin/python3") == 0 ? "/usr/bin/python3" : "python3";
        const std::string script = shell_word(std::string(GIMLET_EXAMPLE_DIR) + "/plot.py");
        plot = python + " " + script + " " + shell_word(io.out.string());
        std::ostringstream cell;  // as summary.csv has it: the maps' particle spacing is half of it
        gimlet::io::exact_numbers(cell);
        cell << s.cell * 1e3;
        figures.emplace(python + " " + script + " --follow " + cell.str() + " " + shell_word(io.out.string()), log);
        io.figures = &*figures;
    }

    // Every flag combination a user may give is one binary of two solvers: the single field, and
    // a multi-field law with the temperature chosen at run time (chosen_law, chosen_temperature in
    // cavity_collapse.hpp), instead of six (3 contact laws x 2 temperatures).
    // The axisymmetric and 3-D runs are one more solver each, of the multi-field laws only (validate()).
    const int rc = s.geometry == geometry_kind::axisymmetric ? run<A>(s, io, chosen_law(s.contact))
                   : s.geometry == geometry_kind::three_d   ? run<S3>(s, io, chosen_law(s.contact))
                   : s.contact == contact_kind::single      ? run<S>(s, io, gimlet::contact::single_field{})
                                                            : run<S>(s, io, chosen_law(s.contact));
    if (!figures) return rc;
    if (figures->finish())
        std::printf("  figures: %s (series.png, hot_material.png, map_*.png, maps_*.png); ParaView: %s\n", io.out.string().c_str(),
                    (io.out / "snapshots" / "particles.pvd").string().c_str());
    else
        std::printf("  (figures not drawn: needs python3 with matplotlib%s; run %s)\n",
                    std::filesystem::exists(log) ? ("; its errors are in " + log.string()).c_str() : "",
                    plot.c_str());
    std::printf("  series: %s\n", (io.out / "series.csv").string().c_str());
    return rc;
    } catch (const std::exception& e) {
        // Every process stops alike (a bad flag on all, a failure agreed on all): one says why.
        if (writer) std::cerr << "cavity_collapse: " << e.what() << '\n';
        return 1;
    }
}
