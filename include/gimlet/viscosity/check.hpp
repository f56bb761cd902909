// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// viscosity::check<T>(): an artificial viscosity checked against viscosity::Viscosity, with each missing requirement named in plain words
/// (docs/concepts.md).

#include "gimlet/viscosity/concepts.hpp"

#include <concepts>

namespace gimlet::viscosity {

namespace check_detail {
template <class V>
concept has_enabled = requires {
    { V::enabled } -> std::convertible_to<bool>;
};
template <class V, int D>
concept pressure_any = requires(V& v, const point_step<double>& st, double c, const archetype_particle<D, V>& p) {
    v.pressure(st, c, p);
};
template <class V, int D>
concept pressure_const = requires(const V& v, const point_step<double>& st, double c,
                                  const archetype_particle<D, V>& p) {
    { v.pressure(st, c, p) } -> std::convertible_to<double>;
};
template <class V, int D>
concept pressure_lazy = requires(const V& v, const point_step<double>& st, const detail::archetype_sound_speed& c,
                                 const archetype_particle<D, V>& p) {
    { v.pressure(st, c, p) } -> std::convertible_to<double>;
};
template <class V, int D>
concept signal_any = requires(V& v, double c, const archetype_particle<D, V>& p) { v.signal_speed(c, c, p); };
template <class V, int D>
concept signal_const = requires(const V& v, double c, const archetype_particle<D, V>& p) {
    { v.signal_speed(c, c, p) } -> std::convertible_to<double>;
};
}  // namespace check_detail

/// True if V is an artificial viscosity (viscosity::Viscosity); otherwise the compiler stops here
/// with one message per missing requirement: `static_assert(gimlet::viscosity::check<my_q>());`
template <class V>
consteval bool check() {
    static_assert(check_detail::has_enabled<V>,
                  "viscosity policy: needs `static constexpr bool enabled = true;` (false only for "
                  "viscosity::none, which the solver compiles out)");
    static_assert(declares_required_fields<V>,
                  "viscosity policy: needs `using required_fields = gimlet::field_list<...>;` (field_list<> if it "
                  "keeps no per-particle state)");
    if constexpr (check_detail::has_enabled<V> && declares_required_fields<V>) {
        if constexpr (V::enabled) {
            constexpr bool pressure = check_detail::pressure_any<V, 2> || check_detail::pressure_any<V, 3>;
            static_assert(pressure,
                          "viscosity policy: needs `template <class Real, class P> Real pressure(const "
                          "gimlet::point_step<Real>& step, Real sound_speed, const P& particle) const` (q >= 0, Pa)");
            if constexpr (pressure)
                static_assert(check_detail::pressure_const<V, 2> && check_detail::pressure_const<V, 3>,
                              "viscosity policy: pressure must be const, take the particle as a template (2-D and "
                              "3-D stores) and return a number");
            if constexpr (lazy_sound_speed<V>)
                static_assert(check_detail::pressure_lazy<V, 2> && check_detail::pressure_lazy<V, 3>,
                              "viscosity policy: declares `lazy_sound_speed = true`, so its pressure must also "
                              "accept the wave speed as a callable (`sound_speed()` returns the number): "
                              "`template <class Real, class C, class P> Real pressure(const "
                              "gimlet::point_step<Real>&, const C& sound_speed, const P&) const`");
            constexpr bool signal = check_detail::signal_any<V, 2> || check_detail::signal_any<V, 3>;
            static_assert(signal,
                          "viscosity policy: needs `template <class Real, class P> Real signal_speed(Real "
                          "sound_speed, Real cell, const P& particle) const` (the speed that sets the stable step; "
                          "return sound_speed where q is zero)");
            if constexpr (signal)
                static_assert(check_detail::signal_const<V, 2> && check_detail::signal_const<V, 3>,
                              "viscosity policy: signal_speed must be const, take the particle as a template (2-D "
                              "and 3-D stores) and return a number");
        }
    }
    return Viscosity<V>;
}

}  // namespace gimlet::viscosity
