// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// scene::check_region<R, S>(): a region checked against scene::Region, with each missing
/// requirement named in plain words (docs/concepts.md, Material and Region).

#include "gimlet/scene/geometry.hpp"

#include <concepts>

namespace gimlet::scene {

namespace check_detail {
template <class R, class S>
concept contains_any = requires(R& r, const typename S::vector& x) { r.contains(x); };
template <class R, class S>
concept contains_const = requires(const R& r, const typename S::vector& x) {
    { r.contains(x) } -> std::convertible_to<bool>;
};
template <class R, class S>
concept bounds_const = requires(const R& r) {
    { r.lower() } -> std::convertible_to<typename S::vector>;
    { r.upper() } -> std::convertible_to<typename S::vector>;
};
}  // namespace check_detail

/// True if R is a region of space S (scene::Region); otherwise the compiler stops here with one
/// message per missing requirement: `static_assert(gimlet::scene::check_region<my_region, S>());`
template <class R, class S>
consteval bool check_region() {
    static_assert(check_detail::contains_any<R, S>,
                  "region: needs `bool contains(const S::vector& x) const` (whether the body fills the point x)");
    if constexpr (check_detail::contains_any<R, S>)
        static_assert(check_detail::contains_const<R, S>,
                      "region: contains must be const and return something convertible to bool");
    static_assert(check_detail::bounds_const<R, S>,
                  "region: needs `S::vector lower() const` and `S::vector upper() const` (its bounding box: "
                  "particles are seeded inside it)");
    return Region<R, S>;
}

}  // namespace gimlet::scene
