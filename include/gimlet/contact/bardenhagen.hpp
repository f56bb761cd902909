// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Multi-velocity-field contact with Coulomb friction (Bardenhagen et al. 2000).

#include "gimlet/contact/concepts.hpp"
#include "gimlet/contact/node.hpp"
#include "gimlet/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gimlet::contact {

namespace detail {

/// The Bardenhagen et al. (2000) correction of body `a` against the centre of mass at one node,
/// along the unit normal n (outward of a), with Coulomb coefficient mu; returns the velocity
/// change of body a, or zero if a is not approaching (PHYSICS.md section 3):
/// approaching if (v_a - v_cm) . n > 0; then the normal relative velocity is removed and the
/// tangential one reduced by at most mu times the normal change (mu = inf: no slip).
/// With `constrained` the normal constraint is kept even if the body is separating (MUSL's
/// re-mapping pass at a node the grid update engaged; see node_view::constrained).
template <class Vector, class Real>
[[nodiscard]] Vector coulomb_correction(const Vector& relative, const Vector& n, Real mu, bool constrained,
                                        bool& engaged) {
    const Real approach = relative.dot(n);
    if (!(approach > Real(0)) && !constrained) return Vector::Zero();
    engaged = true;
    const Vector tangential = relative - approach * n;
    const Real slip = tangential.norm();
    Vector dv = -approach * n;
    if (slip > Real(0)) dv -= std::min(slip, mu * std::abs(approach)) / slip * tangential;
    return dv;
}

/// Apply the correction at a node (and record in node.engaged whether it did). Two bodies share one normal, the average of their own
/// (n = (n^A - n^B)/|n^A - n^B|), and exchange equal and opposite momenta, so momentum is
/// conserved to round-off. With more bodies each is corrected against the centre of mass along
/// its own normal (Bardenhagen et al. 2000, eq. 19). `engaged(a, b)` can veto a pair.
template <Space S, class Engaged>
void correct(node_view<S>& node, typename S::real mu, Engaged engaged) {
    using real = typename S::real;
    using vector = typename S::vector;
    real m_total = 0;
    vector p_total = vector::Zero();
    for (std::size_t b = 0; b < node.count; ++b) m_total += node.mass[b], p_total += node.momentum[b];
    const vector v_cm = p_total / m_total;
    if (node.count == 2) {
        const vector d = node.normal[0] - node.normal[1];
        const real len = d.norm();
        if (!(len > real(0)) || !engaged(0, 1)) return;
        const vector n = d / len;
        const vector dv =
            coulomb_correction(vector(node.momentum[0] / node.mass[0] - v_cm), n, mu, node.constrained, node.engaged);
        node.momentum[0] += node.mass[0] * dv;
        node.momentum[1] -= node.mass[0] * dv;
        return;
    }
    for (std::size_t b = 0; b < node.count; ++b) {
        bool any = false;
        for (std::size_t o = 0; o < node.count; ++o) any = any || (o != b && engaged(b, o));
        if (!any) continue;
        const vector dv = coulomb_correction(vector(node.momentum[b] / node.mass[b] - v_cm), node.normal[b], mu,
                                             node.constrained, node.engaged);
        node.momentum[b] += node.mass[b] * dv;
    }
}

}  // namespace detail

/// Bardenhagen, Guilkey, Roessig, Brackbill, Witzel & Foster (2000), "An improved contact
/// algorithm for the material point method and application to stress propagation in granular
/// material": each body maps its own velocity field; where bodies share a node and approach
/// each other, their normal velocities are set to the centre-of-mass one and the tangential
/// slip is resisted by Coulomb friction. Bodies separate freely. Contact starts as soon as two
/// bodies share a node, that is up to about two cells early: the reference paper's criticism,
/// which contact::distance answers.
class bardenhagen {
public:
    static constexpr bool multi_field = true;
    using required_fields = field_list<>;

    /// \param friction Coulomb coefficient mu >= 0 (0: frictionless; infinity: no slip).
    explicit bardenhagen(double friction = 0.0) : mu_(friction) {
        require(!std::isnan(friction) && friction >= 0.0, "contact friction coefficient mu", friction, ">= 0");
    }

    template <Space S>
    void resolve(node_view<S>& node) const {
        detail::correct(node, typename S::real(mu_), [](std::size_t, std::size_t) { return true; });
    }

    [[nodiscard]] double friction() const noexcept { return mu_; }

private:
    double mu_;
};

static_assert(Contact<bardenhagen>);

}  // namespace gimlet::contact
