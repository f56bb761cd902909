// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Mie-Grueneisen equation of state with the linear U_s-U_p Hugoniot as reference.

#include "gimlet/core/describe.hpp"
#include "gimlet/core/detail/inline.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/eos/concepts.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>

namespace gimlet::eos {

/// What stands for e - e_H(V), the energy above the Hugoniot, in the Mie-Grueneisen pressure.
enum class energy_reference {
    /// Standard form: e is the specific internal energy integrated from the stress power
    /// (artificial viscosity included); P and e at the end of a step are solved together.
    internal_energy,
    /// The reference paper's variant: e - e_H is the accumulated plastic work per unit mass
    /// (fields::plastic_work, kept by strength::von_mises).
    plastic_work,
};

/// Mie-Grueneisen equation of state on a linear U_s-u_p Hugoniot:
/// \f[ P = P_H(V) + \frac{\Gamma}{V}\,(e - e_H(V)), \qquad e_H = \tfrac12 P_H (V_0 - V) \f]
/// with, for \f$ \eta = 1 - V/V_0 \ge 0 \f$, \f$ P_H = \rho_0 c_0^2 \eta / (1 - s\eta)^2 \f$
/// (the Hugoniot of U_s = c_0 + s U_p), and in tension \f$ P_H = \rho_0 c_0^2 (V_0/V - 1) \f$
/// (docs/physics.md section 5; the reference paper's EOS, with its misprinted \f$\rho_0^2\f$ in the
/// tension branch corrected). \f$\Gamma/V = \Gamma\rho\f$ with constant \f$\Gamma\f$.
///
/// \f$P_H\f$ is singular at \f$\eta = 1/s\f$. The EOS stops the run with a numerical_error
/// naming the particle once \f$1 - s\eta\f$ falls to `singularity_margin` (default 0.05: for
/// HMX that is \f$\eta \approx 0.365\f$, \f$P_H \approx 2\f$ TPa, far beyond the model's
/// validity), so it never returns inf or NaN.
/// \tparam Ref which energy stands for e - e_H (default: the standard internal-energy form).
template <energy_reference Ref = energy_reference::internal_energy>
class mie_gruneisen {
public:
    /// No field for the standard form; fields::plastic_work for the reference paper's variant.
    using required_fields = std::conditional_t<Ref == energy_reference::plastic_work,
                                               field_list<fields::plastic_work>, field_list<>>;
    /// The standard form takes the thermal energy e_th = e - s:s/(4 G rho) (eos::Eos).
    static constexpr bool reads_shear_energy = Ref == energy_reference::internal_energy;

    /// \param density0 rho_0 (kg/m^3) > 0; \param sound_speed c_0 (m/s) > 0;
    /// \param slope s of U_s = c_0 + s U_p, in (1, 20] (the Hugoniot is convex; s <= 1 has no
    /// singularity but no physical meaning for solids here; measured slopes lie below 5, and
    /// at s ~ 1e16 the singular J = 1 - 1/s rounds to 1); \param gruneisen Gamma in [0, 20]
    /// (solids lie below 4; J^Gamma overflows for huge Gamma);
    /// \param singularity_margin in (0, 1): stop when 1 - s eta reaches it.
    mie_gruneisen(double density0, double sound_speed, double slope, double gruneisen,
                  double singularity_margin = 0.05)
        : rho0_(density0), c0_(sound_speed), s_(slope), gamma_(gruneisen), margin_(singularity_margin) {
        require_positive("Mie-Grueneisen reference density rho0 (kg/m^3)", density0);
        require_positive("Mie-Grueneisen bulk sound speed c0 (m/s)", sound_speed);
        require(std::isfinite(slope) && slope > 1.0 && slope <= 20.0, "Mie-Grueneisen Hugoniot slope s", slope, "(1, 20]");
        require(std::isfinite(gruneisen) && gruneisen >= 0.0 && gruneisen <= 20.0, "Grueneisen parameter Gamma",
                gruneisen, "[0, 20]");
        require(singularity_margin > 0.0 && singularity_margin < 1.0, "Mie-Grueneisen singularity_margin",
                singularity_margin, "(0, 1)");
    }

    /// Hugoniot pressure P_H at J = V/V_0 (Pa).
    [[nodiscard]] double hugoniot_pressure(double j) const {
        const double eta = 1.0 - j;
        const double k0 = rho0_ * c0_ * c0_;
        if (eta >= 0.0) return k0 * eta / ((1.0 - s_ * eta) * (1.0 - s_ * eta));
        return k0 * (1.0 / j - 1.0);
    }
    /// dP_H/d(eta) at J (Pa).
    [[nodiscard]] double hugoniot_slope(double j) const {
        const double eta = 1.0 - j;
        const double k0 = rho0_ * c0_ * c0_;
        if (eta >= 0.0) {
            // (1 - s eta)^3 by two multiplications: std::pow(x, 3) calls libm's general pow
            // (about 10 ns), and the time step asks this of every compressed particle each step.
            const double d = 1.0 - s_ * eta;
            return k0 * (1.0 + s_ * eta) / (d * d * d);
        }
        return k0 / (j * j);
    }
    /// Hugoniot specific energy e_H = P_H (V_0 - V) / 2 = P_H eta / (2 rho_0) (J/kg).
    [[nodiscard]] double hugoniot_energy(double j) const { return 0.5 * hugoniot_pressure(j) * (1.0 - j) / rho0_; }

