// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// eos::check<T>(): an equation of state checked against eos::Eos, with each missing requirement named in plain words
/// (docs/concepts.md).

#include "gimlet/eos/concepts.hpp"

#include <concepts>

namespace gimlet::eos {

namespace check_detail {
template <class E, int D>
concept pressure_any = requires(E& e, const point_step<double>& st, const archetype_particle<D, E>& p) {
    e.pressure(st, p);
};
template <class E, int D>
concept pressure_const = requires(const E& e, const point_step<double>& st, const archetype_particle<D, E>& p) {
    { e.pressure(st, p) } -> std::convertible_to<double>;
};
template <class E, int D>
concept modulus_any = requires(E& e, const point_state<double>& st, const archetype_particle<D, E>& p) {
    e.bulk_modulus(st, p);
};
template <class E, int D>
concept modulus_const = requires(const E& e, const point_state<double>& st, const archetype_particle<D, E>& p) {
    { e.bulk_modulus(st, p) } -> std::convertible_to<double>;
};
}  // namespace check_detail

/// True if E is an equation of state (eos::Eos); otherwise the compiler stops here with one
/// message per missing requirement: `static_assert(gimlet::eos::check<my_eos>());`
template <class E>
consteval bool check() {
    static_assert(declares_required_fields<E>,
                  "EOS policy: needs `using required_fields = gimlet::field_list<...>;` (field_list<> if it reads "
                  "no per-particle state)");
    if constexpr (declares_required_fields<E>) {
        constexpr bool pressure = check_detail::pressure_any<E, 2> || check_detail::pressure_any<E, 3>;
        static_assert(pressure,
                      "EOS policy: needs `template <class Real, class P> Real pressure(const gimlet::point_step<Real>& "
                      "step, const P& particle) const` (Pa, compression positive, at the end of the step)");
        if constexpr (pressure)
            static_assert(check_detail::pressure_const<E, 2> && check_detail::pressure_const<E, 3>,
                          "EOS policy: pressure must be const, take the particle as a template (2-D and 3-D stores) "
                          "and return a number");
        constexpr bool modulus = check_detail::modulus_any<E, 2> || check_detail::modulus_any<E, 3>;
        static_assert(modulus,
                      "EOS policy: needs `template <class Real, class P> Real bulk_modulus(const "
                      "gimlet::point_state<Real>& state, const P& particle) const` (the tangent bulk modulus, Pa, "
                      "for the time step)");
        if constexpr (modulus)
            static_assert(check_detail::modulus_const<E, 2> && check_detail::modulus_const<E, 3>,
                          "EOS policy: bulk_modulus must be const, take the particle as a template (2-D and 3-D "
                          "stores) and return a number");
    }
    return Eos<E>;
}

}  // namespace gimlet::eos
