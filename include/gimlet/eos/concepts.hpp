// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The equation-of-state contract.

#include "gimlet/core/material_point.hpp"

#include <concepts>

/// Equations of state: the pressure of a material point (eos::Eos).
namespace gimlet::eos {

/// An EOS policy gives the pressure of a material point and its tangent bulk modulus.
///
/// - `required_fields`: field_list of the per-particle state it reads or keeps.
/// - `pressure(step, p)`: the pressure (Pa, compression positive) at the end of the step, from
///   `step.J`, `step.density` and the particle's fields. Must throw gimlet::numerical_error
///   (naming the particle and step) rather than return a non-finite value.
/// - `bulk_modulus(state, p)`: the current tangent bulk modulus K = -V dP/dV (Pa), for the
///   time step. Optionally also `bulk_modulus(state, p, unsigned& guards)`, which adds the
///   eos::guard bits of any silent guard that acted (the solver counts them: solver::health()).
/// - optional `static constexpr bool reads_shear_energy = true`: the pressure reads
///   `step.shear_energy` (the stored elastic shear energy, which is not heat). The material
///   update computes it only for such an EOS or a thermal policy; otherwise it is zero.
template <class E>
concept Eos = requires {
    typename E::required_fields;
    requires FieldList<typename E::required_fields>;
} && requires(const E& e, const point_step<double>& st, const point_state<double>& ps,
              const archetype_particle<2, E>& p2, const archetype_particle<3, E>& p3) {
    { e.pressure(st, p2) } -> std::convertible_to<double>;
    { e.pressure(st, p3) } -> std::convertible_to<double>;
    { e.bulk_modulus(ps, p2) } -> std::convertible_to<double>;
    { e.bulk_modulus(ps, p3) } -> std::convertible_to<double>;
};

/// The silent guards a state can meet on its way to a wave speed (the solver counts them as
/// health events, solver::health()): bits of the `guards` an EOS's optional
/// `bulk_modulus(state, p, unsigned& guards)` sets, and the solver's own.
namespace guard {
inline constexpr unsigned compression_capped = 1;  ///< EOS modulus taken at a capped compression
inline constexpr unsigned negative_modulus = 2;    ///< EOS tangent modulus < 0, taken as 0
inline constexpr unsigned no_wave_speed = 4;       ///< (K + 4G/3)/rho <= 0: wave speed taken as 0
/// Number of guard kinds, the bits above (health_events keeps a count of each).
inline constexpr unsigned kinds = 3;
}  // namespace guard

/// True if E declares that its pressure reads point_step::shear_energy (see Eos).
template <class E>
inline constexpr bool reads_shear_energy = [] {
    if constexpr (requires { E::reads_shear_energy; }) return bool(E::reads_shear_energy);
    else return false;
}();

}  // namespace gimlet::eos
