// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The library's loop schedule: each thread a fixed share of a loop, the same in every loop,
/// and a thread that finishes its share early takes chunks of the others' (affinity
/// scheduling: Markatos and LeBlanc 1994, "Using processor affinity in loop scheduling on
/// shared-memory multiprocessors", IEEE TPDS 5(4)). Fixed shares keep each thread's particles
/// and nodes near its core from loop to loop; taking over the rest keeps a slow core (another
/// job on it, a virtual machine's neighbour, a small core of a hybrid processor) or a share of
/// costlier items from holding up the loop by more than the chunk its thread has claimed.
/// docs/performance.md, "How the step is organised for speed" and "How the step is organised for speed", has the measurements behind it.
///
/// It departs from the paper: the owner claims a shrinking part of what is left (guided
/// self-scheduling, below) rather than a fixed 1/threads of it, and a thread done early goes
/// round the other shares in order rather than to the most loaded one. The constants (an
/// eighth, at most 1024 items, a (2 x shares)-th for another thread, the shares being the
/// threads up to 64) were chosen, not tuned.
///
/// Which thread runs an item changes no result. The particle and node loops write each item's
/// own outputs, and their reductions (minimum indices, maxima, integer counts) do not depend
/// on the order. The slab passes scatter into nodes that neighbouring slabs share; they stay
/// deterministic because slabs of one colour share no node and a barrier separates the
/// colours (solver/slabs.hpp).

#include "gimlet/core/detail/inline.hpp"
#include "gimlet/core/detail/omp.hpp"

#include <algorithm>
#include <atomic>
#include <cstddef>

namespace gimlet::detail {

/// n items split into `threads` consecutive shares of equal size (the first n % threads one
/// larger), each handed out in chunks of consecutive items from its front. Set up before a
/// parallel region; inside it, every thread of the team runs the same loop once:
///
///     detail::thread_shares shares(n, threads, parallel);
///     GIMLET_OMP(parallel num_threads(shares.team()))
///     for (auto claimed = shares.start(); shares.claim(claimed);)
///         for (std::ptrdiff_t i = claimed.first, end = claimed.last; i < end; ++i) { ... }
///
/// The calling thread gets its own share's chunks first, in order, then chunks of the shares
/// after its own (wrapping round) that are not done. Over the team, every i in [0, n) exactly
/// once, whatever the team's size (a team smaller than the shares takes over the rest). The
/// loop is written out at each site rather than taken as a lambda: a template driver per loop
/// cost the solver's test units about a tenth more compile time (docs/performance.md, "How the step is organised for speed"). Where `parallel` is false the region has one thread, which takes
/// the one share from the front, in order. An object runs one loop: a second loop over it
/// finds every share done and runs nothing. The chunk's end is copied into the loop (`end`):
/// `claim` sees the chunk, so the compiler would otherwise reload its end on every item.
class thread_shares {
public:
    /// At most this many shares: a larger team shares them (two threads claim from one share's
    /// front), so that the shares live in the object, on the stack, with nothing to free.
    static constexpr int max_shares = 64;

    /// `threads` shares of [0, n); 1 where `parallel` is false (the region then has one thread).
    GIMLET_NOINLINE thread_shares(std::ptrdiff_t n, int threads, bool parallel = true)
        : team_(parallel ? std::max(1, threads) : 1), count_(std::min(team_, max_shares)) {
        const std::ptrdiff_t size = n / count_, extra = n % count_;
        std::ptrdiff_t at = 0;
        for (int t = 0; t < count_; ++t) {
            slots_[std::size_t(t)].next.store(at, std::memory_order_relaxed);
            at += size + (t < extra ? 1 : 0);
            slots_[std::size_t(t)].end = at;
        }
    }

    thread_shares(const thread_shares&) = delete;
    thread_shares& operator=(const thread_shares&) = delete;

    /// The team to run the loop on: `threads` where `parallel`, otherwise 1.
    [[nodiscard]] int team() const noexcept { return team_; }

    /// A thread's place in the schedule: its own share, how many shares past it it has gone,
    /// and the chunk [first, last) it holds.
    struct chunk {
        int own = 0, k = 0;
        std::ptrdiff_t first = 0, last = 0;
    };

    /// Where the calling thread starts: no chunk yet, its own share next.
    [[nodiscard]] chunk start() const noexcept { return {thread_number() % count_, 0, 0, 0}; }

    /// The calling thread's next chunk, in c.first and c.last; false when every share is done.
    /// Not inlined: it is the same for every loop and called once a chunk, so a copy in each
    /// loop's body would only add compile time.
    GIMLET_NOINLINE bool claim(chunk& c) noexcept {
        for (; c.k < count_; ++c.k) {
            slot& s = slots_[std::size_t((c.own + c.k) % count_)];
            // The chunks shrink with what is left of the share (guided self-scheduling:
            // Polychronopoulos and Kuck 1987, "Guided self-scheduling: a practical scheduling
            // scheme for parallel supercomputers", IEEE Trans. Computers C-36(12)): its owner
            // takes an eighth of the rest (at most 1024 items), another thread a
            // (2 x shares)-th. So the chunk that finishes a share is short, and a thread done
            // early takes over little of a share whose owner is about done (moving little
            // data), but much of one whose owner is stalled. The rest is read before it is
            // claimed: a read shares the counter's cache line, where a claim on a finished
            // share would take it from its owner's core for nothing. The claim is relaxed,
            // since it orders nothing else (a barrier after the loop, the region's end or an
            // explicit one, makes the items' outputs visible).
            const std::ptrdiff_t left = s.end - s.next.load(std::memory_order_relaxed);
            if (left <= 0) continue;
            const std::ptrdiff_t size = c.k == 0 ? std::clamp<std::ptrdiff_t>(left / 8, 1, 1024)
                                                 : std::max<std::ptrdiff_t>(1, left / (2 * count_));
            c.first = s.next.fetch_add(size, std::memory_order_relaxed);
            if (c.first >= s.end) continue;  // taken meanwhile: the share is done
            c.last = std::min(s.end, c.first + size);
            return true;
        }
        return false;
    }

private:
    // A share's next unclaimed item and its end, on a cache line of its own so that threads
    // claiming from their own shares do not share lines.
    struct alignas(64) slot {
        std::atomic<std::ptrdiff_t> next{0};
        std::ptrdiff_t end = 0;
    };
    [[nodiscard]] static int thread_number() noexcept {
#if defined(_OPENMP)
        return omp_get_thread_num();
#else
        return 0;
#endif
    }

    int team_, count_;
    slot slots_[max_shares];
};

}  // namespace gimlet::detail
