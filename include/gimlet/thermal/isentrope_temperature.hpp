// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Temperature from the thermodynamic state (V, e) of a Mie-Grueneisen material, measured from
/// its reference isentrope: the temperature consistent with the EOS's own energy.

#include "gimlet/core/describe.hpp"
#include "gimlet/core/detail/inline.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/eos/mie_gruneisen.hpp"
#include "gimlet/thermal/concepts.hpp"
#include "gimlet/thermal/detail/parameters.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <type_traits>
#include <vector>

namespace gimlet::thermal {

/// Temperature from the specific volume and the thermal part of the specific internal energy,
/// for the Mie-Grueneisen EOS with constant Gamma (Gamma/V = Gamma rho) and constant c_v
/// (Menikoff 2016, LA-UR-16-21706; docs/equations.md, "thermal::isentrope_temperature"):
/// \f[ T(V, e_{th}) = T_s(V) + \frac{e_{th} - e_s(V)}{c_v}, \qquad
///     T_s = T_0 \left(\frac{V_0}{V}\right)^{\Gamma}, \qquad e_s(V) = -\int_{V_0}^{V} P_s\,dV, \f]
/// where the reference isentrope \f$(V, e_s)\f$ runs through \f$(V_0, 0)\f$ at \f$T_0\f$ and obeys
/// \f$ de_s/dV = -P(V, e_s) \f$ with \f$ P = P_H + (\Gamma/V)(e - e_H) \f$. With J = V/V0:
/// \f[ e_s(J) = J^{-\Gamma} \int_1^J -\frac{P_H(J')}{\rho_0} J'^{\Gamma}
///     \left(1 - \frac{\Gamma (1 - J')}{2 J'}\right) dJ' \f]
/// (from \f$ d(J^\Gamma e_s)/dJ = J^\Gamma (-P_H/\rho_0 + \Gamma e_H / J) \f$,
/// \f$ e_H = P_H (1 - J) / (2\rho_0) \f$), tabulated once at construction.
///
/// It is the temperature the EOS's thermodynamics imply (c_v dT = T ds - (Gamma c_v T / V) dV
/// integrated along the isentrope and then at constant V), so on a single shock it equals the
/// Walsh-Christian Hugoniot temperature; on release it keeps the entropy the shock made (T / T_s
/// is constant along any isentrope); and it is bounded by the energy a particle actually holds.
///
/// \f$ e_{th} \f$ is the specific internal energy less the stored elastic shear energy
/// \f$ s:s/(4G\rho) \f$ (point_step::shear_energy), which is not heat; the same \f$ e_{th} \f$ feeds
/// eos::mie_gruneisen's standard form. A particle whose \f$ e_{th} \f$ falls below \f$ e_s(V) \f$ by more than
/// \f$ c_v \f$ times `cold_tolerance` (default 0.1 K) has lost energy to the numerics: the update
/// stops the run with a numerical_error naming it, and never clamps it.
///
/// The reference curve is tabulated from 1 - s eta = 0.01 in compression (beyond the EOS's stop at
/// 0.05) to J = 3 in expansion, uniformly in ln(J - J_1/s) (J_1/s = 1 - 1/s, the singular volume),
/// with cubic Hermite interpolation between nodes; a state outside the table is integrated
/// directly. The particle update takes T_s from the same table, interpolated in the same cell;
/// isentrope() and temperature() compute it exactly. The table is shared between copies.
class isentrope_temperature {
public:
    /// A real thermal policy: the solver stores and updates the temperature (thermal::Thermal).
    static constexpr bool enabled = true;
    /// It keeps the temperature field.
    using required_fields = field_list<fields::temperature>;

    /// \param density0 rho_0 (kg/m^3); \param sound_speed c_0 (m/s); \param slope s (> 1);
    /// \param gruneisen Gamma (>= 0); \param specific_heat c_v (J/(kg K));
    /// \param initial_temperature T_0 (K); \param cold_tolerance how far (K) e_th may fall below
    /// the reference isentrope, as c_v times it, before the update stops the run (>= 0).
    isentrope_temperature(double density0, double sound_speed, double slope, double gruneisen, double specific_heat,
                          double initial_temperature, double cold_tolerance = 0.1)
        : rho0_(density0), c0_(sound_speed), s_(slope), gamma_(gruneisen), cv_(specific_heat),
          t0_(initial_temperature), cold_(cold_tolerance),
          // The reference Hugoniot is the EOS's own; the shock parameters are named as the
          // thermal policy's if they are bad (validated before the EOS sees them).
          hugoniot_((detail::validate_shock_parameters(density0, sound_speed, slope, gruneisen, specific_heat,
                                                       initial_temperature),
                     eos::mie_gruneisen<>(density0, sound_speed, slope, gruneisen))) {
        require_non_negative("cold_tolerance (K)", cold_tolerance);
        table_ = std::make_shared<const table>(build());
    }

