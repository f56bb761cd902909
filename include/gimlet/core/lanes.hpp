// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Two particles in the lanes of one vector. `lanes2` is a pair of doubles that behaves as one
/// number under + - * / and negation, each operation taken lane by lane, so that a policy
/// written as a template on its scalar (`template <class Real, class P> ... update(const
/// point_step<Real>&, ...)`) computes two particles at once when Real is lanes2, with the same
/// IEEE operations, in the same order, as for each particle alone: the same bits. The solver
/// takes this path for the material update where every policy of the material says it is safe
/// (`lane_safe`, below; docs/concepts.md, "Two particles at once"). It uses the vector
/// extension of GCC and clang, on x86-64 without FMA only (below): no header, no library.
///
/// What lanes2 does not have is a comparison that yields one bool: a branch on a value would
/// have to take one side for both particles. Comparisons give a `lanes2_mask`, which converts
/// to bool only through all() and any().
///
/// GIMLET_HAS_LANES is 1 on x86-64 without FMA (where a pair rounds as its two particles do)
/// and 0 elsewhere; define it to 0 before including gimlet to update one particle at a time
/// everywhere (the results are the same bits). This reference documents the lane types as
/// compiled where it is 1.

#include <Eigen/Core>

#include <limits>

// Only where both paths round alike: x86-64 (SSE2 arithmetic on doubles, no x87 excess
// precision) without FMA. Where the compiler may fuse a multiply and an add (-mfma, a
// -march=native build on a recent x86, every arm64 target), it can fuse a * b - c * d in the
// one-particle code but not across lanes2's separate operations, so a pair would differ from
// its particles in the last bits: the solver then updates one particle at a time. A user may
// define GIMLET_HAS_LANES to 0 to update one particle at a time everywhere (the results are
// the same bits).
#ifndef GIMLET_HAS_LANES
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__) && defined(__SSE2__) && !defined(__FMA__)
#define GIMLET_HAS_LANES 1
#else
#define GIMLET_HAS_LANES 0
#endif
#endif

namespace gimlet {

/// Whether a scalar type is a lane type (the material update's checks are written for both).
template <class Real>
inline constexpr bool is_lanes = false;

#if GIMLET_HAS_LANES

/// The two-double vector of the GCC/clang vector extension that holds a lanes2.
using lanes2_vec = double __attribute__((vector_size(16)));

/// Per lane, whether a comparison holds.
struct lanes2_mask {
    /// The vector of per-lane results the extension's comparison gives (all bits set where true).
    using bits = decltype(lanes2_vec{} > lanes2_vec{});  // what the extension's comparison gives
    /// The comparison's result, lane by lane.
    bits m;
    /// True if the comparison holds in both lanes.
    [[nodiscard]] bool all() const noexcept { return m[0] != 0 && m[1] != 0; }
    /// True if the comparison holds in at least one lane.
    [[nodiscard]] bool any() const noexcept { return m[0] != 0 || m[1] != 0; }
    /// Lane-by-lane and of two masks.
    friend lanes2_mask operator&&(lanes2_mask a, lanes2_mask b) noexcept { return {a.m & b.m}; }
};

/// Two doubles computed lane by lane (see the file's comment).
struct lanes2 {
    /// The vector type that holds the two lanes.
    using vec = lanes2_vec;
    /// The two values, lane 0 and lane 1.
    vec v;

    /// Uninitialised, as a double is.
    lanes2() = default;
    /// The same value in both lanes (what `Real(0.5)` or `real q = 0` means for a lane type).
    constexpr lanes2(double a) noexcept : v{a, a} {}  // NOLINT: implicit, as a double literal converts
    /// Lane 0 holds a, lane 1 holds b.
    constexpr lanes2(double a, double b) noexcept : v{a, b} {}
    /// Wraps a vector of the extension.
    [[nodiscard]] static lanes2 of(vec x) noexcept {
        lanes2 r;
        r.v = x;
        return r;
    }
    /// The value in `lane` (0 or 1).
    [[nodiscard]] double operator[](int lane) const noexcept { return v[lane]; }

    ///@{
    /// Arithmetic lane by lane: in each lane the same IEEE operation as on a double.
    friend lanes2 operator+(lanes2 a, lanes2 b) noexcept { return of(a.v + b.v); }
    friend lanes2 operator-(lanes2 a, lanes2 b) noexcept { return of(a.v - b.v); }
    friend lanes2 operator*(lanes2 a, lanes2 b) noexcept { return of(a.v * b.v); }
    friend lanes2 operator/(lanes2 a, lanes2 b) noexcept { return of(a.v / b.v); }
    friend lanes2 operator-(lanes2 a) noexcept { return of(-a.v); }
    friend lanes2 operator+(lanes2 a) noexcept { return a; }
    lanes2& operator+=(lanes2 b) noexcept { return v = v + b.v, *this; }
    lanes2& operator-=(lanes2 b) noexcept { return v = v - b.v, *this; }
    lanes2& operator*=(lanes2 b) noexcept { return v = v * b.v, *this; }
    lanes2& operator/=(lanes2 b) noexcept { return v = v / b.v, *this; }
    ///@}

