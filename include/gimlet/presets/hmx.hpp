// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The reference paper's HMX: von Mises plasticity, Mie-Grueneisen EOS, artificial viscosity,
/// shock and plastic-work heating, with the paper's constants (docs/physics.md section 7).

#include "gimlet/core/elastic_moduli.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/material/material.hpp"
#include "gimlet/eos/mie_gruneisen.hpp"
#include "gimlet/strength/von_mises.hpp"
#include "gimlet/thermal/hugoniot_heating.hpp"
#include "gimlet/thermal/isentrope_temperature.hpp"
#include "gimlet/viscosity/bulk.hpp"

/// Ready-made materials with published constants (HMX).
namespace gimlet::presets {

/// The reference paper's HMX constants (its Table of parameters; docs/physics.md section 7).
struct hmx_constants {
    double young = 11.87e9;          ///< E (Pa)
    double poisson = 0.25;           ///< nu
    double density = 1900.0;         ///< rho_0 (kg/m^3) = 1.9e-3 g/mm^3
    double yield_stress = 100e6;     ///< Y_0 (Pa)
    double hardening = 0.0;          ///< H (Pa)
    double specific_heat = 1250.0;   ///< c_v (J/(kg K))
    double gruneisen = 1.1;          ///< Gamma
    double slope = 2.6;              ///< s (the paper's lambda)
    double sound_speed = 2740.0;     ///< c_0 (m/s)
    double temperature = 300.0;      ///< T_0 (K)
};

/// HMX as a gimlet material.
/// \tparam Ref  e - e_H in the EOS: the standard internal-energy form (default) or the paper's
///              plastic-work variant.
/// \tparam T    the temperature: thermal::isentrope_temperature (default; T(V, e) from the EOS's
///              reference isentrope, docs/equations.md), paper_temperature (the paper's
///              Walsh-Christian heating, for side-by-side reproduction), any thermal policy built
///              from (rho0, c0, s, Gamma, c_v, T0), or thermal::none.
/// \tparam V    artificial viscosity (default: bulk, Abaqus/Explicit coefficients on the cell).
template <eos::energy_reference Ref = eos::energy_reference::internal_energy,
          class T = thermal::isentrope_temperature, class V = viscosity::bulk>
using hmx_material = material<strength::von_mises, eos::mie_gruneisen<Ref>, T, V>;

/// The reference paper's temperature: Walsh-Christian integrated in V plus plastic work.
using paper_temperature = thermal::hugoniot_heating<thermal::expansion::hugoniot>;

/// Build the HMX material from the paper's constants (or modified ones).
template <eos::energy_reference Ref = eos::energy_reference::internal_energy,
          class T = thermal::isentrope_temperature, class V = viscosity::bulk>
[[nodiscard]] hmx_material<Ref, T, V> make_hmx(const hmx_constants& c = {}, const V& viscosity = V{}) {
    // Shear from E and nu; pressure from the EOS (the elastic bulk modulus E/(3(1-2nu)) is not
    // used: docs/physics.md section 7).
    require_positive("density rho0 (kg/m^3)", c.density);  // before the EOS and thermal name it
    const auto moduli = elastic_moduli::from_young_poisson(c.young, c.poisson);
    auto thermal = [&] {
        if constexpr (T::enabled) return T{c.density, c.sound_speed, c.slope, c.gruneisen, c.specific_heat, c.temperature};
        else return T{};
    };
    return {c.density,
            strength::von_mises{moduli.shear, c.yield_stress, c.hardening},
            eos::mie_gruneisen<Ref>{c.density, c.sound_speed, c.slope, c.gruneisen},
            thermal(),
            viscosity};
}

}  // namespace gimlet::presets
