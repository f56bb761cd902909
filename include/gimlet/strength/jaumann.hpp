// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Tensor helpers shared by hypoelastic strength laws.

#include "gimlet/core/lanes.hpp"
#include "gimlet/core/material_point.hpp"

#include <cassert>

namespace gimlet::strength {

/// The deviator a - tr(a)/3 I of a 3x3 tensor.
template <class Real>
[[nodiscard]] GIMLET_INLINE Eigen::Matrix<Real, 3, 3> deviator(const Eigen::Matrix<Real, 3, 3>& a) {
    return minus_identity(a, a.trace() / Real(3));
}

/// The rotation part of a Jaumann-rate update over one step: s <- Q s Q^T with
/// Q = (I - dt W/2)^-1 (I + dt W/2) (Hughes & Winget 1980, eqs. 14-16). To first order in dt it
/// is s + dt (W s - s W), the Jaumann term of docs/physics.md section 4; unlike that explicit form, Q
/// is exactly orthogonal, so a rigid spin rotates the stress without changing its invariants.
template <class Real>
[[nodiscard]] GIMLET_INLINE Eigen::Matrix<Real, 3, 3> jaumann_rotate(const point_step<Real>& st,
                                                       const Eigen::Matrix<Real, 3, 3>& s) {
    using T3 = Eigen::Matrix<Real, 3, 3>;
    // For a skew A = dt W/2 with axial vector a, the Cayley transform has the closed form
    // (I - A)^-1 (I + A) = I + 2 (A + A^2) / (1 + |a|^2) (Rodrigues' form of the Cayley map),
    // which avoids a 3x3 inverse per particle and step.
    // Precondition of the plane-strain path: W spins about z only (checked in debug builds).
    assert(!st.plane_strain || all_lanes(st.W(0, 2) == Real(0) && st.W(1, 2) == Real(0) && st.W(2, 0) == Real(0) &&
                                           st.W(2, 1) == Real(0)));
    if (st.plane_strain) {
        // The same map with a about z only: Q = [[c, -r, 0], [r, c, 0], [0, 0, 1]],
        // c = 1 - 2 w^2 / (1 + w^2), r = 2 w / (1 + w^2), w = dt W_yx / 2. It rotates the
        // in-plane block and the out-of-plane rows and columns, s_zz is unchanged: a third of
        // the 3x3 form's products, with its operands in its order (the same bits in a portable
        // build; docs/performance.md).
        const Real w = Real(0.5) * st.dt * st.W(1, 0);
        const Real k = Real(2) / (Real(1) + w * w);
        const Real c = Real(1) - k * (w * w), r = k * w;
        const Real x = s(0, 0), y = s(0, 1), yt = s(1, 0), z = s(1, 1);
        const Real a00 = c * x - r * yt, a01 = c * y - r * z;  // (Q s), in-plane block
        const Real a10 = r * x + c * yt, a11 = r * y + c * z;
        T3 out;
        out(0, 0) = a00 * c - a01 * r;
        out(0, 1) = a00 * r + a01 * c;
        out(1, 0) = a10 * c - a11 * r;
        out(1, 1) = a10 * r + a11 * c;
        out(0, 2) = c * s(0, 2) - r * s(1, 2);
        out(1, 2) = r * s(0, 2) + c * s(1, 2);
        out(2, 0) = s(2, 0) * c - s(2, 1) * r;
        out(2, 1) = s(2, 0) * r + s(2, 1) * c;
        out(2, 2) = s(2, 2);
        return out;
    }
    const T3 a = Real(0.5) * st.dt * st.W;
    const Real a2 = a(2, 1) * a(2, 1) + a(0, 2) * a(0, 2) + a(1, 0) * a(1, 0);
    const T3 q = T3::Identity() + (Real(2) / (Real(1) + a2)) * (a + a * a);
    return q * s * q.transpose();
}

}  // namespace gimlet::strength
