// SPDX-License-Identifier: MIT
// Hard cases, coarse but real: runs at the edge of what the method does. Each
// one watches the whole run (every step) and asserts
//   * every particle field finite (position, velocity, stress, F, e, temperature), det F > 0;
//   * no particle lost: the count is unchanged and every particle is inside the grid;
//   * momentum conserved to round-off, relative to |m v| of one body;
//   * total energy E = kinetic + internal never rises above its start by more than a stated
//     tolerance; what it loses (contact, grid transfers) is printed.
// What "internal" holds (material/update.hpp): e integrates the whole stress power
// de = dt/rho (sigma^n + sigma^{n+1})/2 : D with sigma = s - (P + q) I, so it holds the
// pressure work, the artificial-viscosity work q (the shock's heat) and the deviatoric work,
// elastic (stored) and plastic (heat) alike. The temperature is a function of these, not an
// extra energy, so E = kinetic + sum m_p e_p is the whole energy of the system.
// docs/robustness.md ("Hard cases") lists the cases, bounds and measured values.
#include "cavity_collapse/cavity_collapse.hpp"

#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <vector>

using Catch::Matchers::Contains;
using S = gimlet::space<2>;
using hmx = gimlet::presets::hmx_material<>;
using elastic = gimlet::elastic_material;

namespace {

const double inf = std::numeric_limits<double>::infinity();

/// What one run came to: filled by watch, checked by check_invariants.
struct record {
    std::string name;
    std::size_t count0 = 0;
    double momentum_scale = 0;  // |m v| of one body (kg m/s per metre)
    bool x_momentum_only = false;  // a wall takes up the y momentum: check x alone
    S::vector p0 = S::vector::Zero();
    double e0 = 0;
    std::size_t samples = 0;
    bool finite = true, inside = true, count_kept = true;
    std::string first_problem;
    double min_det_f = inf, max_det_f = 0;
    double max_speed = 0;
    double max_momentum_error = 0;  // |P - P0| / momentum_scale
    double max_energy_rise = -inf;  // max (E - E0) / E0 after the start
    double min_energy_change = inf; // min (E - E0) / E0
    double final_energy_change = 0;
    double max_stress = 0;          // Pa, largest |sigma_ij| (sigma_zz included)
    double max_compression = 0;     // largest eta = 1 - det F
    std::uint64_t steps = 0;
    double time = 0, seconds = 0;

    void note(const std::string& what) {
        if (first_problem.empty()) first_problem = what;
    }
};

/// Checks every particle of `sol` and the conserved sums; momentum_scale and the start values
/// are taken at the first call.
template <class Solver>
void watch(const Solver& sol, record& r) {
    using namespace gimlet;
    const auto& ps = sol.particles();
    const bool first = r.samples == 0;
    if (first) {
        r.count0 = ps.size();
        r.p0 = diagnostics::linear_momentum(sol);
        r.e0 = diagnostics::kinetic_energy(sol) + diagnostics::internal_energy(sol);
    }
    ++r.samples;
    if (ps.size() != r.count0) r.count_kept = false, r.note("particle count changed");
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const auto p = ps[i];
        const auto& x = p.template get<fields::position>();
        const auto& v = p.template get<fields::velocity>();
        const auto& F = p.template get<fields::deformation_gradient>();
        const auto sigma = stress3(p);
        bool ok = x.allFinite() && v.allFinite() && F.allFinite() && sigma.allFinite() &&
                  std::isfinite(p.template get<fields::specific_internal_energy>());
        if constexpr (Solver::store_type::template has<fields::temperature>)
            ok = ok && std::isfinite(p.template get<fields::temperature>());
        if (!ok) {
            r.finite = false;
            r.note("particle " + std::to_string(i) + ": a field is not finite");
            continue;
        }
        const double j = F.determinant();
        r.min_det_f = std::min(r.min_det_f, j);
        r.max_det_f = std::max(r.max_det_f, j);
        r.max_compression = std::max(r.max_compression, 1.0 - j);
        r.max_speed = std::max(r.max_speed, double(v.norm()));
        r.max_stress = std::max(r.max_stress, double(sigma.cwiseAbs().maxCoeff()));
        if (!sol.background_grid().inside(x)) r.inside = false, r.note("particle " + std::to_string(i) + " off the grid");
    }
    const double e = diagnostics::kinetic_energy(sol) + diagnostics::internal_energy(sol);
    const double de = (e - r.e0) / r.e0;
    if (!first) r.max_energy_rise = std::max(r.max_energy_rise, de);
    r.min_energy_change = std::min(r.min_energy_change, de);
    r.final_energy_change = de;
    const S::vector dp = diagnostics::linear_momentum(sol) - r.p0;
    r.max_momentum_error = std::max(r.max_momentum_error, (r.x_momentum_only ? std::abs(dp[0]) : dp.norm()) / r.momentum_scale);
    r.steps = sol.steps();
    r.time = double(sol.time());
}

void print(const record& r) {
    std::printf("hard case %-34s %6llu steps %8.2f us %6.2f s | energy: max rise %+.2e, min %+.2e, end %+.2e | "
                "momentum err %.1e | det F [%.4f, %.4f] | max |v| %.0f m/s | max |sigma| %.3g Pa\n",
                r.name.c_str(), static_cast<unsigned long long>(r.steps), r.time * 1e6, r.seconds,
                r.max_energy_rise, r.min_energy_change, r.final_energy_change, r.max_momentum_error, r.min_det_f,
                r.max_det_f, r.max_speed, r.max_stress);
    std::fflush(stdout);
}

/// The assertions every case shares: finite fields, det F > 0, no particle lost, momentum to
/// `momentum_bound` of one body's |m v|, total energy never above (1 + energy_rise_bound) E0.
void check_invariants(const record& r, double momentum_bound, double energy_rise_bound) {
    INFO(r.name << ": " << r.first_problem);
    CHECK(r.samples > 1);
    CHECK(r.finite);
    CHECK(r.count_kept);
    CHECK(r.inside);
    CHECK(r.min_det_f > 0);
    CHECK(r.max_momentum_error <= momentum_bound);
    CHECK(r.max_energy_rise <= energy_rise_bound);
}

