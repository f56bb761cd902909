// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Bulk artificial viscosity with linear and quadratic terms on the cell scale.

#include "gimlet/core/detail/inline.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/viscosity/concepts.hpp"

#include <cmath>
#include <concepts>
#include <type_traits>

namespace gimlet::viscosity {

/// Bulk artificial viscosity, quadratic and linear in the compression rate:
/// \f[ q = \rho\, h \left( b_2^2\, h\, \dot\varepsilon_v^2 + b_1\, c\, |\dot\varepsilon_v| \right)
///     \quad \text{if } \dot\varepsilon_v = \mathrm{tr} D < 0, \qquad q = 0 \text{ otherwise} \f]
/// (von Neumann & Richtmyer 1950 quadratic term, Landshoff 1955 linear term, with the terms of
/// the Abaqus/Explicit bulk viscosity but both in compression only, where Abaqus keeps its linear
/// term in expansion too; docs/equations.md), h the grid cell size (the length over
/// which the grid resolves a shock), c the current longitudinal wave speed. It acts in
/// compression only and adds to the EOS pressure; its work enters the specific internal energy
/// through the stress power, so it heats the material. Defaults are Abaqus/Explicit's,
/// b1 = 0.06 and b2 = 1.2 (quadratic coefficient b2^2 = 1.44).
///
/// It also bounds the time step: with q, a compressing particle's stable step is that of a
/// signal speed Q + sqrt(Q^2 + c^2), Q = b1 c + b2^2 h |tr D| (the damped-oscillator limit
/// dt = (2 / omega) (sqrt(1 + xi^2) - xi), xi = Q / c, of the Abaqus/Explicit theory manual).
class bulk {
public:
    /// On: the solver computes q (viscosity::Viscosity).
    static constexpr bool enabled = true;
    /// `pressure` takes the wave speed as a callable and asks for it only in compression.
    static constexpr bool lazy_sound_speed = true;  // q reads the wave speed only in compression
    /// Keeps the compression rate for the time step (signal_speed).
    using required_fields = field_list<fields::compression_rate>;

    /// \param quadratic b2 >= 0 (q's quadratic term has b2 squared); \param linear b1 >= 0.
    explicit bulk(double quadratic = 1.2, double linear = 0.06) : b2_(quadratic), b1_(linear) {
        require_non_negative("artificial viscosity quadratic coefficient b2", quadratic);
        require_non_negative("artificial viscosity linear coefficient b1", linear);
    }

    /// q (Pa) for the step `st` (st.length is the cell size); records the compression rate.
    /// `sound_speed` is the wave speed, or a callable that returns it (`lazy_sound_speed`: the
    /// material update passes one): it is then asked for only in compression, where q reads it.
    template <class Real, class C, class P>
        requires std::convertible_to<C, Real> || std::is_invocable_r_v<Real, const C&>
    [[nodiscard]] GIMLET_INLINE Real pressure(const point_step<Real>& st, const C& sound_speed, const P& p) const {
        const Real rate = st.D.trace() < 0 ? -st.D.trace() : Real(0);
        p.template get<fields::compression_rate>() = rate;
        if (!(rate > 0)) return Real(0);
        const Real h = st.length;
        Real c;
        if constexpr (std::is_invocable_r_v<Real, const C&>) c = sound_speed();
        else c = Real(sound_speed);
        return st.density * h * (Real(b2_ * b2_) * h * rate * rate + Real(b1_) * c * rate);
    }

    /// The signal speed that sets the stable time step of particle p with wave speed c on cells
    /// of size h: c without compression, Q + sqrt(Q^2 + c^2) with it (above).
    template <class Real, class P>
    [[nodiscard]] Real signal_speed(Real sound_speed, Real h, const P& p) const {
        const Real rate = p.template get<fields::compression_rate>();
        if (!(rate > 0)) return sound_speed;
        const Real q = Real(b1_) * sound_speed + Real(b2_ * b2_) * h * rate;
        return q + std::sqrt(q * q + sound_speed * sound_speed);
    }

    /// b2 (q's quadratic term has b2 squared).
    [[nodiscard]] double quadratic() const noexcept { return b2_; }
    /// b1, the linear coefficient.
    [[nodiscard]] double linear() const noexcept { return b1_; }

private:
    double b2_, b1_;
};

static_assert(Viscosity<bulk>);

}  // namespace gimlet::viscosity
