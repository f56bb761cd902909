// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// strength::check<T>(): a strength policy checked against strength::Strength, with each missing requirement named in plain words
/// (docs/concepts.md).

#include "gimlet/strength/concepts.hpp"

#include <concepts>

namespace gimlet::strength {

namespace check_detail {
template <class M, int D>
concept update_any = requires(M& m, const point_step<double>& st, Eigen::Matrix3d& s, const archetype_particle<D, M>& p) {
    m.update(st, s, p);
};
template <class M, int D>
concept update_const = requires(const M& m, const point_step<double>& st, Eigen::Matrix3d& s,
                                const archetype_particle<D, M>& p) {
    { m.update(st, s, p) } -> std::convertible_to<double>;
};
template <class M, int D>
concept shear_any = requires(M& m, const point_state<double>& st, const archetype_particle<D, M>& p) {
    m.shear_modulus(st, p);
};
template <class M, int D>
concept shear_const = requires(const M& m, const point_state<double>& st, const archetype_particle<D, M>& p) {
    { m.shear_modulus(st, p) } -> std::convertible_to<double>;
};
}  // namespace check_detail

/// True if M is a strength policy (strength::Strength); otherwise the compiler stops here with
/// one message per missing requirement: `static_assert(gimlet::strength::check<my_strength>());`
template <class M>
consteval bool check() {
    static_assert(declares_required_fields<M>,
                  "strength policy: needs `using required_fields = gimlet::field_list<...>;` (field_list<> if it "
                  "keeps no per-particle state)");
    if constexpr (declares_required_fields<M>) {
        constexpr bool update = check_detail::update_any<M, 2> || check_detail::update_any<M, 3>;
        static_assert(update,
                      "strength policy: needs `template <class Real, class P> Real update(const "
                      "gimlet::point_step<Real>& step, Eigen::Matrix<Real, 3, 3>& deviator, const P& particle) "
                      "const`: advance the deviatoric stress, return the energy dissipated per unit mass");
        if constexpr (update)
            static_assert(check_detail::update_const<M, 2> && check_detail::update_const<M, 3>,
                          "strength policy: update must be const, take the particle as a template (2-D and 3-D "
                          "stores) and return a number (the dissipated energy per unit mass)");
        constexpr bool shear = check_detail::shear_any<M, 2> || check_detail::shear_any<M, 3>;
        static_assert(shear,
                      "strength policy: needs `template <class Real, class P> Real shear_modulus(const "
                      "gimlet::point_state<Real>& state, const P& particle) const` (the tangent shear modulus, Pa)");
        if constexpr (shear)
            static_assert(check_detail::shear_const<M, 2> && check_detail::shear_const<M, 3>,
                          "strength policy: shear_modulus must be const, take the particle as a template (2-D and "
                          "3-D stores) and return a number");
    }
    return Strength<M>;
}

}  // namespace gimlet::strength
