// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The hot spot: the hottest disc (sphere in 3-D) of a given radius. A single particle's
/// temperature depends on the resolution and on particle noise; a mean over a fixed physical
/// size converges as the cell shrinks, so resolution studies can compare it. On many processes
/// (solver_options::processes) both measurements are the whole run's, bitwise one process's,
/// and collective: every process calls them.

#include "gimlet/core/detail/blocks.hpp"
#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/core/exact_sum.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/material_point.hpp"
#include "gimlet/core/processes.hpp"
#include "gimlet/diagnostics/conservation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

namespace gimlet::diagnostics {

/// What hot_spot finds: the hottest disc's mean temperature, centre and particle count, and the
/// hottest particle's temperature. \tparam Vector the solver's vector type.
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
    ///@{
    /// Scratch of one call (per-block bounds, bins, the particles copied in bin order), resized as
    /// needed; what it holds between calls does not affect the next result.
    std::vector<Vector> block_lo, block_hi, block_hot_lo, block_hot_hi, sorted_x;
    std::vector<std::array<std::size_t, std::size_t(Vector::RowsAtCompileTime)>> cell;
    std::vector<std::size_t> bin, cursor, start, block_hottest, sorted_index;
    std::vector<std::uint8_t> block_hot;
    std::vector<double> block_max, sorted_m, sorted_T, block_mass, block_excess, block_rim;
    std::vector<std::uint8_t> hot_bin, keep_bin, try_bin;
    ///@}
    ///@{
    /// On many processes: the particles this process searches (its own and the others' near
    /// them, in ordinal order), their ordinals, and which are its own.
    std::vector<Vector> local_x;
    std::vector<typename Vector::Scalar> local_m, local_T;
    std::vector<std::uint64_t> local_ordinal;
    std::vector<std::uint8_t> local_own;
    ///@}
};

namespace detail {

// The refusal of a radius too small for the bins, the same wherever it is found.
inline void require_countable_bins(bool countable, double radius) {
    require(countable, "hot-spot radius (m)", radius, "> 0 and at least the particles' extent over 2^(40/dim): at most 2^40 bins");
}

// What one of many processes searches (hot_spot_over_processes), read by hot_spot_search as it
// reads a solver: this process's own particles and the others' near them, in ordinal order
// (copied into the workspace's local_* arrays), and the whole run's box and box of the particles
// hotter than `above`, which set the bins (so that they are one process's bins).
template <class Solver>
struct hot_spot_view {
    static constexpr int dim = Solver::dim;
    using vector = typename Solver::vector;
    // The columns the search reads: position, mass and temperature.
    struct store_type {
        const hot_spot_workspace<vector>* work = nullptr;
        template <class Field>
        [[nodiscard]] const auto& column() const noexcept {
            if constexpr (std::is_same_v<Field, fields::position>) return work->local_x;
            else if constexpr (std::is_same_v<Field, fields::mass>) return work->local_m;
            else {
                static_assert(std::is_same_v<Field, fields::temperature>, "hot_spot reads positions, masses and temperatures");
                return work->local_T;
            }
        }
        [[nodiscard]] std::size_t size() const noexcept { return work->local_x.size(); }
    };
    // The solver's threads (detail::threads_of reads options().threads).
    struct options_type {
        int threads = 1;
    };
    store_type store;
    options_type opt;
    vector lo, hi, hot_lo, hot_hi;
    [[nodiscard]] const store_type& particles() const noexcept { return store; }
    [[nodiscard]] const options_type& options() const noexcept { return opt; }
};
template <class T>
inline constexpr bool is_hot_spot_view = false;
template <class Solver>
inline constexpr bool is_hot_spot_view<hot_spot_view<Solver>> = true;

/// One hot_spot call (see hot_spot below for what it finds). Its passes over the particles, in
/// the order run() calls them:
///  - binning: the particles' box and hottest particle (find_extent), the bins of side `radius`
///    and which of them can hold a sought disc (choose_bins; with no `above`, find_floor and
///    mark_hot_bins narrow them; keep_bins sets the ranges kept and the sort's arrays), and a
///    counting sort of the kept particles by bin (sort_into_bins);
///  - the candidate search: every kept centre whose bins could hold the hottest disc
///    (search_centres);
///  - the disc sums: one centre's mean temperature (disc), summed relative to its bins' hottest
///    particle (bound_at).
/// Each pass gives what the serial pass gives (a minimum, a maximum, a stable order), so
/// nothing depends on the thread count. The members are shared by the threads of run()'s one
/// region; a pass's own scratch is local to it. On many processes it runs over a hot_spot_view:
/// the bins are the whole run's, and only this process's own particles are centres.
template <class Solver>
class hot_spot_search {
public:
    static constexpr int dim = Solver::dim;
    using vector = typename Solver::vector;

    hot_spot_search(const Solver& s, double radius, double above, hot_spot_workspace<vector>& work)
        : x_(s.particles().template column<fields::position>()),
          m_(s.particles().template column<fields::mass>()),
          T_(s.particles().template column<fields::temperature>()),
          n_(s.particles().size()),
          radius_(radius),
          r2_(radius * radius),
          // The discs sought are hotter than this (NaN and +infinity ignored, as documented).
          // With one (a tracked peak), the bins kept are found from the box of the particles
          // hotter than it; without, from a lower bound on the hottest disc (find_floor).
          wanted_(above < std::numeric_limits<double>::infinity() ? above : -std::numeric_limits<double>::infinity()),
          tracked_(wanted_ > -std::numeric_limits<double>::infinity()),
          // The passes over the particles run on the solver's threads from 4096 particles, in
          // `blocks` contiguous ranges of particles, one a thread.
          threads_(gimlet::detail::threads_of(s)),
          blocks_(gimlet::detail::observer_blocks(n_, threads_)),
          team_(blocks_ > 1 ? threads_ : 1),
          extent_pass_(static_cast<std::ptrdiff_t>(blocks_), team_),
          w_(work) {
        if constexpr (many) view_ = &s;
    }

    [[nodiscard]] hot_spot_result<vector> run() {
        hot_spot_result<vector> r;
        r.centre = vector::Zero();
        if (n_ == 0) return r;  // no disc and no hottest particle: the result's defaults say none
        allocate();
        // The passes run in one parallel region, with barriers between them: where idle threads
        // sleep (OMP_WAIT_POLICY=passive) a region costs about nine barriers, and a region per
        // pass (five a call) would cost as much as the second thread saves (docs/performance.md,
        // "How the step is organised for speed"). Each pass's shares are
        // set up where its size is known: the first in the constructor, the others by one
        // thread between the passes. The branches below are the same for every thread: `refine_`
        // and `go_` are written in a `single`, before the barrier that ends it.
        GIMLET_OMP(parallel num_threads(team_) if (blocks_ > 1))
        {
            find_extent();
            GIMLET_OMP(barrier)
            GIMLET_OMP(single)
            choose_bins();
            if (refine_) {
                find_floor();
                mark_hot_bins();
            }
            if (go_) {
                sort_into_bins();
                search_centres();
            }
        }
        if (failed_) std::rethrow_exception(failed_);
        if (hottest_ == none) return r;  // none, as the result's defaults say
        r.max_temperature = double(T_[hottest_]);
        r.temperature = best_.mean;
        if (best_.found) {
            r.centre = x_[best_.index];
            r.particles = best_.count;
        }
        return r;
    }

