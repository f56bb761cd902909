// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The deterministic parallel scatter's schedule: particles grouped in slabs of node rows,
/// slabs coloured so that no two of a colour share a node.

#include "gimlet/core/detail/blocks.hpp"
#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/detail/shares.hpp"
#include "gimlet/core/processes.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

namespace gimlet::detail {

/// The exchange of a slab pass that writes N nodal arrays, on the processes `on` (none: one
/// process, and the pass runs as with no_exchange).
template <std::size_t N>
struct fold_exchange {
    processes* on = nullptr;
    std::array<nodal_array, N> arrays{};
    [[nodiscard]] bool active() const noexcept { return on != nullptr && on->size() > 1; }
    void after_colour(int c) { on->after_colour(c, arrays); }
    void finish() { on->finish(arrays); }
};

/// What a slab pass does between its colours and after the last one where the slabs are split
/// between processes (mpi::node_fold: each node's running sum passes to the process that adds
/// next): nothing in one process. A type for for_each's `exchange` has the same three members.
struct no_exchange {
    /// Whether the pass exchanges anything (false: the colours run in one parallel region).
    [[nodiscard]] static constexpr bool active() noexcept { return false; }
    /// Called once, on one thread, after colour c's slabs have all scattered (c = 0, 1, 2 in order).
    static void after_colour(int) noexcept {}
    /// Called once, on one thread, after after_colour(2).
    static void finish() noexcept {}
};

/// The grid is cut along its last axis into slabs of SlabRows >= stencil - 1 node rows; a
/// particle belongs to the slab of its stencil's first row. Its stencil then reaches at most
/// into the next slab, so slabs two apart never share a node: all even slabs can scatter at
/// once, then all odd ones (and, on a periodic axis with an odd slab count, the last slab,
/// which wraps onto slab 0, alone). Within a slab, particles go in increasing index. Every
/// node therefore sums its contributions in an order fixed by the grid and the particle
/// order, whatever the thread count. (Colouring as in e.g. Gao et al. 2018, "GPU
/// optimization of material point methods", section 4.2, on slabs instead of blocks.)
template <int SlabRows>
class slab_schedule {
public:
    /// The slabs of a grid with `rows` node rows along its last axis (periodic or not).
    void set_up(int rows, bool periodic) {
        // The last slab takes the remainder (between SlabRows and 2 SlabRows - 1 rows), so
        // on a periodic axis only the last slab's stencils wrap, and then only onto slab 0.
        slabs_ = std::max(1, rows / SlabRows);
        rows_ = rows, periodic_ = periodic;
        // (colour() reads slabs_ and periodic_, set above.)
        for (auto& c : colour_slabs_) c.clear();
        for (int s = 0; s < slabs_; ++s) colour_slabs_[std::size_t(colour(s))].push_back(s);
    }

    /// The number of slabs.
    [[nodiscard]] int slabs() const noexcept { return slabs_; }
    /// The node rows along the last axis, and whether that axis is periodic (set_up's).
    [[nodiscard]] int rows() const noexcept { return rows_; }
    [[nodiscard]] bool periodic() const noexcept { return periodic_; }
    /// Slab s's first node row, and the end of its rows (the last slab takes the remainder).
    [[nodiscard]] int first_row(int s) const noexcept { return s * SlabRows; }
    [[nodiscard]] int end_row(int s) const noexcept { return s == slabs_ - 1 ? rows_ : (s + 1) * SlabRows; }
    /// The colour of slab s (0, 1 or 2): the colours scatter in increasing order.
    [[nodiscard]] int colour(int s) const noexcept {
        return periodic_ && slabs_ % 2 == 1 && slabs_ > 1 && s == slabs_ - 1 ? 2 : s % 2;
    }
    /// The node rows per slab (the last slab may have up to twice as many less one).
    static constexpr int slab_rows = SlabRows;

