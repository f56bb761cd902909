// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// multi_field::check<T>(): a partition checked against multi_field::Partition, with each missing
/// requirement named in plain words (docs/concepts.md, "Velocity fields").

#include "gimlet/core/fields.hpp"
#include "gimlet/multi_field/partition.hpp"

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace gimlet::multi_field {

namespace check_detail {
template <class P>
concept has_count = requires {
    { P::fields_per_body } -> std::convertible_to<std::size_t>;
};
template <class P, int D>
concept side_any = requires(P& p, std::size_t node, const archetype_particle<D, P>& particle,
                            const typename space<D, double>::vector& x) { p.side(particle, node, x); };
template <class P, int D>
concept side_const = requires(const P& p, std::size_t node, const archetype_particle<D, P>& particle,
                              const typename space<D, double>::vector& x) {
    { p.side(particle, node, x) } -> std::convertible_to<std::size_t>;
};
}  // namespace check_detail

/// True if P is a partition (multi_field::Partition); otherwise the compiler stops here with one
/// message per missing requirement: `static_assert(gimlet::multi_field::check<my_partition>());`
template <class P>
consteval bool check() {
    static_assert(check_detail::has_count<P>,
                  "partition: needs `static constexpr std::size_t fields_per_body = ...;` (the velocity fields "
                  "each body is divided into, >= 1)");
    static_assert(declares_required_fields<P>,
                  "partition: needs `using required_fields = gimlet::field_list<...>;` (field_list<> if it reads "
                  "no per-particle state of its own)");
    static_assert(!requires(P& p) { p.splits(); } || requires(const P& p) {
        { p.splits() } -> std::convertible_to<bool>;
    }, "partition: splits must be `bool splits() const` (asked after prepare; false: every side is 0 this step)");
    static_assert(!requires(P& p) { p.split_rows(); } || requires(const P& p) {
        { p.split_rows() } -> std::same_as<const std::vector<std::uint8_t>&>;
    }, "partition: split_rows must be `const std::vector<std::uint8_t>& split_rows() const` (asked after prepare on a "
       "step that splits: a flag per row of nodes along the last axis, set where side may answer other than 0)");
    if constexpr (check_detail::has_count<P> && declares_required_fields<P>) {
        static_assert(P::fields_per_body >= 1 && P::fields_per_body <= 255,
                      "partition: fields_per_body must be in [1, 255]");
        if constexpr (P::fields_per_body > 1) {
            constexpr bool side = check_detail::side_any<P, 2> || check_detail::side_any<P, 3>;
            static_assert(side,
                          "partition: with fields_per_body > 1 it needs `template <class P, class V> std::size_t "
                          "side(const P& particle, std::size_t node, const V& node_position) const` (the field of "
                          "the particle's body it scatters to at that node, in [0, fields_per_body))");
            if constexpr (side)
                static_assert(check_detail::side_const<P, 2> && check_detail::side_const<P, 3>,
                              "partition: side must be const, take the particle and the node position as templates "
                              "(2-D and 3-D) and return an index");
        }
    }
    return Partition<P>;
}

}  // namespace gimlet::multi_field
