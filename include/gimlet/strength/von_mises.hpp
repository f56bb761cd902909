// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// von Mises plasticity with linear isotropic hardening, hypoelastic predictor (Jaumann rate),
/// radial return.

#include "gimlet/core/detail/inline.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/strength/concepts.hpp"
#include "gimlet/strength/jaumann.hpp"

#include <cmath>

namespace gimlet::strength {

/// Elastic-plastic deviatoric law of the reference paper (docs/physics.md section 4):
/// - predictor \f$ s^* = Q s^n Q^T + 2 G \Delta t D' \f$ (Jaumann rate, see jaumann_rotate);
/// - yield \f$ \sigma_{eq} = \sqrt{3 J_2} \le Y = Y_0 + H \varepsilon_p \f$, \f$ J_2 = \tfrac12 s:s \f$;
/// - radial return \f$ \Delta\varepsilon_p = (\sigma_{eq}^* - Y)/(3G + H) \f$,
///   \f$ s = s^* \, (Y + H \Delta\varepsilon_p)/\sigma_{eq}^* \f$ (Wilkins 1964; Simo & Hughes 1998,
///   box 3.1, specialised to linear hardening);
/// - plastic work per unit mass \f$ \Delta w_p = \int Y\, d\varepsilon_p / \rho
///   = \tfrac12 (Y^n + Y^{n+1}) \Delta\varepsilon_p / \rho \f$, exact for linear hardening; it is
///   returned as the step's dissipation (it becomes heat).
/// The 3x3 deviator includes s_zz in plane strain, so the yield surface is the 3-D one.
class von_mises {
public:
    /// Keeps the equivalent plastic strain and the plastic work per unit mass.
    using required_fields = field_list<fields::plastic_strain, fields::plastic_work>;

    /// \param shear_modulus G (Pa) > 0; \param yield_stress Y0 (Pa) > 0;
    /// \param hardening_modulus H (Pa) >= 0 (linear isotropic hardening).
    von_mises(double shear_modulus, double yield_stress, double hardening_modulus = 0.0)
        : g_(shear_modulus), y0_(yield_stress), h_(hardening_modulus) {
        require_positive("shear modulus G (Pa)", shear_modulus);
        require_positive("yield stress Y0 (Pa)", yield_stress);
        require_non_negative("hardening modulus H (Pa)", hardening_modulus);
    }

    /// Jaumann-rotate s, add the elastic predictor and return radially to the yield surface;
    /// updates the plastic strain and work and returns the plastic work of the step (J/kg).
    template <class Real, class P>
    GIMLET_INLINE Real update(const point_step<Real>& st, Eigen::Matrix<Real, 3, 3>& s, const P& p) const {
        s = jaumann_rotate(st, s);
        s += st.dt * Real(2 * g_) * deviator(st.D);
        Real& eps_p = p.template get<fields::plastic_strain>();
        const Real y_old = Real(y0_) + Real(h_) * eps_p;
        const Real sigma_eq = std::sqrt(Real(1.5) * s.cwiseProduct(s).sum());
        if (sigma_eq <= y_old) return Real(0);
        const Real d_eps = (sigma_eq - y_old) / Real(3 * g_ + h_);
        const Real y_new = y_old + Real(h_) * d_eps;
        s *= y_new / sigma_eq;
        eps_p += d_eps;
        const Real dw = Real(0.5) * (y_old + y_new) * d_eps / st.density;
        p.template get<fields::plastic_work>() += dw;
        return dw;
    }

    /// G, constant.
    template <class Real, class P>
    [[nodiscard]] Real shear_modulus(const point_state<Real>& /*state*/, const P& /*p*/) const {
        return Real(g_);
    }

    /// G (Pa).
    [[nodiscard]] double shear_modulus() const noexcept { return g_; }
    /// Y0 (Pa), the initial yield stress.
    [[nodiscard]] double yield_stress() const noexcept { return y0_; }
    /// H (Pa), the linear hardening modulus.
    [[nodiscard]] double hardening_modulus() const noexcept { return h_; }

private:
    double g_, y0_, h_;
};

static_assert(Strength<von_mises>);

}  // namespace gimlet::strength
