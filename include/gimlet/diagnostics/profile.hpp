// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Profiles of a particle quantity along an axis, and what is read off them: a plateau mean and
/// a front position.

#include "gimlet/core/fields.hpp"
#include "gimlet/core/processes.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace gimlet::diagnostics {

/// (coordinate along `axis`, value) for every particle accepted by `keep(p)`, sorted by
/// coordinate, then value. `value(p)` and `keep(p)` take a particle handle. On many processes
/// (solver_options::processes) it is collective: every process gets every process's points,
/// joined in the particles' ordinal order (one process's order) before the sort, so the same
/// list as one process, bit for bit (pairs that compare equal, such as 0 and -0, too).
template <class Solver, class Value, class Keep>
[[nodiscard]] std::vector<std::pair<double, double>> profile(const Solver& s, int axis, Value value, Keep keep) {
    std::vector<std::pair<double, double>> out;
    const auto& store = s.particles();
    gimlet::processes* many = gimlet::detail::processes_of(s);
    struct record {
        std::uint64_t ordinal;
        double coordinate, value;
    };
    std::vector<record> mine;
    for (std::size_t i = 0; i < store.size(); ++i) {
        const auto p = store[i];
        if (!keep(p)) continue;
        const double x = double(p.template get<fields::position>()[axis]), v = double(value(p));
        if (many) {
            if constexpr (requires { s.ordinal(i); }) mine.push_back({s.ordinal(i), x, v});
        } else {
            out.emplace_back(x, v);
        }
    }
    if (many)
        for (const record& r : gimlet::detail::in_ordinal_order(*many, mine)) out.emplace_back(r.coordinate, r.value);
    std::sort(out.begin(), out.end());
    return out;
}

/// Mean of the values with coordinate in [lo, hi]; 0 if there are none.
[[nodiscard]] inline double mean_between(const std::vector<std::pair<double, double>>& prof, double lo, double hi) {
    double sum = 0;
    std::size_t n = 0;
    for (const auto& [x, v] : prof)
        if (x >= lo && x <= hi) sum += v, ++n;
    return n ? sum / double(n) : 0.0;
}

/// The largest coordinate in [lo, hi] whose value is at least `threshold` (the leading edge of
/// a wave moving towards larger coordinates); `lo` if none is.
[[nodiscard]] inline double front_position(const std::vector<std::pair<double, double>>& prof, double threshold,
                                           double lo, double hi) {
    double front = lo;
    for (const auto& [x, v] : prof)
        if (x >= lo && x <= hi && v >= threshold) front = std::max(front, x);
    return front;
}

}  // namespace gimlet::diagnostics
