// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Isotropic elastic moduli from the engineering constants, validated.

#include "gimlet/core/error.hpp"

namespace gimlet {

/// Bulk and shear modulus of an isotropic elastic solid.
struct elastic_moduli {
    double bulk = 0;   ///< K (Pa)
    double shear = 0;  ///< G (Pa)

    /// From Young's modulus E (Pa) and Poisson's ratio nu: K = E / (3 (1 - 2 nu)),
    /// G = E / (2 (1 + nu)) (any elasticity text, e.g. Malvern 1969, sec. 6.2).
    [[nodiscard]] static elastic_moduli from_young_poisson(double young, double poisson) {
        require_positive("Young's modulus E (Pa)", young);
        require(std::isfinite(poisson) && poisson > -1.0 && poisson < 0.5, "Poisson's ratio nu", poisson,
                "(-1, 0.5)");
        return {young / (3.0 * (1.0 - 2.0 * poisson)), young / (2.0 * (1.0 + poisson))};
    }
    /// P-wave (longitudinal) modulus K + 4G/3.
    [[nodiscard]] double longitudinal() const noexcept { return bulk + 4.0 * shear / 3.0; }
};

}  // namespace gimlet
