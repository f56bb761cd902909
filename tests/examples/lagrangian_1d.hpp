// SPDX-License-Identifier: MIT
#pragma once
// An independent reference for the slab impact: a 1-D Lagrangian hydrocode, von
// Neumann-Richtmyer's staggered scheme (von Neumann & Richtmyer 1950, J. Appl. Phys. 21; Wilkins,
// "Computer Simulation of Dynamic Phenomena", 1999, ch. 2), on the same Mie-Grueneisen EOS and
// reference-isentrope temperature as the library, for the symmetric impact of two slabs that part
// when the plane between them would pull. No grid, no particles, no transfers: what differs from
// the MPM run is the method (the EOS, the temperature and theta_H below are the library's own
// code). By default strengthless with its own q (the release test, docs/equations.md, "Release
// keeps the entropy"); settings::strength and settings::bulk add the library's von Mises strength
// and bulk viscosity (below).
//
// Only the upper slab is computed; the impact plane is a wall that pushes and never pulls (by
// symmetry, the lower slab). Nodes carry velocities (leapfrog, started from the velocities at
// t = 0: a first-order start, one step's error), cells carry J, e, P and the deviator s_yy:
//   a_i = (sigma_{i} - sigma_{i-1}) / m_i, sigma = -(P + q) + s_yy                 (momentum)
//   e^{n+1} = e^n - ((P^n + P^{n+1}) / 2 + q) (V^{n+1} - V^n)
//                 + (s^n + s^{n+1}) / 2 (V^{n+1} - V^n)                           (energy;
//     P^{n+1} = P_H + Gamma rho (e^{n+1} - w^{n+1} - e_H) is linear in e^{n+1}, so the update is
//     solved in closed form)
//   q = rho (C_Q^2 du^2 - C_L c0 du) where the cell compresses (du < 0), else 0 (Wilkins 1980,
//     J. Comput. Phys. 36: his linear term takes the local sound speed; c0 here).
// With settings::strength (von Mises in uniaxial strain, perfectly plastic, the constants' Y0 and
// G = E / (2 (1 + nu))), as strength::von_mises does it:
//   s_yy += 2 G (d eps_yy - d eps_v / 3) = (4/3) G d eps_yy, d eps_yy = D_yy dt = (J^{n+1} - J^n)
//     / J^{n+1/2} (s_xx = s_zz = -s_yy / 2; Hooke's law in rate form, Wilkins 1999 ch. 2; no
//     rotation in 1-D, so the Jaumann term is zero), then returned radially to the yield surface
//     sqrt(3/2 s:s) = (3/2) |s_yy| <= Y0, i.e. |s_yy| <= 2 Y0 / 3 (Wilkins 1999 ch. 3; Wilkins
//     1964, Methods Comput. Phys. 3);
//   the deviator's work (s^n + s^{n+1}) / 2 dV is in e (sigma : D v dt = sigma_yy dV in uniaxial
//     strain), so e holds the plastic work and the stored elastic shear energy as the library's e
//     does (material/update.hpp: de = dt v_mid sigma_mid : D, the plastic work not added again);
//   w = s:s / (4 G rho) = 3 s_yy^2 / (8 G rho), the stored shear energy, is taken off e for the
//     EOS's Grueneisen term and for the temperature, as eos::mie_gruneisen and
//     thermal::isentrope_temperature take it off (e_th = e - w: it is not heat);
//   T = T(J, e - w) from thermal::isentrope_temperature, the library's temperature.
// With settings::bulk, q is the library's viscosity::bulk instead of the reference's own:
//   q = rho h (b2^2 h r^2 + b1 c r), r = -D_yy = -du / (h J^{n+1/2}) where the cell compresses,
//     else 0, h the cell's reference size (the MPM's h is its cell size), c the longitudinal wave
//     speed sqrt((K_s + 4G/3) / rho) at J^{n+1} and e^n (K_s from eos::mie_gruneisen's own
//     bulk_modulus; G = 0 without strength), as material/update.hpp asks it of the particle
//     after the strain and before the energy (von Neumann & Richtmyer 1950; Landshoff 1955,
//     LA-1930; the library's form in viscosity/bulk.hpp).
// Both terms of q are evaluated at the step's mid-volume (rho = rho0 / J^{n+1/2}), as the
// reference's own q is, and q acts in the step's force and work (the library averages the old
// and new stress in the work).
// The energy update is not the compatible one (Caramana et al. 1998, J. Comput. Phys. 146): the
// forces take P^n, the work the mean of P^n and P^{n+1}, so total energy is not kept exactly and
// the shocked state's theta depends on the step. Measured at 2 us, 800 cells, strengthless with
// its own q: theta / theta_H - 1 = +0.030, +0.0093, +0.0031, +0.0011 % at 500 m/s for 4, 2, 1 and
// 0.5 times the step used here (700 m/s: +0.094, +0.030, +0.0105, +0.0041 %; about order 1.5 in
// the step). The step (settings::courant on 7 km/s, above the largest c / J of these runs,
// 6.8 km/s in the 700 m/s shocked state) leaves 0.003 and 0.010 %. With the strength and the
// library's viscosity (b1, b2) = (0.12, 2.4) on 0.25 mm cells, half the step moves the cell at the
// wall's T - T0 at 1 us from 130.5 to 130.2 K at 500 m/s and from 1225 to 1213 K at 1500 m/s, and
// the plateau's sigma_yy by under 0.01 %.

