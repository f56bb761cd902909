// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Quadratic B-spline shape function: C1, support 1.5 cells.

#include "gimlet/core/fields.hpp"
#include "gimlet/shape/concepts.hpp"
#include "gimlet/shape/detail/stencil.hpp"

namespace gimlet::shape {

/// The uniform quadratic B-spline (Steffen, Kirby & Berzins 2008; docs/physics.md section 2):
/// \f[ N(r) = \tfrac34 - r^2 \ (|r| < \tfrac12), \quad \tfrac12 (\tfrac32 - |r|)^2
///     \ (\tfrac12 \le |r| < \tfrac32), \quad 0 \text{ beyond}. \f]
/// Its smooth gradient removes the cell-crossing error of linear MPM without a particle size.
///
/// With f = x - (nearest node) in [-1/2, 1/2) the three live nodes take the closed forms
/// below (no per-node branch); each is N at that node's distance, 1 + f, f and 1 - f.
struct bspline_quadratic {
    static constexpr const char* name = "bspline_quadratic";  ///< for output and tables
    /// Three nodes per axis.
    static constexpr int stencil = 3;
    /// It reads no per-particle field.
    using required_fields = gimlet::field_list<>;

    /// \tparam Real float or double. The half-width is unused.
    template <class Real>
    static void weights(Real x, Real /*l*/, int& first, Real* w, Real* dw) noexcept {
        const Real f = detail::locate<stencil>(x, first);
        const Real left = Real(0.5) - f;   // 3/2 - distance to node first
        const Real right = Real(0.5) + f;  // 3/2 - distance to node first + 2
        w[0] = left * left / 2;
        w[1] = Real(0.75) - f * f;
        w[2] = right * right / 2;
        dw[0] = -left;
        dw[1] = -2 * f;
        dw[2] = right;
    }

    /// Zero: B-spline particles carry no size.
    template <class P, class Real>
    [[nodiscard]] static typename P::space_type::vector half_width(const P& /*p*/, Real /*h*/) {
        return P::space_type::vector::Zero();
    }
};

}  // namespace gimlet::shape

static_assert(gimlet::shape::Shape<gimlet::shape::bspline_quadratic>);