    /// Pressure at the end of the step. The standard form solves P together with the end-of-step
    /// energy e = e_b - f P (see point_step), from its thermal part e_th = e - w_s (w_s the stored
    /// elastic shear energy, point_step::shear_energy, which is not heat: the Grueneisen term is
    /// the thermal pressure): P = [P_H + Gamma rho (e_b - w_s - e_H)] / (1 + Gamma rho f).
    template <class Real, class P>
    [[nodiscard]] GIMLET_INLINE Real pressure(const point_step<Real>& st, const P& p) const {
        check_singularity(double(st.J), p, st.step, st.time);
        const double j = double(st.J);
        const double grho = gamma_ * double(st.density);
        const double ph = hugoniot_pressure(j);
        if constexpr (Ref == energy_reference::plastic_work) {
            return Real(ph + grho * double(p.template get<fields::plastic_work>()));
        } else {
            const double eb = double(st.energy_before_pressure) - double(st.shear_energy);
            return Real((ph + grho * (eb - hugoniot_energy(j))) / (1.0 + grho * double(st.pressure_work_factor)));
        }
    }

    ///@{
    /// Isentropic tangent bulk modulus K_s = -V (dP/dV)_s = -V (dP/dV)_e + Gamma P, from
    /// de = -P dV along an isentrope, for the time step's wave speed (never negative). It reads
    /// the whole e (a point_state carries no shear energy; at most Y0^2 / (6 G rho), 185 J/kg
    /// for HMX at yield, a 0.4 MPa part of a 14 GPa modulus). The compression is capped at the singularity margin (where pressure() stops the run),
    /// so the modulus is finite for any state; the three-argument form says when that cap, or
    /// the clamp of a negative modulus to 0, acted (eos::guard bits added to `guards`).
    template <class Real, class P>
    [[nodiscard]] Real bulk_modulus(const point_state<Real>& st, const P& p) const {
        unsigned ignored = 0;
        return bulk_modulus(st, p, ignored);
    }
    template <class Real, class P>
    [[nodiscard]] Real bulk_modulus(const point_state<Real>& st, const P& p, unsigned& guards) const {
        const double j_cap = 1.0 - (1.0 - margin_) / s_;
        if (!(double(st.J) >= j_cap)) guards |= guard::compression_capped;
        const double j = std::max(double(st.J), j_cap);
        const double eta = 1.0 - j;
        const double grho = gamma_ * double(st.density);
        const double excess = energy_excess(j, p);
        const double ph = hugoniot_pressure(j), dph = hugoniot_slope(j);
        const double pres = ph + grho * excess;
        // -V d/dV = J d/d(eta) and Gamma de_H/dV = -Gamma (P_H + eta P_H') / 2, with P_H' = dP_H/d(eta).
        const double k = j * dph + grho * excess - 0.5 * gamma_ * (ph + eta * dph) + gamma_ * pres;
        if (!(k >= 0.0)) guards |= guard::negative_modulus;
        return Real(std::max(k, 0.0));
    }
    ///@}

    /// rho_0 (kg/m^3).
    [[nodiscard]] double density0() const noexcept { return rho0_; }
    /// c_0 (m/s), the Hugoniot's bulk sound speed.
    [[nodiscard]] double sound_speed() const noexcept { return c0_; }
    /// s, the slope of the Hugoniot's U_s-u_p line.
    [[nodiscard]] double slope() const noexcept { return s_; }
    /// Gamma, the Grueneisen parameter.
    [[nodiscard]] double gruneisen() const noexcept { return gamma_; }

private:
    template <class P>
    [[nodiscard]] double energy_excess(double j, const P& p) const {
        if constexpr (Ref == energy_reference::plastic_work) return double(p.template get<fields::plastic_work>());
        else return double(p.template get<fields::specific_internal_energy>()) - hugoniot_energy(j);
    }

    template <class P>
    GIMLET_INLINE void check_singularity(double j, const P& p, std::size_t step, double time) const {
        const double eta = 1.0 - j;
        if (eta > 0.0 && 1.0 - s_ * eta <= margin_) singularity_reached(eta, p, step, time);
    }
    template <class P>
    [[noreturn]] GIMLET_COLD void singularity_reached(double eta, const P& p, std::size_t step, double time) const {
        throw numerical_error(describe_particle(p, step, time) + ": compression eta = 1 - V/V0 = " +
                              detail::to_text(eta) + " reached the Mie-Grueneisen limit (1 - s eta = " +
                              detail::to_text(1.0 - s_ * eta) + " <= singularity_margin " + detail::to_text(margin_) +
                              "; P_H is singular at eta = 1/s = " + detail::to_text(1.0 / s_) + ")");
    }

    double rho0_, c0_, s_, gamma_, margin_;
};

static_assert(Eos<mie_gruneisen<energy_reference::internal_energy>>);
static_assert(Eos<mie_gruneisen<energy_reference::plastic_work>>);

}  // namespace gimlet::eos
