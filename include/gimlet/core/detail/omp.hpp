// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// OpenMP pragmas that vanish (without unknown-pragma warnings) when OpenMP is off.

#if defined(_OPENMP)
#include <omp.h>
#define GIMLET_OMP(x) _Pragma(GIMLET_OMP_STR(omp x))
#define GIMLET_OMP_STR(x) #x
#else
#define GIMLET_OMP(x)
#endif

namespace gimlet::detail {

/// The thread count OpenMP would use (1 without OpenMP).
[[nodiscard]] inline int default_threads() noexcept {
#if defined(_OPENMP)
    return omp_get_max_threads();
#else
    return 1;
#endif
}

/// The thread count a solver (or any object with `options().threads`) asks for: that count
/// where it is positive, otherwise default_threads().
template <class Solver>
[[nodiscard]] int threads_of(const Solver& s) noexcept {
    if constexpr (requires { s.options().threads; })
        if (s.options().threads > 0) return int(s.options().threads);
    return default_threads();
}

}  // namespace gimlet::detail
