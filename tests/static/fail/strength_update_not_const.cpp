// SPDX-License-Identifier: MIT
// Must not compile: a strength policy whose update is not const. strength::check names it.
// GIMLET_FAILTEST_EXPECT: update must be const
#include <gimlet/strength/check.hpp>

struct stiff {
    using required_fields = gimlet::field_list<>;
    template <class Real, class P>
#ifdef GIMLET_FAILTEST_OK
    Real update(const gimlet::point_step<Real>&, Eigen::Matrix<Real, 3, 3>&, const P&) const {
#else
    Real update(const gimlet::point_step<Real>&, Eigen::Matrix<Real, 3, 3>&, const P&) {
#endif
        return 0;
    }
    template <class Real, class P>
    Real shear_modulus(const gimlet::point_state<Real>&, const P&) const {
        return 1e9;
    }
};

static_assert(gimlet::strength::check<stiff>());

int main() { return 0; }