    /// The slabs for gimlet::processes::set_up, on a grid of `nodes` nodes, `nodes_per_row` a row.
    [[nodiscard]] slab_layout layout(std::size_t nodes_per_row, std::size_t nodes) const {
        slab_layout out;
        for (int s = 0; s < slabs_; ++s) out.first_row.push_back(first_row(s)), out.colour.push_back(colour(s));
        out.first_row.push_back(rows_);
        out.slab_rows = SlabRows, out.periodic = periodic_, out.nodes_per_row = nodes_per_row, out.nodes = nodes;
        return out;
    }

    /// Room for n particles.
    void resize(std::size_t n) { slab_of_.resize(n); }
    /// Particle i's stencil starts at node row `first_row` of the last axis.
    void assign(std::size_t i, int first_row) {
        slab_of_[i] = static_cast<std::uint32_t>(std::min(first_row / SlabRows, slabs_ - 1));
    }
    /// Each particle's slab, to be permuted with the particles.
    [[nodiscard]] std::vector<std::uint32_t>& slab_of() noexcept { return slab_of_; }

    /// Particle indices grouped by slab, increasing within each (a stable counting sort), on
    /// `threads` threads if `parallel`: each block of particles counts its slabs, takes its
    /// offsets within each slab in block order and places its particles, so the order is that
    /// of the serial sort whatever the thread count.
    void bucket(bool parallel = false, int threads = 1) {
        // A block per 4096 particles, at most 64 blocks (the offsets are a serial pass over
        // blocks x slabs); the order does not depend on the blocks.
        const std::size_t n = slab_of_.size(), slabs = std::size_t(slabs_);
        const std::size_t blocks = std::min<std::size_t>((n + 4095) / 4096, 64);
        block_cursor_.assign(blocks * slabs, 0);
        detail::for_each_block(n, blocks, parallel, threads, [&](std::size_t b, std::size_t first, std::size_t last) {
            std::size_t* count = block_cursor_.data() + b * slabs;
            for (std::size_t i = first; i < last; ++i) ++count[slab_of_[i]];
        });
        detail::block_offsets(block_cursor_, blocks, slabs, slab_start_);
        slab_particles_.resize(n);
        detail::for_each_block(n, blocks, parallel, threads, [&](std::size_t b, std::size_t first, std::size_t last) {
            std::size_t* cursor = block_cursor_.data() + b * slabs;
            for (std::size_t i = first; i < last; ++i) slab_particles_[cursor[slab_of_[i]]++] = i;
        });
    }

    /// f(i) for every particle, slab by slab and colour by colour, on `threads` threads if
    /// `parallel`. f must not throw. Where `exchange.active()`, each colour runs in a parallel
    /// region of its own, followed by exchange.after_colour(colour) on the calling thread (every
    /// colour, even one without slabs, so that processes call it alike), then exchange.finish().
    template <class F, class X = no_exchange>
    void for_each(bool parallel, int threads, F&& f, X&& exchange = X{}) const {
        if constexpr (!std::is_same_v<std::remove_cvref_t<X>, no_exchange>)
            if (exchange.active()) return for_each_exchanging(nullptr, parallel, threads, f, exchange);
        for_each_kept(nullptr, parallel, threads, f);
    }

    /// for_each over the slabs whose particles' stencils can reach a node row r (of the last
    /// axis) with rows[r] != 0 (`rows`: a flag per row, set_up's count); the other slabs'
    /// particles are skipped. Every particle in a kept slab is visited, in for_each's order.
    template <class F, class X = no_exchange>
    void for_each_reaching(const std::vector<std::uint8_t>& rows, bool parallel, int threads, F&& f, X&& exchange = X{}) {
        assert(rows.size() == std::size_t(rows_));
        keep_.assign(std::size_t(slabs_), 0);
        for (int s = 0; s < slabs_; ++s) {
            // A particle's stencil starts in one of its slab's rows and spans at most
            // SlabRows + 1 rows, so it ends before the slab's end plus SlabRows.
            const int first = s * SlabRows, end = (s == slabs_ - 1 ? rows_ : first + SlabRows) + SlabRows;
            for (int r = first; r < end && !keep_[std::size_t(s)]; ++r) {
                if (r >= rows_ && !periodic_) break;
                keep_[std::size_t(s)] = rows[std::size_t(r % rows_)];
            }
        }
        if constexpr (!std::is_same_v<std::remove_cvref_t<X>, no_exchange>)
            if (exchange.active()) return for_each_exchanging(keep_.data(), parallel, threads, f, exchange);
        for_each_kept(keep_.data(), parallel, threads, f);
    }

private:
    // for_each_kept with an exchange after each colour: a parallel region per colour. The same
    // for_each_kept as without one (f passed as the same lvalue), so that each pass's body is
    // compiled once, not once for each path.
    template <class F, class X>
    void for_each_exchanging(const std::uint8_t* keep, bool parallel, int threads, F& f, X& exchange) const {
        for (std::size_t c = 0; c < colour_slabs_.size(); ++c) {
            for_each_kept(keep, parallel, threads, f, c, c + 1);
            exchange.after_colour(int(c));
        }
        exchange.finish();
    }

