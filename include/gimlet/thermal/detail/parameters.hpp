// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The parameters the thermal policies share with the Mie-Grueneisen EOS, validated once.

#include "gimlet/core/error.hpp"

#include <cmath>

namespace gimlet::thermal::detail {

/// Throws invalid_parameter, naming it, for a bad rho0, c0, s (> 1), Gamma, c_v or T0.
inline void validate_shock_parameters(double density0, double sound_speed, double slope, double gruneisen,
                                      double specific_heat, double initial_temperature) {
    require_positive("thermal reference density rho0 (kg/m^3)", density0);
    require_positive("thermal bulk sound speed c0 (m/s)", sound_speed);
    // The same ranges as eos::mie_gruneisen's.
    require(std::isfinite(slope) && slope > 1.0 && slope <= 20.0, "thermal Hugoniot slope s", slope, "(1, 20]");
    require(std::isfinite(gruneisen) && gruneisen >= 0.0 && gruneisen <= 20.0, "thermal Grueneisen parameter Gamma",
            gruneisen, "[0, 20]");
    require_positive("specific heat c_v (J/(kg K))", specific_heat);
    require_positive("initial temperature T0 (K)", initial_temperature);
}

}  // namespace gimlet::thermal::detail