    /// After run(): the index of the centre of the disc it named, if it named one.
    [[nodiscard]] std::optional<std::size_t> centre_index() const {
        return best_.found ? std::optional<std::size_t>(best_.index) : std::nullopt;
    }

private:
    using cell_index = std::array<std::size_t, std::size_t(dim)>;
    using store_type = typename Solver::store_type;
    template <class Field>
    using column_of = std::remove_cvref_t<decltype(std::declval<const store_type&>().template column<Field>())>;
    static constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
    // A search of one of many processes (hot_spot_over_processes).
    static constexpr bool many = is_hot_spot_view<Solver>;

    // The hottest disc so far, ties to the lowest index: a maximum in a total order, so it does
    // not depend on the thread count or on the order the centres are tried in.
    struct best_disc {
        double mean = -std::numeric_limits<double>::infinity();
        std::size_t index = 0, count = 0;
        bool found = false;
        [[nodiscard]] bool beaten_by(double m, std::size_t i) const {
            return !found ? m > mean : (m > mean || (m == mean && i < index));
        }
    };

    // Every entry of bin, cell and the copies is written before it is read.
    void allocate() {
        const vector x0 = x_[0];
        w_.block_lo.assign(blocks_, x0);
        w_.block_hi.assign(blocks_, x0);
        w_.block_hottest.assign(blocks_, none);
        w_.block_hot_lo.assign(blocks_, x0);
        w_.block_hot_hi.assign(blocks_, x0);
        w_.block_hot.assign(blocks_, 0);
        w_.bin.resize(n_);
        w_.cell.resize(n_);
        w_.sorted_x.resize(n_);
        w_.sorted_m.resize(n_);
        w_.sorted_T.resize(n_);
        w_.sorted_index.resize(n_);
        lo_ = hi_ = x0;
    }

    // ---- binning ----

    // Per block: the box of its particles, its hottest particle (the first of its largest
    // temperatures, NaN never taken; `none` where the block has only NaN), and the box of its
    // particles hotter than `wanted_` (only a disc near one of those can be sought; mark_hot_bins
    // reuses block_hot_lo and block_hot_hi for the particles at least hot_floor_ hot).
    void find_extent() {
        gimlet::detail::for_each_block_of(extent_pass_, n_, blocks_, [&](std::size_t b, std::size_t first, std::size_t last) {
            vector lo_b = x_[0], hi_b = x_[0], hot_lo_b = x_[0], hot_hi_b = x_[0];
            std::size_t h = none;
            bool hot = false;
            for (std::size_t i = first; i < last; ++i) {
                lo_b = lo_b.cwiseMin(x_[i]), hi_b = hi_b.cwiseMax(x_[i]);
                if (!std::isnan(double(T_[i])) && (h == none || T_[i] > T_[h])) h = i;
                if (tracked_ && double(T_[i]) > wanted_) {
                    hot_lo_b = hot ? vector(hot_lo_b.cwiseMin(x_[i])) : x_[i];
                    hot_hi_b = hot ? vector(hot_hi_b.cwiseMax(x_[i])) : x_[i];
                    hot = true;
                }
            }
            w_.block_lo[b] = lo_b;
            w_.block_hi[b] = hi_b;
            w_.block_hottest[b] = h;
            w_.block_hot_lo[b] = hot_lo_b;
            w_.block_hot_hi[b] = hot_hi_b;
            w_.block_hot[b] = hot;
        });
    }

    // One thread: the hottest particle, the bins, and which of them the search needs.
    void choose_bins() {
        // The hottest particle, the first of the largest temperatures, NaN never taken: the
        // blocks' own, merged in block order. Where every temperature is NaN, every disc's mean
        // is NaN and none is named: the passes after this are skipped.
        for (const std::size_t h : w_.block_hottest)
            if (h != none && (hottest_ == none || T_[h] > T_[hottest_])) hottest_ = h;
        for (std::size_t b = 0; b < blocks_; ++b) lo_ = lo_.cwiseMin(w_.block_lo[b]), hi_ = hi_.cwiseMax(w_.block_hi[b]);
        // On many processes the bins are the whole run's: the same bins, and so the same discs'
        // sums and references, as one process's.
        if constexpr (many) lo_ = view_->lo, hi_ = view_->hi;
        // Bins of side `radius`: a disc reaches only the 3^dim bins around its centre's bin. The
        // bins per axis, counted in double first: at most 2^40 in all, so that the count and the
        // arrays it sizes do not overflow.
        std::array<double, dim> per_axis{};
        double cells = 1;
        for (int d = 0; d < dim; ++d) cells *= per_axis[d] = std::floor(double(hi_[d] - lo_[d]) / radius_) + 1;
        const bool countable = cells <= 0x1p40;  // false for NaN too
        if (countable)
            for (int d = 0; d < dim; ++d) bins_[d] = std::size_t(per_axis[d]), total_ *= bins_[d];
        // Counting sort of the particle indices by bin (CSR): deterministic and O(n). What a
        // disc sums is copied in that order (position, mass, temperature), so that a disc reads
        // its bins' particles contiguously. Each block counts its particles per bin and takes
        // its offsets within each bin in block order, so the order is the serial sort's: by bin,
        // then by index. (A count per block and bin: at most n / bins blocks, so that the counts
        // take no more room than the particles.)
        sort_blocks_ = std::clamp<std::size_t>(n_ / total_, 1, blocks_);
        merge_blocks_ = gimlet::detail::observer_blocks(total_ * (sort_blocks_ - 1), threads_);
        if (hottest_ == none) return;
        // An exception must not leave the region (that would end the program): a radius too
        // small for the bins or an allocation that fails is kept and thrown after it.
        try {
            require_countable_bins(countable, radius_);
            // No disc is hotter than its hottest particle (the means, exactly: disc): where the
            // hottest particle is no hotter than `above`, no disc is sought and nothing is
            // sorted (the result names none). A caller that tracks a running peak meets this in
            // every step until the material heats past it.
            if (!(double(T_[hottest_]) > wanted_)) return;
            if (tracked_) {
                // The box of the particles hotter than `wanted_` (the hottest one among them).
                vector hot_lo = x_[hottest_], hot_hi = x_[hottest_];
                for (std::size_t b = 0; b < blocks_; ++b)
                    if (w_.block_hot[b]) hot_lo = hot_lo.cwiseMin(w_.block_hot_lo[b]), hot_hi = hot_hi.cwiseMax(w_.block_hot_hi[b]);
                // On many processes the whole run's box: the centres tried are then one
                // process's, and so is the disc named where none is hotter than `above`.
                if constexpr (many) hot_lo = view_->hot_lo, hot_hi = view_->hot_hi;
                keep_bins(hot_lo, hot_hi);
            } else {
                w_.block_mass.assign(blocks_, 0.0);
                w_.block_excess.assign(blocks_, 0.0);
                w_.block_rim.assign(blocks_, 0.0);
                w_.hot_bin.assign(blocks_ * total_, 0);  // a row per block: no two threads write one byte
                near_pass_.emplace(static_cast<std::ptrdiff_t>(blocks_), team_);
                mark_pass_.emplace(static_cast<std::ptrdiff_t>(blocks_), team_);
                refine_ = true;  // last, as `go_`: find_floor and mark_hot_bins run next
            }
        } catch (...) {
            failed_ = std::current_exception();
        }
    }

