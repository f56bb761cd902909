// SPDX-License-Identifier: MIT
// Must not compile: a partition whose side is not const (the solver asks it from many threads).
// multi_field::check names it.
// GIMLET_FAILTEST_EXPECT: side must be const
#include <gimlet/multi_field/check.hpp>

#include <cstddef>

struct halves {
    using required_fields = gimlet::field_list<>;
    static constexpr std::size_t fields_per_body = 2;
#ifdef GIMLET_FAILTEST_OK
    template <class P, class V>
    std::size_t side(const P&, std::size_t, const V& node_position) const {
        return node_position[0] < 0 ? 0 : 1;
    }
#else
    template <class P, class V>
    std::size_t side(const P&, std::size_t, const V& node_position) {
        return node_position[0] < 0 ? 0 : 1;
    }
#endif
};

static_assert(gimlet::multi_field::check<halves>());

int main() { return 0; }
