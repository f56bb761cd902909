// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The hot spot: the hottest disc (sphere in 3-D) of a given radius. A single particle's
/// temperature depends on the resolution and on particle noise; a mean over a fixed physical
/// size converges as the cell shrinks, so resolution studies can compare it.

#include "gimlet/core/detail/blocks.hpp"
#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/core/fields.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace gimlet::diagnostics {

template <class Vector>
struct hot_spot_result {
    /// K: mass-weighted mean temperature in the hottest disc (-infinity: none)
    double temperature = -std::numeric_limits<double>::infinity();
    /// K: the hottest single particle (NaN: none)
    double max_temperature = std::numeric_limits<double>::quiet_NaN();
    Vector centre{};             ///< m: the particle centre the hottest disc is centred on (zero if none)
    std::size_t particles = 0;   ///< particles in that disc
};

/// What hot_spot allocates on each call (its bins and the particles' copies in bin order),
/// kept for the next call. A caller that asks every step passes the same workspace to each
/// call and saves the allocations, their zeroing and their page faults, which run on one
/// thread (at 0.25 mm cells, 215,784 particles, about 14 MB a call: docs/performance.md). It
/// holds nothing the answer depends on: any workspace, new or used, gives the same result. One
/// workspace serves one call at a time: calls that run concurrently need one each.
template <class Vector>
struct hot_spot_workspace {
    std::vector<Vector> block_lo, block_hi, block_hot_lo, block_hot_hi, sorted_x;
    std::vector<std::array<std::size_t, std::size_t(Vector::RowsAtCompileTime)>> cell;
    std::vector<std::size_t> bin, cursor, start, block_hottest, sorted_index;
    std::vector<std::uint8_t> block_hot;
    std::vector<double> block_max, sorted_m, sorted_T, block_mass, block_excess, block_ring;
    std::vector<std::uint8_t> hot_bin, keep_bin, try_bin;
};