    // One thread: the kept and tried bins' ranges around the box [hot_lo, hot_hi] of the hot
    // particles, and the sort's arrays.
    void keep_bins(const vector& hot_lo, const vector& hot_hi) {
        for (int d = 0; d < dim; ++d) {
            const std::size_t a = bin_of(hot_lo, d), z = bin_of(hot_hi, d);
            keep_lo_[d] = a >= 2 ? a - 2 : 0;
            keep_hi_[d] = std::min(z + 2, bins_[d] - 1);
            try_lo_[d] = a >= 1 ? a - 1 : 0;
            try_hi_[d] = std::min(z + 1, bins_[d] - 1);
            keep_from_[d] = (double(keep_lo_[d]) - 1) * radius_;
            keep_to_[d] = (double(keep_hi_[d]) + 2) * radius_;
        }
        w_.cursor.assign(sort_blocks_ * total_, 0);
        w_.block_max.assign(sort_blocks_ * total_, -std::numeric_limits<double>::infinity());
        w_.start.reserve(total_ + 1);  // so that block_offsets does not allocate
        count_pass_.emplace(static_cast<std::ptrdiff_t>(sort_blocks_), team_);
        copy_pass_.emplace(static_cast<std::ptrdiff_t>(sort_blocks_), team_);
        merge_pass_.emplace(static_cast<std::ptrdiff_t>(merge_blocks_), team_);
        go_ = true;
    }

    // With no `above`: a lower bound on the hottest particle's disc as `disc` sums it (the
    // floor): the mean of the particles surely in it (well inside the radius and in the bins
    // `disc` reads), or the coolest particle of the rim, whose membership the two sums' rounding
    // could decide apart, whichever is lower (a mean of the disc's particles is at least the
    // smaller of those two), less a margin. Summed relative to the hottest temperature, as
    // `disc` sums (every term at most zero), block by block: any order of such a sum rounds it
    // by a few ulps of |mean| + |ref - mean| per particle, and a millionth of that is far
    // beyond. A NaN in either gives no bound (the search is not narrowed).
    void find_floor() {
        const vector c = x_[hottest_];
        const double ref = std::isfinite(double(T_[hottest_])) ? double(T_[hottest_]) : 0.0;
        const double r2_in = r2_ * (1 - 1e-9), r2_out = r2_ * (1 + 1e-9);
        cell_index at_hottest{};
        for (int d = 0; d < dim; ++d) at_hottest[d] = bin_of(c, d);
        gimlet::detail::for_each_block_of(*near_pass_, n_, blocks_, [&](std::size_t b, std::size_t first, std::size_t last) {
            double mass = 0, excess = 0, rim = std::numeric_limits<double>::infinity();
            for (std::size_t i = first; i < last; ++i) {
                const double d2 = double((x_[i] - c).squaredNorm());
                if (!(d2 <= r2_out)) continue;  // a NaN place too
                if (d2 > r2_in) {
                    // A NaN stays (std::min would drop it): the sum below then gives no bound.
                    if (!std::isnan(rim)) rim = std::isnan(double(T_[i])) ? double(T_[i]) : std::min(rim, double(T_[i]));
                    continue;
                }
                bool near = true;  // in the 3^dim bins around the hottest particle's, as `disc` reads
                for (int d = 0; d < dim; ++d) {
                    const std::size_t k = bin_of(x_[i], d);
                    near = near && k + 1 >= at_hottest[d] && k <= at_hottest[d] + 1;
                }
                if (!near) continue;
                mass += double(m_[i]);
                excess += double(m_[i]) * (double(T_[i]) - ref);
            }
            w_.block_mass[b] = mass;
            w_.block_excess[b] = excess;
            w_.block_rim[b] = rim;
        });
        GIMLET_OMP(barrier)
        GIMLET_OMP(single)
        {
            double mass = 0, excess = 0, rim = std::numeric_limits<double>::infinity();
            bool nan_rim = false;
            for (std::size_t b = 0; b < blocks_; ++b) {
                mass += w_.block_mass[b], excess += w_.block_excess[b];
                if (std::isnan(w_.block_rim[b])) nan_rim = true;
                else rim = std::min(rim, w_.block_rim[b]);
            }
            const double bound = std::min(ref + excess / mass, rim);
            if (std::isfinite(bound) && !nan_rim) hot_floor_ = bound - 1e-6 * (std::abs(bound) + std::abs(ref - bound));
        }
    }

