// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Where a particle's stencil starts. Shared by every shape policy so that all of them choose
/// `first` by the same rule and all of them are exact at nodes and half-cells.

#include <cmath>

namespace gimlet::shape::detail {

/// Locate a particle for a stencil of `Stencil` nodes and return its offset from the stencil's
/// anchor node, in cell units.
///
/// Even stencils (support `Stencil/2` cells) are anchored at `floor(x)`, offset in [0, 1); odd
/// stencils (support up to `Stencil/2 + 1/2` cells) at the nearest node, offset in [-1/2, 1/2),
/// a half-cell rounding up. `first` is the anchor minus `(Stencil - 1) / 2`. With that rule
/// every node whose support the particle is in lies inside the stencil, for any x; nodes at
/// exactly the support's edge may fall either side and carry zero weight either way.
///
/// The nearest node is not taken as `floor(x + 1/2)`: that sum rounds (x = 0.49999999999999994
/// would give node 1 and an offset below -1/2, dropping a node with non-zero weight). `floor`
/// and `x - floor(x)` are exact, and so is `offset - 1` for an offset in [1/2, 1).
/// \pre x is finite and its floor fits in an int (the solver aborts before either fails).
template <int Stencil, class Real>
[[nodiscard]] inline Real locate(Real x, int& first) noexcept {
    const Real base = std::floor(x);
    Real offset = x - base;
    int anchor = static_cast<int>(base);
    if constexpr (Stencil % 2 == 1) {
        const bool round_up = offset >= Real(0.5);
        anchor += round_up ? 1 : 0;
        offset -= round_up ? Real(1) : Real(0);
    }
    first = anchor - (Stencil - 1) / 2;
    return offset;
}

}  // namespace gimlet::shape::detail
