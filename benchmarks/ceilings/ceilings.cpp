// SPDX-License-Identifier: MIT
// The machine's ceilings for the per-phase table of docs/performance.md (a roofline): what one
// and N threads reach at
//   - scalar multiply-adds: a = a * b + c on 12 independent accumulators kept scalar (the
//     step's loops are scalar), 2 flops each. Twelve chains cover the latency of a
//     multiply and an add (or an FMA) on two pipes each, and fit the 16 SSE registers; fewer
//     chains measure the latency, not the throughput;
//   - vector multiply-adds: the same on 24 or 64 accumulators the compiler vectorises (with the
//     build's instruction set: SSE2 in the portable build, AVX-512 with -march=native; the best
//     of the two is reported);
//   - one at a time, with independent inputs: a division, a square root, std::pow and std::log
//     (what the material update calls), in ns each;
//   - the clock: a chain of dependent integer additions (x86-64 assembly), one per cycle, so
//     that the per-phase table can give each phase's instructions per cycle; and the rate of
//     independent register additions (a loop the integer units bound);
//   - the level-1 data cache's ports: independent 16-byte loads, and stores, per ns;
//   - streaming bandwidth: the triad a = b + s c over three arrays, at a working set the size
//     of the HMX scene's particle data (22 MB: 64,000 particles x about 340 bytes of store and
//     stencil) and at one far larger than the caches (400 MB); bytes counted as 3 x 8 per
//     element (the write's allocate not counted, as STREAM does);
//   - synchronisation on N threads: an empty parallel region (fork and join) and a barrier,
//     in microseconds, which the OpenMP wait policy sets (OMP_WAIT_POLICY).
// Best of several repeats. Flags: --threads N (2; 1 without OpenMP), --quick 1 (a smoke run:
// short loops, the numbers meaningless).
#include "common/bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// Keeps x in a register of its own, so that clang's SLP vectoriser cannot pack the scalar
// chains into vectors (g++ is told not to vectorise scalar_chains instead: with g++ this
// barrier sends each value through memory).
inline void keep_scalar([[maybe_unused]] double& x) {
#if defined(__clang__) && (defined(__x86_64__) || defined(__i386__))
    asm("" : "+x"(x));
#elif defined(__clang__) && defined(__aarch64__)
    asm("" : "+w"(x));
#endif
}

// A function g++ must not vectorise.
#if defined(__GNUC__) && !defined(__clang__)
#define CEILINGS_SCALAR __attribute__((noinline, optimize("no-tree-vectorize", "no-tree-slp-vectorize")))
#else
#define CEILINGS_SCALAR __attribute__((noinline))
#endif

// One thread's scalar chains.
CEILINGS_SCALAR double scalar_chains(long iterations, double seed) {
    constexpr int N = 12;
    double a[N];
    for (int k = 0; k < N; ++k) a[k] = seed + k * 1e-3;
    const double b = 0.999999, c = 1e-7;
    for (long i = 0; i < iterations; ++i)
        for (int k = 0; k < N; ++k) {
            a[k] = a[k] * b + c;
            keep_scalar(a[k]);
        }
    double s = 0;
    for (double x : a) s += x;
    return s;
}

// One thread's vectorised chains: 24 fill SSE2's registers, AVX-512 needs 64.
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

// GFLOP/s of `chains` (per iteration `lanes` multiply-adds) on up to `threads` threads (the
// team's real size counted), best of 3.
template <class F>
double flops(F chains, int lanes, long iterations, [[maybe_unused]] int threads, double& sink) {
    double best = 0;
    for (int rep = 0; rep < 3; ++rep) {
        double total = 0;
        int team = 0;
        const double t0 = now();
        GIMLET_OMP(parallel num_threads(threads) reduction(+ : total, team))
        {
            total += chains(iterations, 1.0 + total);
            team += 1;
        }
        const double t = now() - t0;
        best = std::max(best, 2.0 * lanes * double(iterations) * team / t / 1e9);
        sink += total;
    }
    return best;
}

