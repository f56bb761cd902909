// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The offsets of a stable counting sort done in blocks: each block of consecutive items has
/// counted its items per bucket, and takes its place within each bucket after the blocks before
/// it. The order is then the serial sort's (by bucket, then by index) whatever the blocks, so a
/// sort split over threads gives what one thread gives.

#include <cstddef>
#include <vector>

namespace gimlet::detail {

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
