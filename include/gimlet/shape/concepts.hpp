// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The shape-function contract. Every shape function in gimlet is a tensor product of 1-D
/// factors (docs/physics.md section 2), so a policy states only its 1-D weight and gradient on a
/// uniform grid, in cell units, plus how wide its stencil is and what particle half-width it
/// uses (GIMP families need one; plain MPM and B-splines ignore it).

#include "gimlet/core/fields.hpp"
#include "gimlet/core/particle_store.hpp"

#include <concepts>

/// Shape-function policies: the grid weights of a particle (shape::Shape).
namespace gimlet::shape {

/// A shape-function policy.
///
/// - `stencil`: the number of nodes per axis that can have a non-zero weight (the support).
/// - `required_fields`: a field_list of the per-particle fields it reads beyond the core ones
///   (uGIMP and cpGIMP: fields::domain_half_width; empty for fixed stencils).
/// - `weights(x, l, first, w, dw)`: for a particle at `x` (in cell units, node k sits at x = k)
///   with half-width `l` (cell units, 0 < l <= 1/2 for GIMP's 3-node stencil; ignored by other
///   families), write the first node index `first` and, for nodes `first .. first + stencil - 1`,
///   the weights `w[a]` and derivatives `dw[a] = dS/dx` (per cell). Where S has a kink exactly at
///   x (linear MPM on a node), dw is the derivative from the right, which keeps sum dw = 0.
///   Nodes of the stencil outside the support get exactly zero. gimlet's policies find `first`
///   with shape::detail::locate (exact floor arithmetic) rather than floor(x + 1/2), which can
///   round the wrong way.
/// - `half_width(p, h)`: the particle's half-width per axis in cell units (zero if unused).
/// - optional, `weights_2d(x, l, first, w, dw)` on `std::array`s of the two axes of a 2-D double
///   particle, with `using weights_2d_shape = <the shape itself>`: what `weights` gives axis by
///   axis, bit for bit; the solver then calls it instead (ugimp and cpgimp have one under g++ and
///   clang; docs/concepts.md).
///
/// \code
/// struct nearest_node {                      // a (useless but conforming) user policy
///     static constexpr int stencil = 1;
///     using required_fields = gimlet::field_list<>;
///     template <class Real>
///     static constexpr void weights(Real x, Real, int& first, Real* w, Real* dw) noexcept {
///         first = static_cast<int>(std::floor(x + Real(0.5))); w[0] = 1; dw[0] = 0;
///     }
///     template <class P, class Real>
///     static auto half_width(const P&, Real) { return typename P::space_type::vector::Zero().eval(); }
/// };
/// \endcode
template <class Sh>
concept Shape = requires {
    { Sh::stencil } -> std::convertible_to<int>;
    requires Sh::stencil >= 1;
    typename Sh::required_fields;
    requires FieldList<typename Sh::required_fields>;
} && requires(double x, double l, int& first, double* w, double* dw) {
    { Sh::weights(x, l, first, w, dw) } -> std::same_as<void>;
} && requires(float x, float l, int& first, float* w, float* dw) {
    { Sh::weights(x, l, first, w, dw) } -> std::same_as<void>;
} && requires(const particle_ref<particle_store<space<2, double>,
                                                field_union_t<core_fields<space<2, double>>,
                                                              typename Sh::required_fields>>>& p) {
    { Sh::half_width(p, 1.0) } -> std::convertible_to<Eigen::Vector2d>;
} && requires(const particle_ref<particle_store<space<3, double>,
                                                field_union_t<core_fields<space<3, double>>,
                                                              typename Sh::required_fields>>>& p) {
    { Sh::half_width(p, 1.0) } -> std::convertible_to<Eigen::Vector3d>;
};

}  // namespace gimlet::shape
