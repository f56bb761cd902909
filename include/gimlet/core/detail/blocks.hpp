// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Passes over items (particles) split into blocks of consecutive items, whose results do not
/// depend on the blocks: each block's part is joined to the others in block order. The
/// offsets of a stable counting sort done that way: each block has counted its items per
/// bucket, and takes its place within each bucket after the blocks before it, so the order is
/// the serial sort's (by bucket, then by index) whatever the blocks.

#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/detail/shares.hpp"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace gimlet::detail {

/// The blocks of an observer's pass over n particles on `threads` threads: one a thread from
/// 4096 particles (below, a team costs more than the pass), otherwise one.
[[nodiscard]] inline std::size_t observer_blocks(std::size_t n, int threads) noexcept {
    return n >= 4096 && threads > 1 ? std::size_t(threads) : 1;
}

/// for_each_block's loop inside a parallel region that is already open: every thread of the
/// team calls it once, with the same `shares` (set up for `blocks` items before the call, or by
/// one thread inside the region followed by a barrier), and each block runs once, whatever the
/// team's size. No barrier at its end: a pass that reads its results needs one. f must not
/// throw (an exception cannot leave a parallel region).
template <class F>
void for_each_block_of(thread_shares& shares, std::size_t n, std::size_t blocks, F&& f) {
    if (blocks == 0) return;
    const std::size_t size = (n + blocks - 1) / blocks;
    for (auto claimed = shares.start(); shares.claim(claimed);)
        for (std::ptrdiff_t b = claimed.first, end = claimed.last; b < end; ++b) {
            const std::size_t first = std::min(n, std::size_t(b) * size);
            f(std::size_t(b), first, std::min(n, first + size));
        }
}

/// f(b, first, last) for each of `blocks` ranges [first, last) of consecutive items out of n
/// (equal sizes, the last ones shorter or empty), on `threads` threads if `parallel` and there
/// are several blocks. f must not throw.
template <class F>
void for_each_block(std::size_t n, std::size_t blocks, bool parallel, int threads, F&& f) {
    if (blocks == 0) return;
    const auto count = static_cast<std::ptrdiff_t>(blocks);
    thread_shares shares(count, threads, parallel && count > 1);
    GIMLET_OMP(parallel num_threads(shares.team()))
    for_each_block_of(shares, n, blocks, f);
}

/// `cursor` holds blocks x buckets counts (block-major: cursor[b * buckets + k]); each becomes
/// the first position of block b's items in bucket k. `start` becomes each bucket's first
/// position, with the total count last (buckets + 1 entries).
inline void block_offsets(std::vector<std::size_t>& cursor, std::size_t blocks, std::size_t buckets,
                          std::vector<std::size_t>& start) {
    start.assign(buckets + 1, 0);
    std::size_t at = 0;
    for (std::size_t k = 0; k < buckets; ++k) {
        start[k] = at;
        for (std::size_t b = 0; b < blocks; ++b) {
            const std::size_t c = cursor[b * buckets + k];
            cursor[b * buckets + k] = at;
            at += c;
        }
    }
    start[buckets] = at;
}

}  // namespace gimlet::detail
