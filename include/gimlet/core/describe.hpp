// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// How a numerical_error names the particle it is about.

#include "gimlet/core/fields.hpp"

#include <cstddef>
#include <sstream>
#include <string>

namespace gimlet {

/// "gimlet: step N (t = T s): particle I (body B) at (x, y) m", for numerical_error messages.
template <class P>
[[nodiscard]] std::string describe_particle(const P& p, std::size_t step, double time) {
    const auto& x = p.template get<fields::position>();
    std::ostringstream os;
    os.precision(8);
    os << "gimlet: step " << step << " (t = " << time << " s): particle " << p.index() << " (body "
       << p.template get<fields::body>() << ") at (";
    for (int d = 0; d < x.size(); ++d) os << (d ? ", " : "") << double(x[d]);
    os << ") m";
    return os.str();
}

namespace detail {
/// "(x, y) m" (8 significant digits), for messages that name a place.
template <class V>
[[nodiscard]] std::string format_position(const V& x) {
    std::ostringstream os;
    os.precision(8);
    os << "(";
    for (int d = 0; d < x.size(); ++d) os << (d ? ", " : "") << double(x[d]);
    os << ") m";
    return os.str();
}
}  // namespace detail

}  // namespace gimlet
