// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The library's loop schedule: each thread a fixed share of a loop, the same in every loop,
/// and a thread that finishes its share early takes chunks of the others' (affinity
/// scheduling: Markatos and LeBlanc 1994, "Using processor affinity in loop scheduling on
/// shared-memory multiprocessors", IEEE TPDS 5(4)). Fixed shares keep each thread's particles
/// and nodes near its core from loop to loop; taking over the rest keeps a slow core (another
/// job on it, a virtual machine's neighbour, a small core of a hybrid processor) or a share of
/// costlier items from holding up the loop. docs/performance.md, "Shares that are taken over",
/// has the measurements behind it. Which thread runs an item changes no result: the loops it
/// serves write each item's own outputs, and their reductions (min, max, integer counts) do
/// not depend on the order.

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
    thread_shares(std::ptrdiff_t n, int threads, bool parallel = true)
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
        const int own = thread_number() % count_;
        for (int k = 0; k < count_; ++k) {
            slot& s = slots_[std::size_t((own + k) % count_)];
            for (;;) {
                // The chunks shrink with what is left of the share (guided self-scheduling,
                // Polychronopoulos and Kuck 1987): its owner takes an eighth of the rest (at most
                // 1024 items), another thread a (2 x threads)-th. So the chunk that finishes a
                // share is short, and a thread done early takes over little of a share whose
                // owner is about done (moving little data), but much of one whose owner is
                // stalled. The rest is read before it is claimed, so that a finished share's
                // counter is not pulled to another core's cache for nothing; the claim itself
                // is relaxed, since it orders nothing else (the region's closing barrier makes
                // the items' outputs visible).
                const std::ptrdiff_t left = s.end - s.next.load(std::memory_order_relaxed);
                if (left <= 0) break;
                const std::ptrdiff_t chunk =
                    k == 0 ? std::clamp<std::ptrdiff_t>(left / 8, 1, 1024) : std::max<std::ptrdiff_t>(1, left / (2 * count_));
                const std::ptrdiff_t first = s.next.fetch_add(chunk, std::memory_order_relaxed);
                if (first >= s.end) break;
                for (std::ptrdiff_t i = first, last = std::min(s.end, first + chunk); i < last; ++i) f(i);
            }
        }
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

    int count_;
    std::unique_ptr<slot[]> slots_;
};

/// f(i) for i in [0, n) on `threads` threads if `parallel`, in thread_shares' schedule (in
/// order on one thread otherwise). f must not throw.
template <class F>
void parallel_for(std::ptrdiff_t n, [[maybe_unused]] int threads, bool parallel, F&& f) {
    if (!parallel || threads <= 1) {
        for (std::ptrdiff_t i = 0; i < n; ++i) f(i);
        return;
    }
    thread_shares shares(n, threads);
    GIMLET_OMP(parallel num_threads(threads))
    shares.for_each(f);
}

}  // namespace gimlet::detail
