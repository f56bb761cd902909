// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The 1-D GIMP weight shared by uGIMP and cpGIMP: the two differ only in where the particle
/// half-width comes from, never in the function of (r, l).

#include "gimlet/shape/detail/stencil.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gimlet::shape::detail {

/// Nodes per axis of a GIMP particle: support |r| < 1 + l spans at most 3 nodes while l <= 1/2.
inline constexpr int gimp_stencil = 3;

/// The GIMP weight `w` of a node at signed distance `r = x_p - x_i` (cell units) from a particle
/// of half-width `l`, and `dw = dS/dr`.
///
/// docs/physics.md section 2 states it in branches of a = |r| (Bardenhagen & Kober 2004, the hat
/// averaged over the particle's domain; Wallstedt & Guilkey 2008 for the piecewise form):
/// 1 - (a² + l²)/(2l) for a < l; 1 - a for l <= a < 1 - l; (1 + l - a)²/(4l) for
/// 1 - l <= a < 1 + l; 0 beyond. Here it is one expression, so the hot loop has no
/// data-dependent branch:
/// \f[ S = \frac{t^2}{4l} + \max(0, 1 - l - a) - \frac{p^2}{2l}, \quad
///     \frac{dS}{da} = -\frac{t}{2l} + \frac{p}{l}, \quad
///     t = \mathrm{clamp}(1 + l - a, 0, 2l),\ p = \max(0, l - a). \f]
/// Branch by branch: a < l has t = 2l, p = l - a; the linear branch t = 2l, p = 0; the outer
/// branch t = 1 + l - a, p = 0; beyond the support t = p = 0, so the weight and its derivative
/// are exact zeros there, and every term is non-negative wherever p = 0.
/// `inv_l` is 1/l, computed once per particle and axis: the divisions by l were most of the cost
/// of the weights (the stencil's 3 nodes x 4 divisions per axis).
/// \pre 0 < l <= 1/2 (the branches above only order that way for l <= 1/2).
template <class Real>
inline void gimp_kernel(Real r, Real l, Real inv_l, Real& w, Real& dw) noexcept {
    const Real a = std::abs(r);
    const Real t = std::clamp(1 + l - a, Real(0), 2 * l);
    const Real p = std::max(Real(0), l - a);
    const Real half_inv_l = Real(0.5) * inv_l;
    w = t * t * (Real(0.5) * half_inv_l) + std::max(Real(0), 1 - l - a) - p * p * half_inv_l;
    dw = std::copysign(Real(1), r) * (p * inv_l - t * half_inv_l);
}

/// GIMP weights of a particle at `x` (cell units) for its 3-node stencil; see the Shape concept.
///
/// `l` is clamped into (0, 1/2]. Above 1/2 the support would reach a fourth node and the
/// weights would no longer sum to one; at zero the formula is 0/0, while any tiny positive l
/// gives linear MPM's weights, which is the l -> 0 limit. Scenes validate the half-width where
/// the user sets it; the clamp only keeps the hot loop from producing NaN.
template <class Real>
inline void gimp_weights(Real x, Real l, int& first, Real* w, Real* dw) noexcept {
    l = std::clamp(l, std::numeric_limits<Real>::min(), Real(0.5));
    const Real offset = locate<gimp_stencil>(x, first);
    const Real inv_l = Real(1) / l;
    // Node first + a sits at signed distance x - (first + a) = offset + 1 - a.
    for (int a = 0; a < gimp_stencil; ++a) {
        gimp_kernel(offset + Real(1 - a), l, inv_l, w[a], dw[a]);
    }
}

}  // namespace gimlet::shape::detail