    /// Set a new particle's temperature to T_0.
    template <class P>
    void initialize(const P& p) const {
        auto& t = p.template get<fields::temperature>();
        t = static_cast<std::remove_cvref_t<decltype(t)>>(t0_);
    }

    /// T from the end-of-step state. `dissipated` (plastic work) is already in e: not added again.
    /// T_s(J) comes from the table with e_s(J), interpolated as e_s is (for HMX within 6.1e-13 of
    /// T0 J^-Gamma relative on the table, exact off it; docs/equations.md,
    /// "thermal::isentrope_temperature"), which spares a `pow` per particle and step.
    template <class Real, class P>
    GIMLET_INLINE void update(const point_step<Real>& st, Real /*dissipated*/, const P& p) const {
        const double j = double(st.J);
        const double e_th = double(p.template get<fields::specific_internal_energy>()) - double(st.shear_energy);
        if (!(j > j_sing())) beyond_singularity(j, p, st.step, st.time);
        const reference_state ref = table_->both(*this, j);
        const double below = ref.energy - e_th;
        if (below > cv_ * cold_) too_cold(j, e_th, below, p, st.step, st.time);
        p.template get<fields::temperature>() = Real(ref.temperature - below / cv_);
    }

    /// T_s(J) = T0 J^-Gamma, the reference isentrope's temperature (K).
    [[nodiscard]] double isentrope(double j) const { return t0_ * std::pow(j, -gamma_); }

    /// T(J, e_th) (K), no checks.
    [[nodiscard]] double temperature(double j, double e_th) const {
        return isentrope(j) + (e_th - reference_energy(j)) / cv_;
    }

    /// e_s(J) (J/kg), the specific energy on the reference isentrope. Throws invalid_parameter
    /// at or beyond the singular compression J = 1 - 1/s.
    [[nodiscard]] double reference_energy(double j) const {
        // The message is built only on failure: the volume filter calls this twice per particle and step.
        if (!(std::isfinite(j) && j > j_sing()))
            throw invalid_parameter("J = V/V0 of the reference isentrope", gimlet::detail::to_text(j),
                                    "> 1 - 1/s = " + gimlet::detail::to_text(j_sing()));
        return table_->at(*this, j);
    }

    /// The isentrope's pressure P_s(J) = P_H + Gamma rho0 / J (e_s - e_H) (Pa).
    [[nodiscard]] double reference_pressure(double j) const {
        return hugoniot_pressure(j) + gamma_ * rho0_ / j * (reference_energy(j) - hugoniot_energy(j));
    }

    /// rho_0 (kg/m^3).
    [[nodiscard]] double density0() const noexcept { return rho0_; }
    /// c_0 (m/s), the Hugoniot's bulk sound speed.
    [[nodiscard]] double sound_speed() const noexcept { return c0_; }
    /// s, the slope of the Hugoniot's U_s-u_p line.
    [[nodiscard]] double slope() const noexcept { return s_; }
    /// c_v (J/(kg K)).
    [[nodiscard]] double specific_heat() const noexcept { return cv_; }
    /// T_0 (K), the temperature at the reference state.
    [[nodiscard]] double initial_temperature() const noexcept { return t0_; }
    /// Gamma, the Grueneisen parameter.
    [[nodiscard]] double gruneisen() const noexcept { return gamma_; }
    /// How far (K) e_th may fall below the reference isentrope, as c_v times it, before the update stops the run.
    [[nodiscard]] double cold_tolerance() const noexcept { return cold_; }

private:
    /// e_s(J) and T_s(J) at one J.
    struct reference_state {
        double energy, temperature;
    };

    /// The tabulated reference isentrope: nodes uniform in x = ln(J - J_sing).
    struct table {
        double x0 = 0, dx = 0;
        std::vector<double> e, de_dx;    ///< e_s and de_s/dx at the nodes
        std::vector<double> ts, dts_dx;  ///< T_s and dT_s/dx at the nodes

