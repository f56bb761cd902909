// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// A material: one policy from each constitutive family plus the reference density. Each body
/// of a scene has its own material object (its own parameter values); all bodies of a solver
/// share the policy types, so the step is specialised at compile time.

#include "gimlet/core/elastic_moduli.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/eos/concepts.hpp"
#include "gimlet/eos/linear.hpp"
#include "gimlet/strength/concepts.hpp"
#include "gimlet/strength/linear_elastic.hpp"
#include "gimlet/thermal/concepts.hpp"
#include "gimlet/thermal/none.hpp"
#include "gimlet/viscosity/concepts.hpp"
#include "gimlet/viscosity/none.hpp"

#include <cmath>
#include <concepts>
#include <string>

namespace gimlet {

/// A material model composed of policies.
/// \tparam St strength (deviatoric law), \tparam E equation of state,
/// \tparam T thermal model (thermal::none: no temperature), \tparam V artificial viscosity.
template <strength::Strength St, eos::Eos E, thermal::Thermal T = thermal::none,
          viscosity::Viscosity V = viscosity::none>
struct material {
    /// The strength policy St (strength::Strength).
    using strength_type = St;
    /// The equation of state E (eos::Eos).
    using eos_type = E;
    /// The thermal policy T (thermal::Thermal).
    using thermal_type = T;
    /// The artificial viscosity V (viscosity::Viscosity).
    using viscosity_type = V;
    /// The per-particle fields the material needs: the union of its policies' lists.
    using required_fields = field_union_t<typename St::required_fields, typename E::required_fields, typename T::required_fields,
                                 typename V::required_fields>;

    double density;  ///< reference density rho_0 (kg/m^3)
    /// The deviatoric stress law.
    St strength;
    /// The pressure law.
    E eos;
    /// The temperature model (thermal::none: no temperature field).
    T thermal{};
    /// The artificial viscosity (viscosity::none: none).
    V viscosity{};

    /// Throws invalid_parameter for a bad density, an EOS whose own reference density
    /// (`eos.density0()`, e.g. eos::mie_gruneisen) differs from it, or a thermal policy whose
    /// copy of the EOS's constants (reference density, c0, s, Gamma, where both have them)
    /// differs from the EOS's: a temperature on another EOS's isentrope or Hugoniot is silently
    /// wrong. The policies validate their other parameters themselves.
    void validate() const {
        require_positive("density rho0 (kg/m^3)", density);
        if constexpr (requires { { eos.density0() } -> std::convertible_to<double>; }) {
            const double eos_density = eos.density0();
            require(std::abs(eos_density - density) <= 1e-9 * density, "EOS reference density rho0 (kg/m^3)",
                    eos_density, "equal to the material density rho0 = " + detail::to_text(density) + " kg/m^3");
        }
        auto same = [](double theirs, double ours, const char* name, const char* whose = "the EOS's ") {
            require(std::abs(theirs - ours) <= 1e-9 * std::abs(ours), std::string("thermal ") + name, theirs,
                    "equal to " + std::string(whose) + detail::to_text(ours));
        };
        if constexpr (requires { { thermal.density0() } -> std::convertible_to<double>; })
            same(thermal.density0(), density, "reference density rho0 (kg/m^3)", "the material density ");
        if constexpr (requires { { thermal.sound_speed() } -> std::convertible_to<double>;
                                 { eos.sound_speed() } -> std::convertible_to<double>; })
            same(thermal.sound_speed(), eos.sound_speed(), "bulk sound speed c0 (m/s)");
        if constexpr (requires { { thermal.slope() } -> std::convertible_to<double>;
                                 { eos.slope() } -> std::convertible_to<double>; })
            same(thermal.slope(), eos.slope(), "Hugoniot slope s");
        if constexpr (requires { { thermal.gruneisen() } -> std::convertible_to<double>;
                                 { eos.gruneisen() } -> std::convertible_to<double>; })
            same(thermal.gruneisen(), eos.gruneisen(), "Grueneisen parameter Gamma");
    }
};

/// A type is a material bundle.
template <class M>
concept Material = requires(const M& m) {
    typename M::strength_type;
    typename M::eos_type;
    typename M::thermal_type;
    typename M::viscosity_type;
    typename M::required_fields;
    { m.density } -> std::convertible_to<double>;
    m.validate();
};

/// The elastic material of the verification tests: hypoelastic deviatoric stress plus the
/// linear EOS, from density (kg/m^3), Young's modulus (Pa) and Poisson's ratio.
using elastic_material = material<strength::linear_elastic, eos::linear>;

/// The elastic_material of density rho_0 (kg/m^3, > 0), Young's modulus E (Pa) and Poisson's
/// ratio nu (G and K from elastic_moduli::from_young_poisson).
/// \throws gimlet::invalid_parameter for a density that is not finite and > 0, or moduli that
/// elastic_moduli::from_young_poisson refuses.
[[nodiscard]] inline elastic_material make_elastic_material(double density, double young, double poisson) {
    require_positive("density rho0 (kg/m^3)", density);
    const auto k = elastic_moduli::from_young_poisson(young, poisson);
    return {density, strength::linear_elastic{k.shear}, eos::linear{k.bulk}};
}

}  // namespace gimlet
