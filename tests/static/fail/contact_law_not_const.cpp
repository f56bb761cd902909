// SPDX-License-Identifier: MIT
// Must not compile: a contact law whose in_contact is not const. contact::check names the
// missing requirement in words (docs/concepts.md, Contact), with g++ 12 and clang 14 alike.
// GIMLET_FAILTEST_EXPECT: in_contact must be const
#include <gimlet/contact/check.hpp>

struct touchy {
    static constexpr bool multi_field = true;
    using required_fields = gimlet::field_list<>;
#ifdef GIMLET_FAILTEST_OK
    template <gimlet::Space S>
    bool in_contact(const gimlet::contact::pair_view<S>& pair) const {
        return pair.gap <= pair.cell;
    }
#else
    template <gimlet::Space S>
    bool in_contact(const gimlet::contact::pair_view<S>& pair) {
        return pair.gap <= pair.cell;
    }
#endif
};

static_assert(gimlet::contact::check<touchy>());

int main() { return 0; }
