// SPDX-License-Identifier: MIT
// The loop schedule (core/detail/shares.hpp): every item runs exactly once, on any team
// (smaller than the shares too), a serial schedule runs them in order, and a thread that does
// not come takes nothing with it: the others take over its whole share.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <numeric>
#include <thread>
#include <vector>

namespace {

// How often each item of [0, n) ran on a team of `team` threads over `shares` shares, the
// loop written as the library's loops are (shares.hpp's example).
std::vector<int> runs(std::ptrdiff_t n, int shares, [[maybe_unused]] int team) {
    std::vector<std::atomic<int>> count(static_cast<std::size_t>(n));
    gimlet::detail::thread_shares s(n, shares);
    GIMLET_OMP(parallel num_threads(team))
    for (auto claimed = s.start(); s.claim(claimed);)
        for (std::ptrdiff_t i = claimed.first, end = claimed.last; i < end; ++i)
            count[static_cast<std::size_t>(i)].fetch_add(1, std::memory_order_relaxed);
    std::vector<int> out;
    for (auto& c : count) out.push_back(c.load());
    return out;
}

}  // namespace

TEST_CASE("thread_shares runs every item once, on teams of any size", "[parallel][shares]") {
    for (std::ptrdiff_t n : {0, 1, 5, 17, 1000, 100003})
        for (int shares : {1, 2, 3, 8, 65})  // 65: more than the shares an object holds (64)
            for (int team : {1, 2, 3}) {  // a team of 8 makes LLVM 14's libomp leak (LeakSanitizer)
                CAPTURE(n, shares, team);
                const std::vector<int> count = runs(n, shares, team);
                // The first item not run exactly once (none: n).
                const auto wrong = std::find_if(count.begin(), count.end(), [](int c) { return c != 1; });
                REQUIRE(wrong - count.begin() == n);
            }
}

TEST_CASE("thread_shares: not parallel, one thread runs every item in order", "[parallel][shares]") {
    // `parallel` false: a team of one and one share whatever the thread count, so the region's
    // one thread takes the items from the front, in order (the solver's loops below their
    // thresholds).
    gimlet::detail::thread_shares s(3000, 4, false);
    REQUIRE(s.team() == 1);
    std::vector<std::ptrdiff_t> order;
    GIMLET_OMP(parallel num_threads(s.team()))
    for (auto claimed = s.start(); s.claim(claimed);)
        for (std::ptrdiff_t i = claimed.first, end = claimed.last; i < end; ++i) order.push_back(i);
    std::vector<std::ptrdiff_t> expected(3000);
    std::iota(expected.begin(), expected.end(), std::ptrdiff_t(0));
    REQUIRE(order == expected);
}

TEST_CASE("thread_shares: a thread that does not come has its share taken over", "[parallel][shares]") {
    // Thread 0 of a team of two waits until every item is done before it asks for any: thread 1
    // must take over all of share 0. (Where the runtime gives one thread, thread 0 runs all.)
    const std::ptrdiff_t n = 20000;
    gimlet::detail::thread_shares s(n, 2);
    std::vector<int> by(static_cast<std::size_t>(n), -1);
    std::atomic<std::ptrdiff_t> done{0};
    int team = 1;
    GIMLET_OMP(parallel num_threads(2))
    {
        int me = 0;
#if defined(_OPENMP)
        me = omp_get_thread_num();
        GIMLET_OMP(single)
        team = omp_get_num_threads();
#endif
        if (me == 0 && team == 2) {
            const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
            while (done.load() < n && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
        }
        for (auto claimed = s.start(); s.claim(claimed);)
            for (std::ptrdiff_t i = claimed.first, end = claimed.last; i < end; ++i) {
                by[static_cast<std::size_t>(i)] = me;
                done.fetch_add(1);
            }
    }
    REQUIRE(done.load() == n);
    CAPTURE(team);
    const int taker = team == 2 ? 1 : 0;
    REQUIRE(std::count(by.begin(), by.end(), taker) == n);
}
