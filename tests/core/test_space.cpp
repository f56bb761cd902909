// SPDX-License-Identifier: MIT
// The small tensor helpers of core/space.hpp.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>

namespace {

// Equal bits, or both NaN: how a NaN's payload comes out of `inf * 0` is the compiler's choice.
template <class Real>
bool same(Real x, Real y) {
    return (std::isnan(x) && std::isnan(y)) || std::memcmp(&x, &y, sizeof(Real)) == 0;
}

}  // namespace

// minus_identity(a, c) stands in for Eigen's `a - c * Identity()` in the material update and the
// deviator (it keeps the expression inline in any unit), so it must give the same bits: the
// product with 0 off the diagonal included, which decides the sign of a zero (-0 - (c * 0) is +0
// for c < 0, and -0 for c > 0) and turns an infinite c into NaN there; a NaN reaches what it
// reaches in Eigen's. Both scalar types a space may have.
TEMPLATE_TEST_CASE("minus_identity gives the bits of Eigen's a - c I, signed zeros, infinities and NaN included", "[core]",
                   double, float) {
    using Real = TestType;
    using T3 = Eigen::Matrix<Real, 3, 3>;
    const Real inf = std::numeric_limits<Real>::infinity(), nan = std::numeric_limits<Real>::quiet_NaN();
    const Real cs[] = {Real(-2.5e9), Real(-1), Real(-0.0), Real(0), std::numeric_limits<Real>::denorm_min(),
                       Real(3), Real(7.25e8), inf, -inf, nan};
    for (int k = 0; k < 8; ++k) {
        T3 a;
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) a(i, j) = Real(std::sin(1.7 * (3 * j + i) + 0.9 * k) * 1e9);
        // Signed zeros where the sign of the result depends on the product with 0.
        a(0, 1) = Real(-0.0), a(2, 0) = Real(-0.0), a(1, 2) = Real(0);
        if (k % 2 == 1) a(1, 1) = Real(-0.0);
        if (k == 6) a(2, 1) = nan;
        if (k == 7) a(0, 2) = -inf;
        for (const Real c : cs) {
            const T3 eigen = a - c * T3::Identity();
            const T3 ours = gimlet::minus_identity(a, c);
            for (int j = 0; j < 3; ++j)
                for (int i = 0; i < 3; ++i) CHECK(same(eigen(i, j), ours(i, j)));
        }
        // A negative c turns the -0 entries into +0: the check above would see an entry that
        // skipped the product.
        CHECK_FALSE(std::signbit(gimlet::minus_identity(a, Real(-1))(0, 1)));
        CHECK(std::signbit(gimlet::minus_identity(a, Real(1))(0, 1)));
        CHECK(std::isnan(gimlet::minus_identity(a, inf)(1, 0)));
    }
}