    // With no `above`: every centre whose bins' hottest particle reaches the floor is near a
    // particle at least hot_floor_ hot, so the bins kept are those within two of a bin holding
    // one (`keep_bin`), those tried within one (`try_bin`). A map, not a box: two hot spots far
    // apart would put everything between them in a box.
    void mark_hot_bins() {
        // The bins holding a particle at least hot_floor_, and the box of those particles.
        gimlet::detail::for_each_block_of(*mark_pass_, n_, blocks_, [&](std::size_t b, std::size_t first, std::size_t last) {
            vector hot_lo_b = x_[hottest_], hot_hi_b = x_[hottest_];
            std::uint8_t* hot_row = w_.hot_bin.data() + b * total_;
            for (std::size_t i = first; i < last; ++i) {
                if (!(double(T_[i]) >= hot_floor_)) continue;
                cell_index at{};
                bool inside = true;  // a place in the bins (not NaN)
                for (int d = 0; d < dim; ++d) {
                    const double q = double(x_[i][d] - lo_[d]) / radius_;  // bin_of's quotient
                    inside = inside && q >= 0 && q < double(bins_[d]);
                    at[d] = inside ? std::size_t(q) : 0;
                }
                if (!inside) continue;
                hot_lo_b = hot_lo_b.cwiseMin(x_[i]), hot_hi_b = hot_hi_b.cwiseMax(x_[i]);
                hot_row[flat(at)] = 1;
            }
            w_.block_hot_lo[b] = hot_lo_b;
            w_.block_hot_hi[b] = hot_hi_b;
        });
        GIMLET_OMP(barrier)
        GIMLET_OMP(single)
        {
            vector hot_lo = x_[hottest_], hot_hi = x_[hottest_];
            for (std::size_t b = 0; b < blocks_; ++b)
                hot_lo = hot_lo.cwiseMin(w_.block_hot_lo[b]), hot_hi = hot_hi.cwiseMax(w_.block_hot_hi[b]);
            try {
                w_.keep_bin.assign(total_, 0);
                w_.try_bin.assign(total_, 0);
                keep_bins(hot_lo, hot_hi);
                // Each hot bin marks the bins within two (kept) and one (tried).
                cell_index from{}, to{};
                for (int d = 0; d < dim; ++d) from[d] = bin_of(hot_lo, d), to[d] = bin_of(hot_hi, d);
                for_cells(from, to, [&](const cell_index& h) {
                    bool hot = false;
                    for (std::size_t b = 0; b < blocks_; ++b) hot = hot || w_.hot_bin[b * total_ + flat(h)];
                    if (!hot) return;
                    cell_index a{}, z{};
                    for (int d = 0; d < dim; ++d) a[d] = h[d] >= 2 ? h[d] - 2 : 0, z[d] = std::min(h[d] + 2, bins_[d] - 1);
                    for_cells(a, z, [&](const cell_index& k) { w_.keep_bin[flat(k)] = 1; });
                    for (int d = 0; d < dim; ++d) a[d] = h[d] >= 1 ? h[d] - 1 : 0, z[d] = std::min(h[d] + 1, bins_[d] - 1);
                    for_cells(a, z, [&](const cell_index& k) { w_.try_bin[flat(k)] = 1; });
                });
            } catch (...) {
                go_ = false;
                failed_ = std::current_exception();
            }
        }
    }

    // The kept particles (those in the kept bins, and, with no `above`, in a bin near a hot one)
    // sorted by bin, their copies in that order, and each bin's hottest particle.
    void sort_into_bins() {
        const bool refine = refine_;
        gimlet::detail::for_each_block_of(*count_pass_, n_, sort_blocks_, [&](std::size_t b, std::size_t first, std::size_t last) {
            std::size_t* count = w_.cursor.data() + b * total_;
            double* t_max = w_.block_max.data() + b * total_;
            for (std::size_t i = first; i < last; ++i) {
                // The range one bin wider than the kept bins, in the quantity bin_of divides by
                // the radius, tells most particles outside them without the division.
                bool kept = true;
                for (int d = 0; d < dim; ++d) {
                    const double from_lo = double(x_[i][d] - lo_[d]);  // what bin_of divides
                    kept = kept && from_lo >= keep_from_[d] && from_lo <= keep_to_[d];
                }
                if (kept)
                    for (int d = 0; d < dim; ++d) {
                        w_.cell[i][d] = bin_of(x_[i], d);
                        kept = kept && w_.cell[i][d] >= keep_lo_[d] && w_.cell[i][d] <= keep_hi_[d];
                    }
                if (kept) w_.bin[i] = flat(w_.cell[i]);
                if (!kept || (refine && !w_.keep_bin[w_.bin[i]])) {
                    w_.bin[i] = total_;  // not sorted: no disc that is sought reaches it
                    continue;
                }
                ++count[w_.bin[i]];
                t_max[w_.bin[i]] = std::max(t_max[w_.bin[i]], double(T_[i]));
            }
        });
        GIMLET_OMP(barrier)
        GIMLET_OMP(single)
        gimlet::detail::block_offsets(w_.cursor, sort_blocks_, total_, w_.start);
        // The copies in bin order, and each bin's hottest particle: the blocks' maxima (a
        // maximum, whatever the blocks), in the first block's entries, the bins split between
        // the threads where there are many. No barrier between the two: the copies write
        // `sorted_*` and each block's row of `cursor`, the merge only the first row of
        // `block_max`, reading the others.
        gimlet::detail::for_each_block_of(*copy_pass_, n_, sort_blocks_, [&](std::size_t b, std::size_t first, std::size_t last) {
            std::size_t* at = w_.cursor.data() + b * total_;
            for (std::size_t i = first; i < last; ++i) {
                if (w_.bin[i] == total_) continue;
                const std::size_t j = at[w_.bin[i]]++;
                w_.sorted_x[j] = x_[i];
                w_.sorted_m[j] = double(m_[i]);
                w_.sorted_T[j] = double(T_[i]);
                w_.sorted_index[j] = i;
            }
        });
        gimlet::detail::for_each_block_of(*merge_pass_, total_, merge_blocks_, [&](std::size_t, std::size_t first, std::size_t last) {
            for (std::size_t b = 1; b < sort_blocks_; ++b)
                for (std::size_t k = first; k < last; ++k)
                    w_.block_max[k] = std::max(w_.block_max[k], w_.block_max[b * total_ + k]);
        });
        GIMLET_OMP(barrier)
    }

    // ---- the candidate search ----

    // A centre whose bins' hottest particle is cooler than the disc around the hottest particle
    // (or than `above`, whichever is hotter: the floor) cannot hold the hottest disc, since its
    // mean is at most that particle's temperature, exactly (disc). Nor where that particle is as
    // hot as the floor and the centre comes after the hottest particle, whose own disc is then
    // tried and would win the tie. So where a disc hotter than `above` exists (always, with no
    // `above`), the result is that of trying every centre, at O(n) cost where the hot material
    // is small, and where the temperatures are uniform (before a hot spot forms) every centre
    // after the hottest particle is skipped. The hottest particle's disc is summed once and its
    // bits reused in the loop, so the floor and that disc are the same number whatever the
    // compiler does with the two call sites.
    void search_centres() {
        GIMLET_OMP(single)
        {
            hottest_mean_ = disc(hottest_, bound_at(hottest_), hottest_count_);
            floor_ = std::max(hottest_mean_, wanted_);
        }
        // The centres are tried on demand in small chunks, not in the solver's shares
        // (detail::thread_shares): a centre's cost varies a hundredfold (most are skipped, a hot
        // one sums its disc), and the centres are visited once a call, so there is no data to
        // keep near a core; the hottest disc is the same whoever tries it. Only the kept
        // particles in the bins tried are centres: any other centre's bins hold no particle
        // hotter than `wanted_`, so its disc is not sought.
        const bool refine = refine_;
        best_disc local;
        const auto kept = static_cast<std::ptrdiff_t>(w_.start[total_]);
        GIMLET_OMP(for schedule(dynamic, 256) nowait)
        for (std::ptrdiff_t k = 0; k < kept; ++k) {
            const std::size_t i = w_.sorted_index[std::size_t(k)];
            // On many processes only a process's own particles are centres: another's disc may
            // reach particles this process does not hold.
            if constexpr (many)
                if (!w_.local_own[i]) continue;
            bool tried = true;
            for (int d = 0; d < dim; ++d) tried = tried && w_.cell[i][d] >= try_lo_[d] && w_.cell[i][d] <= try_hi_[d];
            if (!tried || (refine && !w_.try_bin[w_.bin[i]])) continue;
            const double bound = bound_at(i);
            if (bound < floor_ || (bound == floor_ && i > hottest_)) continue;
            std::size_t count = hottest_count_;
            const double mean = i == hottest_ ? hottest_mean_ : disc(i, bound, count);
            if (local.beaten_by(mean, i)) local = {mean, i, count, true};
        }
        GIMLET_OMP(critical(gimlet_hot_spot))
        if (local.found && best_.beaten_by(local.mean, local.index)) best_ = local;
    }

