// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Profiles of a particle quantity along an axis, and what is read off them: a plateau mean and
/// a front position.

#include "gimlet/core/fields.hpp"
#include "gimlet/core/processes.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <utility>
#include <vector>

namespace gimlet::diagnostics {

/// (coordinate along `axis`, value) for every particle accepted by `keep(p)`, sorted by
/// coordinate, then value. `value(p)` and `keep(p)` take a particle handle. On many processes
/// (solver_options::processes) it is collective: every process gets every process's points,
/// the same list as one process (the order sorts equal pairs alike).
template <class Solver, class Value, class Keep>
[[nodiscard]] std::vector<std::pair<double, double>> profile(const Solver& s, int axis, Value value, Keep keep) {
    std::vector<std::pair<double, double>> out;
    const auto& store = s.particles();
    for (std::size_t i = 0; i < store.size(); ++i) {
        const auto p = store[i];
        if (keep(p)) out.emplace_back(double(p.template get<fields::position>()[axis]), double(value(p)));
    }
    if (gimlet::processes* many = gimlet::detail::processes_of(s)) {
        std::vector<std::byte> mine(out.size() * 2 * sizeof(double));
        for (std::size_t k = 0; k < out.size(); ++k) {
            std::memcpy(mine.data() + 2 * k * sizeof(double), &out[k].first, sizeof(double));
            std::memcpy(mine.data() + (2 * k + 1) * sizeof(double), &out[k].second, sizeof(double));
        }
        const auto in = many->all_to_all(std::vector<std::vector<std::byte>>(std::size_t(many->size()), mine));
        out.clear();
        for (const auto& from : in)
            for (std::size_t at = 0; at + 2 * sizeof(double) <= from.size(); at += 2 * sizeof(double)) {
                std::pair<double, double> point;
                std::memcpy(&point.first, from.data() + at, sizeof(double));
                std::memcpy(&point.second, from.data() + at + sizeof(double), sizeof(double));
                out.push_back(point);
            }
    }
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