        /// Cubic Hermite on [x_k, x_k+1] with the exact slopes, at u = (x - x0) / dx in
        /// [0, nodes - 1): the node k and the four basis values. Its error is
        /// f^(4)(xi) / 4! (x - x_k)^2 (x - x_k+1)^2, at most dx^4 / 384 max |f^(4)| (the Hermite
        /// remainder: Burden & Faires, Numerical Analysis, 9th ed., Theorem 3.9).
        struct place {
            /// The node at the cell's lower end.
            std::size_t k;
            ///@{
            /// Hermite basis value at u: h00, h10 weigh the lower node's value and slope, h01, h11 the upper node's.
            double h00, h10, h01, h11;
            ///@}
        };
        GIMLET_INLINE static place hermite(double u) {
            const auto k = static_cast<std::size_t>(u);
            const double t = u - double(k), t2 = t * t, t3 = t2 * t;
            return {k, 2 * t3 - 3 * t2 + 1, t3 - 2 * t2 + t, -2 * t3 + 3 * t2, t3 - t2};
        }
        GIMLET_INLINE double energy(const place& h) const {
            return h.h00 * e[h.k] + h.h10 * dx * de_dx[h.k] + h.h01 * e[h.k + 1] + h.h11 * dx * de_dx[h.k + 1];
        }
        GIMLET_INLINE double temperature(const place& h) const {
            return h.h00 * ts[h.k] + h.h10 * dx * dts_dx[h.k] + h.h01 * ts[h.k + 1] + h.h11 * dx * dts_dx[h.k + 1];
        }

        // e_s at J, and with Temperature T_s too (interpolated in the same cell; off the table,
        // e_s integrated directly and T_s exactly). e_s is the same value either way.
        template <bool Temperature>
        GIMLET_INLINE reference_state lookup(const isentrope_temperature& th, double j) const {
            const double u = (std::log(j - th.j_sing()) - x0) / dx;
            auto off = [&](std::size_t k) -> reference_state {
                return {th.direct(j, k), Temperature ? th.isentrope(j) : 0.0};
            };
            if (!(u >= 0.0)) return off(0);
            if (!(u < double(e.size() - 1))) return off(e.size() - 1);
            const place h = hermite(u);
            return {energy(h), Temperature ? temperature(h) : 0.0};
        }
        GIMLET_INLINE double at(const isentrope_temperature& th, double j) const { return lookup<false>(th, j).energy; }
        GIMLET_INLINE reference_state both(const isentrope_temperature& th, double j) const { return lookup<true>(th, j); }
    };

    static constexpr std::size_t compressed_nodes = 1024;  ///< nodes from the compressed end to J = 1
    static constexpr double table_margin = 0.01;  ///< 1 - s eta at the table's compressed end
    static constexpr double table_top = 3.0;      ///< J at its expanded end (or the first node past it)

    [[nodiscard]] double j_sing() const { return 1.0 - 1.0 / s_; }

    [[nodiscard]] double hugoniot_pressure(double j) const { return hugoniot_.hugoniot_pressure(j); }
    [[nodiscard]] double hugoniot_energy(double j) const { return hugoniot_.hugoniot_energy(j); }

    /// The integrand g(J) = d(J^Gamma e_s)/dJ.
    [[nodiscard]] double integrand(double j) const {
        return -hugoniot_pressure(j) / rho0_ * std::pow(j, gamma_) * (1.0 - gamma_ * (1.0 - j) / (2.0 * j));
    }

    /// int_a^b g(J) dJ by 8-point Gauss-Legendre in x = ln(J - J_sing) (smooth there).
    [[nodiscard]] double integral(double a, double b) const {
        static constexpr std::array<double, 4> node{0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                                    0.9602898564975363};
        static constexpr std::array<double, 4> weight{0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                                      0.1012285362903763};
        const double xa = std::log(a - j_sing()), xb = std::log(b - j_sing());
        const double mid = 0.5 * (xa + xb), half = 0.5 * (xb - xa);
        double sum = 0;
        for (std::size_t i = 0; i < node.size(); ++i)
            for (const double sign : {-1.0, 1.0}) {
                const double x = mid + sign * half * node[i];
                const double jx = j_sing() + std::exp(x);
                sum += weight[i] * integrand(jx) * (jx - j_sing());  // dJ = (J - J_sing) dx
            }
        return half * sum;
    }