/// Over every particle centre c, the mass-weighted mean temperature of the particles whose
/// centres lie within `radius` (m) of c; the largest such mean is the hot-spot temperature.
/// Ties go to the lowest particle index. Needs the temperature field (a thermal policy that is
/// on). Discs are not wrapped across periodic boundaries.
///
/// Each mean is summed relative to a reference T_b, the hottest particle of the search's bins
/// around c (bins of side `radius`; the 3^dim around c's hold the disc, and may hold hotter
/// particles outside it): T_b + sum m (T - T_b) / sum m. With positive masses every term is then
/// at most zero, so the computed mean never exceeds T_b; where every particle of those bins has
/// one temperature (a uniform field) it is exactly that temperature (a plain sum m T / sum m can
/// round a few ulps above every particle). Where T_b is not finite the reference is 0.
///
/// `above` (K) is for a caller that tracks a running peak: only discs hotter than it are
/// sought, so the centres that cannot hold one are skipped too, and only the bins within two of
/// the box of the particles hotter than `above` are sorted (a disc is no hotter than its
/// hottest particle); where no particle is hotter, nothing is sorted or sought. A result hotter
/// than `above` is the hottest disc, the same as without it; otherwise no disc is hotter than
/// `above`, and the result names a disc no hotter than it, or none (temperature -infinity, no
/// particles). Without `above`, only the bins within two of a bin holding a particle about as
/// hot as the hottest particle's disc are sorted (the same disc results). A NaN or
/// +infinity `above` is ignored (as -infinity): the hottest disc is returned.
///
/// max_temperature is the hottest particle's temperature, NaN never taken (NaN where every
/// temperature is NaN; there is then no disc). With no particles there is neither: temperature
/// -infinity, max_temperature NaN, no particles, as where every temperature is NaN.
///
/// `work` is scratch reused between calls (hot_spot_workspace of the solver's vector type);
/// the overload without it makes its own.
template <class Solver>
[[nodiscard]] auto hot_spot(const Solver& s, double radius, double above, hot_spot_workspace<typename Solver::vector>& work) {
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
    r.centre = vector::Zero();
    const std::size_t n = store.size();
    if (n == 0) return r;  // no disc and no hottest particle: the result's defaults say none

    // The passes over the particles run on the solver's threads from 4096 particles, in
    // `blocks` contiguous ranges of particles, one a thread. Each gives what the serial pass
    // gives (a minimum, a maximum, a stable order), so nothing depends on the thread count.
    const int threads = detail::threads_of(s);
    const std::size_t blocks = detail::observer_blocks(n, threads);
    // The discs sought are hotter than this (NaN and +infinity ignored, as documented). With
    // one (a tracked peak), the bins kept are found from the box of the particles hotter than
    // it; without, from a lower bound on the hottest disc (`refine`, below).
    const double wanted =
        above < std::numeric_limits<double>::infinity() ? above : -std::numeric_limits<double>::infinity();
    const bool tracked = wanted > -std::numeric_limits<double>::infinity();

    // The passes run in one parallel region (below), with barriers between them: where idle
    // threads sleep (OMP_WAIT_POLICY=passive) a region costs about nine barriers (48 against
    // 5.5 us on two threads), and five regions a call took as long as the second thread saved
    // (docs/performance.md, "The hot spot's passes in one region"). Each pass's shares are set
    // up where its size is known: the first here, the others by one thread between the passes.
    auto& block_lo = work.block_lo;
    auto& block_hi = work.block_hi;
    auto& block_hottest = work.block_hottest;
    constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
    block_lo.assign(blocks, x[0]);
    block_hi.assign(blocks, x[0]);
    block_hottest.assign(blocks, none);
    // Per block, the box of its particles hotter than `wanted` (if any): only a disc near one of
    // those can be sought.
    auto& block_hot_lo = work.block_hot_lo;
    auto& block_hot_hi = work.block_hot_hi;
    auto& block_hot = work.block_hot;
    block_hot_lo.assign(blocks, x[0]);
    block_hot_hi.assign(blocks, x[0]);
    block_hot.assign(blocks, 0);
    // Every entry of bin, cell and the copies is written before it is read.
    auto& start = work.start;
    auto& bin = work.bin;
    auto& cell = work.cell;  // each particle's bin, per axis
    auto& cursor = work.cursor;  // per block and bin: a count, then an offset
    auto& block_max = work.block_max;  // per block and bin, the hottest particle's temperature
    auto& sorted_x = work.sorted_x;
    auto& sorted_m = work.sorted_m;
    auto& sorted_T = work.sorted_T;
    auto& sorted_index = work.sorted_index;  // each copy's particle
    bin.resize(n);
    cell.resize(n);
    sorted_x.resize(n);
    sorted_m.resize(n);
    sorted_T.resize(n);
    sorted_index.resize(n);
    const int team = blocks > 1 ? threads : 1;
    detail::thread_shares bounds_pass(static_cast<std::ptrdiff_t>(blocks), team);
    std::optional<detail::thread_shares> count_pass, copy_pass, merge_pass;
    vector lo = x[0], hi = x[0];
    std::array<std::size_t, dim> bins{};
    std::size_t total = 1, sort_blocks = 1, merge_blocks = 1;
    // The bins kept per axis (those within two of the box of the particles hotter than
    // `wanted`: every disc that could be sought reads only these), the bins whose particles are
    // tried as centres (within one), and, in the quantity bin_of divides by the radius, a range
    // one bin wider than the kept bins, which tells most particles outside them without the
    // division.
    std::array<std::size_t, dim> keep_lo{}, keep_hi{}, try_lo{}, try_hi{};
    std::array<double, dim> keep_from{}, keep_to{};
    auto bin_of = [&](const vector& p, int d) { return std::size_t(double(p[d] - lo[d]) / radius); };
    auto flat = [&](const std::array<std::size_t, dim>& b) {
        std::size_t k = 0;
        for (int d = dim - 1; d >= 0; --d) k = k * bins[d] + b[d];
        return k;
    };
    // f(k) for each of the 3^dim bins around particle i's that exist, the first axis fastest
    // (the order the discs' sums take). Nested loops over each axis's range: enumerating the
    // 3^dim offsets and testing each cost a fifth of the search's instructions
    // (docs/performance.md, "The hot spot's bins").
    auto around = [&](std::size_t i, auto&& f) {
        const auto& b = cell[i];
        std::array<std::size_t, dim> first{}, last{};
        for (int d = 0; d < dim; ++d) {
            first[d] = b[d] > 0 ? b[d] - 1 : 0;
            last[d] = std::min(b[d] + 1, bins[d] - 1);
        }
        if constexpr (dim == 2) {
            for (std::size_t y = first[1]; y <= last[1]; ++y)
                for (std::size_t x0 = first[0]; x0 <= last[0]; ++x0) f(y * bins[0] + x0);
        } else {
            for (std::size_t z = first[2]; z <= last[2]; ++z)
                for (std::size_t y = first[1]; y <= last[1]; ++y)
                    for (std::size_t x0 = first[0]; x0 <= last[0]; ++x0) f((z * bins[1] + y) * bins[0] + x0);
        }
    };
    // f(cell) for every cell from `from` to `to` (inclusive, per axis), the first axis fastest.
    auto for_cells = [&](const std::array<std::size_t, dim>& from, const std::array<std::size_t, dim>& to, auto&& f) {
        std::array<std::size_t, dim> k{};
        if constexpr (dim == 2) {
            for (k[1] = from[1]; k[1] <= to[1]; ++k[1])
                for (k[0] = from[0]; k[0] <= to[0]; ++k[0]) f(k);
        } else {
            for (k[2] = from[2]; k[2] <= to[2]; ++k[2])
                for (k[1] = from[1]; k[1] <= to[1]; ++k[1])
                    for (k[0] = from[0]; k[0] <= to[0]; ++k[0]) f(k);
        }
    };
    // The hottest particle of the 3^dim bins around particle i's (NaN never taken).
    auto bound_at = [&](std::size_t i) {
        double bound = -std::numeric_limits<double>::infinity();
        around(i, [&](std::size_t b) { bound = std::max(bound, block_max[b]); });
        return bound;
    };
    // The mean over the disc centred on particle i, whose bins' hottest particle is `bound`,
    // summed in bin order relative to it (the same sums wherever it is asked for). Rounding is
    // monotone and 0 is representable: T - bound <= 0 rounds to <= 0, and so do its product
    // with m >= 0, the sum of such terms (a multiply-add too) and its quotient by the mass, so
    // the result is at most `bound`, exactly. (Finite temperatures whose differences do not
    // overflow; the solver stops on a non-finite one.)
    const double r2 = radius * radius;
    auto disc = [&](std::size_t i, double bound, std::size_t& count) {
        const double ref = std::isfinite(bound) ? bound : 0.0;
        double mass = 0, excess = 0;
        count = 0;
        const vector c = x[i];
        around(i, [&](std::size_t k) {
            for (std::size_t j = start[k]; j < start[k + 1]; ++j) {
                if (double((sorted_x[j] - c).squaredNorm()) > r2) continue;
                mass += sorted_m[j];
                excess += sorted_m[j] * (sorted_T[j] - ref);
                ++count;
            }
        });
        return ref + excess / mass;
    };
    // The centres' search (below) keeps the hottest disc, ties to the lowest index: a maximum
    // in a total order, so it does not depend on the thread count.
    struct best_disc {
        double mean = -std::numeric_limits<double>::infinity();
        std::size_t index = 0, count = 0;
        bool found = false;
        [[nodiscard]] bool beaten_by(double m, std::size_t i) const {
            return !found ? m > mean : (m > mean || (m == mean && i < index));
        }
    };
    best_disc best;
    std::size_t hottest = none, hottest_count = 0;
    double hottest_mean = 0, floor = 0;
    // An exception must not leave the region (that would end the program): the serial step's,
    // a radius too small for the bins or an allocation that fails, is kept and thrown after it.
    std::exception_ptr failed;
    bool go = false;  // a particle hotter than `wanted`, and the bins allocated: the passes after the first
    // A search with no `above` (a sample's) is narrowed too, by a lower bound on the hottest
    // disc (`hot_floor`, below the search's floor): every centre whose bins' hottest particle
    // reaches that floor is then near a particle at least hot_floor hot, so the bins kept are
    // those within two of a bin holding one (`keep_bin`, `try_bin` within one). A map, not a
    // box: two hot spots far apart would put everything between them in a box.
    bool refine = false;
    double hot_floor = -std::numeric_limits<double>::infinity();
    auto& block_mass = work.block_mass;
    auto& block_excess = work.block_excess;
    auto& block_ring = work.block_ring;
    auto& hot_bin = work.hot_bin;
    auto& keep_bin = work.keep_bin;
    auto& try_bin = work.try_bin;
    std::optional<detail::thread_shares> near_pass, mark_pass;
    // The kept and tried bins' ranges around the box [hot_lo, hot_hi] of the hot particles, and
    // the sort's arrays (one thread, in a `single`).
    auto prepare = [&](const vector& hot_lo, const vector& hot_hi) {
        for (int d = 0; d < dim; ++d) {
            const std::size_t a = bin_of(hot_lo, d), z = bin_of(hot_hi, d);
            keep_lo[d] = a >= 2 ? a - 2 : 0;
            keep_hi[d] = std::min(z + 2, bins[d] - 1);
            try_lo[d] = a >= 1 ? a - 1 : 0;
            try_hi[d] = std::min(z + 1, bins[d] - 1);
            keep_from[d] = (double(keep_lo[d]) - 1) * radius;
            keep_to[d] = (double(keep_hi[d]) + 2) * radius;
        }
        cursor.assign(sort_blocks * total, 0);
        block_max.assign(sort_blocks * total, -std::numeric_limits<double>::infinity());
        start.reserve(total + 1);  // so that block_offsets does not allocate
        count_pass.emplace(static_cast<std::ptrdiff_t>(sort_blocks), team);
        copy_pass.emplace(static_cast<std::ptrdiff_t>(sort_blocks), team);
        merge_pass.emplace(static_cast<std::ptrdiff_t>(merge_blocks), team);
        go = true;
    };
    GIMLET_OMP(parallel num_threads(team) if (blocks > 1))
    {
        // Bins of side `radius`: a disc reaches only the 3^dim bins around its centre's bin.
        // The same pass finds each block's hottest particle: the first of its largest
        // temperatures, NaN never taken (`none` where the block has only NaN).
        detail::for_each_block_of(bounds_pass, n, blocks, [&](std::size_t b, std::size_t first, std::size_t last) {
            vector lo_b = x[0], hi_b = x[0], hot_lo_b = x[0], hot_hi_b = x[0];
            std::size_t h = none;
            bool hot = false;
            for (std::size_t i = first; i < last; ++i) {
                lo_b = lo_b.cwiseMin(x[i]), hi_b = hi_b.cwiseMax(x[i]);
                if (!std::isnan(double(T[i])) && (h == none || T[i] > T[h])) h = i;
                if (tracked && double(T[i]) > wanted) {
                    hot_lo_b = hot ? vector(hot_lo_b.cwiseMin(x[i])) : x[i];
                    hot_hi_b = hot ? vector(hot_hi_b.cwiseMax(x[i])) : x[i];
                    hot = true;
                }
            }
            block_lo[b] = lo_b;
            block_hi[b] = hi_b;
            block_hottest[b] = h;
            block_hot_lo[b] = hot_lo_b;
            block_hot_hi[b] = hot_hi_b;
            block_hot[b] = hot;
        });
        GIMLET_OMP(barrier)
        GIMLET_OMP(single)
        {
            // The hottest particle, the first of the largest temperatures, NaN never taken:
            // the blocks' own, merged in block order. Where every temperature is NaN, every
            // disc's mean is NaN and none is named: the passes below are skipped.
            for (const std::size_t h : block_hottest)
                if (h != none && (hottest == none || T[h] > T[hottest])) hottest = h;
            for (std::size_t b = 0; b < blocks; ++b) lo = lo.cwiseMin(block_lo[b]), hi = hi.cwiseMax(block_hi[b]);
            // The bins per axis, counted in double first: at most 2^40 in all, so that the
            // count and the arrays it sizes do not overflow.
            std::array<double, dim> per_axis{};
            double cells = 1;
            for (int d = 0; d < dim; ++d) cells *= per_axis[d] = std::floor(double(hi[d] - lo[d]) / radius) + 1;
            const bool countable = cells <= 0x1p40;  // false for NaN too
            if (countable)
                for (int d = 0; d < dim; ++d) bins[d] = std::size_t(per_axis[d]), total *= bins[d];
            // Counting sort of the particle indices by bin (CSR): deterministic and O(n).
            // What a disc sums is copied in that order (position, mass, temperature), so that
            // a disc reads its bins' particles contiguously. Each block counts its particles
            // per bin and takes its offsets within each bin in block order, so the order is
            // the serial sort's: by bin, then by index. (A count per block and bin: at most
            // n / bins blocks, so that the counts take no more room than the particles.)
            sort_blocks = std::clamp<std::size_t>(n / total, 1, blocks);
            merge_blocks = detail::observer_blocks(total * (sort_blocks - 1), threads);
            if (hottest != none) try {
                    require(countable, "hot-spot radius (m)", radius,
                            "> 0 and at least the particles' extent over 2^(40/dim): at most 2^40 bins");
                    // No disc is hotter than its hottest particle (the means, above, exactly):
                    // where the hottest particle is no hotter than `above`, no disc is sought and
                    // nothing is sorted (the result names none). A caller that tracks a running
                    // peak meets this in every step until the material heats past it.
                    if (double(T[hottest]) > wanted) {
                        if (tracked) {
                            // The box of the particles hotter than `wanted` (the hottest one among them).
                            vector hot_lo = x[hottest], hot_hi = x[hottest];
                            for (std::size_t b = 0; b < blocks; ++b)
                                if (block_hot[b]) hot_lo = hot_lo.cwiseMin(block_hot_lo[b]), hot_hi = hot_hi.cwiseMax(block_hot_hi[b]);
                            prepare(hot_lo, hot_hi);
                        } else {
                            block_mass.assign(blocks, 0.0);
                            block_excess.assign(blocks, 0.0);
                            block_ring.assign(blocks, 0.0);
                            hot_bin.assign(blocks * total, 0);  // a row per block: no two threads write one byte
                            near_pass.emplace(static_cast<std::ptrdiff_t>(blocks), team);
                            mark_pass.emplace(static_cast<std::ptrdiff_t>(blocks), team);
                            refine = true;  // last, as `go`: the passes below find hot_floor and the bins near it
                        }
                    }
                } catch (...) {
                    failed = std::current_exception();
                }
        }
        if (refine) {  // the same for every thread, as `go`
            // A lower bound on the hottest particle's disc as `disc` sums it (the floor, with no
            // `above`): the mean of the particles surely in it (well inside the radius and in the
            // bins `disc` reads), or the coolest particle of the rim, whose membership the two
            // sums' rounding could decide apart, whichever is lower (a mean of the disc's
            // particles is at least the smaller of those two), less a margin. Summed relative
            // to the hottest temperature, as `disc` sums (every term at most zero), block by
            // block: any order of such a sum rounds it by a few ulps of |mean| + |ref - mean|
            // per particle, and a millionth of that is far beyond. A NaN in either gives no
            // bound (the search is not narrowed).
            const vector c = x[hottest];
            const double ref = std::isfinite(double(T[hottest])) ? double(T[hottest]) : 0.0;
            const double r2_in = r2 * (1 - 1e-9), r2_out = r2 * (1 + 1e-9);
            std::array<std::size_t, dim> at_hottest{};
            for (int d = 0; d < dim; ++d) at_hottest[d] = bin_of(c, d);
            detail::for_each_block_of(*near_pass, n, blocks, [&](std::size_t b, std::size_t first, std::size_t last) {
                double mass = 0, excess = 0, rim = std::numeric_limits<double>::infinity();
                for (std::size_t i = first; i < last; ++i) {
                    const double d2 = double((x[i] - c).squaredNorm());
                    if (!(d2 <= r2_out)) continue;  // a NaN place too
                    if (d2 > r2_in) {
                        // A NaN stays (std::min would drop it): the single below then gives no bound.
                        if (!std::isnan(rim)) rim = std::isnan(double(T[i])) ? double(T[i]) : std::min(rim, double(T[i]));
                        continue;
                    }
                    bool near = true;  // in the 3^dim bins around the hottest particle's, as `disc` reads
                    for (int d = 0; d < dim; ++d) {
                        const std::size_t k = bin_of(x[i], d);
                        near = near && k + 1 >= at_hottest[d] && k <= at_hottest[d] + 1;
                    }
                    if (!near) continue;
                    mass += double(m[i]);
                    excess += double(m[i]) * (double(T[i]) - ref);
                }
                block_mass[b] = mass;
                block_excess[b] = excess;
                block_ring[b] = rim;
            });
            GIMLET_OMP(barrier)
            GIMLET_OMP(single)
            {
                double mass = 0, excess = 0, rim = std::numeric_limits<double>::infinity();
                bool nan_rim = false;
                for (std::size_t b = 0; b < blocks; ++b) {
                    mass += block_mass[b], excess += block_excess[b];
                    if (std::isnan(block_ring[b])) nan_rim = true;
                    else rim = std::min(rim, block_ring[b]);
                }
                const double bound = std::min(ref + excess / mass, rim);
                if (std::isfinite(bound) && !nan_rim) hot_floor = bound - 1e-6 * (std::abs(bound) + std::abs(ref - bound));
            }
            // The bins holding a particle at least hot_floor, and the box of those particles.
            detail::for_each_block_of(*mark_pass, n, blocks, [&](std::size_t b, std::size_t first, std::size_t last) {
                vector hot_lo_b = x[hottest], hot_hi_b = x[hottest];
                std::uint8_t* hot_row = hot_bin.data() + b * total;
                for (std::size_t i = first; i < last; ++i) {
                    if (!(double(T[i]) >= hot_floor)) continue;
                    std::array<std::size_t, dim> at{};
                    bool inside = true;  // a place in the bins (not NaN)
                    for (int d = 0; d < dim; ++d) {
                        const double q = double(x[i][d] - lo[d]) / radius;  // bin_of's quotient
                        inside = inside && q >= 0 && q < double(bins[d]);
                        at[d] = inside ? std::size_t(q) : 0;
                    }
                    if (!inside) continue;
                    hot_lo_b = hot_lo_b.cwiseMin(x[i]), hot_hi_b = hot_hi_b.cwiseMax(x[i]);
                    hot_row[flat(at)] = 1;
                }
                block_hot_lo[b] = hot_lo_b;
                block_hot_hi[b] = hot_hi_b;
            });
            GIMLET_OMP(barrier)
            GIMLET_OMP(single)
            {
                vector hot_lo = x[hottest], hot_hi = x[hottest];
                for (std::size_t b = 0; b < blocks; ++b)
                    hot_lo = hot_lo.cwiseMin(block_hot_lo[b]), hot_hi = hot_hi.cwiseMax(block_hot_hi[b]);
                try {
                    keep_bin.assign(total, 0);
                    try_bin.assign(total, 0);
                    prepare(hot_lo, hot_hi);
                    // Each hot bin marks the bins within two (kept) and one (tried).
                    std::array<std::size_t, dim> from{}, to{};
                    for (int d = 0; d < dim; ++d) from[d] = bin_of(hot_lo, d), to[d] = bin_of(hot_hi, d);
                    for_cells(from, to, [&](const std::array<std::size_t, dim>& h) {
                        bool hot = false;
                        for (std::size_t b = 0; b < blocks; ++b) hot = hot || hot_bin[b * total + flat(h)];
                        if (!hot) return;
                        std::array<std::size_t, dim> a{}, z{};
                        for (int d = 0; d < dim; ++d) a[d] = h[d] >= 2 ? h[d] - 2 : 0, z[d] = std::min(h[d] + 2, bins[d] - 1);
                        for_cells(a, z, [&](const std::array<std::size_t, dim>& k) { keep_bin[flat(k)] = 1; });
                        for (int d = 0; d < dim; ++d) a[d] = h[d] >= 1 ? h[d] - 1 : 0, z[d] = std::min(h[d] + 1, bins[d] - 1);
                        for_cells(a, z, [&](const std::array<std::size_t, dim>& k) { try_bin[flat(k)] = 1; });
                    });
                } catch (...) {
                    go = false;
                    failed = std::current_exception();
                }
            }
        }
        if (go) {  // the same for every thread: written before the barrier that ends `single`
            detail::for_each_block_of(*count_pass, n, sort_blocks, [&](std::size_t b, std::size_t first, std::size_t last) {
                std::size_t* count = cursor.data() + b * total;
                double* t_max = block_max.data() + b * total;
                for (std::size_t i = first; i < last; ++i) {
                    bool kept = true;
                    for (int d = 0; d < dim; ++d) {
                        const double from_lo = double(x[i][d] - lo[d]);  // what bin_of divides
                        kept = kept && from_lo >= keep_from[d] && from_lo <= keep_to[d];
                    }
                    if (kept)
                        for (int d = 0; d < dim; ++d) {
                            cell[i][d] = bin_of(x[i], d);
                            kept = kept && cell[i][d] >= keep_lo[d] && cell[i][d] <= keep_hi[d];
                        }
                    if (kept) bin[i] = flat(cell[i]);
                    if (!kept || (refine && !keep_bin[bin[i]])) {
                        bin[i] = total;  // not sorted: no disc that is sought reaches it
                        continue;
                    }
                    ++count[bin[i]];
                    t_max[bin[i]] = std::max(t_max[bin[i]], double(T[i]));
                }
            });
            GIMLET_OMP(barrier)
            GIMLET_OMP(single)
            {
                detail::block_offsets(cursor, sort_blocks, total, start);
            }
            // The copies in bin order, and each bin's hottest particle: the blocks' maxima (a
            // maximum, whatever the blocks), in the first block's entries, the bins split
            // between the threads where there are many. No barrier between the two: the copies
            // write `sorted_*` and each block's row of `cursor`, the merge only the first row
            // of `block_max`, reading the others.
            detail::for_each_block_of(*copy_pass, n, sort_blocks, [&](std::size_t b, std::size_t first, std::size_t last) {
                std::size_t* at = cursor.data() + b * total;
                for (std::size_t i = first; i < last; ++i) {
                    if (bin[i] == total) continue;
                    const std::size_t j = at[bin[i]]++;
                    sorted_x[j] = x[i];
                    sorted_m[j] = double(m[i]);
                    sorted_T[j] = double(T[i]);
                    sorted_index[j] = i;
                }
            });
            detail::for_each_block_of(*merge_pass, total, merge_blocks, [&](std::size_t, std::size_t first, std::size_t last) {
                for (std::size_t b = 1; b < sort_blocks; ++b)
                    for (std::size_t k = first; k < last; ++k) block_max[k] = std::max(block_max[k], block_max[b * total + k]);
            });
            GIMLET_OMP(barrier)
            // A centre whose bins' hottest particle is cooler than the disc around the hottest
            // particle (or than `above`, whichever is hotter: the floor) cannot hold the
            // hottest disc, since its mean is at most that particle's temperature, exactly
            // (above). Nor where that particle is as hot as the floor and the centre comes
            // after the hottest particle, whose own disc is then tried and would win the tie.
            // So where a disc hotter than `above` exists (always, with no `above`), the result
            // is that of trying every centre, at O(n) cost where the hot
            // material is small, and where the temperatures are uniform (before a hot spot
            // forms) every centre after the hottest particle is skipped. The hottest
            // particle's disc is summed once and its bits reused in the loop, so the floor and
            // that disc are the same number whatever the compiler does with the two call sites.
            GIMLET_OMP(single)
            {
                hottest_mean = disc(hottest, bound_at(hottest), hottest_count);
                floor = std::max(hottest_mean, wanted);
            }
            // The centres are tried on demand in small chunks, not in the solver's shares
            // (detail::thread_shares): a centre's cost varies a hundredfold (most are skipped,
            // a hot one sums its disc), and the centres are visited once a call, so there is no
            // data to keep near a core; the hottest disc is the same whoever tries it.
            // Only the kept particles in the bins tried are centres: any other centre's bins
            // hold no particle hotter than `wanted`, so its disc is not sought. (The order the
            // centres are tried in does not matter: the result is a maximum in a total order.)
            best_disc local;
            const auto kept = static_cast<std::ptrdiff_t>(start[total]);
            GIMLET_OMP(for schedule(dynamic, 256) nowait)
            for (std::ptrdiff_t k = 0; k < kept; ++k) {
                const std::size_t i = sorted_index[std::size_t(k)];
                bool tried = true;
                for (int d = 0; d < dim; ++d) tried = tried && cell[i][d] >= try_lo[d] && cell[i][d] <= try_hi[d];
                if (!tried || (refine && !try_bin[bin[i]])) continue;
                const double bound = bound_at(i);
                if (bound < floor || (bound == floor && i > hottest)) continue;
                std::size_t count = hottest_count;
                const double mean = i == hottest ? hottest_mean : disc(i, bound, count);
                if (local.beaten_by(mean, i)) local = {mean, i, count, true};
            }
            GIMLET_OMP(critical(gimlet_hot_spot))
            if (local.found && best.beaten_by(local.mean, local.index)) best = local;
        }
    }
    if (failed) std::rethrow_exception(failed);
    if (hottest == none) return r;  // none, as the result's defaults say
    r.max_temperature = double(T[hottest]);
    r.temperature = best.mean;
    if (best.found) {
        r.centre = x[best.index];
        r.particles = best.count;
    }
    return r;
}