/// Runs `sol` to `t_end`, watching every step; fills r's counters and timing.
template <class Solver, class... More>
void run_watched(Solver& sol, double t_end, record& r, More&... more) {
    const auto start = std::chrono::steady_clock::now();
    gimlet::diagnostics::every_steps w(1, [&r](const auto& s) { watch(s, r); });
    sol.run_until(t_end, w, more...);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

gimlet::solver_options<S> one_thread() {
    gimlet::solver_options<S> opt;
    opt.threads = 1;
    return opt;
}

// ---- the cavity scenes ---------------------------------------------------------------------

using cavity_solver = gimlet::solver<S, gimlet::shape::ugimp, cavity_collapse::material, gimlet::contact::distance>;

struct cavity_run {
    record r;
    cavity_collapse::summary sum;
    cavity_collapse::sample last;
};

cavity_run run_cavity(const std::string& name, double velocity, double after_contact) {
    cavity_collapse::settings s;
    s.velocity = velocity;
    s.radius = 10e-3;
    s.cell = 2e-3;
    s.end = cavity_collapse::contact_time(s) + after_contact;
    s.threads = 1;
    cavity_solver sol(cavity_collapse::make_scene(s), one_thread());
    cavity_run out;
    out.r.name = name;
    out.r.momentum_scale = 0.5 * gimlet::diagnostics::total_mass(sol) * velocity;
    cavity_collapse::monitor mon(s);
    auto samples = gimlet::diagnostics::every_time(0.5e-6, [&](const auto& so) {
        out.last = mon.measure(so);
        out.sum.add(out.last, s);
    });
    run_watched(sol, s.end, out.r, samples);
    return out;
}

// ---- uniaxial HMX impact (as examples/impact_1d, any speed) ------------------------------------

/// Two HMX blocks of `length` meeting at +-v along y from `gap` cells apart: a periodic strip 4
/// cells wide (head-on, in uniaxial strain), blocks 5 mm wide with free sides, or such blocks each
/// also sliding at v/2 along x (oblique); the library's viscosity unless b1 and b2 say otherwise.
struct gap_impact {
    enum geometry { strip, blocks, oblique } shape = strip;
    double velocity = 1000, gap = 2.5;  // m/s each block; cells
    gimlet::update_scheme scheme = gimlet::update_scheme::musl;
    int consistent_mass = 0;
    double b1 = 0.06, b2 = 1.2;  // viscosity::bulk's linear and quadratic coefficients
    double closure = gimlet::solver_options<S>{}.contact_closure;
};
/// The solver of a gap_impact on cells of `cell` at `cfl`; the grid leaves room for the blocks
/// to move v t_end outwards (and sideways).
template <class Contact>
gimlet::solver<S, gimlet::shape::ugimp, hmx, Contact> make_impact(const gap_impact& g, double cell, double length,
                                                                  double t_end, double cfl = 0.4) {
    const double gap = g.gap * cell, v = g.velocity;
    const double width = g.shape == gap_impact::strip ? 4 * cell : 5e-3;
    const double margin = cell * std::ceil(v * t_end / cell + 10), side = g.shape == gap_impact::strip ? 0.0 : margin;
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector(-side, -length - gap - margin);
    gs.upper = S::vector(width + side, length + gap + margin);
    gs.cell = cell;
    gs.bc = {g.shape == gap_impact::strip ? gimlet::boundary::periodic : gimlet::boundary::free, gimlet::boundary::free};
    gimlet::scene::scene<S, hmx> sc(gs);
    const auto m = gimlet::presets::make_hmx({}, gimlet::viscosity::bulk(g.b2, g.b1));
    const double vx = g.shape == gap_impact::oblique ? 0.5 * v : 0.0;
    sc.add_body(gimlet::scene::box<S>(S::vector(0.0, 0.5 * gap), S::vector(width, length + 0.5 * gap)), m,
                S::vector(-vx, -v), 2, "upper block");
    sc.add_body(gimlet::scene::box<S>(S::vector(0.0, -length - 0.5 * gap), S::vector(width, -0.5 * gap)), m,
                S::vector(vx, v), 2, "lower block");
    auto opt = one_thread();
    opt.scheme = g.scheme;
    opt.cfl = cfl;
    opt.consistent_mass_iterations = g.consistent_mass;
    opt.contact_closure = g.closure;
    return gimlet::solver<S, gimlet::shape::ugimp, hmx, Contact>(sc, opt);
}

/// Two HMX slabs of `length` in a periodic strip 4 cells wide, touching at t = 0, hit each other
/// at +-v along y (USF, as impact_1d: it keeps the energy of a shock).
template <class Contact = gimlet::contact::single_field>
gimlet::solver<S, gimlet::shape::ugimp, hmx, Contact> make_strip(double velocity, double cell, double length,
                                                                 double t_end,
                                                                 gimlet::update_scheme scheme = gimlet::update_scheme::usf,
                                                                 double cfl = 0.4) {
    gap_impact g;
    g.velocity = velocity;
    g.gap = 0;
    g.scheme = scheme;
    return make_impact<Contact>(g, cell, length, t_end, cfl);
}

// ---- the sparse cloud ------------------------------------------------------------------------

template <class Contact = gimlet::contact::single_field>
using cloud_solver = gimlet::solver<S, gimlet::shape::ugimp, elastic, Contact>;
constexpr double cloud_cell = 1e-3, steel_density = 7800, steel_young = 200e9, steel_nu = 0.3, fragment_speed = 800;

/// A steel-like elastic block 8 x 8 cells at rest in a doubly periodic grid of 24 x 24 cells, and
/// twelve single particles (fragments, a block particle's mass each) on a ring 10 cells around
/// it, every other one flying at the block, the rest away from it through empty cells. With
/// light_a or light_b > 0, one more single particle each, of steel's wave speed and that fraction
/// of a fragment's mass: a at lattice point (2, 20) flying at (700, -300) m/s, b at (20, 2) at
/// (-500, 400) m/s, both across the fragments' paths.
/// An empty scene on a doubly periodic grid of nx x ny cells of cloud_cell.
gimlet::scene::scene<S, elastic> periodic_scene(int nx, int ny) {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector(nx * cloud_cell, ny * cloud_cell);
    gs.cell = cloud_cell;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::periodic};
    return gimlet::scene::scene<S, elastic>(gs);
}

