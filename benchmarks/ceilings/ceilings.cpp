// SPDX-License-Identifier: MIT
// The machine's ceilings for the per-phase table of docs/performance.md (a roofline): what one
// and N threads reach at
//   - scalar multiply-adds: a = a * b + c on 8 independent accumulators, not vectorised
//     (the step's loops are scalar today), 2 flops each;
//   - vector multiply-adds: the same on 16 or 64 accumulators the compiler vectorises (with the
//     build's instruction set: SSE2 in the portable build, AVX-512 with -march=native);
//   - streaming bandwidth: the triad a = b + s c over three arrays, at a working set the size
//     of the HMX scene's particle data (22 MB: 64,000 particles x about 340 bytes of store and
//     stencil) and at one far larger than the caches (400 MB); bytes counted as 3 x 8 per
//     element (the write's allocate not counted, as STREAM does).
// Best of several repeats, each long enough (about 0.2-1 s) to swamp the timer. Flags:
// --threads N (2), --quick 1 (a smoke run: short loops, the numbers meaningless).
#include "common/bench.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <vector>


namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

int thread_id() {
#if defined(_OPENMP)
    return omp_get_thread_num();  // <omp.h> comes with the library's GIMLET_OMP
#else
    return 0;
#endif
}

// One thread's scalar chains: kept scalar so that the figure is the one scalar code can reach.
#if defined(__clang__)
__attribute__((noinline)) double scalar_chains(long iterations, double seed) {
    double a[8];
    for (int k = 0; k < 8; ++k) a[k] = seed + k * 1e-3;
    const double b = 0.999999, c = 1e-7;
    for (long i = 0; i < iterations; ++i) {
#pragma clang loop vectorize(disable) unroll(full)
        for (int k = 0; k < 8; ++k) a[k] = a[k] * b + c;
    }
    double s = 0;
    for (double x : a) s += x;
    return s;
}
#else
__attribute__((noinline, optimize("no-tree-vectorize", "no-tree-slp-vectorize"))) double scalar_chains(long iterations,
                                                                                                          double seed) {
    double a[8];
    for (int k = 0; k < 8; ++k) a[k] = seed + k * 1e-3;
    const double b = 0.999999, c = 1e-7;
    for (long i = 0; i < iterations; ++i)
        for (int k = 0; k < 8; ++k) a[k] = a[k] * b + c;
    double s = 0;
    for (double x : a) s += x;
    return s;
}
#endif

// One thread's vectorised chains: 16 fill SSE2's registers, a 64-wide AVX-512 build needs 64
// (the best of the two is reported).
template <int N>
double vector_chains(long iterations, double seed) {
    double a[N];
    for (int k = 0; k < N; ++k) a[k] = seed + k * 1e-3;
    const double b = 0.999999, c = 1e-7;
    for (long i = 0; i < iterations; ++i) {
        GIMLET_OMP(simd)
        for (int k = 0; k < N; ++k) a[k] = a[k] * b + c;
    }
    double s = 0;
    for (double x : a) s += x;
    return s;
}

// GFLOP/s of `chains` (per iteration `lanes` multiply-adds) on `threads` threads, best of 3.
template <class F>
double flops(F chains, int lanes, long iterations, int threads, double& sink) {
    double best = 0;
    for (int rep = 0; rep < 3; ++rep) {
        double total = 0;
        const double t0 = now();
        GIMLET_OMP(parallel num_threads(threads) reduction(+ : total))
        total += chains(iterations, 1.0 + thread_id());
        const double t = now() - t0;
        best = std::max(best, 2.0 * lanes * double(iterations) * threads / t / 1e9);
        sink += total;
    }
    return best;
}

// GB/s of the triad over three arrays of mb / 3 megabytes each on `threads` threads, best of 5.
double triad(double mb, [[maybe_unused]] int threads, double seconds) {
    const auto n = std::size_t(mb * 1e6 / 3 / 8);
    std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
    const auto length = static_cast<std::ptrdiff_t>(n);
    const int passes = std::max(1, int(seconds * 20e9 / (24.0 * double(n))));  // about `seconds` at 20 GB/s
    double best = 0;
    for (int rep = 0; rep < 5; ++rep) {
        const double t0 = now();
        for (int p = 0; p < passes; ++p) {
            GIMLET_OMP(parallel for schedule(static) num_threads(threads))
            for (std::ptrdiff_t i = 0; i < length; ++i) a[std::size_t(i)] = b[std::size_t(i)] + 0.5 * c[std::size_t(i)];
        }
        best = std::max(best, 24.0 * double(n) * passes / (now() - t0) / 1e9);
    }
    if (a[0] != 2.0) std::printf("(triad check failed: %g)\n", a[0]);
    return best;
}

}  // namespace

int main(int argc, char** argv) try {
    bench::flags f(argc, argv);
#if defined(_OPENMP)
    const int threads = static_cast<int>(f.number("threads", 2));
#else
    const int threads = static_cast<int>(f.number("threads", 1)) > 0 ? 1 : 0;  // one thread without OpenMP
#endif
    const bool quick = f.number("quick", 0) != 0;
    if (threads < 1 || threads > 1024) throw std::invalid_argument("--threads: in [1, 1024]");
    f.finish();
    const long iterations = quick ? 1000 : 100'000'000;
    const double seconds = quick ? 0.001 : 0.5;
    double sink = 0;
    std::printf("ceilings, double precision (best of repeats)\n");
    std::printf("| threads | scalar multiply-add (GFLOP/s) | vectorised multiply-add (GFLOP/s) | triad, 22 MB (GB/s) | triad, 400 MB (GB/s) |\n");
    std::printf("| --- | --- | --- | --- | --- |\n");
    for (int t : {1, threads}) {
        std::printf("| %d | %.1f | %.1f | %.1f | %.1f |\n", t, flops(scalar_chains, 8, iterations, t, sink),
                    std::max(flops(vector_chains<16>, 16, iterations / 2, t, sink),
                             flops(vector_chains<64>, 64, iterations / 8, t, sink)), triad(quick ? 0.3 : 22, t, seconds),
                    triad(quick ? 0.3 : 400, t, seconds));
        if (threads == 1) break;
    }
    if (sink == 42.0) std::printf("\n");  // keeps the chains' results alive
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "bench_ceilings: %s\n", e.what());
    return 1;
}