    // A schedule for each colour's slabs, and the last colour with slabs (no barrier after it
    // but the region's). Built out of line: it is the same for every pass.
    struct colour_shares {
        GIMLET_NOINLINE colour_shares(const std::array<std::vector<int>, 3>& slabs, int threads, bool parallel)
            : of{thread_shares(std::ptrdiff_t(slabs[0].size()), threads, parallel),
                 thread_shares(std::ptrdiff_t(slabs[1].size()), threads, parallel),
                 thread_shares(std::ptrdiff_t(slabs[2].size()), threads, parallel)} {
            for (std::size_t c = 0; c < slabs.size(); ++c)
                if (!slabs[c].empty()) last = c;
        }
        std::array<thread_shares, 3> of;
        std::size_t last = 0;
    };

    // for_each over the slabs s with keep[s] != 0 (all where keep is null), of the colours
    // [first, end) in one parallel region.
    template <class F>
    void for_each_kept(const std::uint8_t* keep, bool parallel, int threads, F& f, std::size_t first = 0,
                       std::size_t end = 3) const {
        // Each thread the same slabs of a colour in every pass, so their particles and nodes
        // stay near its core, and a thread done early takes over slabs of the others' shares
        // (thread_shares; solver/core.hpp, above parallel_threshold, says why). A colour's slabs
        // are shared by count, not by the particles they hold (a split by particles measured
        // no faster on 2 threads: docs/performance.md, "How the step is organised for speed").
        colour_shares shares(colour_slabs_, threads, parallel);
        GIMLET_OMP(parallel num_threads(shares.of[first].team()))
        for (std::size_t c = first; c < end && c <= shares.last; ++c) {
            const auto& slabs = colour_slabs_[c];
            if (slabs.empty()) continue;  // the same for every thread: no barrier for an empty colour
            thread_shares& colour = shares.of[c];
            for (auto claimed = colour.start(); colour.claim(claimed);)
                for (std::ptrdiff_t j = claimed.first, end = claimed.last; j < end; ++j) {
                    const auto s = static_cast<std::size_t>(slabs[static_cast<std::size_t>(j)]);
                    if (keep && !keep[s]) continue;
                    for (std::size_t k = slab_start_[s]; k < slab_start_[s + 1]; ++k) f(slab_particles_[k]);
                }
            // Slabs of one colour share no node; those of the next may share nodes with these,
            // so no thread starts the next colour before every thread has ended this one.
            if (c < shares.last && c + 1 < end) {
                GIMLET_OMP(barrier)
            }
        }
    }

    int slabs_ = 1, rows_ = 1;
    bool periodic_ = false;
    std::vector<std::uint8_t> keep_;  // for_each_reaching's slabs
    std::vector<std::uint32_t> slab_of_;  // each particle's slab
    std::vector<std::size_t> slab_start_, slab_particles_;
    std::vector<std::size_t> block_cursor_;  // per block of particles and slab: a count, then a cursor
    std::array<std::vector<int>, 3> colour_slabs_;  // the slabs of each colour
};

}  // namespace gimlet::detail
