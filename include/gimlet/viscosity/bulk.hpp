// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Bulk artificial viscosity with linear and quadratic terms.

#include "gimlet/core/error.hpp"
#include "gimlet/viscosity/concepts.hpp"

#include <cmath>

namespace gimlet::viscosity {

/// \f[ q = \rho\, l \left( c_Q\, l\, (\mathrm{tr} D)^2 + c_L\, c\, |\mathrm{tr} D| \right)
///     \quad \text{if } \mathrm{tr} D < 0, \qquad q = 0 \text{ otherwise} \f]
/// (von Neumann & Richtmyer 1950 quadratic term, Landshoff 1955 linear term; PHYSICS.md
/// section 5), l the particle length scale, c the current longitudinal wave speed. It acts in
/// compression only and adds to the EOS pressure; its work q |tr D| / rho enters the specific
/// internal energy through the stress power, so it heats the material in the EOS's energy.
/// Defaults are LS-DYNA's bulk-viscosity defaults (quadratic 1.5, linear 0.06).
class bulk {
public:
    static constexpr bool enabled = true;
    using required_fields = field_list<>;

    /// \param quadratic c_Q >= 0; \param linear c_L >= 0.
    explicit bulk(double quadratic = 1.5, double linear = 0.06) : cq_(quadratic), cl_(linear) {
        require_non_negative("artificial viscosity quadratic coefficient c_Q", quadratic);
        require_non_negative("artificial viscosity linear coefficient c_L", linear);
    }

    template <class Real, class P>
    [[nodiscard]] Real pressure(const point_step<Real>& st, Real sound_speed, const P& /*p*/) const {
        const Real div = st.D.trace();
        if (!(div < 0)) return Real(0);
        const Real l = st.length;
        return st.density * l * (Real(cq_) * l * div * div + Real(cl_) * sound_speed * (-div));
    }

    [[nodiscard]] double quadratic() const noexcept { return cq_; }
    [[nodiscard]] double linear() const noexcept { return cl_; }

private:
    double cq_, cl_;
};

static_assert(Viscosity<bulk>);

}  // namespace gimlet::viscosity
