// SPDX-License-Identifier: MIT
#pragma once
// The command-line flags of the HMX examples' numerics, read the same way by cavity_collapse,
// impact_1d and contact_validation: --consistent-mass K (0 = the lumped mass, at most 5 at the
// solver's Courant number 0.4), --viscosity-linear B1 and --viscosity-quadratic B2
// (viscosity::bulk's b1 and b2), defaulting to common/hmx_defaults.hpp, and --cfl C (the
// Courant number, solver_options::cfl, defaulting to the solver's; the solver refuses one that
// is too large for the consistent mass or the scheme, by name).

#include "common/cli.hpp"
#include "common/hmx_defaults.hpp"

#include <gimlet/solver/options.hpp>

namespace example {

struct numerics {
    int consistent_mass;         // solver_options::consistent_mass_iterations
    double viscosity_linear;     // viscosity::bulk's b1
    double viscosity_quadratic;  // viscosity::bulk's b2
    double cfl;                  // solver_options::cfl
};

// `lumped_by_default`: the consistent mass's default is 0 (USL refuses the consistent mass:
// solver_options::validate).
inline numerics read_numerics(cli& args, bool lumped_by_default = false) {
    numerics m{};
    m.consistent_mass = args.integer("consistent-mass", lumped_by_default ? 0 : hmx_defaults::consistent_mass, 0, 5);
    m.viscosity_linear = args.real("viscosity-linear", hmx_defaults::viscosity_linear, 0.0, 10.0, true);
    m.viscosity_quadratic = args.real("viscosity-quadratic", hmx_defaults::viscosity_quadratic, 0.0, 10.0, true);
    m.cfl = args.real("cfl", gimlet::solver_options<gimlet::space<2>>{}.cfl, 0.0, 1.0);
    return m;
}

}  // namespace example
