// SPDX-License-Identifier: MIT
// Must not compile: a material bundle of one's own whose validate() is not const.
// check_material names it (docs/concepts.md, Material and Region).
// GIMLET_FAILTEST_EXPECT: validate\(\) must be const
#include <gimlet/material/check.hpp>

struct my_material {
    using strength_type = gimlet::strength::linear_elastic;
    using eos_type = gimlet::eos::linear;
    using thermal_type = gimlet::thermal::none;
    using viscosity_type = gimlet::viscosity::none;
    using required_fields = gimlet::field_list<>;
    double density = 1000;
#ifdef GIMLET_FAILTEST_OK
    void validate() const {}
#else
    void validate() {}
#endif
};

static_assert(gimlet::check_material<my_material>());

int main() { return 0; }
