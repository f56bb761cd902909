// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Numbers in text files that read back exactly: for the CSV files a run writes.

#include "gimlet/io/detail/text.hpp"

#include <algorithm>
#include <iterator>
#include <locale>
#include <ostream>
#include <string>

namespace gimlet::io {

namespace detail {
// Formats every floating-point value in the shortest text that reads back to exactly the same
// double (exact_text, std::to_chars); floats are promoted to double by operator<< and come back
// exactly too. Integers, text and the stream's other settings are untouched.
class exact_num_put : public std::num_put<char> {
protected:
    iter_type do_put(iter_type out, std::ios_base& str, char_type, double v) const override {
        str.width(0);  // a field width applies to one item, as the standard num_put has it (no padding here)
        const std::string t = exact_text(v);
        return std::copy(t.begin(), t.end(), out);
    }
    // A long double is written as the double nearest to it (exact only for values a double holds).
    iter_type do_put(iter_type out, std::ios_base& str, char_type fill, long double v) const override {
        return do_put(out, str, fill, static_cast<double>(v));
    }
};
}  // namespace detail

/// From now on, `os << x` for a floating-point x writes the shortest text that reads back to
/// exactly x (std::to_chars), whatever the stream's precision: 0.1 as "0.1", 1/3 to 17 digits,
/// infinities and NaN as "inf" and "nan". Every CSV an example writes goes through it, so a
/// value written once compares equal when read back (Python's float() and std::strtod read it).
inline void exact_numbers(std::ostream& os) { os.imbue(std::locale(os.getloc(), new detail::exact_num_put)); }

}  // namespace gimlet::io
