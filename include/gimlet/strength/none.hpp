// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// No strength: an inviscid fluid whose stress is the EOS pressure alone.

#include "gimlet/strength/concepts.hpp"

namespace gimlet::strength {

/// Strength off: the deviatoric stress stays zero; sigma = -(P + q) I.
struct none {
    /// It keeps no per-particle state.
    using required_fields = field_list<>;

    /// Set s to zero; returns 0.
    template <class Real, class P>
    Real update(const point_step<Real>& /*st*/, Eigen::Matrix<Real, 3, 3>& s, const P& /*p*/) const {
        s.setZero();
        return Real(0);
    }
    /// 0: no shear stiffness.
    template <class Real, class P>
    [[nodiscard]] Real shear_modulus(const point_state<Real>& /*state*/, const P& /*p*/) const {
        return Real(0);
    }
};

static_assert(Strength<none>);

}  // namespace gimlet::strength