/// `options` may change the solver options (the cut-off is set before it).
template <class Contact = gimlet::contact::single_field, class Options = void (*)(gimlet::solver_options<S>&)>
cloud_solver<Contact> make_cloud(double mass_cutoff, double light_a = 0, double light_b = 0,
                                 Options options = [](gimlet::solver_options<S>&) {}) {
    auto sc = periodic_scene(24, 24);
    const auto steel = gimlet::make_elastic_material(steel_density, steel_young, steel_nu);
    sc.add_body(gimlet::scene::box<S>(S::vector(8 * cloud_cell, 8 * cloud_cell), S::vector(16 * cloud_cell, 16 * cloud_cell)),
                steel, S::vector::Zero(), 2, "block");
    // One particle each: a box smaller than the particle spacing (h/2) around one lattice point.
    auto single = [&](double i, double j, const S::vector& v, const elastic& mat, const std::string& name) {
        const S::vector c((i + 0.25) * cloud_cell, (j + 0.25) * cloud_cell);
        sc.add_body(gimlet::scene::box<S>(c - S::vector::Constant(0.2 * cloud_cell), c + S::vector::Constant(0.2 * cloud_cell)),
                    mat, v, 2, name);
    };
    for (int k = 0; k < 12; ++k) {
        const double a = k * std::numbers::pi / 6;
        const S::vector dir(std::cos(a), std::sin(a));
        const S::vector at = S::vector::Constant(12.0) + 10.0 * dir;
        single(std::floor(at[0]), std::floor(at[1]), (k % 2 ? 1.0 : -1.0) * fragment_speed * dir, steel,
               "fragment " + std::to_string(k));
    }
    auto light = [](double ratio) { return gimlet::make_elastic_material(steel_density * ratio, steel_young * ratio, steel_nu); };
    if (light_a > 0) single(2, 20, S::vector(700, -300), light(light_a), "light a");
    if (light_b > 0) single(20, 2, S::vector(-500, 400), light(light_b), "light b");
    auto opt = one_thread();
    opt.mass_cutoff = mass_cutoff;
    options(opt);
    return cloud_solver<Contact>(sc, opt);
}

double fragment_momentum() { return steel_density * (cloud_cell / 2) * (cloud_cell / 2) * fragment_speed; }

}  // namespace

// ---------------------------------------------------------------------------------------------

TEST_CASE("hard case: cavity collapse with jetting at 700 m/s through full closure", "[robustness][hard]") {
    // The paper's scene (R = 10 mm) at 2 mm cells, 3372 particles, distance-switched contact,
    // MUSL, to 25 us after contact: the jets land on the far walls about 17 us after contact.
    const auto c = run_cavity("cavity 700 m/s, R 10 mm", 700.0, 25e-6);
    print(c.r);
    std::printf("  first contact %.2f us, collapse %.2f / %.2f us, closure %.2f / %.2f us, max wall velocity %.0f m/s, "
                "hot spot %.0f K; energy lost %.1f %%\n",
                c.sum.first_contact * 1e6, c.sum.collapse[0] * 1e6, c.sum.collapse[1] * 1e6, c.sum.closure[0] * 1e6,
                c.sum.closure[1] * 1e6, c.sum.max_wall_relative_velocity, c.sum.max_hot_spot,
                -100 * c.r.final_energy_change);
    // Momentum: the total is zero (symmetric impact); round-off over 3400 particles and 400
    // steps is below 1e-13 of one block's |m v|. Energy: exactly kept in free flight, then only
    // lost (contact, transfers); 1e-6 is the stated round-off tolerance on a rise.
    check_invariants(c.r, 1e-12, 1e-6);
    // Measured loss 14 %: most of it where the jet lands, over-compressed and hot. The bound
    // guards against a regression, it is not a physical limit.
    CHECK(c.r.final_energy_change > -0.20);
    // Both cavities collapsed and closed, after the contact.
    CHECK(c.sum.first_contact > 0);
    CHECK(c.sum.collapse[0] > c.sum.first_contact);
    CHECK(c.sum.collapse[1] > c.sum.first_contact);
    CHECK(c.sum.closure[0] > 0);
    CHECK(c.sum.closure[1] > 0);
    CHECK(c.r.time > std::max(c.sum.closure[0], c.sum.closure[1]) + 4e-6);  // a few us past closure
}

// `long` (release only); its coarse twin, the same run to 25 us after contact, follows it.
TEST_CASE("hard case: the long weak-shock run, 150 m/s, 180 us after contact", "[robustness][hard][long]") {
    // R = 10 mm at 2 mm cells: first contact, separation, the secondary impact, final separation.
    const auto c = run_cavity("weak shock 150 m/s, 180 us", 150.0, 180e-6);
    print(c.r);
    std::printf("  first contact %.2f us, separation %.2f us, D_max %.3f mm at %.2f us, secondary impact %.2f us, "
                "final D %.3f mm; energy lost %.1f %%\n",
                c.sum.first_contact * 1e6, c.sum.separation * 1e6, c.sum.D_max * 1e3, c.sum.t_D_max * 1e6,
                c.sum.secondary_impact * 1e6, c.last.D * 1e3, -100 * c.r.final_energy_change);
    check_invariants(c.r, 1e-12, 1e-6);
    CHECK(c.r.final_energy_change > -0.08);  // measured 4.8 % lost over 860 steps; regression guard
    CHECK(c.sum.first_contact > 0);
    CHECK(c.sum.separation > c.sum.first_contact);
    CHECK(c.sum.secondary_impact > c.sum.separation);
    CHECK(c.last.D > 0.25 * 1e-3);  // separated at the end (more than a quarter particle spacing apart)
}

// The coarse twin of the run above, for asan-ubsan: the same scene to 25 us after contact, through
// the first contact (13.0 us) and the first separation (33.6 us), with the same invariants every
// step.
TEST_CASE("hard case: the weak-shock run to the first separation, 150 m/s, 25 us after contact",
          "[robustness][hard]") {
    const auto c = run_cavity("weak shock 150 m/s, 25 us", 150.0, 25e-6);
    print(c.r);
    std::printf("  first contact %.2f us, separation %.2f us; energy lost %.1f %%\n", c.sum.first_contact * 1e6,
                c.sum.separation * 1e6, -100 * c.r.final_energy_change);
    check_invariants(c.r, 1e-12, 1e-6);
    // The energy never rises (checked every step), so the long run's guard holds here a fortiori
    // (measured 4.0 % lost at 25 us after contact).
    CHECK(c.r.final_energy_change > -0.08);
    CHECK(c.sum.first_contact > 0);
    CHECK(c.sum.separation > c.sum.first_contact);
}

