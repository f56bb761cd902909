// SPDX-License-Identifier: MIT
// Must not compile: a viscosity without signal_speed (the stable step needs it).
// viscosity::check names it.
// GIMLET_FAILTEST_EXPECT: needs `template <class Real, class P> Real signal_speed
#include <gimlet/viscosity/check.hpp>

struct constant_q {
    static constexpr bool enabled = true;
    using required_fields = gimlet::field_list<>;
    template <class Real, class P>
    Real pressure(const gimlet::point_step<Real>&, Real, const P&) const {
        return 1e6;
    }
#ifdef GIMLET_FAILTEST_OK
    template <class Real, class P>
    Real signal_speed(Real sound_speed, Real, const P&) const {
        return sound_speed;
    }
#endif
};

static_assert(gimlet::viscosity::check<constant_q>());

int main() { return 0; }
