// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// How a numerical_error names the particle it is about.

#include "gimlet/core/fields.hpp"

#include <cstddef>
#include <optional>
#include <sstream>
#include <stdexcept>
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

/// Where describe_particle's "particle I (body" first stands in `message`: the index I, the
/// offset of its first digit and its number of digits.
struct named_particle {
    std::size_t index = 0, at = 0, digits = 0;
};
[[nodiscard]] inline std::optional<named_particle> find_named_particle(const std::string& message) {
    const std::string before = "particle ", after = " (body";
    for (std::size_t at = message.find(before); at != std::string::npos; at = message.find(before, at + 1)) {
        const std::size_t first = at + before.size();
        std::size_t end = first;
        while (end < message.size() && message[end] >= '0' && message[end] <= '9') ++end;
        if (end == first || message.compare(end, after.size(), after) != 0) continue;
        named_particle n;
        n.at = first, n.digits = end - first;
        try {
            n.index = std::size_t(std::stoull(message.substr(first, n.digits)));
        } catch (const std::out_of_range&) {
            continue;  // more digits than any index has
        }
        return n;
    }
    return std::nullopt;
}
}  // namespace detail

}  // namespace gimlet
