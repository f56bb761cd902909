// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// No artificial viscosity.

#include "gimlet/viscosity/concepts.hpp"

namespace gimlet::viscosity {

/// Artificial viscosity off: q = 0, and no viscosity code is compiled into the step.
struct none {
    /// Off: the solver compiles no viscosity code.
    static constexpr bool enabled = false;
    /// It keeps no per-particle state.
    using required_fields = field_list<>;
};

static_assert(Viscosity<none>);

}  // namespace gimlet::viscosity
