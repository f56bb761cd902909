// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The multi-field contact framework at one node: which pairs a pass may engage, the law's
/// decisions, the projection of what the law asks onto the dissipative set, and the momentum
/// bookkeeping (docs/equations.md, Contact; docs/concepts.md, Contact).

#include "gimlet/contact/concepts.hpp"
#include "gimlet/contact/node.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>

namespace gimlet::multi_field {

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

namespace detail {

/// The tangential part of `wanted` for a pair whose normal impulse has magnitude `normal` >= 0:
/// against the slip, at most all of it and at most mu times `normal` (mu = inf: no slip);
/// zero if the pair does not press (normal = 0) or the law asks for nothing finite.
template <Space S>
[[nodiscard]] typename S::vector tangential_part(const contact::pair_view<S>& pair, const typename S::vector& wanted,
                                                 typename S::real mu, typename S::real normal) {
    using real = typename S::real;
    using vector = typename S::vector;
    const vector slip = pair.slip();
    const real speed = slip.norm();
    if (!(speed > real(0) && normal > real(0))) return vector::Zero();
    const vector along = slip / speed;
    const real limit = std::min(pair.reduced_mass() * speed, mu * normal);
    const real tangential = std::clamp(real(-wanted.dot(along)), real(0), limit);
    return std::isfinite(tangential) ? vector(-tangential * along) : vector(vector::Zero());
}

}  // namespace detail

/// The momentum body a may receive from `wanted` (b receives the opposite), projected onto the
/// dissipative set of the pair (contact::Law): along the normal, between none and all of the
/// approach; across it, against the slip, at most all of the slip and at most mu times the
/// normal part. Components that neither oppose the approach nor the slip are dropped.
template <Space S>
[[nodiscard]] typename S::vector dissipative_impulse(const contact::pair_view<S>& pair, const typename S::vector& wanted,
                                                     typename S::real mu) {
    using real = typename S::real;
    using vector = typename S::vector;
    const real stop = pair.reduced_mass() * pair.approach();  // > 0: the pair approaches
    const real normal = std::clamp(real(-wanted.dot(pair.normal)), real(0), stop);
    if (!std::isfinite(normal)) return vector::Zero();  // a NaN impulse does nothing
    return vector(-normal * pair.normal + detail::tangential_part(pair, wanted, mu, normal));
}

namespace detail {

/// Whether law L asks for its own impulse.
template <class L, class S>
concept has_impulse = requires(const L& l, const contact::pair_view<S>& p) {
    { l.impulse(p) } -> std::convertible_to<typename S::vector>;
};

struct no_tally {};

}  // namespace detail

/// Corrects the bodies' momenta at one node for a contact::Law: every pair the pass allows
/// (node_view::kept_pairs, open_pairs), recording the pairs it engaged in node.engaged_pairs.
/// A pair shares one normal, the average of its two bodies' own (n = (n^a - n^b)/|n^a - n^b|),
/// and exchanges equal and opposite momenta, so momentum is conserved to round-off however many
/// bodies meet.
/// - A kept pair (engaged earlier in the step) has its normal constraint held whether it
///   approaches or not, with Coulomb friction if it approaches: the law is not asked again.
/// - An open pair that approaches (only those) is in contact if law.in_contact(pair) says so; it then takes
///   the Bardenhagen et al. (2000) correction (its normal approach removed against the pair's
///   centre of mass, the slip reduced by at most mu times that: law.friction()), or, if the law
///   has impulse(pair), what it asks projected by dissipative_impulse. A pair whose correction
///   stopped part of its approach is engaged.
/// Two bodies: one pass. More: pairs in turn, in the node's body order, each against its own
/// centre of mass (Bardenhagen et al. correct each body against the node's centre of mass along
/// its own normal, their eq. 19, which moves momentum into or out of the node where the normals
/// of three bodies do not cancel). A pair's correction can undo an earlier pair's, so with three
/// or more bodies the sweep is repeated until no engaged pair approaches or is pulled apart by
/// more than 1e-12 of the largest velocity there (at most 64 sweeps). Every correction removes
/// kinetic energy, so the repetition converges and creates none.
/// With a `tally` (contact::Counting), law.count(tally, pair, outcome) is called for every open
/// pair the law engaged, with the momentum this correction gave body a. Where a law with
/// impulse() engages a pair, the fractions of the approach and of the slip its projected impulse
/// removed are recorded (node_view::normal_fraction, slip_fraction); wherever a later sweep or
/// pass of the step sees the pair again, the same fractions of its normal relative velocity
/// (approaching or not) and slip are removed, and the law is not asked again. A law without
/// impulse() is held with the whole normal relative velocity removed and Coulomb friction with
/// law.friction(). (A node view without room for the fractions, a user's own, keeps them for
/// its sweeps; kept pairs it brings are held whole, without friction.)
template <Space S, contact::Law L, class Tally = detail::no_tally>
void correct(contact::node_view<S>& node, const L& law, Tally* tally = nullptr) {
    using real = typename S::real;
    using vector = typename S::vector;
    const real mu = real(contact::friction_of(law));
    real speed = 0;
    for (std::size_t b = 0; b < node.count; ++b) speed = std::max(speed, real(node.momentum[b].norm() / node.mass[b]));
    const real tolerance = real(1e-12) * speed;
    const int sweeps = node.count > 2 ? 64 : 1;
    // What a law's impulse removed where it engaged a pair (node_view::normal_fraction), kept
    // here for the node's later sweeps where the view brings no room for it (a user's own view;
    // its kept pairs are then held whole and without friction).
    [[maybe_unused]] std::array<real, contact::node_view<S>::max_fields * contact::node_view<S>::max_fields> own_normal,
        own_slip;
    real* normal_fraction = node.normal_fraction;
    real* slip_fraction = node.slip_fraction;
    if constexpr (detail::has_impulse<L, S>) {
        if (!normal_fraction || !slip_fraction) {
            own_normal.fill(real(1));
            own_slip.fill(real(0));
            normal_fraction = own_normal.data();
            slip_fraction = own_slip.data();
        }
    }
    for (int sweep = 0; sweep < sweeps; ++sweep) {
        real largest = 0;  // the largest normal relative speed corrected in this sweep
        for (std::size_t a = 0; a + 1 < node.count; ++a) {
            for (std::size_t b = a + 1; b < node.count; ++b) {
                // A pair engaged by an earlier sweep is held from then on, as a kept one.
                const bool kept = node.kept(a, b) || (node.engaged_pairs & node.pair_bit(a, b));
                if (!kept && !node.open(a, b)) continue;
                const vector n = node.pair_normal(a, b);
                if (n.isZero()) continue;
                contact::pair_view<S> pair;
                pair.node = node.node;
                pair.position = node.position;
                pair.field_a = node.field[a];
                pair.field_b = node.field[b];
                pair.body_a = node.body[a];
                pair.body_b = node.body[b];
                pair.mass_a = node.mass[a];
                pair.mass_b = node.mass[b];
                pair.velocity_a = node.momentum[a] / node.mass[a];
                pair.velocity_b = node.momentum[b] / node.mass[b];
                pair.normal = n;
                pair.gap = node.gap(a, b);
                pair.cell = node.cell;
                pair.dt = node.dt;
                const real m_ab = node.mass[a] + node.mass[b];
                const vector v_cm = (node.momentum[a] + node.momentum[b]) / m_ab;
                const vector relative = node.momentum[a] / node.mass[a] - v_cm;
                // The law is asked about approaching pairs only (the sign of the approach as the
                // correction measures it, against the pair's centre of mass).
                if (!kept && (!(relative.dot(n) > real(0)) || !law.in_contact(pair))) continue;
                vector dp = vector::Zero();  // to a
                if constexpr (detail::has_impulse<L, S>) {
                    const std::size_t slot = a * node.count + b;
                    const real stop = pair.reduced_mass() * pair.approach();
                    const vector slip = pair.slip();
                    if (!kept) {
                        dp = dissipative_impulse(pair, vector(law.impulse(pair)), mu);
                        const real normal = -dp.dot(n);
                        if (!(normal > real(0))) continue;  // stops no approach: not engaged
                        // What the law chose, for the step's later passes to repeat.
                        const real slipping = pair.reduced_mass() * slip.norm();
                        normal_fraction[slot] = std::min(real(1), normal / stop);
                        slip_fraction[slot] =
                            slipping > real(0) ? std::min(real(1), vector(dp + normal * n).norm() / slipping) : real(0);
                    } else {
                        // The same fractions of this pass's normal relative velocity (approaching
                        // or not) and slip: asked again on other velocities, the law could stick
                        // where it let the pair slide, or hold where it stopped part of the
                        // approach.
                        dp = -normal_fraction[slot] * stop * n - slip_fraction[slot] * pair.reduced_mass() * slip;
                    }
                }
                if (!detail::has_impulse<L, S>) {
                    bool engaged = false;
                    const vector dv = coulomb_correction(relative, n, mu, kept, engaged);
                    if (!engaged) continue;
                    dp = node.mass[a] * dv;
                }
                largest = std::max(largest, std::abs(relative.dot(n)));
                node.momentum[a] += dp;
                node.momentum[b] -= dp;
                node.engaged_pairs |= node.pair_bit(a, b);
                if constexpr (!std::is_same_v<Tally, detail::no_tally>)
                    if (tally && !kept) law.count(*tally, pair, contact::pair_outcome<S>{dp});
            }
        }
        if (!(largest > tolerance)) break;
    }
}

}  // namespace gimlet::multi_field