#include <gimlet/gimlet.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace lagrangian_1d {

struct settings {
    double velocity = 500.0;  // m/s, each slab
    int cells = 400;          // over the slab
    double length = 10e-3;    // m
    double exclude = 0.5e-3;  // m: the medians skip cells this close to either face
    double quadratic = 2.0;   // C_Q
    double linear = 0.1;      // C_L
    double courant = 0.05;    // dt = courant * (cell) / 7 km/s
    // von Mises strength in uniaxial strain with the constants' G and Y0 (off: strengthless).
    bool strength = false;
    // The library's bulk viscosity (its b1, b2; h = the cell) instead of C_Q and C_L.
    std::optional<gimlet::viscosity::bulk> bulk;
};

// The cells from the impact plane outwards at one of run()'s times.
struct profile {
    double time = 0;               // s
    std::vector<double> heating;   // T - T0 (K)
    std::vector<double> sigma_yy;  // Pa, compression positive
};

struct sample {
    double time = 0;           // s
    double theta = 0;          // median T / T_s(J) over the interior
    double heating = 0;        // median T - T0 (K) over the interior
    double lower_face = 0;     // m, the impact-plane face (0 until the slabs part)
};

// A particle to the EOS's bulk_modulus, which reads its specific internal energy alone.
struct energy_only {
    mutable double e;
    template <class Field>
    double& get() const {
        return e;
    }
};

// The library's EOS and temperature for the constants c.
struct model {
    gimlet::eos::mie_gruneisen<> eos;
    gimlet::thermal::isentrope_temperature th;
    double gruneisen_rho0;  // Gamma rho0: Gamma rho = gruneisen_rho0 / J
    double shear;           // G = E / (2 (1 + nu)), as presets::make_hmx builds it

    explicit model(const gimlet::presets::hmx_constants& c)
        : eos{c.density, c.sound_speed, c.slope, c.gruneisen},
          th{c.density, c.sound_speed, c.slope, c.gruneisen, c.specific_heat, c.temperature},
          gruneisen_rho0(c.gruneisen * c.density),
          shear(gimlet::elastic_moduli::from_young_poisson(c.young, c.poisson).shear) {}

    // P = P_H(J) + Gamma rho (e - e_H(J)) (eos::mie_gruneisen, without the shear energy: no strength).
    [[nodiscard]] double pressure(double j, double e) const {
        return eos.hugoniot_pressure(j) + gruneisen_rho0 / j * (e - eos.hugoniot_energy(j));
    }

    // The longitudinal wave speed sqrt((K_s + 4 g / 3) / rho) at (J, e), K_s from the EOS's own
    // bulk_modulus (which reads the whole e), as gimlet::longitudinal_wave_speed forms it.
    [[nodiscard]] double wave_speed(double j, double e, double g, double density0) const {
        gimlet::point_state<double> st;
        st.J = j;
        st.density0 = density0;
        st.density = density0 / j;
        const double k = eos.bulk_modulus(st, energy_only{e});
        return std::sqrt(std::max(0.0, (k + 4.0 / 3.0 * g) / st.density));
    }
};

