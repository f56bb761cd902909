// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The thermal contract.

#include "gimlet/core/material_point.hpp"

#include <concepts>

/// Thermal policies: the temperature of a material point (thermal::Thermal).
namespace gimlet::thermal {

/// A thermal policy advances the temperature of a material point.
///
/// - `enabled`: false for thermal::none; the solver then stores no temperature and runs no
///   thermal code (removed with `if constexpr`).
/// - `required_fields`: field_list of its per-particle state (the temperature field for any real one).
/// - `initialize(p)`: set the initial state of a new particle (e.g. T = T0).
/// - `update(step, dissipated, p)`: advance the state over the step; `dissipated` is the
///   energy per unit mass the strength law dissipated in it (plastic work, J/kg).
template <class T>
concept Thermal = requires {
    { T::enabled } -> std::convertible_to<bool>;
    typename T::required_fields;
    requires FieldList<typename T::required_fields>;
} && (!T::enabled || requires(const T& t, const point_step<double>& st, double w,
                                const archetype_particle<2, T>& p2,
                                const archetype_particle<3, T>& p3) {
    t.initialize(p2);
    t.initialize(p3);
    t.update(st, w, p2);
    t.update(st, w, p3);
});

}  // namespace gimlet::thermal