    // ---- the disc sums ----

    // The mean over the disc centred on particle i, whose bins' hottest particle is `bound`,
    // summed in bin order relative to it (the same sums wherever it is asked for). Rounding is
    // monotone and 0 is representable: T - bound <= 0 rounds to <= 0, and so do its product
    // with m >= 0, the sum of such terms (a multiply-add too) and its quotient by the mass, so
    // the result is at most `bound`, exactly. (Finite temperatures whose differences do not
    // overflow; the solver stops on a non-finite one.)
    double disc(std::size_t i, double bound, std::size_t& count) const {
        const double ref = std::isfinite(bound) ? bound : 0.0;
        double mass = 0, excess = 0;
        count = 0;
        const vector c = x_[i];
        around(i, [&](std::size_t k) {
            for (std::size_t j = w_.start[k]; j < w_.start[k + 1]; ++j) {
                if (double((w_.sorted_x[j] - c).squaredNorm()) > r2_) continue;
                mass += w_.sorted_m[j];
                excess += w_.sorted_m[j] * (w_.sorted_T[j] - ref);
                ++count;
            }
        });
        return ref + excess / mass;
    }

    // The hottest particle of the 3^dim bins around particle i's (NaN never taken).
    [[nodiscard]] double bound_at(std::size_t i) const {
        double bound = -std::numeric_limits<double>::infinity();
        around(i, [&](std::size_t b) { bound = std::max(bound, w_.block_max[b]); });
        return bound;
    }

    // f(k) for each of the 3^dim bins around particle i's that exist, the first axis fastest
    // (the order the discs' sums take). Nested loops over each axis's range: enumerating the
    // 3^dim offsets and testing each would cost a fifth of the search's instructions
    // (docs/performance.md, "How the step is organised for speed").
    template <class F>
    void around(std::size_t i, F&& f) const {
        const auto& b = w_.cell[i];
        cell_index first{}, last{};
        for (int d = 0; d < dim; ++d) {
            first[d] = b[d] > 0 ? b[d] - 1 : 0;
            last[d] = std::min(b[d] + 1, bins_[d] - 1);
        }
        if constexpr (dim == 2) {
            for (std::size_t y = first[1]; y <= last[1]; ++y)
                for (std::size_t x0 = first[0]; x0 <= last[0]; ++x0) f(y * bins_[0] + x0);
        } else {
            for (std::size_t z = first[2]; z <= last[2]; ++z)
                for (std::size_t y = first[1]; y <= last[1]; ++y)
                    for (std::size_t x0 = first[0]; x0 <= last[0]; ++x0) f((z * bins_[1] + y) * bins_[0] + x0);
        }
    }

    // f(cell) for every cell from `from` to `to` (inclusive, per axis), the first axis fastest.
    template <class F>
    static void for_cells(const cell_index& from, const cell_index& to, F&& f) {
        cell_index k{};
        if constexpr (dim == 2) {
            for (k[1] = from[1]; k[1] <= to[1]; ++k[1])
                for (k[0] = from[0]; k[0] <= to[0]; ++k[0]) f(k);
        } else {
            for (k[2] = from[2]; k[2] <= to[2]; ++k[2])
                for (k[1] = from[1]; k[1] <= to[1]; ++k[1])
                    for (k[0] = from[0]; k[0] <= to[0]; ++k[0]) f(k);
        }
    }

    [[nodiscard]] std::size_t bin_of(const vector& p, int d) const { return std::size_t(double(p[d] - lo_[d]) / radius_); }
    [[nodiscard]] std::size_t flat(const cell_index& b) const {
        std::size_t k = 0;
        for (int d = dim - 1; d >= 0; --d) k = k * bins_[d] + b[d];
        return k;
    }

