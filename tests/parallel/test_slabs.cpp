// SPDX-License-Identifier: MIT
// The scatter's slab schedule (solver/slabs.hpp): for_each_reaching, which the contact's reach
// pass uses to skip the slabs that reach no shared node, must still visit every particle whose
// stencil touches a flagged node row, on a periodic axis across the seam too, in for_each's
// order, and on any thread count; and on several threads the colours never overlap.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <thread>
#include <vector>

namespace {

// Particles at every first row a stencil of `width` rows can start in, three per row, their
// indices not in row order.
template <int SlabRows>
void check_reaching(int rows, bool periodic, int width) {
    gimlet::detail::slab_schedule<SlabRows> slabs;
    slabs.set_up(rows, periodic);
    const int starts = periodic ? rows : rows - width + 1;
    if (starts < 1 || rows < width) return;  // no stencil fits
    const std::size_t n = std::size_t(3 * starts);
    std::vector<int> first(n);
    for (std::size_t i = 0; i < n; ++i) {
        const int r = int(i % std::size_t(starts));
        first[i] = (i / std::size_t(starts)) % 2 == 0 ? r : starts - 1 - r;  // ascending, then descending
    }
    slabs.resize(n);
    for (std::size_t i = 0; i < n; ++i) slabs.assign(i, first[i]);
    slabs.bucket();
    std::vector<std::size_t> all;
    slabs.for_each(false, 1, [&](std::size_t i) { all.push_back(i); });
    REQUIRE(all.size() == n);
    for (int flagged = 0; flagged < rows; ++flagged) {
        CAPTURE(rows, periodic, width, flagged);
        std::vector<std::uint8_t> flags(std::size_t(rows), 0);
        flags[std::size_t(flagged)] = 1;
        std::vector<std::size_t> seen;
        slabs.for_each_reaching(flags, false, 1, [&](std::size_t i) { seen.push_back(i); });
        // In for_each's order: a subsequence of it.
        std::size_t at = 0;
        for (std::size_t i : seen) {
            while (at < all.size() && all[at] != i) ++at;
            REQUIRE(at < all.size());
            ++at;
        }
        std::vector<std::uint8_t> visited(n, 0), threaded(n, 0);
        for (std::size_t i : seen) visited[i] = 1;
        slabs.for_each_reaching(flags, true, 2, [&](std::size_t i) { threaded[i] = 1; });
        CHECK(threaded == visited);
        std::size_t reaching = 0;
        for (std::size_t i = 0; i < n; ++i) {
            bool reaches = false;
            for (int r = first[i]; r < first[i] + width; ++r) reaches = reaches || r % rows == flagged;
            if (reaches) {
                ++reaching;
                CHECK(visited[i] == 1);
            }
        }
        CHECK(reaching > 0);
        // What the pass is for: on a long axis the slabs far from the row are skipped.
        if (rows >= 8 * SlabRows) CHECK(seen.size() < n / 2);
    }
}

}  // namespace

TEST_CASE("slab schedule: for_each_reaching visits every particle whose stencil reaches a flagged row",
          "[parallel][slabs]") {
    // The solver's slabs are max(stencil - 1, 1) rows: one for the linear shape, two for uGIMP,
    // cpGIMP and the quadratic B-spline, three for the cubic B-spline; a user's shape may have
    // a narrower stencil than its slabs allow.
    for (bool periodic : {false, true}) {
        for (int rows : {2, 3, 5, 7, 12, 13, 40}) {
            check_reaching<1>(rows, periodic, 2);  // linear
            check_reaching<1>(rows, periodic, 1);
            check_reaching<2>(rows, periodic, 3);  // uGIMP, cpGIMP, quadratic B-spline
            check_reaching<2>(rows, periodic, 2);
            check_reaching<3>(rows, periodic, 4);  // cubic B-spline
        }
    }
}

TEST_CASE("slab schedule: on several threads, no slab of the next colour starts before the last of a colour ends",
          "[parallel][slabs]") {
    // Slabs of one colour share no node, so the scatter is deterministic only if the colours
    // never overlap (the barrier between them in for_each_kept). The first particle of slab 0
    // is slow, so that a thread without that barrier would start the next colour meanwhile.
    for (bool periodic : {false, true}) {
        const int rows = 2 * 21;  // 21 slabs of 2 rows: on a periodic axis the last is a third colour
        gimlet::detail::slab_schedule<2> slabs;
        slabs.set_up(rows, periodic);
        const int count = rows / 2;
        const std::size_t n = std::size_t(4 * count);
        slabs.resize(n);
        for (std::size_t i = 0; i < n; ++i) slabs.assign(i, int(2 * (i % std::size_t(count))));
        slabs.bucket();
        auto colour = [&](std::size_t i) {
            const int s = int(i % std::size_t(count));
            return periodic && count % 2 == 1 && s == count - 1 ? 2 : s % 2;
        };
        std::atomic<long> clock{0};
        std::vector<long> start(n), end(n);
        slabs.for_each(true, 2, [&](std::size_t i) {
            start[i] = clock.fetch_add(1);
            if (i == 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
            end[i] = clock.fetch_add(1);
        });
        for (int c = 0; c + 1 < 3; ++c) {
            long last_end = -1, first_start = std::numeric_limits<long>::max();
            for (std::size_t i = 0; i < n; ++i) {
                if (colour(i) == c) last_end = std::max(last_end, end[i]);
                if (colour(i) > c) first_start = std::min(first_start, start[i]);
            }
            CAPTURE(periodic, c);
            CHECK(last_end < first_start);
        }
    }
}
