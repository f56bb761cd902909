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
    /// \param interval the interval (s) of simulated time, finite and > 0; \param f the callable.
    /// \throws gimlet::invalid_parameter for an interval that is not finite and > 0.
    every_time(double interval, F f) : interval_(interval), f_(std::move(f)) {
        require_positive("observer interval (s)", interval);
    }
    /// Call f(s) if s.time() has reached the next multiple of the interval (solver::run_until
    /// calls it at its start and after every step).
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

namespace detail {
// Due at step 0 and every n steps, once per step.
class step_interval {
public:
    step_interval(std::uint64_t n, const char* name) : n_(n) { require(n >= 1, name, double(n), ">= 1"); }
    [[nodiscard]] bool due(std::uint64_t steps) {
        if (steps % n_ != 0 || steps == last_) return false;
        last_ = steps;
        return true;
    }

private:
    std::uint64_t n_;
    std::uint64_t last_ = std::numeric_limits<std::uint64_t>::max();
};
}  // namespace detail

/// Calls `f(solver)` at step 0 and every `n` steps.
template <class F>
class every_steps {
public:
    /// \param n the step interval, >= 1; \param f the callable.
    /// \throws gimlet::invalid_parameter if n is 0.
    every_steps(std::uint64_t n, F f) : when_(n, "observer step interval"), f_(std::move(f)) {}
    /// Call f(s) if s.steps() is a multiple of n and f has not yet been called at this step.
    template <class Solver>
    void maybe_call(const Solver& s) {
        if (when_.due(s.steps())) f_(s);
    }

private:
    detail::step_interval when_;
    F f_;
};

/// A user hook between steps: calls `f(solver)` with the solver **writable** at step 0 and every
/// `n` steps, so a user field can be updated (or particles changed) without re-writing
/// run_until. What it changes through `solver.particles()` is checked before the next step
/// uses it, and a bad value is blamed on its particle. The observers above get the solver read
/// only.
template <class F>
class between_steps {
public:
    /// \param n the step interval, >= 1; \param f the callable, given the solver writable.
    /// \throws gimlet::invalid_parameter if n is 0.
    between_steps(std::uint64_t n, F f) : when_(n, "hook step interval"), f_(std::move(f)) {}
    /// Call f(s) if s.steps() is a multiple of n and f has not yet been called at this step.
    template <class Solver>
    void maybe_call(Solver& s) {
        if (when_.due(s.steps())) f_(s);
    }

private:
    detail::step_interval when_;
    F f_;
};

}  // namespace gimlet::diagnostics
