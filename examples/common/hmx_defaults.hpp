// SPDX-License-Identifier: MIT
#pragma once
// The mass matrix and the artificial viscosity the HMX examples run by default (cavity_collapse,
// impact_1d, contact_validation): four consistent-mass iterations with twice Abaqus/Explicit's
// bulk-viscosity coefficients, the pair that meets the 1-D shock's plateau, heat, plastic-work
// and rise criteria (docs/equations.md, "The examples' defaults"). The library's own defaults
// stay the lumped mass and Abaqus's (0.06, 1.2): a scene pays for the consistent mass only
// where it asks.

namespace example::hmx_defaults {

inline constexpr int consistent_mass = 4;              // solver_options::consistent_mass_iterations
inline constexpr double viscosity_linear = 0.12;       // viscosity::bulk's b1
inline constexpr double viscosity_quadratic = 2.4;     // viscosity::bulk's b2

}  // namespace example::hmx_defaults
