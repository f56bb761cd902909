// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Simple solid geometry for building bodies: boxes (rectangles in 2-D), balls (circles in 2-D)
/// and boolean difference (a block with a cavity). A region is anything with `contains(x)` and
/// an axis-aligned bounding box; users can write their own.

#include "gimlet/core/error.hpp"
#include "gimlet/core/space.hpp"

#include <cmath>
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
    /// A point of S.
    using vector = typename S::vector;
    /// \param lo lower corner (m); \param hi upper corner (m).
    /// \throws gimlet::invalid_parameter unless every coordinate is finite and hi > lo on every axis.
    box(const vector& lo, const vector& hi) : lo_(lo), hi_(hi) {
        for (int d = 0; d < S::dim; ++d) {
            require(std::isfinite(double(lo[d])) && std::isfinite(double(hi[d])) && hi[d] > lo[d],
                    std::string("box extent along axis ") + std::to_string(d) + " (hi - lo, m)",
                    double(hi[d]) - double(lo[d]), "finite and > 0");
        }
    }
    /// True if x lies in the box or on its boundary.
    [[nodiscard]] bool contains(const vector& x) const {
        return (x.array() >= lo_.array()).all() && (x.array() <= hi_.array()).all();
    }
    /// The lower corner (m).
    [[nodiscard]] vector lower() const { return lo_; }
    /// The upper corner (m).
    [[nodiscard]] vector upper() const { return hi_; }

private:
    vector lo_, hi_;
};

/// Ball of given centre and radius (a circle in 2-D). Points on the sphere belong to it.
template <Space S>
class ball {
public:
    /// A point of S.
    using vector = typename S::vector;
    /// The scalar type of S.
    using real = typename S::real;
    /// \param centre the centre (m); \param radius the radius (m).
    /// \throws gimlet::invalid_parameter unless radius > 0 and the centre is finite.
    ball(const vector& centre, real radius) : c_(centre), r_(radius) {
        require_positive("ball radius (m)", double(radius));
        for (int d = 0; d < S::dim; ++d) require_finite("ball centre coordinate (m)", double(centre[d]));
    }
    /// True if x lies in the ball or on its sphere.
    [[nodiscard]] bool contains(const vector& x) const { return (x - c_).squaredNorm() <= r_ * r_; }
    /// The lower corner of the bounding box: centre - radius (m).
    [[nodiscard]] vector lower() const { return c_.array() - r_; }
    /// The upper corner of the bounding box: centre + radius (m).
    [[nodiscard]] vector upper() const { return c_.array() + r_; }
    /// The centre (m).
    [[nodiscard]] const vector& centre() const { return c_; }
    /// The radius (m).
    [[nodiscard]] real radius() const { return r_; }

private:
    vector c_;
    real r_;
};

}  // namespace gimlet::scene

namespace gimlet::detail {
template <class T>
inline constexpr bool is_scene_box = false;
template <Space S>
inline constexpr bool is_scene_box<scene::box<S>> = true;
template <class T>
inline constexpr bool is_scene_ball = false;
template <Space S>
inline constexpr bool is_scene_ball<scene::ball<S>> = true;
}  // namespace gimlet::detail

namespace gimlet::scene {

/// Points of A that are not in B: a block with a cavity is difference(box, ball).
///
/// Validated: B must overlap A (a cavity that misses its block is misplaced, often by a unit
/// slip). For a box minus a ball the check is exact: the radius must exceed the distance from
/// the centre to the box. A ball that pokes out of its box (a notch) is allowed; a cavity that
/// removes the whole block is refused when the solver fills it (no particles).
template <class A, class B>
class difference {
public:
    /// \param a the region kept; \param b the region removed from it.
    /// \throws gimlet::invalid_parameter if b does not overlap a (see the class's comment).
    difference(A a, B b) : a_(std::move(a)), b_(std::move(b)) {
        if constexpr (gimlet::detail::is_scene_box<A> && gimlet::detail::is_scene_ball<B>) {
            double nearest = 0;
            std::string where = "(";
            for (int d = 0; d < int(b_.centre().size()); ++d) {
                const double c = double(b_.centre()[d]), lo = double(a_.lower()[d]), hi = double(a_.upper()[d]);
                const double out = c < lo ? lo - c : c > hi ? c - hi : 0.0;
                nearest += out * out;
                where += (d ? ", " : "") + gimlet::detail::to_text(c);
            }
            nearest = std::sqrt(nearest);
            require(double(b_.radius()) > nearest, "cavity (ball) radius (m)", double(b_.radius()),
                    "> " + gimlet::detail::to_text(nearest) + ", the distance from its centre " + where +
                        ") m to the block: a smaller ball misses the block");
        } else {
            const auto alo = a_.lower(), ahi = a_.upper(), blo = b_.lower(), bhi = b_.upper();
            for (int d = 0; d < int(alo.size()); ++d) {
                require(double(blo[d]) < double(ahi[d]) && double(bhi[d]) > double(alo[d]),
                        std::string("removed region's extent along ") + "xyz"[d] + " (m, upper end; lower end " +
                            gimlet::detail::to_text(double(blo[d])) + ")",
                        double(bhi[d]),
                        "overlapping the region it is removed from, [" + gimlet::detail::to_text(double(alo[d])) +
                            ", " + gimlet::detail::to_text(double(ahi[d])) + "]");
            }
        }
    }
    /// True if x is in a and not in b.
    template <class V>
    [[nodiscard]] bool contains(const V& x) const {
        return a_.contains(x) && !b_.contains(x);
    }
    /// The lower corner of a's bounding box (b only removes).
    [[nodiscard]] auto lower() const { return a_.lower(); }
    /// The upper corner of a's bounding box.
    [[nodiscard]] auto upper() const { return a_.upper(); }
    /// The region kept, a.
    [[nodiscard]] const A& outer() const { return a_; }
    /// The region removed, b.
    [[nodiscard]] const B& removed() const { return b_; }

private:
    A a_;
    B b_;
};

}  // namespace gimlet::scene
