// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Observers called at chosen intervals by solver::run_until.

#include "gimlet/core/error.hpp"

#include <cstdint>
#include <limits>
#include <utility>

namespace gimlet::diagnostics {

/// Calls `f(solver)` at t = 0 and then at the first step at or after each multiple of the
/// interval (s) of simulated time.
template <class F>
class every_time {
public:
    every_time(double interval, F f) : interval_(interval), f_(std::move(f)) {
        require_positive("observer interval (s)", interval);
    }
    template <class Solver>
    void maybe_call(const Solver& s) {
        if (double(s.time()) + 1e-12 * interval_ < next_) return;
        f_(s);
        while (next_ <= double(s.time()) + 1e-12 * interval_) next_ += interval_;
    }

    /// The time (s) of the next call; with resume(), what a checkpoint keeps of the observer.
    [[nodiscard]] double next() const noexcept { return next_; }
    /// Continue a schedule saved with next(), e.g. in a run resumed from a checkpoint.
    void resume(double next) {
        require_finite("observer next time (s)", next);
        next_ = next;
    }

private:
    double interval_;
    F f_;
    double next_ = 0;
};

/// Calls `f(solver)` at step 0 and every `n` steps.
template <class F>
class every_steps {
public:
    every_steps(std::uint64_t n, F f) : n_(n), f_(std::move(f)) {
        require(n >= 1, "observer step interval", double(n), ">= 1");
    }
    template <class Solver>
    void maybe_call(const Solver& s) {
        if (s.steps() % n_ == 0 && s.steps() != last_) {
            last_ = s.steps();
            f_(s);
        }
    }

private:
    std::uint64_t n_;
    F f_;
    std::uint64_t last_ = std::numeric_limits<std::uint64_t>::max();
};

}  // namespace gimlet::diagnostics
