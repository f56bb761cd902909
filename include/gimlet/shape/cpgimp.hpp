// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Convected-particle-domain GIMP (cpGIMP): the particle box stretches with the material.

#include "gimlet/core/fields.hpp"
#include "gimlet/shape/concepts.hpp"
#include "gimlet/shape/detail/gimp_kernel.hpp"

namespace gimlet::shape {

/// cpGIMP: the GIMP weight of ugimp, with a half-width that follows the deformation, so a
/// stretched particle still covers the space it occupies (Bardenhagen & Kober 2004;
/// Wallstedt & Guilkey 2008; docs/physics.md section 2). The box stays axis-aligned: per axis,
/// `l_d = l0_d |F_dd|`, the stretch along that axis; shear is not followed (that needs CPDI).
struct cpgimp : detail::gimp_weights_of<cpgimp> {
    static constexpr const char* name = "cpgimp";  ///< for output and tables
    /// It reads the particle's initial domain half-width.
    using required_fields = gimlet::field_list<gimlet::fields::domain_half_width>;

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
