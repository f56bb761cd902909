// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Cubic B-spline shape function: C2, support 2 cells.

#include "gimlet/core/fields.hpp"
#include "gimlet/shape/concepts.hpp"
#include "gimlet/shape/detail/stencil.hpp"

namespace gimlet::shape {

/// The uniform cubic B-spline (Steffen, Kirby & Berzins 2008; docs/physics.md section 2):
/// \f[ N(r) = \tfrac23 - r^2 + \tfrac12 |r|^3 \ (|r| < 1), \quad \tfrac16 (2 - |r|)^3
///     \ (1 \le |r| < 2), \quad 0 \text{ beyond}. \f]
/// Smoother than the quadratic one at the price of a 4-node stencil per axis.
///
/// With t = x - floor(x) in [0, 1) and u = 1 - t the four live nodes sit at distances
/// 1 + t, t, u, 1 + u; the inner two share one cubic (in t and in u), the outer two another.
struct bspline_cubic {
    static constexpr const char* name = "bspline_cubic";  ///< for output and tables
    /// Four nodes per axis.
    static constexpr int stencil = 4;
    /// It reads no per-particle field.
    using required_fields = gimlet::field_list<>;

    /// \tparam Real float or double. The half-width is unused.
    template <class Real>
    static void weights(Real x, Real /*l*/, int& first, Real* w, Real* dw) noexcept {
        const Real t = detail::locate<stencil>(x, first);
        const Real u = 1 - t;
        w[0] = u * u * u / 6;
        w[1] = Real(2) / 3 - t * t + t * t * t / 2;
        w[2] = Real(2) / 3 - u * u + u * u * u / 2;
        w[3] = t * t * t / 6;
        // d/dx = d/dt = -d/du.
        dw[0] = -u * u / 2;
        dw[1] = t * (Real(1.5) * t - 2);
        dw[2] = -u * (Real(1.5) * u - 2);
        dw[3] = t * t / 2;
    }

    /// Zero: B-spline particles carry no size.
    template <class P, class Real>
    [[nodiscard]] static typename P::space_type::vector half_width(const P& /*p*/, Real /*h*/) {
        return P::space_type::vector::Zero();
    }
};

}  // namespace gimlet::shape

static_assert(gimlet::shape::Shape<gimlet::shape::bspline_cubic>);
