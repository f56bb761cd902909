// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Uniform GIMP (uGIMP): each particle a box of fixed half-width, the paper's shape function.

#include "gimlet/core/fields.hpp"
#include "gimlet/shape/concepts.hpp"
#include "gimlet/shape/detail/gimp_kernel.hpp"

#include <cmath>
#include <concepts>

namespace gimlet::shape {

/// Uniform GIMP: the hat averaged over a particle domain of fixed half-width l_p
/// (Bardenhagen & Kober 2004; docs/physics.md section 2), C1 so particles crossing cell edges do not
/// kick the grid. The half-width never changes with the deformation; see cpgimp for one that
/// does.
///
/// With l_p = h/4 (2x2 particles per cell) it is the reference paper's Φ (eq-mpm-shape, see
/// paper_phi). The 1-D function and its branches are in detail::gimp_kernel.
struct ugimp : detail::gimp_weights_of<ugimp> {
    static constexpr const char* name = "ugimp";  ///< for output and tables
    /// It reads the particle's domain half-width.
    using required_fields = gimlet::field_list<gimlet::fields::domain_half_width>;

    /// The particle's initial half-width in cell units: `domain_half_width / h`.
    template <class P, class Real>
    [[nodiscard]] static typename P::space_type::vector half_width(const P& p, Real h) {
        using real = typename P::space_type::real;
        return p.template get<gimlet::fields::domain_half_width>() / static_cast<real>(h);
    }
};

/// The reference paper's Φ (eq-mpm-shape), `r = |x_p - x_i| / L` in cell units, with its
/// misprint corrected (docs/physics.md section 2): the paper prints the inner branch as
/// (7 - 16r²)/16, which jumps from 3/8 to 3/4 at r = 1/4 and breaks partition of unity; the
/// branch is (7 - 16r²)/8.
///
/// It equals ugimp's weight at l = 1/4. It is kept in the paper's own branches rather than
/// forwarded to ugimp so that the two forms check each other in the tests.
template <std::floating_point Real>
[[nodiscard]] Real paper_phi(Real r) noexcept {
    const Real a = std::abs(r);
    if (a <= Real(0.25)) return (Real(7) - Real(16) * a * a) / Real(8);
    if (a <= Real(0.75)) return Real(1) - a;
    if (a <= Real(1.25)) return (Real(5) - Real(4) * a) * (Real(5) - Real(4) * a) / Real(16);
    return Real(0);
}

}  // namespace gimlet::shape

static_assert(gimlet::shape::Shape<gimlet::shape::ugimp>);
