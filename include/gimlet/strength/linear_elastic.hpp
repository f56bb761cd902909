// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Hypoelastic isotropic linear elasticity for the deviatoric stress, Jaumann rate.

#include "gimlet/core/detail/inline.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/strength/concepts.hpp"
#include "gimlet/strength/jaumann.hpp"

namespace gimlet::strength {

/// Deviatoric hypoelastic law with the Jaumann (co-rotational) rate
/// \f[ \dot s = 2 G D' + W s - s W \f]
/// (docs/physics.md section 4; the elastic predictor of the reference paper's plasticity model),
/// integrated with the rotation part in incrementally objective form (see jaumann_rotate).
/// The Jaumann terms keep a rigidly rotating stressed body's stress rotating with it and leave
/// an unstressed one unstressed. Combine with an EOS for the pressure (e.g. eos::linear).
class linear_elastic {
public:
    /// It keeps no per-particle state.
    using required_fields = field_list<>;
    /// Its templates compute lane by lane for a lane type (gimlet::lane_safe): no branch on a
    /// value, nothing read through the handle.
    static constexpr bool lane_safe = true;

    /// \param shear_modulus G in Pa, finite and > 0.
    explicit linear_elastic(double shear_modulus) : g_(shear_modulus) {
        require_positive("shear modulus G (Pa)", shear_modulus);
    }

    /// Jaumann-rotate s and add 2 G dt D'; returns 0 (nothing dissipated).
    template <class Real, class P>
    GIMLET_INLINE Real update(const point_step<Real>& st, Eigen::Matrix<Real, 3, 3>& s, const P& /*p*/) const {
        s = jaumann_rotate(st, s);
        s += st.dt * Real(2 * g_) * deviator(st.D);
        return Real(0);
    }

    /// G, constant.
    template <class Real, class P>
    [[nodiscard]] Real shear_modulus(const point_state<Real>& /*state*/, const P& /*p*/) const {
        return Real(g_);
    }

    /// G (Pa).
    [[nodiscard]] double shear_modulus() const noexcept { return g_; }

private:
    double g_;
};

static_assert(Strength<linear_elastic>);

}  // namespace gimlet::strength
