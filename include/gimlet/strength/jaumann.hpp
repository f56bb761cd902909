// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Tensor helpers shared by hypoelastic strength laws.

#include "gimlet/core/material_point.hpp"

namespace gimlet::strength {

/// The deviator a - tr(a)/3 I of a 3x3 tensor.
template <class Real>
[[nodiscard]] Eigen::Matrix<Real, 3, 3> deviator(const Eigen::Matrix<Real, 3, 3>& a) {
    return a - (a.trace() / Real(3)) * Eigen::Matrix<Real, 3, 3>::Identity();
}

/// The rotation part of a Jaumann-rate update over one step: s <- Q s Q^T with
/// Q = (I - dt W/2)^-1 (I + dt W/2) (Hughes & Winget 1980, eqs. 14-16). To first order in dt it
/// is s + dt (W s - s W), the Jaumann term of docs/physics.md section 4; unlike that explicit form, Q
/// is exactly orthogonal, so a rigid spin rotates the stress without changing its invariants.
template <class Real>
[[nodiscard]] Eigen::Matrix<Real, 3, 3> jaumann_rotate(const point_step<Real>& st,
                                                       const Eigen::Matrix<Real, 3, 3>& s) {
    using T3 = Eigen::Matrix<Real, 3, 3>;
    // For a skew A = dt W/2 with axial vector a, the Cayley transform has the closed form
    // (I - A)^-1 (I + A) = I + 2 (A + A^2) / (1 + |a|^2) (Rodrigues' form of the Cayley map),
    // which avoids a 3x3 inverse per particle and step.
    const T3 a = Real(0.5) * st.dt * st.W;
    const Real a2 = a(2, 1) * a(2, 1) + a(0, 2) * a(0, 2) + a(1, 0) * a(1, 0);
    const T3 q = T3::Identity() + (Real(2) / (Real(1) + a2)) * (a + a * a);
    return q * s * q.transpose();
}

}  // namespace gimlet::strength
