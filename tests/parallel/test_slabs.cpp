// SPDX-License-Identifier: MIT
// The scatter's slab schedule (solver/slabs.hpp): for_each_reaching, which the contact's reach
// pass uses to skip the slabs that reach no shared node, must still visit every particle whose
// stencil touches a flagged node row, on a periodic axis across the seam too, in for_each's
// order, and on any thread count.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cstddef>
#include <cstdint>
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