TEST_CASE("hard case: uniaxial HMX impact towards the Mie-Grueneisen singularity", "[robustness][hard][eos]") {
    // Slabs 5 mm long at 0.25 mm cells (USF, as examples/impact_1d). The singularity check stops
    // the run once 1 - s eta <= 0.05 (eta >= 0.365); the steady Hugoniot state of a symmetric
    // impact has 1 - s eta = c0 / (c0 + s v), which reaches 0.05 at v = 20 km/s.
    const double cell = 0.25e-3, length = 5e-3, s_slope = 2.6;
    auto t_end = [&](double v) { return 0.6 * length / (2740.0 + s_slope * v); };  // shock 60 % through

    // The strips that run through: 2000 m/s (steady Hugoniot state eta = 0.129) and 4000 m/s
    // (1 - s eta = 0.21 there). Their first steps over-compress the contact plane: measured eta
    // 0.3248 and 0.3645 (1 - s eta = 0.052); the stop comes between 4000 and 5000 m/s.
    for (const double v : {2000.0, 4000.0}) {
        DYNAMIC_SECTION(v << " m/s: runs through, stays finite and balanced, short of the limit") {
            auto sol = make_strip(v, cell, length, t_end(v));
            record r;
            r.name = "strip " + std::to_string(int(v)) + " m/s";
            r.momentum_scale = 0.5 * gimlet::diagnostics::total_mass(sol) * v;
            run_watched(sol, t_end(v), r);
            print(r);
            std::printf("  max eta %.4f (1 - s eta = %.4f); energy lost %.1f %%\n", r.max_compression,
                        1 - s_slope * r.max_compression, -100 * r.final_energy_change);
            check_invariants(r, 1e-12, 1e-6);
            CHECK(r.time == Approx(t_end(v)));
            CHECK(r.max_compression > 0.3);                 // close to the limit
            CHECK(1 - s_slope * r.max_compression > 0.05);  // but short of the stop
        }
    }
    // Beyond: 5000 m/s has a steady state at 1 - s eta = 0.17, but the impact's first steps
    // over-compress the particles at the contact plane past the margin (step 23); 30 km/s is
    // beyond the limit on the Hugoniot itself and jumps past 1/s within two steps. Both must stop
    // with the EOS's numerical_error naming the particle, its position and the step, every state
    // before it finite.
    for (const double v : {5000.0, 30000.0}) {
        DYNAMIC_SECTION(v << " m/s: stops cleanly at the singularity") {
            auto sol = make_strip(v, cell, length, t_end(v));
            record r;
            r.name = "strip " + std::to_string(int(v)) + " m/s";
            r.momentum_scale = 0.5 * gimlet::diagnostics::total_mass(sol) * v;
            std::string message;
            try {
                run_watched(sol, t_end(v), r);
            } catch (const gimlet::numerical_error& e) {
                message = e.what();
            }
            print(r);
            std::printf("  stopped: %s\n", message.c_str());
            INFO(message);
            CHECK_THAT(message, Contains("reached the Mie-Grueneisen limit") && Contains("particle") &&
                                    Contains("step") && Contains(") m") && Contains("singular at eta = 1/s"));
            check_invariants(r, 1e-12, 1e-6);  // every step up to the stop
        }
    }
}

// ---- energy in strong impacts, every contact and scheme --------------------------------------

// The largest (E - E0) / E0 over a uniaxial strip run (5 mm slabs, 0.25 mm cells, to 60 % of the
// shock's transit, as above), E = kinetic + internal, checked every step.
template <class Contact>
double strip_energy_rise(double v, gimlet::update_scheme scheme, double cfl = 0.4) {
    const double cell = 0.25e-3, length = 5e-3, t_end = 0.6 * length / (2740.0 + 2.6 * v);
    auto sol = make_strip<Contact>(v, cell, length, t_end, scheme, cfl);
    auto energy = [&] { return gimlet::diagnostics::kinetic_energy(sol) + gimlet::diagnostics::internal_energy(sol); };
    const double e0 = energy();
    double rise = -inf;
    while (sol.time() < t_end) {
        sol.step(std::min(sol.stable_time_step(), t_end - sol.time()));
        rise = std::max(rise, energy() / e0 - 1);
    }
    return rise;
}

const char* scheme_label(gimlet::update_scheme s) {
    return s == gimlet::update_scheme::musl ? "MUSL" : s == gimlet::update_scheme::usl ? "USL " : "USF ";
}

// With the distance or Bardenhagen contact, or under USF, the energy never rises
// above its start (the first contact step is an inelastic impact at the shared nodes). MUSL and
// USL with a single field do create energy in a strong impact: measured at CFL 0.4, MUSL +1.37,
// +1.84, +4.89 % at 300, 1000, 2500 m/s, USL +1.10, +1.41, +2.12 %. It is the schemes' own
// time-discretisation error, first order in dt: at 2500 m/s MUSL gives +4.89, +2.23, +1.06,
// +0.51 % at CFL 0.4, 0.2, 0.1, 0.05 (and halves with the cell at a fixed CFL at 300 m/s: 2.74,
// 1.37, 0.68 % at 0.5, 0.25, 0.125 mm), so the bound stated for them is 5.5 % at CFL 0.4 and
// 0.25 mm, and the test checks the order (docs/robustness.md).
TEST_CASE("hard case: energy in strong 1-D impacts for every contact and scheme up to 2500 m/s",
          "[robustness][hard][energy]") {
    using gimlet::update_scheme;
    for (const auto scheme : {update_scheme::musl, update_scheme::usl, update_scheme::usf}) {
        for (const double v : {300.0, 1000.0, 2500.0}) {
            const double single = strip_energy_rise<gimlet::contact::single_field>(v, scheme);
            const double bardenhagen = strip_energy_rise<gimlet::contact::bardenhagen>(v, scheme);
            const double distance = strip_energy_rise<gimlet::contact::distance>(v, scheme);
            std::printf("energy, %s %4.0f m/s: largest (E - E0)/E0: single %+.4f %%, bardenhagen %+.4f %%, "
                        "distance %+.4f %%\n",
                        scheme_label(scheme), v, 100 * single, 100 * bardenhagen, 100 * distance);
            INFO(scheme_label(scheme) << " " << v << " m/s");
            CHECK(bardenhagen <= 1e-12);
            CHECK(distance <= 1e-12);
            if (scheme == update_scheme::usf) CHECK(single <= 1e-12);
            else CHECK(single <= 0.055);
        }
    }
    // First order in dt: the rise halves with the Courant number (ratios 0.455 and 0.475 measured).
    const double r4 = strip_energy_rise<gimlet::contact::single_field>(2500, update_scheme::musl, 0.4);
    const double r2 = strip_energy_rise<gimlet::contact::single_field>(2500, update_scheme::musl, 0.2);
    const double r1 = strip_energy_rise<gimlet::contact::single_field>(2500, update_scheme::musl, 0.1);
    std::printf("energy, MUSL single field 2500 m/s at CFL 0.4, 0.2, 0.1: %+.3f, %+.3f, %+.3f %%\n", 100 * r4,
                100 * r2, 100 * r1);
    CHECK(r2 / r4 > 0.4);
    CHECK(r2 / r4 < 0.6);
    CHECK(r1 / r2 > 0.4);
    CHECK(r1 / r2 < 0.6);
}

