// SPDX-License-Identifier: MIT
// Must not compile: a strength policy without shear_modulus() is rejected by the Strength
// concept where the material is formed (one readable constraint error, not a backtrace).
// GIMLET_FAILTEST_EXPECT: constraint
#include <gimlet/gimlet.hpp>

struct broken_strength {
    using required_fields = gimlet::field_list<>;
    template <class Real, class P>
    Real update(const gimlet::point_step<Real>&, Eigen::Matrix<Real, 3, 3>&, const P&) const { return 0; }
#ifdef GIMLET_FAILTEST_OK
    template <class Real, class P>
    Real shear_modulus(const gimlet::point_state<Real>&, const P&) const { return 0; }
#endif
};

int main() {
    gimlet::material<broken_strength, gimlet::eos::linear> m{1000.0, broken_strength{}, gimlet::eos::linear{1e9}};
    return m.density > 0 ? 0 : 1;
}
