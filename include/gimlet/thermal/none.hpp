// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// No thermal model: no temperature field, no thermal work.

#include "gimlet/thermal/concepts.hpp"

namespace gimlet::thermal {

/// Thermal effects off. A scene with this policy has no temperature column.
struct none {
    /// Off: the solver stores no temperature and compiles no thermal code.
    static constexpr bool enabled = false;
    /// It keeps no per-particle state.
    using required_fields = field_list<>;
};

static_assert(Thermal<none>);

}  // namespace gimlet::thermal