// ---- energy in impacts from a gap: the contact's step -------------------------------------------

// A gap_impact of blocks 5 mm thick on 0.25 mm cells, to 60 % of the shock's transit after they
// meet, in steps the solver chooses
// (solver::step(): solver_options::contact_closure shortens those in which the fields close in).
// The largest (E - E0) / E0, E = kinetic + internal, checked every step: before contact the
// blocks fly freely and E is E0 to round-off, so any rise is energy the contact step created.
template <class Contact>
double gap_energy_rise(const gap_impact& g) {
    const double cell = 0.25e-3, length = 5e-3, gap = g.gap * cell, v = g.velocity;
    const double t_end = 0.5 * gap / v + 0.6 * length / (2740.0 + 2.6 * v);
    auto sol = make_impact<Contact>(g, cell, length, t_end);
    auto energy = [&] { return gimlet::diagnostics::kinetic_energy(sol) + gimlet::diagnostics::internal_energy(sol); };
    const double e0 = energy();
    double rise = -inf;
    while (sol.time() < t_end) {
        if (sol.stable_time_step() < t_end - sol.time()) sol.step();
        else sol.step(t_end - sol.time());
        rise = std::max(rise, energy() / e0 - 1);
    }
    return rise;
}

// At the library's defaults (lumped mass, the Abaqus viscosity (0.06, 1.2)) under MUSL, USF and
// USL, and at the examples' (k = 4, (0.12, 2.4)) under MUSL and USF: no law gains energy, head-on
// or oblique, from 300 to 2500 m/s, from two gaps (the step's phase against the engagement
// differs); 15 s, so release only. Measured without the contact's step (contact_closure = 0), over gaps of 1.5 to 4.5
// cells: the distance law gains up to +4.3 % (USL, 2500 m/s, the examples' viscosity), +2.7 %
// (USF) and +2.0 % at 1000 m/s (USL); Bardenhagen's up to +0.25 % (MUSL); k = 4 up to +1.9 %
// (USF, distance); at 0.25 cells a step, up to +3.0 % still (USF, k = 4). The first contact
// step makes it: a pair that closes a third of a cell in the step it engages takes that
// compression in one step (docs/equations.md, "Contact and the time step").
TEST_CASE("hard case: impacts from a gap, head-on and oblique, at every scheme: no contact law gains energy",
          "[robustness][hard][energy][long]") {
    using gimlet::update_scheme;
    struct setting {
        int k;
        double b1, b2;
        std::vector<update_scheme> schemes;
    };
    const setting settings[] = {{0, 0.06, 1.2, {update_scheme::musl, update_scheme::usf, update_scheme::usl}},
                                {4, 0.12, 2.4, {update_scheme::musl, update_scheme::usf}}};
    double most = -inf;
    for (const auto& st : settings)
        for (const auto scheme : st.schemes)
            for (const auto shape : {gap_impact::strip, gap_impact::blocks, gap_impact::oblique})
                for (const double v : {300.0, 1000.0, 2500.0})
                    for (const double gap : {1.5, 3.5}) {
                        gap_impact g;
                        g.shape = shape;
                        g.velocity = v;
                        g.gap = gap;
                        g.scheme = scheme;
                        g.consistent_mass = st.k;
                        g.b1 = st.b1;
                        g.b2 = st.b2;
                        const double distance = gap_energy_rise<gimlet::contact::distance>(g);
                        const double bardenhagen = gap_energy_rise<gimlet::contact::bardenhagen>(g);
                        most = std::max({most, distance, bardenhagen});
                        INFO(scheme_label(scheme) << ", k = " << st.k << ", " << (shape == gap_impact::strip ? "strip" : shape == gap_impact::blocks ? "blocks" : "oblique")
                                                  << ", " << v << " m/s, gap " << gap << " cells");
                        CHECK(distance <= 1e-12);
                        CHECK(bardenhagen <= 1e-12);
                    }
    std::printf("energy from a gap, every scheme, law and shape, 300-2500 m/s: largest (E - E0)/E0 %+.2e\n", most);
    // Without the contact's step the case fails (it can tell).
    gap_impact g;
    g.velocity = 2500;
    g.gap = 3.5;
    g.scheme = update_scheme::usf;
    g.consistent_mass = 4;
    g.b1 = 0.12;
    g.b2 = 2.4;
    g.closure = 0;
    const double off = gap_energy_rise<gimlet::contact::distance>(g);
    std::printf("  USF, k = 4, 2500 m/s, strip, distance law, without the contact's step: %+.3f %%\n", 100 * off);
    CHECK(off > 0.005);
    // And Bardenhagen's law (measured +0.15 %, MUSL).
    g.scheme = update_scheme::musl;
    const double off_b = gap_energy_rise<gimlet::contact::bardenhagen>(g);
    std::printf("  MUSL, k = 4, 2500 m/s, strip, Bardenhagen's law, without the contact's step: %+.3f %%\n", 100 * off_b);
    CHECK(off_b > 0.0005);
}

TEST_CASE("hard case: a block crossing hundreds of cells at high speed", "[robustness][hard]") {
    // An HMX block 6 mm x 6 mm, off the lattice by 0.3 mm, in a doubly periodic 16 mm x 16 mm grid
    // of 1 mm cells moves at (1500, 600) m/s for 200 us: 300 cells along x, 120 along y.
    const double cell = 1e-3, t_end = 200e-6;
    const S::vector v(1500.0, 600.0);
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector(16 * cell, 16 * cell);
    gs.cell = cell;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::periodic};
    gimlet::scene::scene<S, hmx> sc(gs);
    sc.add_body(gimlet::scene::box<S>(S::vector(5.3e-3, 5.3e-3), S::vector(11.3e-3, 11.3e-3)),
                gimlet::presets::make_hmx(), v, 2, "block");
    gimlet::solver<S, gimlet::shape::ugimp, hmx> sol(sc, one_thread());
    record r;
    r.name = "translation, 300 cells";
    r.momentum_scale = gimlet::diagnostics::total_mass(sol) * v.norm();
    run_watched(sol, t_end, r);
    print(r);
    // A rigid translation: energy and momentum to round-off, det F = 1, stress at round-off
    // (1 Pa is 2e-10 of G).
    check_invariants(r, 1e-12, 1e-12);
    CHECK(r.min_energy_change > -1e-12);
    CHECK(r.min_det_f > 1 - 1e-12);
    CHECK(r.max_det_f < 1 + 1e-12);
    CHECK(r.max_stress < 1.0);
    CHECK(v[0] * t_end / cell == Approx(300));
}

