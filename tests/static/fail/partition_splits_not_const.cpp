// SPDX-License-Identifier: MIT
// Must not compile: a partition whose optional splits() is not const (the solver would not see
// it and would ask side() of every particle). multi_field::check names it.
// GIMLET_FAILTEST_EXPECT: splits must be `bool splits\(\) const`
#include <gimlet/multi_field/check.hpp>

#include <cstddef>

struct halves {
    using required_fields = gimlet::field_list<>;
    static constexpr std::size_t fields_per_body = 2;
    template <class P, class V>
    std::size_t side(const P&, std::size_t, const V& node_position) const {
        return node_position[0] < 0 ? 0 : 1;
    }
#ifdef GIMLET_FAILTEST_OK
    bool splits() const { return true; }
#else
    bool splits() { return true; }
#endif
};

static_assert(gimlet::multi_field::check<halves>());

int main() { return 0; }
