// SPDX-License-Identifier: MIT
// Must not compile: a multi-field contact policy that is neither a law (in_contact) nor a node
// resolver (resolve), and declares no required_fields. contact::check names both omissions.
// GIMLET_FAILTEST_EXPECT: needs `template <gimlet::Space S> bool in_contact
// GIMLET_FAILTEST_EXPECT: needs `using required_fields
#include <gimlet/contact/check.hpp>

struct nothing_yet {
    static constexpr bool multi_field = true;
#ifdef GIMLET_FAILTEST_OK
    using required_fields = gimlet::field_list<>;
    template <gimlet::Space S>
    bool in_contact(const gimlet::contact::pair_view<S>&) const {
        return true;
    }
#endif
};

static_assert(gimlet::contact::check<nothing_yet>());

int main() { return 0; }