TEST_CASE("hard case: a body touching the grid edge", "[robustness][hard]") {
    const double cell = 1e-3, side = 10e-3, v = 300;
    const auto m = gimlet::presets::make_hmx();
    SECTION("fixed wall under the block's face: it hits the wall at 300 m/s") {
        gimlet::grid_spec<S> gs;
        gs.lower = S::vector::Zero();
        gs.upper = S::vector(side, 3 * side);
        gs.cell = cell;
        gs.bc = {gimlet::boundary::periodic, gimlet::boundary::fixed};
        gimlet::scene::scene<S, hmx> sc(gs);
        sc.add_body(gimlet::scene::box<S>(S::vector(0.0, 0.0), S::vector(side, side)), m, S::vector(0.0, -v), 2, "block");
        gimlet::solver<S, gimlet::shape::ugimp, hmx> sol(sc, one_thread());
        record r;
        r.name = "fixed wall at the face";
        r.momentum_scale = gimlet::diagnostics::total_mass(sol) * v;
        r.x_momentum_only = true;  // the wall takes up y momentum
        double max_py = 0;
        auto wall = gimlet::diagnostics::every_steps(1, [&](const auto& so) {
            max_py = std::max(max_py, std::abs(gimlet::diagnostics::linear_momentum(so)[1]));
        });
        run_watched(sol, 12e-6, r, wall);
        print(r);
        std::printf("  |p_y| max %.4f of m v, at the end %.4f; energy lost %.1f %%\n", max_py / r.momentum_scale,
                    gimlet::diagnostics::linear_momentum(sol)[1] / r.momentum_scale, -100 * r.final_energy_change);
        check_invariants(r, 1e-12, 1e-6);
        CHECK(max_py <= r.momentum_scale * (1 + 1e-12));  // the wall never adds momentum
    }
    SECTION("free edges at the blocks' outer faces: they collide at +-300 m/s, then rebound off the grid") {
        gimlet::grid_spec<S> gs;
        gs.lower = S::vector::Zero();
        gs.upper = S::vector(side, 2 * side + 2 * cell);
        gs.cell = cell;
        gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
        gimlet::scene::scene<S, hmx> sc(gs);
        sc.add_body(gimlet::scene::box<S>(S::vector(0.0, 0.0), S::vector(side, side)), m, S::vector(0.0, v), 2,
                    "lower block");
        sc.add_body(gimlet::scene::box<S>(S::vector(0.0, side + 2 * cell), S::vector(side, 2 * side + 2 * cell)), m,
                    S::vector(0.0, -v), 2, "upper block");
        gimlet::solver<S, gimlet::shape::ugimp, hmx, gimlet::contact::distance> sol(sc, one_thread());
        record r;
        r.name = "free edges at the faces";
        r.momentum_scale = 0.5 * gimlet::diagnostics::total_mass(sol) * v;
        // Contact at 3.3 us; the release from the outer faces sends them back to the grid's edges
        // at about 14.8 us. Up to 12 us every assertion holds ...
        run_watched(sol, 12e-6, r);
        print(r);
        check_invariants(r, 1e-12, 1e-6);
        // ... and a face that reaches a free edge stops the run, naming the particle.
        std::string message;
        try {
            run_watched(sol, 20e-6, r);
        } catch (const gimlet::numerical_error& e) {
            message = e.what();
        }
        std::printf("  then stopped: %s\n", message.c_str());
        CHECK_THAT(message, Contains("left the grid through a non-periodic boundary") && Contains("particle") &&
                                Contains("step"));
        check_invariants(r, 1e-12, 1e-6);
    }
}

TEST_CASE("hard case: near-empty nodes (a sparse cloud of single particles)", "[robustness][hard]") {
    // Single particles alone on their nodes fly through empty cells for 40 us (32 mm, 32 cells);
    // half of them hit the block and bounce. Nodes at the edges of their stencils carry tiny masses.
    SECTION("default mass cut-off (1e-12)") {
        auto sol = make_cloud(1e-12);
        record r;
        r.name = "sparse cloud, cut-off 1e-12";
        r.momentum_scale = fragment_momentum();
        run_watched(sol, 40e-6, r);
        print(r);
        // Momentum: the force on a node under the cut-off goes back to the particles that
        // exerted it, so it is exact (measured 7.5e-15 of one fragment's |m v|; dropping that
        // force would lose 6.7e-9). Energy: the fragments' elastic impacts on the block overshoot
        // by 0.94 % (MUSL, as in the two-disk test of tests/solver/test_conservation.cpp);
        // bound 2 %.
        check_invariants(r, 1e-12, 0.02);
        // No particle holds more than the whole energy: 1/2 m v^2 <= 1.02 E0 = 1.02 x 12 fragments'
        // 1/2 m 800^2, i.e. |v| <= 800 sqrt(12.24) = 2800 m/s (measured 1102 m/s, a block particle
        // struck by a fragment).
        CHECK(r.max_speed < fragment_speed * std::sqrt(12 * 1.02));
    }
    SECTION("no mass cut-off: only nodes of exactly zero mass are skipped") {
        auto sol = make_cloud(0.0);
        record r;
        r.name = "sparse cloud, cut-off 0";
        r.momentum_scale = fragment_momentum();
        run_watched(sol, 40e-6, r);
        print(r);
        check_invariants(r, 1e-12, 0.02);
        CHECK(r.max_speed < fragment_speed * std::sqrt(12 * 1.02));
    }
}

