// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// shape::check<Sh>(): a shape-function policy checked against shape::Shape, with each missing
/// requirement named in plain words (docs/concepts.md, Checkers).

#include "gimlet/shape/concepts.hpp"

#include <concepts>

namespace gimlet::shape {

namespace check_detail {
template <class Sh>
concept has_stencil = requires {
    { Sh::stencil } -> std::convertible_to<int>;
};
template <class Sh, class Real>
concept weights_for = requires(Real x, Real l, int& first, Real* w, Real* dw) {
    { Sh::weights(x, l, first, w, dw) } -> std::same_as<void>;
};
template <class Sh, int D>
using particle = particle_ref<particle_store<space<D, double>, field_union_t<core_fields<space<D, double>>,
                                                                              typename Sh::required_fields>>>;
template <class Sh, int D>
concept half_width_any = requires(const particle<Sh, D>& p) { Sh::half_width(p, 1.0); };
template <class Sh, int D>
concept half_width_vector = requires(const particle<Sh, D>& p) {
    { Sh::half_width(p, 1.0) } -> std::convertible_to<typename space<D, double>::vector>;
};
}  // namespace check_detail

/// True if Sh is a shape-function policy (shape::Shape); otherwise the compiler stops here with
/// one message per missing requirement: `static_assert(gimlet::shape::check<my_shape>());`
template <class Sh>
consteval bool check() {
    static_assert(check_detail::has_stencil<Sh>,
                  "shape policy: needs `static constexpr int stencil` (nodes per axis a particle can weigh, >= 1)");
    if constexpr (check_detail::has_stencil<Sh>)
        static_assert(Sh::stencil >= 1, "shape policy: stencil must be at least 1");
    static_assert(declares_required_fields<Sh>,
                  "shape policy: needs `using required_fields = gimlet::field_list<...>;` (field_list<> unless it "
                  "reads a per-particle half-width)");
    static_assert(check_detail::weights_for<Sh, double> && check_detail::weights_for<Sh, float>,
                  "shape policy: needs `template <class Real> static void weights(Real x, Real half_width, int& "
                  "first, Real* w, Real* dw)` for float and double (static: the solver calls it without an object)");
    if constexpr (declares_required_fields<Sh>) {
        constexpr bool any = check_detail::half_width_any<Sh, 2> || check_detail::half_width_any<Sh, 3>;
        static_assert(any, "shape policy: needs `template <class P, class Real> static auto half_width(const P& "
                           "particle, Real cell)` returning the half-width per axis in cell units (zero if unused)");
        if constexpr (any)
            static_assert(check_detail::half_width_vector<Sh, 2> && check_detail::half_width_vector<Sh, 3>,
                          "shape policy: half_width must be static, take the particle as a template (2-D and 3-D "
                          "stores) and return the space's vector");
    }
    return Shape<Sh>;
}

}  // namespace gimlet::shape