    // The particles and the question.
    const column_of<fields::position>& x_;
    const column_of<fields::mass>& m_;
    const column_of<fields::temperature>& T_;
    const std::size_t n_;
    const double radius_, r2_, wanted_;
    const bool tracked_;
    // The threads: blocks of particles, a team for the region, and each pass's shares.
    const int threads_;
    const std::size_t blocks_;
    const int team_;
    gimlet::detail::thread_shares extent_pass_;
    std::optional<gimlet::detail::thread_shares> near_pass_, mark_pass_, count_pass_, copy_pass_, merge_pass_;
    hot_spot_workspace<vector>& w_;
    // The bins: the particles' box, the count per axis and in all, and the blocks of the sort.
    vector lo_, hi_;
    cell_index bins_{};
    std::size_t total_ = 1, sort_blocks_ = 1, merge_blocks_ = 1;
    // The bins kept per axis (those within two of the box of the particles hotter than
    // `wanted_`: every disc that could be sought reads only these), the bins whose particles are
    // tried as centres (within one), and, in the quantity bin_of divides by the radius, a range
    // one bin wider than the kept bins.
    cell_index keep_lo_{}, keep_hi_{}, try_lo_{}, try_hi_{};
    std::array<double, dim> keep_from_{}, keep_to_{};
    // The search: the hottest particle and its disc, the floor below which no centre is tried,
    // and the hottest disc found.
    std::size_t hottest_ = none, hottest_count_ = 0;
    double hottest_mean_ = 0, floor_ = 0;
    double hot_floor_ = -std::numeric_limits<double>::infinity();
    best_disc best_;
    // What the one thread of a `single` decides for all: a particle hotter than `wanted_` and the
    // bins allocated (go_: the sort and the search run); no `above`, so the bins are narrowed by
    // the floor first (refine_); an exception, thrown after the region.
    bool go_ = false, refine_ = false;
    std::exception_ptr failed_;
    // On many processes, what this process searches (the whole run's boxes); nothing on one
    // process (an empty member, last: the one-process search's members keep their places, whose
    // layout measurably affects its speed).
    struct no_view {};
    [[no_unique_address]] std::conditional_t<many, const Solver*, no_view> view_{};
};

// The records hot_spot_over_processes passes between processes: each process's summary (to
// every process), a particle another process needs (a ghost), and each process's hottest disc
// (to every process). Plain numbers, copied byte for byte.
template <int Dim, class Real>
struct hot_spot_summary {
    std::uint64_t count = 0;    // the process's own particles
    std::uint64_t hottest = 0;  // the ordinal of its hottest particle (none: every temperature NaN)
    std::array<Real, Dim> lo{}, hi{}, hottest_x{}, hot_lo{}, hot_hi{};  // boxes; the hottest's place
    Real hottest_T = 0;
    std::uint8_t hot = 0;  // whether a particle is hotter than `above` (hot_lo, hot_hi their box)
};
template <int Dim, class Real>
struct hot_spot_ghost {
    std::uint64_t ordinal = 0;
    std::array<Real, Dim> x{};
    Real m = 0, T = 0;
};
template <int Dim, class Real>
struct hot_spot_disc {
    std::uint64_t ordinal = 0;  // of its centre (none: the process named no disc)
    std::uint64_t count = 0;
    double mean = 0;
    std::array<Real, Dim> centre{};
};

// Records to bytes and back (trivially copyable records, whole).
template <class Record>
void append_record(std::vector<std::byte>& out, const Record& r) {
    static_assert(std::is_trivially_copyable_v<Record>, "records are copied byte for byte");
    const std::size_t at = out.size();
    out.resize(at + sizeof(Record));
    std::memcpy(out.data() + at, &r, sizeof(Record));
}
template <class Record>
[[nodiscard]] std::vector<Record> records_in(const std::vector<std::byte>& in) {
    static_assert(std::is_trivially_copyable_v<Record>, "records are copied byte for byte");
    std::vector<Record> out(in.size() / sizeof(Record));
    if (!out.empty()) std::memcpy(out.data(), in.data(), out.size() * sizeof(Record));
    return out;
}
template <class Vector, class Real, std::size_t Dim>
[[nodiscard]] Vector vector_of(const std::array<Real, Dim>& a) {
    Vector v;
    for (std::size_t d = 0; d < Dim; ++d) v[Eigen::Index(d)] = a[d];
    return v;
}
template <class Vector>
[[nodiscard]] auto array_of(const Vector& v) {
    std::array<typename Vector::Scalar, std::size_t(Vector::RowsAtCompileTime)> a{};
    for (std::size_t d = 0; d < a.size(); ++d) a[d] = v[Eigen::Index(d)];
    return a;
}

// hot_spot on a solver split between processes (solver_options::processes): one process's
// result, bit for bit, on every process. Collective.
//  1. Every process's box, hottest particle (the largest temperature, NaN never taken, ties to
//     the lowest ordinal: one process's "first") and box of the particles hotter than `above` go
//     to every process. The whole run's box sets the bins, as one process sets them from its
//     particles' box (minima and maxima are exact in any order); the answers before any search
//     (no particle, every temperature NaN, none hotter than `above`) and the refusal of a radius
//     too small for the bins are then one process's, on every process alike.
//  2. Ghosts: each process sends every other one its particles in the bins within one of that
//     process's box's bins (the 3^dim bins around each of its centres: each of its discs and
//     their reference T_b are then whole), and to all its particles in the bins within one of
//     the hottest particle's (every process then sums the hottest particle's disc, the search's
//     floor, as one process sums it). Bins are integer indices computed from the same numbers
//     (hot_spot_search::bin_of) on every process, so every process draws the same lines.
//  3. Each process runs one process's search over its own particles and the ghosts in ordinal
//     order (so that each bin's particles are summed in one process's order, and "ties to the
//     lowest index" is the lowest ordinal), with the whole run's bins and only its own particles
//     as centres. It tries one process's centres among its own: the same floor and bins' maxima
//     and, with `above`, the same box; without `above` its map of hot bins is drawn from the
//     particles it holds at a floor of its own, which keeps every centre whose bins reach the
//     search's floor (a lower bound on the hottest particle's disc is all the map needs).
//  4. The hottest disc of all: the largest mean, ties to the lowest ordinal (a maximum in a total
//     order, as best_disc's), its centre and count sent to every process.
template <class Solver>
[[nodiscard]] hot_spot_result<typename Solver::vector> hot_spot_over_processes(const Solver& s, gimlet::processes& procs,
                                                                               double radius, double above,
                                                                               hot_spot_workspace<typename Solver::vector>& work) {
    constexpr int dim = Solver::dim;
    using vector = typename Solver::vector;
    using real = typename vector::Scalar;
    using summary = hot_spot_summary<dim, real>;
    using ghost = hot_spot_ghost<dim, real>;
    using disc = hot_spot_disc<dim, real>;
    using cell_index = std::array<std::size_t, std::size_t(dim)>;
    constexpr std::uint64_t none = std::numeric_limits<std::uint64_t>::max();
    const auto& store = s.particles();
    const auto& x = store.template column<fields::position>();
    const auto& m = store.template column<fields::mass>();
    const auto& T = store.template column<fields::temperature>();
    static_assert(std::is_same_v<std::remove_cvref_t<decltype(m[0])>, real> &&
                      std::is_same_v<std::remove_cvref_t<decltype(T[0])>, real>,
                  "hot_spot: masses and temperatures of the positions' scalar type");
    const std::size_t n = store.size(), ranks = std::size_t(procs.size()), me = std::size_t(procs.rank());
    const bool tracked = above > -std::numeric_limits<double>::infinity() && above < std::numeric_limits<double>::infinity();
    const double wanted = tracked ? above : -std::numeric_limits<double>::infinity();  // as hot_spot_search's

    // 1. This process's summary, from blocks of consecutive particles on the solver's threads,
    // merged in block order (the hottest: the first of the largest, by ordinal).
    const int threads = gimlet::detail::threads_of(s);
    const std::size_t blocks = gimlet::detail::observer_blocks(n, threads);
    struct block_summary {
        vector lo, hi, hot_lo, hot_hi;
        std::size_t hottest = std::numeric_limits<std::size_t>::max();
        bool any = false, hot = false;
    };
    std::vector<block_summary> part(blocks);
    gimlet::detail::for_each_block(n, blocks, true, threads, [&](std::size_t b, std::size_t first, std::size_t last) {
        if (first == last) return;
        block_summary u{x[first], x[first], x[first], x[first], std::size_t(none), true, false};
        for (std::size_t i = first; i < last; ++i) {
            u.lo = u.lo.cwiseMin(x[i]), u.hi = u.hi.cwiseMax(x[i]);
            if (!std::isnan(double(T[i])) && (u.hottest == none || T[i] > T[u.hottest])) u.hottest = i;
            if (tracked && double(T[i]) > wanted) {
                u.hot_lo = u.hot ? vector(u.hot_lo.cwiseMin(x[i])) : x[i];
                u.hot_hi = u.hot ? vector(u.hot_hi.cwiseMax(x[i])) : x[i];
                u.hot = true;
            }
        }
        part[b] = u;
    });
    summary mine{};
    mine.count = n;
    mine.hottest = none;
    {
        std::size_t h = none;
        vector lo = n ? x[0] : vector(vector::Zero()), hi = lo, hot_lo = lo, hot_hi = lo;
        bool hot = false;
        for (const auto& u : part) {
            if (!u.any) continue;
            lo = lo.cwiseMin(u.lo), hi = hi.cwiseMax(u.hi);
            if (u.hottest != none && (h == none || T[u.hottest] > T[h])) h = u.hottest;
            if (u.hot) {
                hot_lo = hot ? vector(hot_lo.cwiseMin(u.hot_lo)) : u.hot_lo;
                hot_hi = hot ? vector(hot_hi.cwiseMax(u.hot_hi)) : u.hot_hi;
                hot = true;
            }
        }
        mine.lo = array_of(lo), mine.hi = array_of(hi), mine.hot_lo = array_of(hot_lo), mine.hot_hi = array_of(hot_hi);
        mine.hot = hot;
        if (h != none) mine.hottest = s.ordinal(h), mine.hottest_T = T[h], mine.hottest_x = array_of(x[h]);
    }
    std::vector<std::vector<std::byte>> out(ranks);
    append_record(out[0], mine);
    for (std::size_t q = 1; q < ranks; ++q) out[q] = out[0];
    std::vector<summary> all(ranks);
    {
        const auto in = procs.all_to_all(out);
        for (std::size_t q = 0; q < ranks; ++q) all[q] = records_in<summary>(in[q]).at(0);
    }
    std::uint64_t total = 0;
    vector lo = vector::Zero(), hi = vector::Zero(), hot_lo = vector::Zero(), hot_hi = vector::Zero(), hottest_x = vector::Zero();
    std::uint64_t hottest = none;
    real hottest_T = 0;
    bool hot = false;
    for (const summary& u : all) {
        if (u.count == 0) continue;
        const vector u_lo = vector_of<vector>(u.lo), u_hi = vector_of<vector>(u.hi);
        lo = total ? vector(lo.cwiseMin(u_lo)) : u_lo;
        hi = total ? vector(hi.cwiseMax(u_hi)) : u_hi;
        total += u.count;
        if (u.hottest != none && (hottest == none || u.hottest_T > hottest_T || (u.hottest_T == hottest_T && u.hottest < hottest)))
            hottest = u.hottest, hottest_T = u.hottest_T, hottest_x = vector_of<vector>(u.hottest_x);
        if (u.hot) {
            const vector u_hot_lo = vector_of<vector>(u.hot_lo), u_hot_hi = vector_of<vector>(u.hot_hi);
            hot_lo = hot ? vector(hot_lo.cwiseMin(u_hot_lo)) : u_hot_lo;
            hot_hi = hot ? vector(hot_hi.cwiseMax(u_hot_hi)) : u_hot_hi;
            hot = true;
        }
    }
    hot_spot_result<vector> r;
    r.centre = vector::Zero();
    if (total == 0 || hottest == none) return r;  // no particle, or every temperature NaN: none
    // The bins, counted as hot_spot_search::choose_bins counts them.
    cell_index bins{};
    {
        std::array<double, dim> per_axis{};
        double cells = 1;
        for (int d = 0; d < dim; ++d) cells *= per_axis[d] = std::floor(double(hi[d] - lo[d]) / radius) + 1;
        require_countable_bins(cells <= 0x1p40, radius);
        for (int d = 0; d < dim; ++d) bins[std::size_t(d)] = std::size_t(per_axis[d]);
    }
    r.max_temperature = double(hottest_T);
    if (!(double(hottest_T) > wanted)) return r;  // no disc is sought (hot_spot_search::choose_bins)

    // 2. The ghosts: the bins within one of each other process's box's, and of the hottest
    // particle's (hot_spot_search::bin_of: the same integers on every process).
    auto bin_of = [&](const vector& p, int d) { return std::size_t(double(p[d] - lo[d]) / radius); };
    auto around = [&](const vector& a, const vector& z, cell_index& from, cell_index& to) {
        for (int d = 0; d < dim; ++d) {
            const std::size_t first = bin_of(a, d), last = bin_of(z, d);
            from[std::size_t(d)] = first > 0 ? first - 1 : 0;
            to[std::size_t(d)] = std::min(last + 1, bins[std::size_t(d)] - 1);
        }
    };
    std::vector<cell_index> from(ranks), to(ranks);
    for (std::size_t q = 0; q < ranks; ++q)
        if (all[q].count) around(vector_of<vector>(all[q].lo), vector_of<vector>(all[q].hi), from[q], to[q]);
    cell_index hot_from{}, hot_to{};
    around(hottest_x, hottest_x, hot_from, hot_to);
    for (auto& o : out) o.clear();
    for (std::size_t i = 0; i < n; ++i) {
        // A position that is not finite has no bin (converting it to an index is undefined): the
        // measurement of a run stopped by such a particle still completes on every process.
        if (!x[i].allFinite()) continue;
        cell_index at{};
        for (int d = 0; d < dim; ++d) at[std::size_t(d)] = bin_of(x[i], d);
        auto within = [&](const cell_index& a, const cell_index& z) {
            bool in = true;
            for (std::size_t d = 0; d < std::size_t(dim); ++d) in = in && at[d] >= a[d] && at[d] <= z[d];
            return in;
        };
        const bool near_hottest = within(hot_from, hot_to);
        for (std::size_t q = 0; q < ranks; ++q)
            if (q != me && all[q].count && (near_hottest || within(from[q], to[q])))
                append_record(out[q], ghost{s.ordinal(i), array_of(x[i]), m[i], T[i]});
    }
    // This process's particles and the ghosts, in ordinal order, into the workspace.
    {
        const auto in = procs.all_to_all(out);
        std::vector<std::vector<ghost>> ghosts(ranks);
        std::size_t count = n;
        for (std::size_t q = 0; q < ranks; ++q)
            if (q != me) ghosts[q] = records_in<ghost>(in[q]), count += ghosts[q].size();
        struct source {
            std::uint64_t ordinal;
            std::size_t rank, at;  // rank me: this process's particle `at`; else ghosts[rank][at]
        };
        std::vector<source> order;
        order.reserve(count);
        for (std::size_t i = 0; i < n; ++i) order.push_back({s.ordinal(i), me, i});
        for (std::size_t q = 0; q < ranks; ++q)
            for (std::size_t k = 0; k < ghosts[q].size(); ++k) order.push_back({ghosts[q][k].ordinal, q, k});
        std::sort(order.begin(), order.end(), [](const source& a, const source& b) { return a.ordinal < b.ordinal; });
        work.local_x.resize(count);
        work.local_m.resize(count);
        work.local_T.resize(count);
        work.local_ordinal.resize(count);
        work.local_own.resize(count);
        for (std::size_t k = 0; k < count; ++k) {
            const source& o = order[k];
            work.local_ordinal[k] = o.ordinal;
            work.local_own[k] = o.rank == me;
            if (o.rank == me) {
                work.local_x[k] = x[o.at], work.local_m[k] = m[o.at], work.local_T[k] = T[o.at];
            } else {
                const ghost& g = ghosts[o.rank][o.at];
                work.local_x[k] = vector_of<vector>(g.x), work.local_m[k] = g.m, work.local_T[k] = g.T;
            }
        }
    }

    // 3. The search over them, this process's own particles the centres (none where it has none).
    disc best{};
    best.ordinal = none;
    procs.together([&] {
        if (n == 0) return;
        hot_spot_view<Solver> view;
        view.store.work = &work;
        view.opt.threads = threads;
        view.lo = lo, view.hi = hi;
        view.hot_lo = hot ? hot_lo : hottest_x, view.hot_hi = hot ? hot_hi : hottest_x;
        hot_spot_search<hot_spot_view<Solver>> search(view, radius, above, work);
        const auto found = search.run();
        if (const auto c = search.centre_index())
            best = {work.local_ordinal[*c], std::uint64_t(found.particles), found.temperature, array_of(found.centre)};
    });

    // 4. The hottest of the processes' discs: the largest mean, ties to the lowest ordinal.
    for (auto& o : out) o.clear();
    append_record(out[0], best);
    for (std::size_t q = 1; q < ranks; ++q) out[q] = out[0];
    const auto in = procs.all_to_all(out);
    best.ordinal = none;
    for (std::size_t q = 0; q < ranks; ++q) {
        const disc c = records_in<disc>(in[q]).at(0);
        if (c.ordinal != none && (best.ordinal == none || c.mean > best.mean || (c.mean == best.mean && c.ordinal < best.ordinal)))
            best = c;
    }
    if (best.ordinal != none) {
        r.temperature = best.mean;
        r.centre = vector_of<vector>(best.centre);
        r.particles = std::size_t(best.count);
    }
    return r;
}

}  // namespace detail

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
/// On many processes (solver_options::processes) it is collective (every process calls it, with
/// the same radius and `above`) and every process gets the whole run's result, bit for bit what
/// one process gives for the same particles: "index" above is then the particle's ordinal
/// (solver::ordinal), and the bins are the whole run's. Each process sends the others its
/// particles within about two radii of their own (and all of them those near the hottest
/// particle), so a radius wider than a process's slab costs more of the exchange, not another
/// answer.
///
/// `work` is scratch reused between calls (hot_spot_workspace of the solver's vector type);
/// the overload without it makes its own.
template <class Solver>
[[nodiscard]] hot_spot_result<typename Solver::vector> hot_spot(const Solver& s, double radius, double above,
                                                                hot_spot_workspace<typename Solver::vector>& work) {
    static_assert(Solver::store_type::template has<fields::temperature>,
                  "hot_spot needs particle temperatures: use a thermal policy that is on");
    require_positive("hot-spot radius (m)", radius);
    if constexpr (requires { s.processes(); })
        if (gimlet::processes* p = s.processes()) return detail::hot_spot_over_processes(s, *p, radius, above, work);
    return detail::hot_spot_search<Solver>(s, radius, above, work).run();
}

