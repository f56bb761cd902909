// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The artificial-viscosity contract.

#include "gimlet/core/material_point.hpp"

#include <concepts>

/// Artificial-viscosity policies: the viscous pressure q of a material point
/// (viscosity::Viscosity).
namespace gimlet::viscosity {

/// Whether viscosity V asks for the wave speed as a callable (`lazy_sound_speed`: see
/// viscosity::Viscosity below).
template <class V>
inline constexpr bool lazy_sound_speed = [] {
    if constexpr (requires { V::lazy_sound_speed; }) return bool(V::lazy_sound_speed);
    else return false;
}();

namespace detail {
/// What the material update passes a `lazy_sound_speed` policy (an archetype for the checks).
struct archetype_sound_speed {
    double operator()() const { return 1.0; }
};
}  // namespace detail

/// An artificial-viscosity policy.
///
/// - `enabled`: false for viscosity::none. The solver removes every viscosity step with
///   `if constexpr` when it is false, so an inactive policy costs nothing.
/// - `required_fields`: field_list of the per-particle state it needs.
/// - `pressure(step, sound_speed, p)`: the viscous pressure q >= 0 (Pa), added to the EOS
///   pressure: sigma = s - (P + q) I. `step.length` is the grid cell size. `sound_speed` is the
///   particle's longitudinal wave speed (m/s), a number.
/// - optionally `static constexpr bool lazy_sound_speed = true;`: the material update then passes
///   `sound_speed` as a callable instead (`sound_speed()` returns the number), so that the speed
///   (the EOS's tangent modulus and a square root) is computed only where the policy asks for it;
///   viscosity::bulk does, in compression. Such a policy's `pressure` must accept a callable there
///   as well as a number. Without the flag a policy is always given the number, whatever type its
///   parameter has.
/// - `signal_speed(sound_speed, cell, p)`: the speed (m/s, >= sound_speed) that sets particle p's
///   stable time step, dt = C h / max_p (signal_speed + |v_p|): a viscosity damps the fastest
///   mode and so shortens the step (return sound_speed where q is zero). The solver calls it
///   before each step, from the state the last update left.
template <class V>
concept Viscosity = requires {
    { V::enabled } -> std::convertible_to<bool>;
    typename V::required_fields;
    requires FieldList<typename V::required_fields>;
} && (!V::enabled || requires(const V& v, const point_step<double>& st, double c,
                                const archetype_particle<2, V>& p2,
                                const archetype_particle<3, V>& p3) {
    { v.pressure(st, c, p2) } -> std::convertible_to<double>;
    { v.pressure(st, c, p3) } -> std::convertible_to<double>;
    { v.signal_speed(c, c, p2) } -> std::convertible_to<double>;
    { v.signal_speed(c, c, p3) } -> std::convertible_to<double>;
}) && (!lazy_sound_speed<V> || requires(const V& v, const point_step<double>& st,
                                         const detail::archetype_sound_speed& c,
                                         const archetype_particle<2, V>& p2,
                                         const archetype_particle<3, V>& p3) {
    { v.pressure(st, c, p2) } -> std::convertible_to<double>;
    { v.pressure(st, c, p3) } -> std::convertible_to<double>;
});

}  // namespace gimlet::viscosity
