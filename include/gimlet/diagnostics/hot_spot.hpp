// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The hot spot: the hottest disc (sphere in 3-D) of a given radius. A single particle's
/// temperature depends on the resolution and on particle noise; a mean over a fixed physical
/// size converges as the cell shrinks, so resolution studies can compare it.

#include "gimlet/core/error.hpp"
#include "gimlet/core/fields.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace gimlet::diagnostics {

template <class Vector>
struct hot_spot_result {
    double temperature = 0;      ///< K: mass-weighted mean temperature in the hottest disc
    double max_temperature = 0;  ///< K: the hottest single particle
    Vector centre{};             ///< m: the particle centre the hottest disc is centred on
    std::size_t particles = 0;   ///< particles in that disc
};

/// Over every particle centre c, the mass-weighted mean temperature of the particles whose
/// centres lie within `radius` (m) of c; the largest such mean is the hot-spot temperature.
/// Ties go to the lowest particle index. Needs the temperature field (a thermal policy that is
/// on). Discs are not wrapped across periodic boundaries.
template <class Solver>
[[nodiscard]] auto hot_spot(const Solver& s, double radius) {
    static_assert(Solver::store_type::template has<fields::temperature>,
                  "hot_spot needs particle temperatures: use a thermal policy that is on");
    require_positive("hot-spot radius (m)", radius);
    constexpr int dim = Solver::dim;
    using vector = typename Solver::vector;
    const auto& store = s.particles();
    const auto& x = store.template column<fields::position>();
    const auto& m = store.template column<fields::mass>();
    const auto& T = store.template column<fields::temperature>();
    hot_spot_result<vector> r;
    const std::size_t n = store.size();
    if (n == 0) return r;

    // Bins of side `radius`: a disc reaches only the 3^dim bins around its centre's bin.
    vector lo = x[0], hi = x[0];
    for (std::size_t i = 0; i < n; ++i) lo = lo.cwiseMin(x[i]), hi = hi.cwiseMax(x[i]);
    std::array<std::size_t, dim> bins{};
    std::size_t total = 1;
    for (int d = 0; d < dim; ++d) {
        bins[d] = std::size_t(double(hi[d] - lo[d]) / radius) + 1;
        total *= bins[d];
    }
    auto bin_of = [&](const vector& p, int d) { return std::size_t(double(p[d] - lo[d]) / radius); };
    auto flat = [&](const std::array<std::size_t, dim>& b) {
        std::size_t k = 0;
        for (int d = dim - 1; d >= 0; --d) k = k * bins[d] + b[d];
        return k;
    };
    // Counting sort of the particle indices by bin (CSR): deterministic and O(n).
    std::vector<std::size_t> start(total + 1, 0), order(n);
    std::vector<std::size_t> bin(n);
    std::vector<std::array<std::size_t, dim>> cell(n);  // each particle's bin, per axis
    for (std::size_t i = 0; i < n; ++i) {
        for (int d = 0; d < dim; ++d) cell[i][d] = bin_of(x[i], d);
        bin[i] = flat(cell[i]);
        ++start[bin[i] + 1];
    }
    for (std::size_t k = 0; k < total; ++k) start[k + 1] += start[k];
    {
        std::vector<std::size_t> fill(start.begin(), start.end() - 1);
        for (std::size_t i = 0; i < n; ++i) order[fill[bin[i]]++] = i;
    }

    const double r2 = radius * radius;
    r.temperature = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
        r.max_temperature = std::max(r.max_temperature, double(T[i]));
        const auto& b = cell[i];
        double mass = 0, heat = 0;
        std::size_t count = 0;
        std::array<int, dim> off{};
        off.fill(-1);
        while (true) {
            bool valid = true;
            std::array<std::size_t, dim> nb{};
            for (int d = 0; d < dim; ++d) {
                const long k = long(b[d]) + off[d];
                if (k < 0 || k >= long(bins[d])) valid = false;
                else nb[d] = std::size_t(k);
            }
            if (valid) {
                const std::size_t k = flat(nb);
                for (std::size_t j = start[k]; j < start[k + 1]; ++j) {
                    const std::size_t q = order[j];
                    if (double((x[q] - x[i]).squaredNorm()) > r2) continue;
                    mass += double(m[q]);
                    heat += double(m[q]) * double(T[q]);
                    ++count;
                }
            }
            int d = 0;
            while (d < dim && ++off[d] > 1) off[d] = -1, ++d;
            if (d == dim) break;
        }
        const double mean = heat / mass;
        if (mean > r.temperature) {
            r.temperature = mean;
            r.centre = x[i];
            r.particles = count;
        }
    }
    return r;
}

}  // namespace gimlet::diagnostics
