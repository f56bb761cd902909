// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Classic MPM: the piecewise-linear hat of the grid, C0 across nodes.

#include "gimlet/core/fields.hpp"
#include "gimlet/shape/concepts.hpp"
#include "gimlet/shape/detail/stencil.hpp"

namespace gimlet::shape {

/// The linear hat `S(r) = 1 - |r|/h` for |r| < h (Sulsky, Chen & Schreyer 1994; docs/physics.md
/// section 2). Its gradient jumps at nodes, which is the cell-crossing noise GIMP removes.
///
/// On a node the gradient is one-sided (from the right), the choice `first = floor(x)` implies;
/// it keeps sum(dw) = 0 and sum(dw x_i) = 1 exact there too.
struct linear {
    static constexpr const char* name = "linear";  ///< for output and tables
    /// Two nodes per axis.
    static constexpr int stencil = 2;
    /// It reads no per-particle field.
    using required_fields = gimlet::field_list<>;

    /// \tparam Real float or double. The half-width is unused: a point particle.
    template <class Real>
    static void weights(Real x, Real /*l*/, int& first, Real* w, Real* dw) noexcept {
        const Real t = detail::locate<stencil>(x, first);
        w[0] = 1 - t;
        w[1] = t;
        dw[0] = -1;
        dw[1] = 1;
    }

    /// Zero: MPM particles are points.
    template <class P, class Real>
    [[nodiscard]] static typename P::space_type::vector half_width(const P& /*p*/, Real /*h*/) {
        return P::space_type::vector::Zero();
    }
};

}  // namespace gimlet::shape

static_assert(gimlet::shape::Shape<gimlet::shape::linear>);
