// SPDX-License-Identifier: MIT
/// \file
/// Verification: free axial vibration of an elastic bar fixed at one end (the first mode of the
/// wave equation), run through the whole solver for every shape function.
///
/// Set-up (plane strain, SI units, everything O(1) so the numbers read directly):
/// - bar 0 <= x <= L = 1 m, rho = 1 kg/m^3, E = 1 Pa, nu = 0. With nu = 0, K = E/3 and
///   G = E/2, so the longitudinal modulus K + 4G/3 = E and uniaxial strain is uniaxial stress:
///   c = sqrt(E / rho) = 1 m/s (docs/physics.md section 1, step 6).
/// - fixed at x = 0: the grid's lower x bound with boundary::fixed. grid.hpp applies a fixed
///   axis at both of its ends (nodes k <= 0 and k >= N), so the grid extends `free_cells`
///   cells beyond x = L: the upper wall nodes are then out of reach of every particle's stencil
///   and the end x = L is free.
/// - periodic in y, a strip of `stencil` cells (the least a periodic axis accepts), so the
///   problem is 1-D and cheap.
/// - initial velocity in the first mode, v(x) = v0 sin(pi x / (2L)), no initial stress. The
///   exact motion is u = (v0/omega) sin(pi x / (2L)) sin(omega t), omega = pi c / (2L), so the
///   period is T = 4L/c and the centre-of-mass velocity is
///   V(t) = (2 v0 / pi) cos(omega t): its zero crossings are T/2 apart.
///   v0 = 1e-4 c keeps the strain amplitude v0/c = 1e-4: the model is linear to 1e-4.
///
/// The period is measured from the zero crossings of V (linear interpolation between steps)
/// over three periods, and must be within 1 % of 4L/c.

#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <tuple>
#include <vector>