// The median of v (reorders it; v not empty).
inline double median(std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

// The strengthless Rankine-Hugoniot state of the symmetric impact at v (U_s = c0 + s u_p, u_p = v):
// its theta = T_H / T_s(J_H), which an isentropic release keeps.
inline double hugoniot_theta(double v, const gimlet::presets::hmx_constants& c = {}) {
    const model md(c);
    const double eta = v / (c.sound_speed + c.slope * v), j = 1.0 - eta;
    return md.th.temperature(j, 0.5 * v * v) / md.th.isentrope(j);  // e_H = u_p^2 / 2
}

// T - T0 after an isentropic release from that state to P = 0: on the isentrope theta = theta_H,
// T = theta_H T_s(J) and e = e_s(J) + c_v (T - T_s(J)); P(J, e) = 0 solved for J by bisection
// (P falls as J grows there).
inline double isentropic_release_heating(double v, const gimlet::presets::hmx_constants& c = {}) {
    const model md(c);
    const double theta = hugoniot_theta(v, c);
    auto pressure = [&](double j) {
        return md.pressure(j, md.th.reference_energy(j) + c.specific_heat * (theta - 1.0) * md.th.isentrope(j));
    };
    double lo = 1.0, hi = 1.1;  // P > 0 at J = 1 (the heat's pressure), < 0 at 1.1
    if (!(pressure(lo) > 0 && pressure(hi) < 0))
        throw std::domain_error("isentropic_release_heating: P = 0 is not between J = 1 and 1.1 at this velocity");
    for (int k = 0; k < 60; ++k) (pressure(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
    return theta * md.th.isentrope(0.5 * (lo + hi)) - c.temperature;
}

// Runs to the last of `times` (s, increasing) and returns one sample at each; with `profiles`,
// also every cell's state at each.
inline std::vector<sample> run(const settings& s, const std::vector<double>& times,
                               const gimlet::presets::hmx_constants& c = {}, std::vector<profile>* profiles = nullptr) {
    const model md(c);
    if (s.strength && c.hardening != 0.0)
        throw std::invalid_argument("lagrangian_1d: the reference's strength is perfectly plastic (hardening 0)");
    const int n = s.cells;
    const double dx0 = s.length / n, rho0 = c.density, m = rho0 * dx0;
    const double g = s.strength ? md.shear : 0.0, s_max = 2.0 / 3.0 * c.yield_stress;
    std::vector<double> x(n + 1), u(n + 1, -s.velocity), J(n, 1.0), e(n, 0.0), P(n, 0.0), q(n, 0.0);
    std::vector<double> dev(n, 0.0), w(n, 0.0);  // s_yy (Pa) and the stored shear energy (J/kg)
    for (int i = 0; i <= n; ++i) x[i] = i * dx0;
    const double dt = s.courant * dx0 / 7000.0;
    auto sigma = [&](int k) { return s.strength ? dev[k] - (P[k] + q[k]) : -(P[k] + q[k]); };
    std::vector<sample> out;
    double t = 0;
    std::vector<double> theta, heating;
    for (double until : times) {
        while (t < until - 0.5 * dt) {
            for (int i = 0; i <= n; ++i) {
                const double above = i < n ? sigma(i) : 0.0, below = i > 0 ? sigma(i - 1) : 0.0;
                u[i] += dt * (above - below) / ((i == 0 || i == n) ? 0.5 * m : m);
            }
            if (x[0] + u[0] * dt < 0.0) u[0] = -x[0] / dt;  // the wall pushes, never pulls
            for (int i = 0; i <= n; ++i) x[i] += u[i] * dt;
            for (int k = 0; k < n; ++k) {
                const double j1 = (x[k + 1] - x[k]) / dx0, dv = (j1 - J[k]) / rho0, du = u[k + 1] - u[k];
                const double rho = rho0 / (0.5 * (j1 + J[k]));
                const double dev_old = dev[k];
                if (s.strength) {
                    dev[k] = std::clamp(dev[k] + 4.0 / 3.0 * g * (j1 - J[k]) / (0.5 * (j1 + J[k])), -s_max, s_max);
                    w[k] = 3.0 * dev[k] * dev[k] / (8.0 * g * rho0 / j1);
                }
                if (s.bulk) {
                    const double rate = -du / (dx0 * 0.5 * (j1 + J[k])), b1 = s.bulk->linear(), b2 = s.bulk->quadratic();
                    q[k] = rate > 0 ? rho * dx0 * (b2 * b2 * dx0 * rate * rate + b1 * md.wave_speed(j1, e[k], g, rho0) * rate)
                                    : 0.0;
                } else {
                    q[k] = du < 0 ? rho * (s.quadratic * s.quadratic * du * du - s.linear * c.sound_speed * du) : 0.0;
                }
                const double g1 = md.gruneisen_rho0 / j1, ph = md.eos.hugoniot_pressure(j1), eh = md.eos.hugoniot_energy(j1);
                if (s.strength) {
                    e[k] = (e[k] - (0.5 * (P[k] + ph - g1 * (eh + w[k])) + q[k]) * dv + 0.5 * (dev_old + dev[k]) * dv) /
                           (1.0 + 0.5 * g1 * dv);
                    J[k] = j1;
                    P[k] = ph + g1 * (e[k] - w[k] - eh);
                } else {
                    e[k] = (e[k] - (0.5 * (P[k] + ph - g1 * eh) + q[k]) * dv) / (1.0 + 0.5 * g1 * dv);
                    J[k] = j1;
                    P[k] = ph + g1 * (e[k] - eh);
                }
            }
            t += dt;
        }
        theta.clear();
        heating.clear();
        for (int k = 0; k < n; ++k) {
            const double y = 0.5 * (x[k] + x[k + 1]);
            if (y < x[0] + s.exclude || y > x[n] - s.exclude) continue;
            const double temperature = md.th.temperature(J[k], e[k] - w[k]);
            theta.push_back(temperature / md.th.isentrope(J[k]));
            heating.push_back(temperature - c.temperature);
        }
        out.push_back({t, median(theta), median(heating), x[0]});
        if (profiles) {
            profile pr;
            pr.time = t;
            for (int k = 0; k < n; ++k) {
                pr.heating.push_back(md.th.temperature(J[k], e[k] - w[k]) - c.temperature);
                pr.sigma_yy.push_back(-sigma(k));
            }
            profiles->push_back(std::move(pr));
        }
    }
    return out;
}

}  // namespace lagrangian_1d