TEST_CASE("hard case: particles far lighter than their neighbours", "[robustness][hard]") {
    // The sparse cloud with two more single particles of 1e-10 and 1e-14 of a fragment's mass,
    // across the fragments' paths. A light particle next to a node where a heavy particle has a
    // tiny weight reads that node's acceleration (~ 1/sqrt(S)) with weight O(1): without the
    // light-particle treatment it is flung at 52-115 km/s and crushed (det F 0) in every variant
    // measured (docs/robustness.md). With it, it reads the nodes by their reliability and the
    // momentum it changes goes back to its heavy neighbours.
    auto run = [](auto sol, const char* name, double bound_rise = 0.02) {
        record r;
        r.name = name;
        r.momentum_scale = fragment_momentum();
        std::size_t light = 0;
        gimlet::diagnostics::every_steps count(1, [&light](const auto& s) { light = std::max(light, s.light_particles()); });
        run_watched(sol, 40e-6, r, count);
        print(r);
        std::printf("  at most %zu light particles in a step\n", light);
        // Momentum: the returned momentum is exact to rounding (measured 1e-14). Energy: the
        // cloud's own rise (MUSL 0.94 %, the near-empty-nodes case), bound 2 % unless given.
        check_invariants(r, 1e-12, bound_rise);
        CHECK(r.min_det_f > 0.5);
        return std::pair{r, light};
    };
    // No particle faster than twice the fragments (the cloud alone reaches 1103 m/s, a block
    // particle struck by a fragment), and none crushed (det F > 0.5; the cloud alone 0.83).
    SECTION("mass ratios 1e-10 and 1e-14") {
        const auto [r, light] = run(make_cloud(1e-12, 1e-10, 1e-14), "light particles 1e-10, 1e-14");
        CHECK(light == 2);  // both at once at some steps (measured: 1164 m/s, det F 0.697)
        CHECK(r.max_speed < 2 * fragment_speed);
    }
    SECTION("mass ratios 1e-10 and 1e-2") {
        const auto [r, light] = run(make_cloud(1e-12, 1e-10, 1e-2), "light particles 1e-10, 1e-2");
        CHECK(light == 2);  // (measured: 1173 m/s, det F 0.696)
        CHECK(r.max_speed < 2 * fragment_speed);
    }
    SECTION("the other schemes, the PIC blend and volumetric averaging") {
        // Without the treatment these runs fling a light particle at 238 km/s (USF), 7.9 km/s (the
        // PIC blend) and 105 km/s (volumetric averaging); with it the fastest particle reaches
        // 800, 2247, 3403 and 2959 m/s (USL, USF, PIC 0.3, averaging; the cloud without light
        // particles 800, 1149, 800 and 1192 m/s). Bound: no fling, under 5 times the fragments'
        // speed. The energy bound is each scheme's own on this cloud: USF gains 28.4 % without
        // light particles (27.4 % with them), the others stay under 2 %.
        using gimlet::update_scheme;
        struct variant {
            const char* name;
            update_scheme scheme;
            double pic_fraction;
            bool volumetric_average;
            double bound_rise;
        };
        for (const variant& c : {variant{"light particles, USL", update_scheme::usl, 0.0, false, 0.02},
                                 variant{"light particles, USF", update_scheme::usf, 0.0, false, 0.30},
                                 variant{"light particles, MUSL, PIC 0.3", update_scheme::musl, 0.3, false, 0.02},
                                 variant{"light particles, MUSL, vol. average", update_scheme::musl, 0.0, true, 0.02}}) {
            auto sol = make_cloud(1e-12, 1e-10, 1e-2, [&c](gimlet::solver_options<S>& o) {
                o.scheme = c.scheme;
                o.pic_fraction = c.pic_fraction;
                o.volumetric_average = c.volumetric_average;
            });
            const auto [r, light] = run(std::move(sol), c.name, c.bound_rise);
            CHECK(light == 2);
            CHECK(r.max_speed < 5 * fragment_speed);
        }
    }
    SECTION("light particles inside a body with a field per body (distance contact)") {
        // Every 16th particle of the block made 2 % of the others' mass, its volume kept (so
        // of 2 % of their density, a material the block does not have; its wave speed 7 times
        // theirs, so 5 us only), changed through particles() before the first step: lightness,
        // the maxima and the return then work within the block's field.
        auto sol = make_cloud<gimlet::contact::distance>(1e-12);
        auto& ps = sol.particles();
        auto& mass = ps.template column<gimlet::fields::mass>();
        const auto& body = ps.template column<gimlet::fields::body>();
        std::size_t changed = 0;
        for (std::size_t i = 0; i < mass.size(); i += 16)
            if (body[i] == 0) mass[i] *= 0.02, ++changed;
        REQUIRE(changed == 16);
        record r;
        r.name = "light particles in the block, distance";
        r.momentum_scale = fragment_momentum();
        std::size_t light = 0;
        gimlet::diagnostics::every_steps count(1, [&light](const auto& s) { light = std::max(light, s.light_particles()); });
        run_watched(sol, 5e-6, r, count);
        print(r);
        check_invariants(r, 1e-12, 0.02);
        CHECK(light == 16);
    }
    SECTION("one material seeded finely beside coarsely is never light") {
        // Particles of one material at 5 x 5 and 1 per cell (a mass ratio of 1/25) in one field:
        // lightness compares densities, so none is light. (A mass test would make the fine ones
        // light, and the treatment would remove 9-16 % of the energy of the two blocks' impact,
        // where nothing is flung without it: docs/equations.md.)
        auto sc = periodic_scene(12, 8);
        const auto steel = gimlet::make_elastic_material(steel_density, steel_young, steel_nu);
        sc.add_body(gimlet::scene::box<S>(S::vector(2 * cloud_cell, 2 * cloud_cell), S::vector(6 * cloud_cell, 6 * cloud_cell)), steel,
                    S::vector(150, 0), 5, "fine");
        sc.add_body(gimlet::scene::box<S>(S::vector(6 * cloud_cell, 2 * cloud_cell), S::vector(10 * cloud_cell, 6 * cloud_cell)), steel,
                    S::vector(-150, 0), 1, "coarse");
        cloud_solver<> sol(sc, one_thread());
        const auto& mass = sol.particles().template column<gimlet::fields::mass>();
        REQUIRE(*std::min_element(mass.begin(), mass.end()) < 0.05 * *std::max_element(mass.begin(), mass.end()));
        std::size_t light = 0;
        gimlet::diagnostics::every_steps count(1, [&light](const auto& s) { light = std::max(light, s.light_particles()); });
        sol.run_until(2e-6, count);
        CHECK(sol.steps() > 10);
        CHECK(light == 0);
    }
    SECTION("a field per body (distance contact): light bodies meet heavy ones through the contact") {
        // Each single particle is a body, alone in its field, so none is ever light: the contact
        // acts between them (measured 2326 m/s, det F 0.64: a light body struck by a fragment
        // leaves it at up to twice its speed plus its own, the elastic limit). No fling: under
        // 5 times the fragments' speed, where one field flings the light particles at 52-67 km/s.
        const auto [r, light] = run(make_cloud<gimlet::contact::distance>(1e-12, 1e-10, 1e-14), "light bodies, distance");
        CHECK(light == 0);
        CHECK(r.max_speed < 5 * fragment_speed);
    }
}

