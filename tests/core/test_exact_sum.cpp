// SPDX-License-Identifier: MIT
// gimlet::exact_sum: the sum is the exact one rounded once, to nearest with ties to even; any
// order of the terms and any grouping into partial sums (merged directly or through their
// digits, as two processes would) gives the same bits; non-finite terms and overflow read as
// IEEE arithmetic would give them.
#include <gimlet/core/exact_sum.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace {

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

double exact(std::initializer_list<double> terms) {
    gimlet::exact_sum s;
    for (double x : terms) s += x;
    return s.value();
}

// Terms spanning 600 binary orders of magnitude, of both signs, some subnormal.
std::vector<double> wide_terms(std::mt19937_64& rng, std::size_t n) {
    std::uniform_real_distribution<double> mant(0.5, 1.0);
    std::uniform_int_distribution<int> exp(-300, 300), sign(0, 1);
    std::vector<double> x(n);
    for (auto& v : x) v = (sign(rng) ? -1 : 1) * std::ldexp(mant(rng), exp(rng));
    x[n / 3] = std::numeric_limits<double>::denorm_min();
    x[n / 2] = -3 * std::numeric_limits<double>::denorm_min();
    return x;
}

}  // namespace

TEST_CASE("exact_sum rounds the exact sum once, to nearest with ties to even", "[exact_sum]") {
    const double ulp = std::ldexp(1.0, -52), half = std::ldexp(1.0, -53);
    // Cancellation that a running double sum loses entirely.
    CHECK(exact({1e100, 1.0, -1e100}) == 1.0);
    CHECK(exact({1e100, -1e100}) == 0.0);
    CHECK(exact({}) == 0.0);
    // A tie rounds to the even neighbour; a term far below the tie decides it.
    CHECK(same_bits(exact({1.0, half}), 1.0));
    CHECK(same_bits(exact({1.0 + ulp, half}), 1.0 + 2 * ulp));
    CHECK(same_bits(exact({1.0, half, std::ldexp(1.0, -400)}), 1.0 + ulp));
    CHECK(same_bits(exact({1.0, half, -std::ldexp(1.0, -400)}), 1.0));
    CHECK(same_bits(exact({-1.0, -half, -std::ldexp(1.0, -400)}), -(1.0 + ulp)));
    // The lowest and highest terms a double holds.
    const double tiny = std::numeric_limits<double>::denorm_min(), big = std::numeric_limits<double>::max();
    CHECK(same_bits(exact({tiny, tiny, tiny}), 3 * tiny));
    CHECK(same_bits(exact({big, -big, big}), big));
    CHECK(same_bits(exact({big, tiny, -big}), tiny));
    // A sum past the largest double overflows as IEEE addition would, whatever it then cancels.
    CHECK(exact({big, big}) == std::numeric_limits<double>::infinity());
    CHECK(exact({-big, -big}) == -std::numeric_limits<double>::infinity());
    CHECK(exact({big, big, -big}) == big);
    // Every integer multiple of the smallest subnormal: 0.1 + 0.2 exactly, then rounded once.
    CHECK(same_bits(exact({0.1, 0.2}), 0.1 + 0.2));  // one addition is already correctly rounded
    CHECK(same_bits(exact({0.1, 0.2, -0.3}), std::ldexp(1.0, -55)));  // the binary64 terms' exact sum
}

TEST_CASE("exact_sum of non-finite terms reads as IEEE arithmetic", "[exact_sum]") {
    const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
    CHECK(exact({1.0, inf}) == inf);
    CHECK(exact({1.0, -inf}) == -inf);
    CHECK(std::isnan(exact({inf, -inf})));
    CHECK(std::isnan(exact({1.0, nan, 2.0})));
    gimlet::exact_sum a, b;
    a += inf, b += 1.0;
    CHECK(gimlet::exact_sum(a).add(b).value() == inf);
}

TEST_CASE("exact_sum gives the same bits for any order and grouping of its terms", "[exact_sum]") {
    std::mt19937_64 rng(20261207);
    const auto terms = wide_terms(rng, 5000);
    gimlet::exact_sum whole;
    for (double x : terms) whole += x;
    const double reference = whole.value();
    REQUIRE(std::isfinite(reference));
    auto shuffled = terms;
    for (int trial = 0; trial < 20; ++trial) {
        std::shuffle(shuffled.begin(), shuffled.end(), rng);
        // Split at random points into parts, summed apart, merged directly and through digits.
        std::uniform_int_distribution<std::size_t> cut(0, shuffled.size());
        std::vector<std::size_t> cuts{0, shuffled.size(), cut(rng), cut(rng), cut(rng)};
        std::sort(cuts.begin(), cuts.end());
        gimlet::exact_sum merged;
        gimlet::exact_sum::digit_array digit_sum{};
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
            gimlet::exact_sum part;
            for (std::size_t i = cuts[k]; i < cuts[k + 1]; ++i) part += shuffled[i];
            merged += part;
            const auto d = part.digits();
            for (std::size_t j = 0; j < d.size(); ++j) digit_sum[j] += d[j];
        }
        CHECK(same_bits(merged.value(), reference));
        CHECK(same_bits(gimlet::exact_sum::from_digits(digit_sum).value(), reference));
    }
}

TEST_CASE("exact_sum matches a sum of exact integers, rounded once", "[exact_sum]") {
    // Terms that are integers below 2^53 times 2^-40: their exact sum is an integer times 2^-40
    // that a 64-bit integer holds, and that integer converts to double correctly rounded.
    std::mt19937_64 rng(7);
    std::uniform_int_distribution<std::int64_t> n(-(std::int64_t(1) << 52), std::int64_t(1) << 52);
    for (int trial = 0; trial < 200; ++trial) {
        gimlet::exact_sum s;
        std::int64_t total = 0;
        for (int k = 0; k < 1000; ++k) {
            const std::int64_t i = n(rng) >> (k % 40);  // magnitudes from 2^12 to 2^52
            total += i;
            s += std::ldexp(double(i), -40);
        }
        CHECK(same_bits(s.value(), std::ldexp(double(total), -40)));
    }
    // Digit sums far above a digit's range (a thousand processes' partial sums) carry exactly.
    gimlet::exact_sum part;
    for (int k = 0; k < 100; ++k) part += std::ldexp(double((std::int64_t(1) << 53) - 1 - k), 7 * k - 400);
    gimlet::exact_sum::digit_array thousand{};
    for (int r = 0; r < 1000; ++r)
        for (std::size_t j = 0; j < thousand.size(); ++j) thousand[j] += part.digits()[j];
    gimlet::exact_sum direct;
    for (int r = 0; r < 1000; ++r) direct += part;
    CHECK(same_bits(gimlet::exact_sum::from_digits(thousand).value(), direct.value()));
    CHECK(std::abs(direct.value() / part.value() - 1000) < 1e-12);
}
