// SPDX-License-Identifier: MIT
// The small tensor helpers of core/space.hpp.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>

// minus_identity(a, c) stands in for Eigen's `a - c * Identity()` in the material update and the
// deviator (it keeps the expression inline in any unit), so it must give the same bits: the
// product with 0 off the diagonal included, which decides the sign of a zero (-0 - (c * 0) is +0
// for c < 0, and -0 for c > 0), and a NaN c reaches every entry as it does there.
TEST_CASE("minus_identity gives the bits of Eigen's a - c I, signed zeros and NaN included", "[core]") {
    using T3 = Eigen::Matrix3d;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double cs[] = {-2.5e9, -1.0, -0.0, 0.0, 1e-300, 3.0, 7.25e8};
    for (int k = 0; k < 8; ++k) {
        T3 a;
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) a(i, j) = std::sin(1.7 * (3 * j + i) + 0.9 * k) * 1e9;
        // Signed zeros where the sign of the result depends on the product with 0.
        a(0, 1) = -0.0, a(2, 0) = -0.0, a(1, 2) = 0.0;
        if (k % 2 == 1) a(1, 1) = -0.0;
        for (const double c : cs) {
            const T3 eigen = a - c * T3::Identity();
            const T3 ours = gimlet::minus_identity(a, c);
            CHECK(std::memcmp(eigen.data(), ours.data(), sizeof(T3)) == 0);
        }
        // A negative c turns the -0 entries into +0: the check above would see an entry that
        // skipped the product.
        CHECK_FALSE(std::signbit(gimlet::minus_identity(a, -1.0)(0, 1)));
        CHECK(std::signbit(gimlet::minus_identity(a, 1.0)(0, 1)));
        const T3 with_nan = gimlet::minus_identity(a, nan);
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) CHECK(std::isnan(with_nan(i, j)));
    }
}