// Every grid mode at once: a doubly periodic elastic block whose particles' velocities are
// scrambled, 2000 steps at the largest Courant number each scheme accepts (solver_options: 1,
// and 0.7 with USL). Kinetic plus internal energy may not grow: it oscillates, because the
// particles' velocities lag the stress by half a step (by about omega dt / 2 of it, large for
// the grid's fastest modes at these steps), but an unstable mode grows without bound. Measured:
// the largest energy over the last 500 steps is that of the first 500 (USL at 0.7 with 1 and 2
// particles per cell: 1.064 and 1.001 of the start, MUSL and USF at 1: 1.002); USL at 0.72
// (1 particle per cell) or 0.8 (2) grows it a thousandfold (docs/equations.md, step 6).
TEST_CASE("hard case: every scheme at its largest accepted Courant number stays stable", "[robustness][hard]") {
    struct run_case {
        gimlet::update_scheme scheme;
        double cfl;
        int ppc;
    };
    for (const auto& c : {run_case{gimlet::update_scheme::usl, 0.7, 1}, run_case{gimlet::update_scheme::usl, 0.7, 2},
                          run_case{gimlet::update_scheme::musl, 1.0, 2}, run_case{gimlet::update_scheme::usf, 1.0, 2}}) {
        gimlet::grid_spec<S> gs;
        gs.lower = S::vector::Zero();
        gs.upper = S::vector(16e-3, 16e-3);
        gs.cell = 1e-3;
        gs.bc = {gimlet::boundary::periodic, gimlet::boundary::periodic};
        gimlet::scene::scene<S, elastic> sc(gs);
        sc.add_body(gimlet::scene::box<S>(S::vector::Zero(), gs.upper), gimlet::make_elastic_material(1900, 10e9, 0.3),
                    S::vector::Zero(), c.ppc, "block");
        auto opt = one_thread();
        opt.scheme = c.scheme;
        opt.cfl = c.cfl;
        gimlet::solver<S, gimlet::shape::ugimp, elastic> sol(sc, opt);
        auto& v = sol.particles().column<gimlet::fields::velocity>();
        for (std::size_t i = 0; i < v.size(); ++i) v[i] = S::vector(std::sin(1.7 * double(i)), std::cos(2.3 * double(i)));
        const double e0 = gimlet::diagnostics::kinetic_energy(sol) + gimlet::diagnostics::internal_energy(sol);
        double early = 0, late = 0;  // the largest energy over the first and the last 500 steps
        for (int n = 0; n < 2000; ++n) {
            sol.step();
            const double e = gimlet::diagnostics::kinetic_energy(sol) + gimlet::diagnostics::internal_energy(sol);
            if (n < 500) early = std::max(early, e);
            if (n >= 1500) late = std::max(late, e);
        }
        INFO("scheme " << int(c.scheme) << ", Courant " << c.cfl << ", " << c.ppc << " particles per cell: largest energy "
                       << early / e0 << " of the start in the first 500 steps, " << late / e0 << " in the last 500");
        CHECK(late <= 1.01 * early);
        CHECK(late <= 1.1 * e0);
    }
}

namespace {

// The rms over the particle rows in the middle 8 mm of a strip of the second difference of the
// rows' mean y velocities (m/s): motion at the rows' scale, which a smooth field does not have.
template <class Solver>
double row_noise(const Solver& sol, double cell) {
    const auto& ps = sol.particles();
    double lo = 1e9, hi = -1e9;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const double y = ps[i].template get<gimlet::fields::position>()(1);
        lo = std::min(lo, y), hi = std::max(hi, y);
    }
    const double mid = 0.5 * (lo + hi);
    std::map<long, std::pair<double, int>> rows;  // row key -> (sum of v_y, count), bottom to top
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const double y = ps[i].template get<gimlet::fields::position>()(1);
        if (std::abs(y - mid) > 4e-3) continue;
        auto& row = rows[std::lround(y / (0.25 * cell))];
        row.first += ps[i].template get<gimlet::fields::velocity>()(1);
        ++row.second;
    }
    std::vector<double> v;  // the rows' mean velocities, bottom to top
    for (const auto& [key, row] : rows) v.push_back(row.first / row.second);
    double sq = 0;
    for (std::size_t k = 1; k + 1 < v.size(); ++k) {
        const double d = v[k] - 0.5 * (v[k - 1] + v[k + 1]);
        sq += d * d;
    }
    return std::sqrt(sq / double(v.size() - 2));
}

template <class Shape>
double expansion_noise(double rate, double t_end) {
    const double cell = 0.1e-3, half = 20e-3, width = 4 * cell;
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector(0.0, -half - 10e-3);
    gs.upper = S::vector(width, half + 10e-3);
    gs.cell = cell;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
    gimlet::scene::scene<S, hmx> sc(gs);
    sc.add_body(gimlet::scene::box<S>(S::vector(0.0, -half), S::vector(width, half)), gimlet::presets::make_hmx(),
                S::vector::Zero(), 2, "strip");
    gimlet::solver<S, Shape, hmx> sol(sc, one_thread());
    auto& ps = sol.particles();
    for (std::size_t i = 0; i < ps.size(); ++i)
        ps[i].template get<gimlet::fields::velocity>()(1) = rate * ps[i].template get<gimlet::fields::position>()(1);
    sol.run_until(t_end);
    return row_noise(sol, cell);
}

}  // namespace

// A 40 mm HMX strip (uniaxial strain, 0.1 mm cells, the library's defaults: MUSL, lumped mass,
// (0.06, 1.2)) set expanding uniformly, v_y = rate * y, to J = 1.086 and about -1 GPa at 3 us;
// the free surfaces' release waves do not reach the middle 8 mm where the rows are read. A
// homogeneous state has no motion at the rows' scale, and at rest none appears. cpGIMP keeps it
// so (measured 0.005 m/s); uGIMP's domains keep their size, no longer tile the stretched strip,
// and the rows' motion grows from round-off to 5.8 m/s (known limitation, docs/equations.md: if
// uGIMP's figure falls, update the docs).
TEST_CASE("hard case: a homogeneous expansion keeps the particle rows together with cpGIMP, not uGIMP",
          "[robustness][hard]") {
    const double cp = expansion_noise<gimlet::shape::cpgimp>(3e4, 3e-6);
    const double ug = expansion_noise<gimlet::shape::ugimp>(3e4, 3e-6);
    const double rest = expansion_noise<gimlet::shape::ugimp>(0.0, 3e-6);
    std::printf("homogeneous expansion, 3e4 /s to 3 us: the rows' motion (rms second difference) cpGIMP %.4f m/s, "
                "uGIMP %.3f m/s; at rest %.1e m/s\n",
                cp, ug, rest);
    CHECK(rest < 1e-9);
    CHECK(cp < 0.05);
    CHECK(ug > 1.0);
}
