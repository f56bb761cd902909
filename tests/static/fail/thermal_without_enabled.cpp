// SPDX-License-Identifier: MIT
// Must not compile: a thermal policy without `enabled`. thermal::check names it.
// GIMLET_FAILTEST_EXPECT: needs `static constexpr bool enabled
#include <gimlet/thermal/check.hpp>

struct heater {
#ifdef GIMLET_FAILTEST_OK
    static constexpr bool enabled = true;
#endif
    using required_fields = gimlet::field_list<gimlet::fields::temperature>;
    template <class P>
    void initialize(const P& p) const {
        p.template get<gimlet::fields::temperature>() = 300;
    }
    template <class Real, class P>
    void update(const gimlet::point_step<Real>&, Real dissipated, const P& p) const {
        p.template get<gimlet::fields::temperature>() += dissipated / 1000;
    }
};

static_assert(gimlet::thermal::check<heater>());

int main() { return 0; }
