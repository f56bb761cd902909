// SPDX-License-Identifier: MIT
#pragma once
// The command-line flags of the HMX examples' mass matrix and viscosity, read the same way by
// cavity_collapse, impact_1d and contact_validation: --consistent-mass K (0 = the lumped mass,
// at most 5 at the solver's Courant number 0.4), --viscosity-linear B1 and
// --viscosity-quadratic B2 (viscosity::bulk's b1 and b2), defaulting to common/hmx_defaults.hpp.

#include "common/cli.hpp"
#include "common/hmx_defaults.hpp"

namespace example {

struct mass_and_viscosity {
    int consistent_mass;         // solver_options::consistent_mass_iterations
    double viscosity_linear;     // viscosity::bulk's b1
    double viscosity_quadratic;  // viscosity::bulk's b2
};

// `lumped_by_default`: the consistent mass's default is 0 (USL refuses the consistent mass:
// solver_options::validate).
inline mass_and_viscosity read_mass_and_viscosity(cli& args, bool lumped_by_default = false) {
    mass_and_viscosity m{};
    m.consistent_mass = args.integer("consistent-mass", lumped_by_default ? 0 : hmx_defaults::consistent_mass, 0, 5);
    m.viscosity_linear = args.real("viscosity-linear", hmx_defaults::viscosity_linear, 0.0, 10.0, true);
    m.viscosity_quadratic = args.real("viscosity-quadratic", hmx_defaults::viscosity_quadratic, 0.0, 10.0, true);
    return m;
}

}  // namespace example