/// hot_spot with scratch of its own (see hot_spot_workspace).
template <class Solver>
[[nodiscard]] auto hot_spot(const Solver& s, double radius, double above = -std::numeric_limits<double>::infinity()) {
    hot_spot_workspace<typename Solver::vector> work;
    return hot_spot(s, radius, above, work);
}

/// The material hotter than each of `temperatures` (K): its mass (kg; per metre of depth in plane
/// strain) and current volume J V0 (m^3; m^2 per metre in plane strain), each the exact sum
/// rounded once (gimlet::exact_sum: independent of the particle order and of the thread count);
/// in an axisymmetric space the whole body's, 2 pi times the rings' per-radian sums (as
/// diagnostics::total_mass). This is
/// how pore-collapse studies compare hot spots across resolutions: the amount of material above
/// a temperature, not the hottest particle (docs/reproduction.md).
struct hot_material_result {
    ///@{
    /// Per entry of `temperatures`, in its order: the mass (kg) and the current volume (m^3) above it.
    std::vector<double> mass, volume;
    ///@}
};
/// Computes hot_material_result for each of `temperatures` (K), on the solver's threads from
/// 4096 particles. Needs the temperature field (a thermal policy that is on). On many processes
/// (solver_options::processes) the sums are the whole run's, the same bits as one process's
/// (each process's exact sums completed over every process), and the call is collective.
template <class Solver>
[[nodiscard]] hot_material_result hot_material(const Solver& s, const std::vector<double>& temperatures) {
    static_assert(Solver::store_type::template has<fields::temperature>,
                  "hot_material needs particle temperatures: use a thermal policy that is on");
    const auto& store = s.particles();
    const auto& m = store.template column<fields::mass>();
    const auto& v0 = store.template column<fields::volume0>();
    const auto& T = store.template column<fields::temperature>();
    // From 4096 particles the blocks of consecutive particles are summed on the solver's
    // threads; the sums are exact until read (gimlet::exact_sum), so the blocks merge in any
    // grouping to the same bits.
    const std::size_t n = store.size(), t = temperatures.size();
    const int threads = gimlet::detail::threads_of(s);
    const std::size_t blocks = gimlet::detail::observer_blocks(n, threads);
    std::vector<exact_sum> mass(blocks * t), volume(blocks * t);  // per block and temperature
    gimlet::detail::for_each_block(n, blocks, true, threads, [&](std::size_t b, std::size_t first, std::size_t last) {
        for (std::size_t i = first; i < last; ++i) {
            const double Ti = double(T[i]);
            if (std::none_of(temperatures.begin(), temperatures.end(), [&](double above) { return Ti > above; })) continue;
            const double current = double(gimlet::jacobian(store[i])) * double(v0[i]);
            for (std::size_t k = 0; k < t; ++k)
                if (Ti > temperatures[k]) mass[b * t + k] += double(m[i]), volume[b * t + k] += current;
        }
    });
    hot_material_result r;
    r.mass.assign(t, 0.0);
    r.volume.assign(t, 0.0);
    for (std::size_t k = 0; k < t; ++k) {
        exact_sum mass_above, volume_above;
        for (std::size_t b = 0; b < blocks; ++b) mass_above += mass[b * t + k], volume_above += volume[b * t + k];
        r.mass[k] = detail::over_processes(s, mass_above).value();
        r.volume[k] = detail::over_processes(s, volume_above).value();
    }
    for (std::size_t k = 0; k < temperatures.size(); ++k) {
        r.mass[k] = detail::whole_body<Solver>(r.mass[k]);
        r.volume[k] = detail::whole_body<Solver>(r.volume[k]);
    }
    return r;
}

}  // namespace gimlet::diagnostics
