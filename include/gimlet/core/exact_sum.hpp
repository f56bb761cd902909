// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// gimlet::exact_sum: a sum of doubles that is exact until it is read, so that it does not
/// depend on the order of its terms: not on the particle order, the thread count or how the
/// particles are split between processes.

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace gimlet {

/// An exact sum of doubles (a long accumulator: Kulisch and Miranker 1986, "The arithmetic of
/// the digital computer: a new approach", SIAM Review 28(1); the digit layout as in Neal 2015,
/// "Fast exact summation using small and large superaccumulators", arXiv:1505.05571). Every
/// finite double is an integer multiple of 2^-1074 below 2^1024, so the accumulator holds the
/// exact sum as 32-bit digits, each in a 64-bit signed integer, with its carries propagated
/// every 2^30 additions. value() rounds the exact sum once, to nearest (ties to even). So the result is a function of the multiset of terms alone: any order of adding
/// them, and any grouping into partial sums merged with add(const exact_sum&), gives the same
/// bits. Two processes can merge partial sums by adding their digits() as integers.
///
/// A NaN term makes the sum NaN; infinite terms make it that infinity (NaN if both signs
/// occur). An exact sum whose magnitude reaches 2^1024 reads as an infinity.
class exact_sum {
public:
    /// 32-bit digits: digit k weighs 2^(32 k - 1088), the lowest just below 2^-1074, the highest
    /// with room above 2^1024 for the carries of sums of many terms.
    static constexpr int digit_count = 70;

    /// The digits, their non-finite state last (what two processes merge: integer sums).
    using digit_array = std::array<std::int64_t, digit_count + 1>;

    exact_sum() = default;
    /// The sum of one term.
    explicit exact_sum(double x) { add(x); }

    /// Add the term x, exactly.
    exact_sum& add(double x) {
        if (!std::isfinite(x)) {
            special_ |= std::isnan(x) ? nan_bit : x > 0 ? plus_inf_bit : minus_inf_bit;
            return *this;
        }
        if (x == 0) return *this;
        const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
        const int biased = int((bits >> 52) & 0x7ff);
        std::uint64_t mantissa = bits & ((std::uint64_t(1) << 52) - 1);
        // x = mantissa 2^(exponent), exponent >= -1074, mantissa < 2^53.
        int exponent = -1074;
        if (biased != 0) mantissa |= std::uint64_t(1) << 52, exponent = biased - 1075;
        const int at = exponent + 1088;  // the accumulator bit the mantissa's lowest bit lands on
        const int k = at / 32, shift = at % 32;
        // mantissa << shift spans at most 85 bits: three digits, each part below 2^32.
        const std::uint64_t low = (mantissa << shift) & 0xffffffffu;
        const std::uint64_t mid = (mantissa >> (32 - shift)) & 0xffffffffu;
        const std::uint64_t high = shift == 0 ? 0 : mantissa >> (64 - shift);
        const std::int64_t sign = (bits >> 63) ? -1 : 1;
        digits_[std::size_t(k)] += sign * std::int64_t(low);
        digits_[std::size_t(k) + 1] += sign * std::int64_t(mid);
        digits_[std::size_t(k) + 2] += sign * std::int64_t(high);
        if (++pending_ == max_pending) carry();
        return *this;
    }

    /// Add another exact sum (a partial sum of other terms), exactly.
    exact_sum& add(const exact_sum& other) {
        exact_sum o = other;
        o.carry();
        carry();
        for (std::size_t k = 0; k < digit_count; ++k) digits_[k] += o.digits_[k];
        special_ |= o.special_;
        pending_ = 1;  // every digit within 2^33 of its range: room for 2^30 more terms
        return *this;
    }

    /// add(x).
    exact_sum& operator+=(double x) { return add(x); }
    /// add(other).
    exact_sum& operator+=(const exact_sum& other) { return add(other); }

    /// The digits and the non-finite state, carried (every digit but the top in [0, 2^32)), for
    /// another process to merge with from_digits(a + b) digit by digit.
    [[nodiscard]] digit_array digits() const {
        exact_sum c = *this;
        c.carry();
        digit_array out{};
        for (std::size_t k = 0; k < digit_count; ++k) out[k] = c.digits_[k];
        out[digit_count] = c.special_;
        return out;
    }

    /// The sum whose digits() are `d`, or the digit-wise sum of at most 2^30 such arrays, with
    /// the bitwise OR of their non-finite states in the last entry.
    [[nodiscard]] static exact_sum from_digits(const digit_array& d) {
        exact_sum s;
        for (std::size_t k = 0; k < digit_count; ++k) s.digits_[k] = d[k];
        s.special_ = d[digit_count] & (nan_bit | plus_inf_bit | minus_inf_bit);
        s.pending_ = 1;
        s.carry();
        return s;
    }

    /// The exact sum rounded to the nearest double.
    [[nodiscard]] double value() const {
        if (special_ & nan_bit || (special_ & plus_inf_bit && special_ & minus_inf_bit))
            return std::numeric_limits<double>::quiet_NaN();
        if (special_ & plus_inf_bit) return std::numeric_limits<double>::infinity();
        if (special_ & minus_inf_bit) return -std::numeric_limits<double>::infinity();
        exact_sum c = *this;
        c.carry();
        // The top digit carries the sign; negate a negative sum and read its magnitude.
        double sign = 1;
        if (c.digits_[digit_count - 1] < 0) {
            sign = -1;
            for (auto& d : c.digits_) d = -d;
            c.pending_ = 1;
            c.carry();
        }
        int top = digit_count - 1;
        while (top >= 0 && c.digits_[std::size_t(top)] == 0) --top;
        if (top < 0) return 0.0;
        // The 64 bits from the highest set bit down (the top digit's `lead` bits, the next
        // digit's 32, the highest 32 - lead of the one below), and whether any bit below is set.
        const auto digit = [&](int k) { return k >= 0 ? std::uint64_t(c.digits_[std::size_t(k)]) : 0; };
        const int lead = int(std::bit_width(digit(top)));  // 1..32
        const std::uint64_t window =
            digit(top) << (64 - lead) | digit(top - 1) << (32 - lead) | digit(top - 2) >> lead;
        std::uint64_t rest = digit(top - 2) & ((std::uint64_t(1) << lead) - 1);
        for (int k = top - 3; k >= 0 && rest == 0; --k) rest = digit(k);
        // A set bit 11 places below a double's last bit decides no tie, only its direction.
        const int window_low = top * 32 + lead - 64;  // the accumulator bit of window's bit 0
        return sign * std::ldexp(double(rest != 0 ? window | 1 : window), window_low - 1088);
    }

private:
    static constexpr std::int64_t nan_bit = 1, plus_inf_bit = 2, minus_inf_bit = 4;
    // Each term adds less than 2^32 to a digit: 2^30 of them between carries keep every digit
    // within 2^63 (a carried digit is below 2^32 and the top one far below 2^62).
    static constexpr std::uint32_t max_pending = std::uint32_t(1) << 30;

    // Propagate the carries: every digit but the top in [0, 2^32), the value unchanged.
    void carry() {
        if (pending_ == 0) return;
        for (std::size_t k = 0; k + 1 < digit_count; ++k) {
            const std::int64_t c = digits_[k] >> 32;  // floor division by 2^32
            digits_[k] -= c * (std::int64_t(1) << 32);
            digits_[k + 1] += c;
        }
        pending_ = 0;
    }

    std::array<std::int64_t, digit_count> digits_{};
    std::int64_t special_ = 0;
    std::uint32_t pending_ = 0;  // terms added since the last carry
};

}  // namespace gimlet
