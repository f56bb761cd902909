// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// check_material<M>(): a material bundle checked against gimlet::Material, with each missing
/// requirement named in plain words (docs/concepts.md, Material and Region). Most users bundle
/// their policies with gimlet::material<...>, which passes; this is for a bundle of one's own.

#include "gimlet/material/material.hpp"

#include <concepts>

namespace gimlet {

namespace check_detail {
template <class M>
concept has_policy_types = requires {
    typename M::strength_type;
    typename M::eos_type;
    typename M::thermal_type;
    typename M::viscosity_type;
};
template <class M>
concept has_density = requires(const M& m) {
    { m.density } -> std::convertible_to<double>;
};
template <class M>
concept validate_any = requires(M& m) { m.validate(); };
template <class M>
concept validate_const = requires(const M& m) { m.validate(); };
}  // namespace check_detail

/// True if M is a material bundle (gimlet::Material); otherwise the compiler stops here with one
/// message per missing requirement: `static_assert(gimlet::check_material<my_material>());`
template <class M>
consteval bool check_material() {
    static_assert(check_detail::has_policy_types<M>,
                  "material: needs the types strength_type, eos_type, thermal_type and viscosity_type (one policy of "
                  "each family; gimlet::material<St, E, T, V> has them)");
    static_assert(declares_required_fields<M>,
                  "material: needs `using required_fields = gimlet::field_list<...>;` (the union of its policies' "
                  "fields)");
    static_assert(check_detail::has_density<M>, "material: needs a member `density` (the reference density, kg/m^3)");
    if constexpr (check_detail::validate_any<M>)
        static_assert(check_detail::validate_const<M>,
                      "material: validate() must be const (it throws gimlet::invalid_parameter for bad values)");
    else
        static_assert(check_detail::validate_any<M>,
                      "material: needs `void validate() const` (throw gimlet::invalid_parameter for bad values)");
    return Material<M>;
}

}  // namespace gimlet
