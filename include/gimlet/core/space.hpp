// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The space a solver works in: its dimension and its scalar type, and the small fixed-size
/// Eigen types derived from them.

#include "gimlet/core/detail/inline.hpp"

#include <Eigen/Core>
#include <Eigen/LU>  // determinant
#include <concepts>

/// gimlet: a header-only GIMP/MPM library. Start from gimlet::solver, scene::scene and
/// gimlet::material; gimlet/gimlet.hpp includes everything.
namespace gimlet {

/// Dimension and scalar type of a simulation.
/// \tparam Dim  2 (plane strain) or 3.
/// \tparam Real float or double.
template <int Dim, std::floating_point Real = double>
struct space {
    static_assert(Dim == 2 || Dim == 3, "gimlet supports Dim = 2 (plane strain) and Dim = 3");
    /// Number of axes, 2 or 3.
    static constexpr int dim = Dim;
    /// The scalar type.
    using real = Real;
    /// A position, velocity or force: Dim components.
    using vector = Eigen::Matrix<Real, Dim, 1>;
    /// A node index per axis.
    using ivector = Eigen::Matrix<int, Dim, 1>;
    /// A Dim x Dim tensor (deformation gradient, in-plane stress).
    using matrix = Eigen::Matrix<Real, Dim, Dim>;
    /// Constitutive laws always work on 3x3 tensors; in plane strain the out-of-plane
    /// components are carried explicitly (docs/physics.md section 4: s_zz != 0).
    using tensor3 = Eigen::Matrix<Real, 3, 3>;
};

/// The 2-D axisymmetric space: axis 0 is the radius r >= 0, axis 1 the axis of symmetry z, and
/// the out-of-plane direction the hoop direction theta. Every particle is a ring: its mass and
/// volume are per radian (m_p = rho A_p r_p), its weights average over its domain with the
/// weight r, and its stress carries sigma_thetatheta in the slot plane strain keeps for sigma_zz
/// (docs/equations.md, "Axisymmetric GIMP"). The grid must start at r = 0.
/// \tparam Real float or double.
template <std::floating_point Real = double>
struct axisymmetric_space : space<2, Real> {
    /// True: the solver adds the hoop terms (is_axisymmetric_v).
    static constexpr bool axisymmetric = true;
};

/// Whether S is an axisymmetric space (axisymmetric_space): plane-strain and 3-D spaces are not.
template <class S>
inline constexpr bool is_axisymmetric_v = requires { requires S::axisymmetric; };

/// A type is a space if it names a dimension and the derived types.
template <class S>
concept Space = requires {
    { S::dim } -> std::convertible_to<int>;
    typename S::real;
    typename S::vector;
    typename S::matrix;
    typename S::tensor3;
};

/// Embed an in-plane tensor into 3x3 (zero out-of-plane entries); identity in 3-D.
template <class Real, int Dim>
[[nodiscard]] GIMLET_INLINE Eigen::Matrix<Real, 3, 3> embed3(const Eigen::Matrix<Real, Dim, Dim>& a) {
    if constexpr (Dim == 3) {
        return a;
    } else {
        Eigen::Matrix<Real, 3, 3> r = Eigen::Matrix<Real, 3, 3>::Zero();
        r.template topLeftCorner<2, 2>() = a;
        return r;
    }
}

/// a - c I for a 3x3 tensor, entry by entry as Eigen's expression `a - c * Identity()` forms it
/// (a_ij - c * delta_ij, the product taken with 0 off the diagonal as well, so that signed zeros
/// and NaNs come out the same, under the default floating-point model: not under -ffast-math).
/// Written out because a unit that holds several solvers leaves that expression to an
/// out-of-line Eigen loop, a call per particle with the tensors in memory (docs/performance.md,
/// "How the step is organised for speed").
template <class Real>
[[nodiscard]] GIMLET_INLINE Eigen::Matrix<Real, 3, 3> minus_identity(const Eigen::Matrix<Real, 3, 3>& a, Real c) {
    Eigen::Matrix<Real, 3, 3> r;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) r(i, j) = a(i, j) - c * (i == j ? Real(1) : Real(0));
    return r;
}

/// The in-plane block of a 3x3 tensor; identity in 3-D.
template <int Dim, class Real>
[[nodiscard]] GIMLET_INLINE Eigen::Matrix<Real, Dim, Dim> in_plane(const Eigen::Matrix<Real, 3, 3>& a) {
    return a.template topLeftCorner<Dim, Dim>();
}

}  // namespace gimlet
