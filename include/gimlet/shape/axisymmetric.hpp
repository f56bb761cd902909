// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The axisymmetric forms of the shape functions: which shapes an axisymmetric solver
/// (axisymmetric_space) can use, and their radial factors.

#include "gimlet/shape/detail/axisymmetric_gimp.hpp"
#include "gimlet/shape/detail/stencil.hpp"
#include "gimlet/shape/linear.hpp"
#include "gimlet/shape/ugimp.hpp"

#include <array>

namespace gimlet::shape {

/// A shape's axisymmetric form: along r, the r-weighted weight, gradient and hoop factor of each
/// node of its stencil (gimlet::radial_factors; docs/equations.md, "Axisymmetric GIMP");
/// along z the shape's own 1-D factors. Defined for ugimp and linear; a shape without one is
/// refused by an axisymmetric solver at compile time.
///
/// `radial(r_p, half, h, first, f)`: for a particle at radius r_p > 0 (m) of half-width `half`
/// (m; unused by linear) on cells of h (m), the axis at r = 0 and node k at r = k h: the stencil's
/// first node `first` and node first + a's factors f[a]; a node beyond the axis (k < 0) has none.
template <class Sh>
struct axisymmetric_form;

/// uGIMP's: the r-weighted average over the particle's domain, clipped at the axis.
template <>
struct axisymmetric_form<ugimp> {
    /// The factors of the stencil's nodes along r (the primary template's `radial`).
    template <class Real>
    static void radial(Real r_p, Real half, Real h, int& first,
                       std::array<radial_factors<Real>, ugimp::stencil>& f) noexcept {
        detail::axisymmetric_gimp_radial_stencil(r_p, half, h, first, f);
    }
};

/// Linear MPM's: the point particle's S = N_i(r_p), G = N_i'(r_p), T = N_i(r_p) / r_p.
template <>
struct axisymmetric_form<linear> {
    /// The factors of the stencil's nodes along r (the primary template's `radial`).
    template <class Real>
    static void radial(Real r_p, Real /*half*/, Real h, int& first,
                       std::array<radial_factors<Real>, linear::stencil>& f) noexcept {
        (void)detail::locate<linear::stencil>(r_p / h, first);
        for (int a = 0; a < linear::stencil; ++a) {
            const int k = first + a;
            f[a] = k < 0 ? radial_factors<Real>{} : detail::axisymmetric_linear_radial(r_p, Real(k) * h, h);
        }
    }
};

/// Whether shape Sh has an axisymmetric form (axisymmetric_form).
template <class Sh>
concept has_axisymmetric_form = requires(double r, int& first, std::array<radial_factors<double>, Sh::stencil>& f) {
    axisymmetric_form<Sh>::radial(r, r, r, first, f);
};

}  // namespace gimlet::shape