    /// e_s(J) for a state off the table: integrated onwards from the table's end node `k`
    /// (int_1^J g = e_s(J_k) J_k^Gamma + int_{J_k}^J g), in steps no wider than the table's.
    [[nodiscard]] double direct(double j, std::size_t k) const {
        const table& t = *table_;
        const double xa = t.x0 + t.dx * double(k), xb = std::log(j - j_sing());
        const double ja = j_sing() + std::exp(xa);
        const auto steps = static_cast<std::size_t>(std::ceil(std::abs(xb - xa) / t.dx)) + 1;
        double sum = t.e[k] * std::pow(ja, gamma_), prev = ja;
        for (std::size_t n = 1; n <= steps; ++n) {
            const double next = j_sing() + std::exp(xa + (xb - xa) * double(n) / double(steps));
            sum += integral(prev, next);
            prev = next;
        }
        return sum * std::pow(j, -gamma_);
    }

    [[nodiscard]] table build() const {
        table t;
        // J = 1 is node k1 exactly, so e_s(1) = 0 exactly; 1 - s eta = margin at node 0.
        const std::size_t k1 = compressed_nodes;
        const double x1 = std::log(1.0 - j_sing());
        t.x0 = std::log(table_margin / s_);  // 1 - s eta = margin  <=>  J - J_sing = margin / s
        t.dx = (x1 - t.x0) / double(k1);
        const auto nodes = k1 + static_cast<std::size_t>(std::ceil((std::log(table_top - j_sing()) - x1) / t.dx)) + 1;
        t.e.resize(nodes);
        t.de_dx.resize(nodes);
        t.ts.resize(nodes);
        t.dts_dx.resize(nodes);
        auto j_at = [&](std::size_t k) { return k == k1 ? 1.0 : j_sing() + std::exp(t.x0 + t.dx * double(k)); };
        // Outwards from J = 1 node by node: I(J) = int_1^J g.
        std::vector<double> cumulative(nodes);
        cumulative[k1] = 0.0;
        for (std::size_t k = k1; k-- > 0;) cumulative[k] = cumulative[k + 1] + integral(j_at(k + 1), j_at(k));
        for (std::size_t k = k1 + 1; k < nodes; ++k) cumulative[k] = cumulative[k - 1] + integral(j_at(k - 1), j_at(k));
        for (std::size_t k = 0; k < nodes; ++k) {
            const double j = j_at(k);
            const double es = cumulative[k] * std::pow(j, -gamma_);
            t.e[k] = es;
            // de_s/dJ = -P(J, e_s) / rho0 on the isentrope, and dJ/dx = J - J_sing.
            const double p = hugoniot_pressure(j) + gamma_ * rho0_ / j * (es - hugoniot_energy(j));
            t.de_dx[k] = -p / rho0_ * (j - j_sing());
            // T_s = T0 J^-Gamma: dT_s/dJ = -Gamma T_s / J, and dJ/dx = J - J_sing. With
            // w = (J - J_sing) / J, d^4 T_s / dx^4 is T_s times a quartic in w whose
            // coefficients are polynomials in Gamma; for HMX (Gamma = 1.1) it is at most 0.57
            // on the table, so the interpolation keeps T_s to 6.1e-13 (the remainder above,
            // dx = ln(100) / 1024).
            t.ts[k] = isentrope(j);
            t.dts_dx[k] = -gamma_ * t.ts[k] / j * (j - j_sing());
        }
        return t;
    }

    // The messages of update's two checks, out of line (GIMLET_COLD).
    template <class P>
    [[noreturn]] GIMLET_COLD void beyond_singularity(double j, const P& p, std::size_t step, double time) const {
        throw numerical_error(describe_particle(p, step, time) + ": J = " + gimlet::detail::to_text(j) +
                              " is at or beyond the singular compression 1 - 1/s = " + gimlet::detail::to_text(j_sing()) +
                              " of the reference isentrope");
    }
    template <class P>
    [[noreturn]] GIMLET_COLD void too_cold(double j, double e_th, double below, const P& p, std::size_t step,
                                           double time) const {
        throw numerical_error(describe_particle(p, step, time) + ": thermal energy e_th = " +
                              gimlet::detail::to_text(e_th) + " J/kg is below the reference isentrope e_s(V) by " +
                              gimlet::detail::to_text(below) + " J/kg (" + gimlet::detail::to_text(below / cv_) +
                              " K, more than cold_tolerance " + gimlet::detail::to_text(cold_) + " K) at J = " +
                              gimlet::detail::to_text(j) + ": the numerics lost energy");
    }

    double rho0_, c0_, s_, gamma_, cv_, t0_, cold_;
    eos::mie_gruneisen<> hugoniot_;  // the reference curve P_H(J), e_H(J)
    std::shared_ptr<const table> table_;
};

static_assert(Thermal<isentrope_temperature>);

}  // namespace gimlet::thermal