    ///@{
    /// Comparison lane by lane: a lanes2_mask, which a branch reduces with all() or any().
    friend lanes2_mask operator>(lanes2 a, lanes2 b) noexcept { return {a.v > b.v}; }
    friend lanes2_mask operator<(lanes2 a, lanes2 b) noexcept { return {a.v < b.v}; }
    friend lanes2_mask operator>=(lanes2 a, lanes2 b) noexcept { return {a.v >= b.v}; }
    friend lanes2_mask operator<=(lanes2 a, lanes2 b) noexcept { return {a.v <= b.v}; }
    friend lanes2_mask operator==(lanes2 a, lanes2 b) noexcept { return {a.v == b.v}; }
    ///@}
};

/// Per lane, whether x is finite (x - x is +0 exactly for a finite x, NaN for an infinity or a
/// NaN).
[[nodiscard]] inline lanes2_mask finite_lanes(lanes2 x) noexcept { return x - x == lanes2(0.0); }

/// lanes2 is a lane type.
template <>
inline constexpr bool is_lanes<lanes2> = true;
#endif

/// Whether a condition holds: a bool as it is; a lane mask in every lane (for the assertions
/// of code written for both).
[[nodiscard]] constexpr bool all_lanes(bool b) noexcept { return b; }
#if GIMLET_HAS_LANES
/// True if the mask holds in both lanes.
[[nodiscard]] inline bool all_lanes(lanes2_mask m) noexcept { return m.all(); }
#endif

/// A constitutive policy whose templates on Real compute lane by lane when Real is a lane type,
/// with the operations it would take on each double in the same order, and that says so:
/// `static constexpr bool lane_safe = true;`. The promise (docs/concepts.md, "Two particles at
/// once"): no branch, comparison or library call on a Real value; no Eigen reduction over
/// three or more stored entries (sum, squaredNorm, dot: Eigen orders them differently for
/// double); no long double; nothing read or written through the particle handle.
template <class Policy>
concept lane_safe = requires {
    requires bool(Policy::lane_safe);
};

}  // namespace gimlet

#if GIMLET_HAS_LANES
namespace Eigen {
/// lanes2 as an Eigen scalar: no packets of its own (each lanes2 is already one), no
/// initialisation required.
template <>
struct NumTraits<gimlet::lanes2> : GenericNumTraits<double> {
    ///@{
    /// lanes2 itself: a lanes2 is real, non-integer, and its own literal and nested type.
    using Real = gimlet::lanes2;
    using NonInteger = gimlet::lanes2;
    using Literal = gimlet::lanes2;
    using Nested = gimlet::lanes2;
    ///@}
    enum { IsComplex = 0, IsInteger = 0, IsSigned = 1, RequireInitialization = 0, ReadCost = 1, AddCost = 1, MulCost = 1 };
};
}  // namespace Eigen

/// std::numeric_limits of a lane type: those of double, in both lanes (without it,
/// numeric_limits<lanes2>::epsilon() would be a value-initialised lanes2: zero).
template <>
struct std::numeric_limits<gimlet::lanes2> : std::numeric_limits<double> {
    ///@{
    /// The limit of double, in both lanes.
    static constexpr gimlet::lanes2 min() noexcept { return std::numeric_limits<double>::min(); }
    static constexpr gimlet::lanes2 max() noexcept { return std::numeric_limits<double>::max(); }
    static constexpr gimlet::lanes2 lowest() noexcept { return std::numeric_limits<double>::lowest(); }
    static constexpr gimlet::lanes2 epsilon() noexcept { return std::numeric_limits<double>::epsilon(); }
    static constexpr gimlet::lanes2 round_error() noexcept { return std::numeric_limits<double>::round_error(); }
    static constexpr gimlet::lanes2 infinity() noexcept { return std::numeric_limits<double>::infinity(); }
    static constexpr gimlet::lanes2 quiet_NaN() noexcept { return std::numeric_limits<double>::quiet_NaN(); }
    static constexpr gimlet::lanes2 signaling_NaN() noexcept { return std::numeric_limits<double>::signaling_NaN(); }
    static constexpr gimlet::lanes2 denorm_min() noexcept { return std::numeric_limits<double>::denorm_min(); }
    ///@}
};
#endif