// ns per call of f over independent inputs in [0.8, 1.2), one thread, best of 5.
template <class F>
CEILINGS_SCALAR double per_call(F f, int count, double& sink) {
    std::vector<double> x(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) x[std::size_t(i)] = 0.8 + 0.4 * i / count;
    double best = 1e9;
    for (int rep = 0; rep < 5; ++rep) {
        double s[8] = {};
        const double t0 = now();
        for (int i = 0; i + 8 <= count; i += 8)
            for (int k = 0; k < 8; ++k) {
                s[k] += f(x[std::size_t(i + k)]);
                keep_scalar(s[k]);
            }
        best = std::min(best, (now() - t0) / count * 1e9);
        for (double v : s) sink += v;
    }
    return best;
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define CEILINGS_X86_ASM 1
// Billions of `per_iteration` per second over `iterations` runs of loop(n), best of 5.
template <class Loop>
double best_rate(long iterations, double per_iteration, Loop loop) {
    double best = 0;
    for (int rep = 0; rep < 5; ++rep) {
        const double t0 = now();
        loop(iterations);
        best = std::max(best, per_iteration * double(iterations) / (now() - t0) / 1e9);
    }
    return best;
}
#endif

// The core's clock in GHz, one thread, best of 5: a chain of dependent integer additions, one
// per cycle (12 per iteration; the loop's decrement and branch run beside the chain). A
// register operand: some cores fold additions of an immediate at rename (such a core reads
// about 9.3 GHz with them). 0 where there is no x86-64 assembly (AT&T syntax, the compilers'
// default).
double clock_ghz([[maybe_unused]] long iterations) {
#if defined(CEILINGS_X86_ASM)
    return best_rate(iterations, 12.0, [](long n) {
        long x = 0;
        const long step = 1;
        asm volatile(
            "1:\n\t"
            "add %2, %1\n\tadd %2, %1\n\tadd %2, %1\n\tadd %2, %1\n\t"
            "add %2, %1\n\tadd %2, %1\n\tadd %2, %1\n\tadd %2, %1\n\t"
            "add %2, %1\n\tadd %2, %1\n\tadd %2, %1\n\tadd %2, %1\n\t"
            "dec %0\n\tjnz 1b\n\t"
            : "+r"(n), "+r"(x)
            : "r"(step)
            : "cc");
    });
#else
    return 0;
#endif
}

// Instructions per ns of independent register additions, one thread, best of 5: 12 chains on
// 12 registers plus the loop's decrement and branch, 14 instructions per iteration (as
// callgrind counts them). A loop the integer units bound, so not the most the core issues of
// a mix; it moves with other work on the same physical core. 0 where there is no x86-64
// assembly.
double addition_rate([[maybe_unused]] long iterations) {
#if defined(CEILINGS_X86_ASM)
    return best_rate(iterations, 14.0, [](long n) {
        const long step = 1;
        asm volatile(
            "1:\n\t"
            "add %1, %%rax\n\tadd %1, %%rbx\n\tadd %1, %%rcx\n\tadd %1, %%rdx\n\t"
            "add %1, %%rsi\n\tadd %1, %%rdi\n\tadd %1, %%r8\n\tadd %1, %%r9\n\t"
            "add %1, %%r10\n\tadd %1, %%r11\n\tadd %1, %%r12\n\tadd %1, %%r13\n\t"
            "dec %0\n\tjnz 1b\n\t"
            : "+r"(n)
            : "r"(step)
            : "rax", "rbx", "rcx", "rdx", "rsi", "rdi", "r8", "r9", "r10", "r11", "r12", "r13", "cc");
    });
#else
    return 0;
#endif
}

// Memory accesses per ns that the level-1 data cache serves one thread, best of 5: 12
// independent 16-byte loads (or stores) per iteration, one in each of the 12 lines of a
// 768-byte block that stays in that cache, at staggered offsets within their lines (so that a
// cache built of banks serves them from different banks), plus the loop's decrement and
// branch. A load's data goes nowhere and a store writes zeroed registers, so only the cache's
// ports bound them. These are the SSE2 accesses of the portable build: 32- and 64-byte ones
// (AVX) are not measured. 0 where there is no x86-64 assembly.
struct l1_rates {
    double loads = 0, stores = 0;
};
l1_rates l1_access_rates([[maybe_unused]] long iterations) {
    l1_rates r;
#if defined(CEILINGS_X86_ASM)
    alignas(64) double block[12 * 64 / 8] = {};  // 12 lines
    double* p = block;
#if defined(__AVX__)
    // Legacy SSE instructions after AVX code with dirty upper halves pay a transition on some
    // cores: a clean state first (a -march=native build).
#define CEILINGS_CLEAN_UPPER "vzeroupper\n\t"
#else
#define CEILINGS_CLEAN_UPPER ""
#endif
    r.loads = best_rate(iterations, 12.0, [p](long n) {
        asm volatile(
            CEILINGS_CLEAN_UPPER
            "1:\n\t"
            "movapd (%1), %%xmm0\n\tmovapd 80(%1), %%xmm1\n\tmovapd 160(%1), %%xmm2\n\tmovapd 240(%1), %%xmm3\n\t"
            "movapd 256(%1), %%xmm4\n\tmovapd 336(%1), %%xmm5\n\tmovapd 416(%1), %%xmm6\n\tmovapd 496(%1), %%xmm7\n\t"
            "movapd 512(%1), %%xmm8\n\tmovapd 592(%1), %%xmm9\n\tmovapd 672(%1), %%xmm10\n\tmovapd 752(%1), %%xmm11\n\t"
            "dec %0\n\tjnz 1b\n\t"
            : "+r"(n)
            : "r"(p)
            : "xmm0", "xmm1", "xmm2", "xmm3", "xmm4", "xmm5", "xmm6", "xmm7", "xmm8", "xmm9", "xmm10", "xmm11", "cc",
              "memory");
    });
    r.stores = best_rate(iterations, 12.0, [p](long n) {
        asm volatile(
            CEILINGS_CLEAN_UPPER
            "xorpd %%xmm0, %%xmm0\n\txorpd %%xmm1, %%xmm1\n\txorpd %%xmm2, %%xmm2\n\txorpd %%xmm3, %%xmm3\n\t"
            "1:\n\t"
            "movapd %%xmm0, (%1)\n\tmovapd %%xmm1, 80(%1)\n\tmovapd %%xmm2, 160(%1)\n\tmovapd %%xmm3, 240(%1)\n\t"
            "movapd %%xmm0, 256(%1)\n\tmovapd %%xmm1, 336(%1)\n\tmovapd %%xmm2, 416(%1)\n\tmovapd %%xmm3, 496(%1)\n\t"
            "movapd %%xmm0, 512(%1)\n\tmovapd %%xmm1, 592(%1)\n\tmovapd %%xmm2, 672(%1)\n\tmovapd %%xmm3, 752(%1)\n\t"
            "dec %0\n\tjnz 1b\n\t"
            : "+r"(n)
            : "r"(p)
            : "xmm0", "xmm1", "xmm2", "xmm3", "cc", "memory");
    });
#undef CEILINGS_CLEAN_UPPER
#endif
    return r;
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

// What the step's synchronisation points cost on `threads` threads, in microseconds (best of
// repeats): an empty parallel region, its fork and join (one per `parallel for` of the step),
// and a barrier inside a region (one per colour of the scatter) that one thread reaches 20 us
// after the others, as an uneven loop does (the 20 us not counted): what the last thread pays
// to release the others, which under OMP_WAIT_POLICY=passive have gone to sleep. A sleeper's
// own wake-up, where under 20 us, hides behind the next round's late arrival: a lower bound.
struct sync_cost {
    double region = 1e9, barrier = 1e9;
};
sync_cost synchronisation([[maybe_unused]] int threads, int count) {
    constexpr double late = 20e-6;
    sync_cost best;
    for (int rep = 0; rep < 5; ++rep) {
        double t0 = now();
        for (int k = 0; k < count; ++k) {
            GIMLET_OMP(parallel num_threads(threads))
            { asm volatile("" ::: "memory"); }
        }
        best.region = std::min(best.region, (now() - t0) / count * 1e6);
        t0 = now();
        GIMLET_OMP(parallel num_threads(threads))
        for (int k = 0; k < count; ++k) {
#if defined(_OPENMP)
            if (omp_get_thread_num() == 0)
#endif
                for (const double t1 = now(); now() - t1 < late;) {
                }
            GIMLET_OMP(barrier)
        }
        best.barrier = std::min(best.barrier, (now() - t0) / count * 1e6 - late * 1e6);
    }
    return best;
}

}  // namespace

int main(int argc, char** argv) try {
    bench::flags f(argc, argv);
    const double asked = f.number("threads", 2);
    const bool quick = f.number("quick", 0) != 0;
    f.finish();
    if (!(asked >= 1 && asked <= 1024)) throw std::invalid_argument("--threads: in [1, 1024]");
#if defined(_OPENMP)
    const int threads = static_cast<int>(asked);
#else
    const int threads = 1;
    if (asked > 1) std::printf("(built without OpenMP: one thread)\n");
#endif
    const long iterations = quick ? 1000 : 100'000'000;
    const double seconds = quick ? 0.001 : 0.5;
    double sink = 0;
    std::printf("ceilings, double precision (best of repeats)\n");
    std::printf("| threads | scalar multiply-add (GFLOP/s) | vectorised multiply-add (GFLOP/s) | triad, 22 MB (GB/s) | triad, 400 MB (GB/s) |\n");
    std::printf("| --- | --- | --- | --- | --- |\n");
    for (int t : {1, threads}) {
        std::printf("| %d | %.1f | %.1f | %.1f | %.1f |\n", t, flops(scalar_chains, 12, iterations, t, sink),
                    std::max(flops(vector_chains<24>, 24, iterations / 2, t, sink),
                             flops(vector_chains<64>, 64, iterations / 4, t, sink)),
                    triad(quick ? 0.3 : 22, t, seconds), triad(quick ? 0.3 : 400, t, seconds));
        if (threads == 1) break;
    }
    const int calls = quick ? 1024 : 1 << 22;
    std::printf("\none at a time, independent inputs, one thread (ns per call): division %.2f, square root %.2f, "
                "pow %.2f, log %.2f\n",
                per_call([](double x) { return 1.0 / x; }, calls, sink),
                per_call([](double x) { return std::sqrt(x); }, calls, sink),
                per_call([](double x) { return std::pow(x, -1.1); }, calls, sink),
                per_call([](double x) { return std::log(x); }, calls, sink));
    const auto sync = synchronisation(threads, quick ? 200 : 2000);
    std::printf("\nsynchronisation on %d threads (us each): an empty parallel region %.2f, a barrier %.2f\n", threads,
                sync.region, sync.barrier);
    std::printf("\nclock (a chain of dependent integer additions, one per cycle): %.2f GHz\n", clock_ghz(iterations / 4));
    std::printf("independent register additions: %.2f instructions per ns\n", addition_rate(iterations / 4));
    const auto l1 = l1_access_rates(iterations / 4);
    std::printf("level-1 data cache, one thread: 16-byte loads %.2f per ns, 16-byte stores %.2f per ns\n", l1.loads,
                l1.stores);
    if (sink == 42.0) std::printf("\n");  // keeps the chains' results alive
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "bench_ceilings: %s\n", e.what());
    return 1;
}
