// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// GIMLET_INLINE: asks the compiler to inline a small function of the per-particle hot path
/// that it would otherwise call (g++ 12 kept embed3, deviator and jaumann_rotate out of line,
/// about 20 % of an elastic step in calls and copies of 3x3 matrices; docs/performance.md).

#if defined(__GNUC__) || defined(__clang__)
#define GIMLET_INLINE [[gnu::always_inline]] inline
#else
#define GIMLET_INLINE inline
#endif
