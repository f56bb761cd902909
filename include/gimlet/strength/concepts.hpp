// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The strength (deviatoric constitutive law) contract.

#include "gimlet/core/material_point.hpp"

#include <concepts>

/// Strength policies: the deviatoric stress of a material point (strength::Strength).
namespace gimlet::strength {

/// A strength policy advances the deviatoric Cauchy stress of one material point.
///
/// - `required_fields`: field_list of the per-particle state it keeps (e.g. plastic strain).
/// - `update(step, s, p)`: advance the 3x3 deviatoric stress `s` (in/out, traceless) over
///   `step.dt` given the rates `step.D`, `step.W`; return the energy dissipated in the step per
///   unit mass (J/kg; plastic work, 0 for elastic laws). The solver adds the pressure from the
///   EOS and the artificial viscosity: sigma = s - (P + q) I (docs/physics.md section 4).
/// - `shear_modulus(state, p)`: the current tangent shear modulus G (Pa), used in the wave
///   speed sqrt((K + 4G/3) / rho) that sets the time step.
///
/// The template parameter of update/shear_modulus is any particle handle; write them as
/// templates so they work for every store. See docs/concepts.md for a minimal example.
template <class M>
concept Strength = requires {
    typename M::required_fields;
    requires FieldList<typename M::required_fields>;
} && requires(const M& m, const point_step<double>& st, const point_state<double>& ps,
              Eigen::Matrix3d& s, const archetype_particle<2, M>& p2,
              const archetype_particle<3, M>& p3) {
    { m.update(st, s, p2) } -> std::convertible_to<double>;
    { m.update(st, s, p3) } -> std::convertible_to<double>;
    { m.shear_modulus(ps, p2) } -> std::convertible_to<double>;
    { m.shear_modulus(ps, p3) } -> std::convertible_to<double>;
};

}  // namespace gimlet::strength
