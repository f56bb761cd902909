// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// GIMLET_INLINE: asks the compiler to inline a small function of the per-particle hot path
/// that it would otherwise call (without it g++ 12 keeps embed3, deviator and jaumann_rotate
/// out of line, about 20 % of an elastic step in calls and copies of 3x3 matrices; in a unit
/// holding two solvers, von_mises::update and the isentrope's table look-up, a tenth of the HMX
/// material update: docs/performance.md). Whether g++ inlines depends on how much the unit holds.
///
/// GIMLET_COLD: the opposite, for what only an error reaches (building a message, throwing):
/// kept out of line, so that the hot function that calls it stays small.
///
/// GIMLET_NOINLINE: kept out of line without being cold: code that many loops share and call
/// rarely (once a chunk of items), where a copy in each would only cost compile time.

#if defined(__GNUC__) || defined(__clang__)
#define GIMLET_INLINE [[gnu::always_inline]] inline
#define GIMLET_COLD [[gnu::cold, gnu::noinline]]
#define GIMLET_NOINLINE [[gnu::noinline]]
#else
#define GIMLET_INLINE inline
#define GIMLET_COLD
#define GIMLET_NOINLINE
#endif