/// hot_spot with scratch of its own (see hot_spot_workspace).
template <class Solver>
[[nodiscard]] auto hot_spot(const Solver& s, double radius, double above = -std::numeric_limits<double>::infinity()) {
    hot_spot_workspace<typename Solver::vector> work;
    return hot_spot(s, radius, above, work);
}

/// The material hotter than each of `temperatures` (K): its mass (kg; per metre of depth in 2-D)
/// and current volume det(F) V0 (m^3; m^2 per metre in 2-D), summed in particle order. This is
/// how pore-collapse studies compare hot spots across resolutions: the amount of material above
/// a temperature, not the hottest particle (docs/reproduction.md).
struct hot_material_result {
    std::vector<double> mass, volume;
};
template <class Solver>
[[nodiscard]] hot_material_result hot_material(const Solver& s, const std::vector<double>& temperatures) {
    static_assert(Solver::store_type::template has<fields::temperature>,
                  "hot_material needs particle temperatures: use a thermal policy that is on");
    const auto& store = s.particles();
    const auto& m = store.template column<fields::mass>();
    const auto& v0 = store.template column<fields::volume0>();
    const auto& F = store.template column<fields::deformation_gradient>();
    const auto& T = store.template column<fields::temperature>();
    hot_material_result r;
    r.mass.assign(temperatures.size(), 0.0);
    r.volume.assign(temperatures.size(), 0.0);
    // From 4096 particles the hot particles are found on the solver's threads, a block of
    // consecutive particles each, with their current volumes; the sums then run over them in
    // particle order, as the serial pass summed them.
    const std::size_t n = store.size();
    const int threads = detail::threads_of(s);
    const std::size_t blocks = detail::observer_blocks(n, threads);
    std::vector<std::vector<std::pair<std::size_t, double>>> hot(blocks);  // (index, det(F) V0)
    detail::for_each_block(n, blocks, true, threads, [&](std::size_t b, std::size_t first, std::size_t last) {
        for (std::size_t i = first; i < last; ++i)
            if (std::any_of(temperatures.begin(), temperatures.end(), [&](double t) { return double(T[i]) > t; }))
                hot[b].push_back({i, double(F[i].determinant()) * double(v0[i])});
    });
    for (const auto& found : hot)
        for (const auto& [i, volume] : found)
            for (std::size_t k = 0; k < temperatures.size(); ++k)
                if (double(T[i]) > temperatures[k]) {
                    r.mass[k] += double(m[i]);
                    r.volume[k] += volume;
                }
    return r;
}

}  // namespace gimlet::diagnostics