namespace {

using S = gimlet::space<2>;

using shapes = std::tuple<gimlet::shape::linear, gimlet::shape::ugimp, gimlet::shape::cpgimp,
                          gimlet::shape::bspline_quadratic, gimlet::shape::bspline_cubic>;


constexpr double pi = 3.141592653589793;

struct bar_result {
    double period = 0;          ///< measured (s)
    double exact = 0;           ///< 4L/c (s)
    std::size_t crossings = 0;  ///< zero crossings of V used
    double omega_dt = 0;        ///< omega dt of the run
    double energy_error = 0;    ///< max |KE + IE - E0| / E0 with the diagnostics as they are
    double centred_error = 0;   ///< max |KE_c + IE - E0| / E0, KE_c time-centred (see below)
    double centred_gain = 0;    ///< max (KE_c + IE - E0) / E0, 0 if it never rose above E0
};

template <class Shape>
bar_result vibrate() {
    constexpr double length = 1.0, rho = 1.0, young = 1.0, v0 = 1e-4;
    constexpr int cells = 50;       // along the bar: h = L/50
    constexpr int free_cells = 4;   // grid beyond the free end (> the widest stencil reach, 2h)
    constexpr int periods = 3;
    constexpr double cfl = 0.4;     // the solver's default Courant number
    const double h = length / cells, c = std::sqrt(young / rho);
    const int strip = Shape::stencil;

    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector(length + free_cells * h, strip * h);
    gs.cell = h;
    gs.bc = {gimlet::boundary::fixed, gimlet::boundary::periodic};
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    sc.add_body(gimlet::scene::box<S>(S::vector(0.0, 0.0), S::vector(length, strip * h)),
                gimlet::make_elastic_material(rho, young, 0.0), S::vector::Zero(), 2, "bar");
    gimlet::solver_options<S> opt;
    opt.threads = 1;  // tiny problem: threads would only add overhead (results do not depend on it)
    gimlet::solver<S, Shape, gimlet::elastic_material> sol(sc, opt);

    auto& parts = sol.particles();
    auto& x = parts.template column<gimlet::fields::position>();
    auto& v = parts.template column<gimlet::fields::velocity>();
    const auto& m = parts.template column<gimlet::fields::mass>();
    double mass = 0;
    for (std::size_t p = 0; p < parts.size(); ++p) {
        v[p] = S::vector(v0 * std::sin(pi * x[p][0] / (2 * length)), 0.0);
        mass += m[p];
    }
    auto centre_velocity = [&] {
        double s = 0;
        for (std::size_t p = 0; p < parts.size(); ++p) s += m[p] * v[p][0];
        return s / mass;
    };

    bar_result r;
    r.exact = 4 * length / c;
    const double dt = cfl * h / c;
    const double omega = pi * c / (2 * length);
    r.omega_dt = omega * dt;
    const double e0 = gimlet::diagnostics::kinetic_energy(sol) + gimlet::diagnostics::internal_energy(sol);

    // The step is leapfrog-like: the force at t_n (stress and positions at t_n) turns the
    // particle velocities of before the step into those after it, and the positions advance
    // with the new ones. So after the step to t_{n+1} the particles carry v^{n+1/2} while the
    // internal energy (integrated from sigma:D over the step) is at t_{n+1}: the plain sum
    // KE + IE is off by half a step: for a single mode v ~ cos(omega t),
    // KE(v^{n+1/2}) - KE(v^{n+1}) ~ -(dt/2) d(KE)/dt = (omega dt / 2) E0 sin(2 omega t), an
    // oscillation of relative amplitude omega dt / 2 (6.3e-3 here) that is no energy error. The
    // time-centred kinetic energy KE_c(t_n) = (1/2) sum m v^{n-1/2} . v^{n+1/2} removes that
    // offset (for a linear system it is the energy leapfrog conserves exactly), so KE_c + IE
    // at t_n shows what the scheme really gains or loses.
    std::vector<S::vector> v_before(parts.size());
    std::vector<double> crossings;
    double v_old = centre_velocity(), t_old = 0, ie_old = gimlet::diagnostics::internal_energy(sol);
    const int steps = static_cast<int>(std::ceil(periods * r.exact / dt));
    for (int s = 0; s < steps; ++s) {
        std::copy(v.begin(), v.end(), v_before.begin());
        sol.step(dt);
        const double t = double(sol.time()), v_new = centre_velocity();
        if ((v_old > 0) != (v_new > 0)) crossings.push_back(t_old + (t - t_old) * v_old / (v_old - v_new));
        v_old = v_new;
        t_old = t;
        const double ke = gimlet::diagnostics::kinetic_energy(sol), ie = gimlet::diagnostics::internal_energy(sol);
        r.energy_error = std::max(r.energy_error, std::abs(ke + ie - e0) / e0);
        // Time-centred kinetic energy at the start of this step: (1/2) sum m v^- . v^+.
        double centred = 0;
        for (std::size_t p = 0; p < parts.size(); ++p) centred += 0.5 * m[p] * v_before[p].dot(v[p]);
        r.centred_error = std::max(r.centred_error, std::abs(centred + ie_old - e0) / e0);
        r.centred_gain = std::max(r.centred_gain, (centred + ie_old - e0) / e0);
        ie_old = ie;
    }
    r.crossings = crossings.size();
    if (crossings.size() >= 2)
        r.period = 2 * (crossings.back() - crossings.front()) / double(crossings.size() - 1);
    return r;
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("elastic bar, fixed-free: first-mode period and energy", "[core][verification]", shapes) {
    const bar_result r = vibrate<TestType>();
    const double error = r.period / r.exact - 1;
    std::printf("bar %-18s T = %.6f s (exact 4L/c = %.6f s), error %+.4f %% (%zu crossings); "
                "max |dE|/E0: KE+IE %.2e (omega dt/2 = %.2e), time-centred %.2e\n",
                TestType::name, r.period, r.exact, 100 * error, r.crossings, r.energy_error,
                r.omega_dt / 2, r.centred_error);
    // Three periods give six zero crossings of V (at T/4 + k T/2).
    REQUIRE(r.crossings >= 5);
    // The requirement: the first-mode period within 1 % of 4L/c. At 50 cells along the
    // bar the dispersion error of the mode is far smaller (linear/GIMP: ~1e-4, second order in
    // h); the B-splines carry a first-order error from the fixed wall (their ghost nodes beyond
    // it are held at zero velocity, which moves the effective clamp outwards by a fraction of
    // a cell), still inside the requirement at this resolution.
    CHECK(std::abs(error) < 0.01);
    // Energy. Tolerance 0.5 % of E0 over the three periods for what the transfers and the wall
    // may dissipate: a loss that size damps the mode by a quarter of a percent, which neither
    // hides a wrong period nor an unstable bar; it catches a scheme that loses or gains energy
    // grossly (a non-conservative transfer, a wrong stress power in the internal energy).
    constexpr double dissipation_allowance = 0.005;
    CHECK(r.centred_error < dissipation_allowance);
    // No gain beyond the O((omega dt)^2) by which the midpoint-in-time stress power may differ
    // from the exact strain energy: a real gain would mean an instability.
    CHECK(r.centred_gain < r.omega_dt * r.omega_dt);
    // The diagnostics as a user sums them: the half-step offset of the kinetic energy on top.
    CHECK(r.energy_error < r.omega_dt / 2 + dissipation_allowance);
}
