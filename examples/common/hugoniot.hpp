// SPDX-License-Identifier: MIT
#pragma once
// The elastic-plastic Rankine-Hugoniot state of a symmetric impact of HMX on itself, from the
// jump conditions and the material model (Mie-Grueneisen EOS, von Mises strength), and its
// temperature on the EOS's own thermodynamics. Shared by impact_1d (its reference state) and
// cavity_collapse (the bulk shock temperature T_EP(v) its hot spots are measured above).

#include <gimlet/gimlet.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace example {

// ---- the Rankine-Hugoniot state (jump conditions + the material model) -------------------

struct hugoniot_state {
    double sigma_yy = 0;        // Pa, compression positive, behind the (plastic) shock
    double pressure = 0;        // Pa
    double eta = 0;             // 1 - V/V0 behind the (plastic) shock
    double energy = 0;          // J/kg, specific internal energy behind it (shear energy included)
    double eta_hel = 0;         // 1 - V/V0 at the Hugoniot elastic limit
    double shock_speed = 0;     // m/s, relative to the material ahead of the (plastic) shock
    bool two_wave = false;      // an elastic precursor runs ahead
    double precursor_sigma = 0; // Pa, the Hugoniot elastic limit state (two-wave only)
    double precursor_speed = 0; // m/s (two-wave only)
    double precursor_velocity = 0;  // m/s, particle-velocity jump across the precursor
};

// Stress of the model in uniaxial strain on the Hugoniot: sigma = P(eta, e) + 2Y/3 once
// yielded, with P the Mie-Grueneisen pressure at energy e (standard form). For the elastic part
// the Jaumann hypoelastic law integrates to s_yy = (4G/3) ln J (compression: |s_yy| grows),
// which reaches the yield surface at ln J = -Y / (2G).
inline double model_sigma(const gimlet::eos::mie_gruneisen<>& eos, double g, double y, double eta, double e) {
    const double j = 1.0 - eta;
    const double rho = eos.density0() / j;
    const double p = eos.hugoniot_pressure(j) + eos.gruneisen() * rho * (e - eos.hugoniot_energy(j));
    const double dev = std::min(-4.0 / 3.0 * g * std::log(j), 2.0 / 3.0 * y);
    return p + dev;
}

// Bisection on the shock speed U for a jump from state (sigma0, eta0, e0) with particle-velocity
// jump du: sigma = sigma0 + rho0 U du, eta = eta0 + du / U, e = e0 + (sigma + sigma0)(eta - eta0) / (2 rho0).
inline double solve_shock(const gimlet::eos::mie_gruneisen<>& eos, double g, double y, double sigma0, double eta0,
                          double e0, double du) {
    const double rho0 = eos.density0();
    auto residual = [&](double u) {
        const double sigma = sigma0 + rho0 * u * du;
        const double eta = eta0 + du / u;
        const double e = e0 + 0.5 * (sigma + sigma0) * (eta - eta0) / rho0;
        return sigma - model_sigma(eos, g, y, eta, e);
    };
    double lo = 1.05 * du / (1.0 / eos.slope() - eta0), hi = 1e5;  // eta below the EOS singularity
    if (residual(lo) * residual(hi) > 0) throw std::runtime_error("Rankine-Hugoniot: no bracket");
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (residual(lo) * residual(mid) <= 0 ? hi : lo) = mid;
    }
    return 0.5 * (lo + hi);
}

// The state behind the wave(s) of a symmetric impact at +-v (particle-velocity jump v).
template <class Material>
hugoniot_state rankine_hugoniot(const Material& m, double v) {
    const auto& eos = m.eos;
    const double g = m.strength.shear_modulus(), y = m.strength.yield_stress(), rho0 = eos.density0();
    hugoniot_state out;
    // Hugoniot elastic limit: the elastic jump that just reaches the yield surface.
    const double eta_hel = 1.0 - std::exp(-y / (2.0 * g));
    double sigma_hel = 0, e_hel = 0;
    for (int i = 0; i < 50; ++i) {  // e_hel = sigma_hel eta_hel / (2 rho0), fixed point
        sigma_hel = model_sigma(eos, g, y, eta_hel, e_hel);
        e_hel = 0.5 * sigma_hel * eta_hel / rho0;
    }
    const double u_pre = std::sqrt(sigma_hel / (rho0 * eta_hel));  // precursor speed
    const double v_hel = u_pre * eta_hel;
    const double u_single = solve_shock(eos, g, y, 0, 0, 0, v);
    out.eta_hel = eta_hel;
    if (v <= v_hel || u_single >= u_pre) {
        out.shock_speed = u_single;
        out.sigma_yy = rho0 * u_single * v;
        out.eta = v / u_single;
        out.energy = 0.5 * out.sigma_yy * out.eta / rho0;
    } else {
        out.two_wave = true;
        out.precursor_sigma = sigma_hel;
        out.precursor_speed = u_pre;
        out.precursor_velocity = v_hel;
        // Lagrangian plastic-wave speed relative to the precursor state; the material ahead of it
        // moves at v_hel relative to the unshocked slab, so relative speed = U_L (1 - eta_hel).
        const double u_l = solve_shock(eos, g, y, sigma_hel, eta_hel, e_hel, v - v_hel);
        out.sigma_yy = sigma_hel + rho0 * u_l * (v - v_hel);
        out.shock_speed = u_l * (1.0 - eta_hel);
        out.eta = eta_hel + (v - v_hel) / u_l;
        out.energy = e_hel + 0.5 * (out.sigma_yy + sigma_hel) * (out.eta - eta_hel) / rho0;
    }
    // P behind the shock: the yielded deviator is 2Y/3 (standard form; the viscosity is zero
    // in a steady plateau).
    out.pressure = out.sigma_yy - 2.0 / 3.0 * y;
    return out;
}

// The temperature of a Rankine-Hugoniot state on the EOS's own thermodynamics: T(V, e_th)
// from the reference isentrope (thermal::isentrope_temperature), with e_th the energy less the
// stored shear energy s:s/(4 G rho) = Y^2/(6 G rho) of the yielded deviator.
inline double hugoniot_temperature(const hugoniot_state& rh, const gimlet::presets::hmx_constants& c = {}) {
    const double g = gimlet::elastic_moduli::from_young_poisson(c.young, c.poisson).shear;
    const double rho = c.density / (1.0 - rh.eta);
    const gimlet::thermal::isentrope_temperature th(c.density, c.sound_speed, c.slope, c.gruneisen, c.specific_heat,
                                                    c.temperature);
    return th.temperature(1.0 - rh.eta, rh.energy - c.yield_stress * c.yield_stress / (6.0 * g * rho));
}

// The plastic work of uniaxial strain from the elastic limit to eta, as kelvin of heating:
// 2 Y (eta - eta_HEL) / (3 rho0 c_v) (perfect plasticity, small strains).
inline double uniaxial_plastic_heat(const hugoniot_state& rh, const gimlet::presets::hmx_constants& c = {}) {
    return 2.0 * c.yield_stress * std::max(0.0, rh.eta - rh.eta_hel) / (3.0 * c.density * c.specific_heat);
}

}  // namespace example
