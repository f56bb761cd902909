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

/// The Bardenhagen et al. (2000) correction of body `a` against the centre of mass of a pair at
/// one node, along the unit normal n (outward of a), with Coulomb coefficient mu; returns the
/// velocity change of body a, or zero if a is not approaching (docs/physics.md section 3):
/// approaching if (v_a - v_cm) . n > 0; then the normal relative velocity is removed and the
/// tangential one reduced by at most mu times the normal change (mu = inf: no slip).
/// With `kept` the normal constraint holds even if the body is separating
/// (node_view::kept_pairs). Sets `engaged` if it corrects.
/// Friction needs a compressive normal impulse: a kept pair that is separating is held along
/// the normal only.
template <class Vector, class Real>
[[nodiscard]] Vector coulomb_correction(const Vector& relative, const Vector& n, Real mu, bool kept, bool& engaged) {
    const Real approach = relative.dot(n);
    if (!(approach > Real(0)) && !kept) return Vector::Zero();
    engaged = true;
    Vector dv = -approach * n;
    if (!(approach > Real(0))) return dv;
    const Vector tangential = relative - approach * n;
    const Real slip = tangential.norm();
    if (slip > Real(0)) dv -= std::min(slip, mu * approach) / slip * tangential;
    return dv;
}

/// Apply the correction at a node to every pair of bodies there that `in_contact(a, b)` admits
/// and the pass allows (node_view::kept_pairs, open_pairs), recording the pairs it corrected in
/// node.engaged_pairs. A pair shares one normal, the average of its two bodies' own
/// (n = (n^a - n^b)/|n^a - n^b|), and exchanges equal and opposite momenta, so momentum is
/// conserved to round-off however many bodies meet. Two bodies: the correction of Bardenhagen
/// et al. (2000). More: pairs in turn, in the node's body order, each against its own centre of
/// mass (Bardenhagen et al. correct each body against the node's centre of mass along its own
/// normal, their eq. 19, which moves momentum into or out of the node where the normals of
/// three bodies do not cancel). A pair's correction can undo an earlier pair's, so with three
/// or more bodies the sweep is repeated until no engaged pair approaches or is pulled apart by
/// more than 1e-12 of the largest velocity there (at most 64 sweeps). Every correction removes
/// kinetic energy, so the repetition converges and creates none.
template <Space S, class InContact>
void correct(node_view<S>& node, typename S::real mu, InContact in_contact) {
    using real = typename S::real;
    using vector = typename S::vector;
    real speed = 0;
    for (std::size_t b = 0; b < node.count; ++b) speed = std::max(speed, real(node.momentum[b].norm() / node.mass[b]));
    const real tolerance = real(1e-12) * speed;
    const int sweeps = node.count > 2 ? 64 : 1;
    for (int sweep = 0; sweep < sweeps; ++sweep) {
        real largest = 0;  // the largest normal relative speed corrected in this sweep
        for (std::size_t a = 0; a + 1 < node.count; ++a) {
            for (std::size_t b = a + 1; b < node.count; ++b) {
                // A pair engaged by an earlier sweep is held from then on, as a kept one.
                const bool kept = node.kept(a, b) || (node.engaged_pairs & node.pair_bit(a, b));
                if (!kept && !node.open(a, b)) continue;
                const vector n = node.pair_normal(a, b);
                if (n.isZero() || !in_contact(a, b)) continue;
                const real m_ab = node.mass[a] + node.mass[b];
                const vector v_cm = (node.momentum[a] + node.momentum[b]) / m_ab;
                const vector relative = node.momentum[a] / node.mass[a] - v_cm;
                bool engaged = false;
                const vector dv = coulomb_correction(relative, n, mu, kept, engaged);
                if (!engaged) continue;
                largest = std::max(largest, std::abs(relative.dot(n)));
                node.momentum[a] += node.mass[a] * dv;
                node.momentum[b] -= node.mass[a] * dv;
                node.engaged_pairs |= node.pair_bit(a, b);
            }
        }
        if (!(largest > tolerance)) break;
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
