// SPDX-License-Identifier: MIT
// Must not compile: a low-level contact policy (contact::NodeResolver) whose resolve is not
// const. contact::check names it (docs/concepts.md, Contact).
// GIMLET_FAILTEST_EXPECT: resolve must be const
#include <gimlet/contact/check.hpp>

struct stick_all {
    static constexpr bool multi_field = true;
    using required_fields = gimlet::field_list<>;
#ifdef GIMLET_FAILTEST_OK
    template <gimlet::Space S>
    void resolve(gimlet::contact::node_view<S>&) const {}
#else
    template <gimlet::Space S>
    void resolve(gimlet::contact::node_view<S>&) {}
#endif
};

static_assert(gimlet::contact::check<stick_all>());

int main() { return 0; }
