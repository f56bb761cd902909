// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// thermal::check<T>(): a thermal policy checked against thermal::Thermal, with each missing requirement named in plain words
/// (docs/concepts.md).

#include "gimlet/thermal/concepts.hpp"

#include <concepts>

namespace gimlet::thermal {

namespace check_detail {
template <class T>
concept has_enabled = requires {
    { T::enabled } -> std::convertible_to<bool>;
};
template <class T, int D>
concept initialize_any = requires(T& t, const archetype_particle<D, T>& p) { t.initialize(p); };
template <class T, int D>
concept initialize_const = requires(const T& t, const archetype_particle<D, T>& p) { t.initialize(p); };
template <class T, int D>
concept update_any = requires(T& t, const point_step<double>& st, double w, const archetype_particle<D, T>& p) {
    t.update(st, w, p);
};
template <class T, int D>
concept update_const = requires(const T& t, const point_step<double>& st, double w, const archetype_particle<D, T>& p) {
    t.update(st, w, p);
};
}  // namespace check_detail

/// True if T is a thermal policy (thermal::Thermal); otherwise the compiler stops here with one
/// message per missing requirement: `static_assert(gimlet::thermal::check<my_thermal>());`
template <class T>
consteval bool check() {
    static_assert(check_detail::has_enabled<T>,
                  "thermal policy: needs `static constexpr bool enabled = true;` (false only for a policy that "
                  "does nothing, like thermal::none)");
    static_assert(declares_required_fields<T>,
                  "thermal policy: needs `using required_fields = gimlet::field_list<...>;` (with "
                  "gimlet::fields::temperature for a real one)");
    if constexpr (check_detail::has_enabled<T> && declares_required_fields<T>) {
        if constexpr (T::enabled) {
            constexpr bool init = check_detail::initialize_any<T, 2> || check_detail::initialize_any<T, 3>;
            static_assert(init, "thermal policy: needs `template <class P> void initialize(const P& particle) const` "
                                "(a new particle's state, e.g. T = T0)");
            if constexpr (init)
                static_assert(check_detail::initialize_const<T, 2> && check_detail::initialize_const<T, 3>,
                              "thermal policy: initialize must be const and take the particle as a template (2-D and "
                              "3-D stores)");
            constexpr bool update = check_detail::update_any<T, 2> || check_detail::update_any<T, 3>;
            static_assert(update,
                          "thermal policy: needs `template <class Real, class P> void update(const "
                          "gimlet::point_step<Real>& step, Real dissipated, const P& particle) const`");
            if constexpr (update)
                static_assert(check_detail::update_const<T, 2> && check_detail::update_const<T, 3>,
                              "thermal policy: update must be const and take the particle as a template (2-D and 3-D "
                              "stores)");
        }
    }
    return Thermal<T>;
}

}  // namespace gimlet::thermal
