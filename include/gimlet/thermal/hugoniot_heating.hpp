// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Shock heating along the Hugoniot (Walsh-Christian) plus plastic-work heating.

#include "gimlet/core/error.hpp"
#include "gimlet/thermal/concepts.hpp"
#include "gimlet/thermal/detail/parameters.hpp"

#include <cmath>
#include <type_traits>

namespace gimlet::thermal {

/// What happens to the Hugoniot term when a particle expands.
enum class expansion {
    /// The reference paper's form: the same formula in both directions (default, for
    /// reproduction).
    hugoniot,
    /// Irreversible variant: on expansion only the isentropic part -(Gamma/V) T dV acts, so
    /// shock heating is not undone by release.
    isentropic,
};

/// Temperature from volume changes and dissipation (docs/physics.md section 6):
/// \f[ \frac{dT}{dV} = \frac{s c_0^2 (V_0 - V)^2}{c_v\,[(s-1)V_0 - sV]^3} - \frac{\Gamma}{V} T \f]
/// (Walsh & Christian 1955, for the Hugoniot U_s = c_0 + s U_p and constant Gamma), integrated over each step's volume change with the integrating factor
/// V^Gamma: T_new V_new^Gamma = T_old V_old^Gamma + int a(V) V^Gamma dV (Simpson's rule),
/// then plastic (and any other dissipated) work \f$ dT = dw / c_v \f$. No conduction.
/// \tparam X what the Hugoniot term does on expansion.
template <expansion X = expansion::hugoniot>
class hugoniot_heating {
public:
    /// A real thermal policy: the solver stores and updates the temperature (thermal::Thermal).
    static constexpr bool enabled = true;
    /// It keeps the temperature field.
    using required_fields = field_list<fields::temperature>;

    /// \param density0 rho_0 (kg/m^3); \param sound_speed c_0 (m/s); \param slope s (> 1);
    /// \param gruneisen Gamma (>= 0); \param specific_heat c_v (J/(kg K)); \param initial_temperature T_0 (K).
    hugoniot_heating(double density0, double sound_speed, double slope, double gruneisen, double specific_heat,
                     double initial_temperature)
        : v0_(1.0 / density0), c0_(sound_speed), s_(slope), gamma_(gruneisen), cv_(specific_heat),
          t0_(initial_temperature) {
        detail::validate_shock_parameters(density0, sound_speed, slope, gruneisen, specific_heat, initial_temperature);
    }

    /// Set a new particle's temperature to T_0.
    template <class P>
    void initialize(const P& p) const {
        auto& t = p.template get<fields::temperature>();
        t = static_cast<std::remove_cvref_t<decltype(t)>>(t0_);
    }

    /// Advance the temperature over the step: advance() from V_old = V_0 J_old to V = V_0 J, plus
    /// `dissipated` / c_v (plastic work, J/kg).
    template <class Real, class P>
    void update(const point_step<Real>& st, Real dissipated, const P& p) const {
        Real& t = p.template get<fields::temperature>();
        t = Real(advance(double(t), v0_ * double(st.J_old), v0_ * double(st.J)) + double(dissipated) / cv_);
    }

    /// Temperature after a volume change from v_old to v_new (specific volumes, m^3/kg)
    /// starting at t_old, Hugoniot term only (no dissipation).
    [[nodiscard]] double advance(double t_old, double v_old, double v_new) const {
        const double factor = std::pow(v_old / v_new, gamma_);  // isentropic part, exact
        if (v_new == v_old) return t_old;
        if constexpr (X == expansion::isentropic) {
            if (v_new > v_old) return t_old * factor;
        }
        const double vm = 0.5 * (v_old + v_new);
        const double integral =
            (v_new - v_old) / 6.0 * (source(v_old) * std::pow(v_old, gamma_) + 4.0 * source(vm) * std::pow(vm, gamma_) +
                                     source(v_new) * std::pow(v_new, gamma_));
        return t_old * factor + integral / std::pow(v_new, gamma_);
    }

    /// The Hugoniot source term a(V) = s c0^2 (V0 - V)^2 / (c_v [(s - 1) V0 - s V]^3).
    [[nodiscard]] double source(double v) const {
        const double d = (s_ - 1.0) * v0_ - s_ * v;
        return s_ * c0_ * c0_ * (v0_ - v) * (v0_ - v) / (cv_ * d * d * d);
    }

    /// rho_0 (kg/m^3).
    [[nodiscard]] double density0() const noexcept { return 1.0 / v0_; }
    /// c_0 (m/s), the Hugoniot's bulk sound speed.
    [[nodiscard]] double sound_speed() const noexcept { return c0_; }
    /// s, the slope of the Hugoniot's U_s-u_p line.
    [[nodiscard]] double slope() const noexcept { return s_; }
    /// c_v (J/(kg K)).
    [[nodiscard]] double specific_heat() const noexcept { return cv_; }
    /// T_0 (K), the initial temperature.
    [[nodiscard]] double initial_temperature() const noexcept { return t0_; }
    /// Gamma, the Grueneisen parameter.
    [[nodiscard]] double gruneisen() const noexcept { return gamma_; }

private:
    double v0_, c0_, s_, gamma_, cv_, t0_;
};

static_assert(Thermal<hugoniot_heating<expansion::hugoniot>>);
static_assert(Thermal<hugoniot_heating<expansion::isentropic>>);

}  // namespace gimlet::thermal
