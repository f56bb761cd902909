// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Simple solid geometry for building bodies: boxes (rectangles in 2-D), balls (circles in 2-D)
/// and boolean difference (a block with a cavity). A region is anything with `contains(x)` and
/// an axis-aligned bounding box; users can write their own.

#include "gimlet/core/error.hpp"
#include "gimlet/core/space.hpp"

#include <concepts>
#include <string>

namespace gimlet::scene {

/// A region of space that a body fills.
template <class R, class S>
concept Region = requires(const R& r, const typename S::vector& x) {
    { r.contains(x) } -> std::convertible_to<bool>;
    { r.lower() } -> std::convertible_to<typename S::vector>;
    { r.upper() } -> std::convertible_to<typename S::vector>;
};

/// Axis-aligned box [lo, hi] (a rectangle in 2-D). Points on the boundary belong to it.
template <Space S>
class box {
public:
    using vector = typename S::vector;
    box(const vector& lo, const vector& hi) : lo_(lo), hi_(hi) {
        for (int d = 0; d < S::dim; ++d) {
            require(std::isfinite(double(lo[d])) && std::isfinite(double(hi[d])) && hi[d] > lo[d],
                    std::string("box extent along axis ") + std::to_string(d) + " (hi - lo, m)",
                    double(hi[d]) - double(lo[d]), "finite and > 0");
        }
    }
    [[nodiscard]] bool contains(const vector& x) const {
        return (x.array() >= lo_.array()).all() && (x.array() <= hi_.array()).all();
    }
    [[nodiscard]] vector lower() const { return lo_; }
    [[nodiscard]] vector upper() const { return hi_; }

private:
    vector lo_, hi_;
};

/// Ball of given centre and radius (a circle in 2-D). Points on the sphere belong to it.
template <Space S>
class ball {
public:
    using vector = typename S::vector;
    using real = typename S::real;
    ball(const vector& centre, real radius) : c_(centre), r_(radius) {
        require_positive("ball radius (m)", double(radius));
        for (int d = 0; d < S::dim; ++d) require_finite("ball centre coordinate (m)", double(centre[d]));
    }
    [[nodiscard]] bool contains(const vector& x) const { return (x - c_).squaredNorm() <= r_ * r_; }
    [[nodiscard]] vector lower() const { return c_.array() - r_; }
    [[nodiscard]] vector upper() const { return c_.array() + r_; }
    [[nodiscard]] const vector& centre() const { return c_; }
    [[nodiscard]] real radius() const { return r_; }

private:
    vector c_;
    real r_;
};

/// Points of A that are not in B: a block with a cavity is difference(box, ball).
template <class A, class B>
class difference {
public:
    difference(A a, B b) : a_(std::move(a)), b_(std::move(b)) {}
    template <class V>
    [[nodiscard]] bool contains(const V& x) const {
        return a_.contains(x) && !b_.contains(x);
    }
    [[nodiscard]] auto lower() const { return a_.lower(); }
    [[nodiscard]] auto upper() const { return a_.upper(); }
    [[nodiscard]] const A& outer() const { return a_; }
    [[nodiscard]] const B& removed() const { return b_; }

private:
    A a_;
    B b_;
};

}  // namespace gimlet::scene
