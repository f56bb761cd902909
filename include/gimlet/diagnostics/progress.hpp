// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// A progress line for long runs: step, simulated time, and the wall time left, estimated from
/// the simulated time covered so far. An observer for solver::run_until.

#include "gimlet/core/error.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>

namespace gimlet::diagnostics {

/// An observer for solver::run_until that prints a line such as "step 1200, t = 3.000 of
/// 10.000 us, 12 s elapsed, about 28 s left" at most every `interval_s` of wall time, and a
/// last line "done in ... s" when the run reaches `t_end`. The time left is extrapolated from
/// the simulated time covered since its first call.
class progress {
public:
    /// The wall clock it measures with.
    using clock = std::chrono::steady_clock;

    /// Report to `out` at most every `interval_s` seconds of wall time, for a run that ends at
    /// simulated time `t_end` (s).
    progress(std::ostream& out, double t_end, double interval_s = 2.0) : out_(&out), t_end_(t_end), interval_(interval_s) {
        require(std::isfinite(t_end) && t_end > 0, "progress end time (s)", t_end, "finite and > 0");
        require_positive("progress interval (s)", interval_s);
    }

    /// The first call starts the clock; later calls print a line if `interval_s` has passed or
    /// the run has reached `t_end`.
    template <class Solver>
    void maybe_call(const Solver& s) {
        const auto now = clock::now();
        const double t = double(s.time());
        if (!started_) {
            started_ = true, start_ = last_ = now, t_start_ = t;
            return;
        }
        const bool done = t >= t_end_;
        if (!done && seconds(last_, now) < interval_) return;
        last_ = now;
        const double elapsed = seconds(start_, now);
        const double covered = t - t_start_;
        char line[160];
        if (done) {
            std::snprintf(line, sizeof line, "step %llu, t = %.3f us: done in %.1f s\n",
                          static_cast<unsigned long long>(s.steps()), t * 1e6, elapsed);
        } else {
            const double left = covered > 0 ? elapsed * (t_end_ - t) / covered : 0.0;
            std::snprintf(line, sizeof line, "step %llu, t = %.3f of %.3f us, %.0f s elapsed, about %.0f s left\n",
                          static_cast<unsigned long long>(s.steps()), t * 1e6, t_end_ * 1e6, elapsed, left);
        }
        *out_ << line << std::flush;
    }

private:
    static double seconds(clock::time_point a, clock::time_point b) {
        return std::chrono::duration<double>(b - a).count();
    }
    std::ostream* out_;
    double t_end_, interval_;
    bool started_ = false;
    clock::time_point start_{}, last_{};
    double t_start_ = 0;
};

}  // namespace gimlet::diagnostics
