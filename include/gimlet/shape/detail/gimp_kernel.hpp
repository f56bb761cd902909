// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The 1-D GIMP weight shared by uGIMP and cpGIMP: the two differ only in where the particle
/// half-width comes from, never in the function of (r, l).

#include "gimlet/shape/detail/stencil.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
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
/// `inv_l` is 1/l, computed once per particle and axis: dividing by l at every node would be
/// most of the cost of the weights (the stencil's 3 nodes x 4 divisions per axis).
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

#if defined(__GNUC__)  // g++ and clang: their vector types (no header, no flag)
/// gimp_weights for both axes of a 2-D particle at once, the axes in the two lanes of one
/// 16-byte vector: gimp_kernel's formula (docs/physics.md section 2; Bardenhagen & Kober 2004),
/// the same expressions lane by lane, so the same numbers bit for bit (tested,
/// in the build the test runs in: a build that contracts products and sums into FMAs, such as
/// g++ with -march=native, may fuse the two forms differently).
/// Why: g++ 12 compiles gimp_kernel's max and clamp into a compare and a jump each (13 jumps
/// per axis, 42-44 ns per particle), where clang uses maxsd/minsd (16-17 ns); on vectors g++
/// selects without jumps too (23-24 ns; docs/performance.md, "What bounds each phase").
inline void gimp_weights_2d(const std::array<double, 2>& x, const std::array<double, 2>& l_in, std::array<int, 2>& first,
                            std::array<std::array<double, gimp_stencil>, 2>& w,
                            std::array<std::array<double, gimp_stencil>, 2>& dw) noexcept {
    typedef double V __attribute__((vector_size(16)));
    typedef std::int64_t M __attribute__((vector_size(16)));
    const double l0 = std::clamp(l_in[0], std::numeric_limits<double>::min(), 0.5);
    const double l1 = std::clamp(l_in[1], std::numeric_limits<double>::min(), 0.5);
    const double o0 = locate<gimp_stencil>(x[0], first[0]), o1 = locate<gimp_stencil>(x[1], first[1]);
    const V l = {l0, l1}, offset = {o0, o1}, zero = {0.0, 0.0}, one = {1.0, 1.0};
    const V inv_l = one / l, half_inv_l = 0.5 * inv_l, two_l = 2.0 * l;
    const M sign = {std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::min()};
    for (int a = 0; a < gimp_stencil; ++a) {
        const V r = offset + double(1 - a);
        const V abs_r = std::bit_cast<V>(std::bit_cast<M>(r) & ~sign);  // std::abs
        const V u = one + l - abs_r;
        const V t_low = u < zero ? zero : u;                 // std::clamp(u, 0, 2l): u < 0 ? 0 : (2l < u ? 2l : u)
        const V t = two_l < t_low ? two_l : t_low;
        const V pl = l - abs_r;
        const V p = zero < pl ? pl : zero;                   // std::max(0, l - a): 0 < v ? v : 0
        const V ol = one - l - abs_r;
        const V outer = zero < ol ? ol : zero;
        const V wv = t * t * (0.5 * half_inv_l) + outer - p * p * half_inv_l;
        const V s = std::bit_cast<V>((std::bit_cast<M>(r) & sign) | std::bit_cast<M>(one));  // std::copysign(1, r)
        const V dv = s * (p * inv_l - t * half_inv_l);
        w[0][a] = wv[0], w[1][a] = wv[1];
        dw[0][a] = dv[0], dw[1][a] = dv[1];
    }
}
#endif

/// The members uGIMP and cpGIMP share, which differ only in their half-width: the stencil, the
/// weights (the Shape concept's), and under g++ and clang the optional weights_2d with the name
/// of the shape it belongs to (docs/concepts.md, "Shape"): a shape derived from ugimp or cpgimp
/// inherits the member but not the name, so its own weights() is used.
template <class Self>
struct gimp_weights_of {
    static constexpr int stencil = gimp_stencil;

    /// \tparam Real float or double. \pre 0 < l <= 1/2 (clamped there; see gimp_weights).
    template <class Real>
    static void weights(Real x, Real l, int& first, Real* w, Real* dw) noexcept {
        gimp_weights(x, l, first, w, dw);
    }

#if defined(__GNUC__)
    /// Both axes of a 2-D particle at once, the same numbers as weights() axis by axis, bit for
    /// bit (why, at gimp_weights_2d).
    using weights_2d_shape = Self;
    static void weights_2d(const std::array<double, 2>& x, const std::array<double, 2>& l, std::array<int, 2>& first,
                           std::array<std::array<double, gimp_stencil>, 2>& w,
                           std::array<std::array<double, gimp_stencil>, 2>& dw) noexcept {
        gimp_weights_2d(x, l, first, w, dw);
    }
#endif
};

}  // namespace gimlet::shape::detail
