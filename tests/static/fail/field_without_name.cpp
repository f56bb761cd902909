// SPDX-License-Identifier: MIT
// Must not compile: a field tag without a name. check_field names what is missing.
// GIMLET_FAILTEST_EXPECT: field tag: needs `static constexpr const char\* name
#include <gimlet/core/fields.hpp>

struct damage {
    template <class S>
    using type = typename S::real;
#ifdef GIMLET_FAILTEST_OK
    static constexpr const char* name = "damage";
#endif
};

static_assert(gimlet::check_field<damage>());

int main() { return 0; }
