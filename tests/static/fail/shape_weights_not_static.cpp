// SPDX-License-Identifier: MIT
// Must not compile: a shape policy whose weights are a member, not static. shape::check names it.
// GIMLET_FAILTEST_EXPECT: for float and double \(static
#include <gimlet/shape/check.hpp>

#include <cmath>

struct nearest_node {
    static constexpr int stencil = 1;
    using required_fields = gimlet::field_list<>;
    template <class Real>
#ifdef GIMLET_FAILTEST_OK
    static void weights(Real x, Real, int& first, Real* w, Real* dw) noexcept {
#else
    void weights(Real x, Real, int& first, Real* w, Real* dw) noexcept {
#endif
        first = static_cast<int>(std::floor(x + Real(0.5)));
        w[0] = 1;
        dw[0] = 0;
    }
    template <class P, class Real>
    static auto half_width(const P&, Real) {
        return P::space_type::vector::Zero().eval();
    }
};

static_assert(gimlet::shape::check<nearest_node>());

int main() { return 0; }
