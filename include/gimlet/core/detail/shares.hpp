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
/// docs/performance.md, "Shares that are taken over", has the measurements behind it.
///
/// It departs from the paper: the owner claims a shrinking part of what is left (guided
/// self-scheduling, below) rather than a fixed 1/threads of it, and a thread done early goes
/// round the other shares in order rather than to the most loaded one. The constants (an
/// eighth, at most 1024 items, a (2 x threads)-th for another thread) were chosen, not tuned.
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
#include <memory>

namespace gimlet::detail {

/// n items split into `threads` consecutive shares of equal size (the first n % threads one
/// larger), each handed out in chunks of consecutive items from its front. Set up before a
/// parallel region; inside it, every thread of the team calls for_each once.
class thread_shares {
public:
    /// `threads` shares of [0, n); 1 where `parallel` is false (the region then has one thread).
    GIMLET_NOINLINE thread_shares(std::ptrdiff_t n, int threads, bool parallel = true)
        : count_(parallel ? std::max(1, threads) : 1), slots_(new slot[std::size_t(count_)]) {
        const std::ptrdiff_t size = n / count_, extra = n % count_;
        std::ptrdiff_t at = 0;
        for (int t = 0; t < count_; ++t) {
            slots_[std::size_t(t)].next.store(at, std::memory_order_relaxed);
            at += size + (t < extra ? 1 : 0);
            slots_[std::size_t(t)].end = at;
        }
    }

    /// f(i) for every item the calling thread gets: its own share's chunks first, in order, then
    /// chunks of the shares after its own (wrapping round) that are not done. Over the team,
    /// every i in [0, n) exactly once, whatever the team's size (a team smaller than the shares
    /// takes over the rest). f must not throw.
    template <class F>
    void for_each(F&& f) {
        cursor at{thread_number() % count_, 0};
        for (std::ptrdiff_t first = 0, last = 0; claim(at, first, last);)
            for (std::ptrdiff_t i = first; i < last; ++i) f(i);
    }

private:
    // A share's next unclaimed item and its end, on a cache line of its own so that threads
    // claiming from their own shares do not share lines.
    struct alignas(64) slot {
        std::atomic<std::ptrdiff_t> next{0};
        std::ptrdiff_t end = 0;
    };
    // Where a thread is: its own share, and how many shares past it it has gone.
    struct cursor {
        int own, k;
    };

    // The calling thread's next chunk [first, last); false when every share is done. Not
    // inlined: it is the same for every loop, called once a chunk, and a copy in each loop's
    // body made the solver's units a quarter slower to compile.
    GIMLET_NOINLINE bool claim(cursor& at, std::ptrdiff_t& first, std::ptrdiff_t& last) noexcept {
        for (; at.k < count_; ++at.k) {
            slot& s = slots_[std::size_t((at.own + at.k) % count_)];
            // The chunks shrink with what is left of the share (guided self-scheduling:
            // Polychronopoulos and Kuck 1987, "Guided self-scheduling: a practical scheduling
            // scheme for parallel supercomputers", IEEE Trans. Computers C-36(12)): its owner
            // takes an eighth of the rest (at most 1024 items), another thread a
            // (2 x threads)-th. So the chunk that finishes a share is short, and a thread done
            // early takes over little of a share whose owner is about done (moving little
            // data), but much of one whose owner is stalled. The rest is read before it is
            // claimed: a read shares the counter's cache line, where a claim on a finished
            // share would take it from its owner's core for nothing. The claim is relaxed,
            // since it orders nothing else (the region's closing barrier makes the items'
            // outputs visible).
            const std::ptrdiff_t left = s.end - s.next.load(std::memory_order_relaxed);
            if (left <= 0) continue;
            const std::ptrdiff_t chunk = at.k == 0 ? std::clamp<std::ptrdiff_t>(left / 8, 1, 1024)
                                                   : std::max<std::ptrdiff_t>(1, left / (2 * count_));
            first = s.next.fetch_add(chunk, std::memory_order_relaxed);
            if (first >= s.end) continue;  // taken meanwhile: the share is done
            last = std::min(s.end, first + chunk);
            return true;
        }
        return false;
    }

    [[nodiscard]] static int thread_number() noexcept {
#if defined(_OPENMP)
        return omp_get_thread_num();
#else
        return 0;
#endif
    }

    int count_;
    std::unique_ptr<slot[]> slots_;
};

/// f(i) for i in [0, n) on `threads` threads if `parallel`, in thread_shares' schedule (in
/// order on one thread otherwise: one share, claimed from the front). f must not throw. Each
/// call allocates 64 bytes a thread. The serial case goes through the same region (its `if`
/// clause) rather than a loop of its own, so that f's body is compiled once, not twice: a
/// second copy cost the solver's test unit a quarter more compile time and memory.
template <class F>
void parallel_for(std::ptrdiff_t n, [[maybe_unused]] int threads, bool parallel, F&& f) {
    thread_shares shares(n, threads, parallel);
    GIMLET_OMP(parallel num_threads(threads) if (parallel))
    shares.for_each(f);
}

}  // namespace gimlet::detail
