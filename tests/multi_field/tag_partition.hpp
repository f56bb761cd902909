// SPDX-License-Identifier: MIT
#pragma once
// A partition the multi-field tests share (one type, so its solvers' contact-independent part
// is compiled once in the family's unit): each body split into two fields by a per-particle tag.
#include <gimlet/gimlet.hpp>

#include <cstddef>
#include <cstdint>

namespace gimlet_multi_field_tests {

// A user's per-particle field: which half of its body a particle belongs to, set at t = 0.
struct half {
    template <class> using type = std::uint32_t;
    static constexpr const char* name = "half";
};

// Splits each body by the particle's own tag: the two halves meet, as two bodies would.
struct by_tag {
    using required_fields = gimlet::field_list<half>;
    static constexpr std::size_t fields_per_body = 2;
    template <class P, class V>
    [[nodiscard]] std::size_t side(const P& p, std::size_t, const V&) const {
        return p.template get<half>();
    }
};

}  // namespace gimlet_multi_field_tests
