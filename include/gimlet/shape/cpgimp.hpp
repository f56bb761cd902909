// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Convected-particle-domain GIMP (cpGIMP): the particle box stretches with the material.

#include "gimlet/core/fields.hpp"
#include "gimlet/shape/concepts.hpp"
#include "gimlet/shape/detail/gimp_kernel.hpp"

#include <array>

namespace gimlet::shape {

/// cpGIMP: the GIMP weight of ugimp, with a half-width that follows the deformation, so a
/// stretched particle still covers the space it occupies (Bardenhagen & Kober 2004;
/// Wallstedt & Guilkey 2008; docs/physics.md section 2). The box stays axis-aligned: per axis,
/// `l_d = l0_d |F_dd|`, the stretch along that axis; shear is not followed (that needs CPDI).
struct cpgimp {
    static constexpr const char* name = "cpgimp";  ///< for output and tables
    static constexpr int stencil = detail::gimp_stencil;
    using required_fields = gimlet::field_list<gimlet::fields::domain_half_width>;

    /// \tparam Real float or double. \pre 0 < l <= 1/2 (half_width guarantees it).
    template <class Real>
    static void weights(Real x, Real l, int& first, Real* w, Real* dw) noexcept {
        detail::gimp_weights(x, l, first, w, dw);
    }

#if defined(__GNUC__)
    /// Both axes of a 2-D particle at once, the same numbers as weights() axis by axis, bit for
    /// bit (an optional member: detail::stencil uses it where a shape has one and names itself in
    /// weights_2d_shape, so that a shape derived from this one, with weights() of its own, does not
    /// inherit it; why, at detail::gimp_weights_2d).
    using weights_2d_shape = cpgimp;
    static void weights_2d(const std::array<double, 2>& x, const std::array<double, 2>& l, std::array<int, 2>& first,
                           std::array<std::array<double, stencil>, 2>& w,
                           std::array<std::array<double, stencil>, 2>& dw) noexcept {
        detail::gimp_weights_2d(x, l, first, w, dw);
    }
#endif

    /// `domain_half_width_d * |F_dd| / h` per axis, in cell units, at most 1/2.
    ///
    /// The cap keeps the support within the 3-node stencil (a half-width above 1/2 cell would
    /// reach a fourth node and the weights would stop summing to one). A particle stretched
    /// that far has already left gaps between neighbours, so the capped box under-covers its
    /// material instead of breaking partition of unity for everyone it touches.
    template <class P, class Real>
    [[nodiscard]] static typename P::space_type::vector half_width(const P& p, Real h) {
        using real = typename P::space_type::real;
        const auto& l0 = p.template get<gimlet::fields::domain_half_width>();
        const auto& f = p.template get<gimlet::fields::deformation_gradient>();
        return (l0.array() * f.diagonal().array().abs() / static_cast<real>(h))
            .min(real(0.5))
            .matrix();
    }
};

}  // namespace gimlet::shape

static_assert(gimlet::shape::Shape<gimlet::shape::cpgimp>);
