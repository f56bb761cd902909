// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The contact contract (docs/concepts.md, Contact).

#include "gimlet/contact/node.hpp"
#include "gimlet/core/fields.hpp"

#include <concepts>
#include <utility>

/// Contact policies: how bodies that share grid nodes interact (contact::Contact).
namespace gimlet::contact {

/// A multi-field contact law: the physics of contact and nothing else. The framework
/// (multi_field/correct.hpp) owns the passes of a step, the pair masks, the normals and the
/// momentum bookkeeping, and asks the law, pair by pair at every node where two or more bodies
/// have mass:
/// - `in_contact(pair)` (required): whether bodies a and b touch at this node
///   (contact::pair_view: the node, the two bodies' masses and velocities, their normal and
///   the gap between their facing particle centres);
/// - `friction()` (optional, default 0): the Coulomb coefficient mu >= 0 (infinity: no slip);
/// - `impulse(pair)` (optional, default: stop the approach, Coulomb friction with `friction()`):
///   the momentum body a is to receive (b receives the opposite).
/// The framework asks only about pairs that approach, and keeps the answer for the rest of the
/// step: a pair engaged when the law decided has its normal constraint held (with Coulomb
/// friction, `friction()`) through the step's later passes, where the law is not asked again; a
/// pair left free stays free for the rest of the step. Under USF the
/// law decides on the velocities the forces of the current stress would give, and the pairs it
/// engages are held. So `impulse` decides the correction of a pair once per step: the step's
/// later passes remove the same fractions of the approach and of the slip as it did, and do not
/// ask again (without `impulse`: the whole approach, Coulomb with `friction()`). It projects whatever `impulse` returns onto
/// the dissipative set before applying it: a normal part that only removes approach (from none
/// of it to all of it) and a tangential part that opposes the slip, stops at most all of it, and
/// stays within mu times the normal part. So a law cannot create momentum or energy, whatever it
/// returns. Both members are const: the law is called at many nodes of a step, in any order.
template <class C>
concept Law = C::multi_field &&
              requires(const C& c, const pair_view<space<2, double>>& p2, const pair_view<space<3, double>>& p3) {
                  { c.in_contact(p2) } -> std::convertible_to<bool>;
                  { c.in_contact(p3) } -> std::convertible_to<bool>;
              };

/// The low-level contract, opt-in for advanced policies: `resolve(node)` corrects the bodies'
/// nodal momenta at a node itself (contact::node_view). Its obligations, which the framework
/// meets for a Law and nothing checks here: move momentum between bodies without creating any;
/// record in `node.engaged_pairs` the pairs it corrected (the framework records every pair
/// where momenta changed without); hold the normal constraint of `node.kept_pairs` without
/// testing whether they approach (dropping it where a later pass sees separating velocities
/// creates energy: docs/equations.md, Contact); engage no pair outside `node.open_pairs`; and
/// remove kinetic energy, never add it.
template <class C>
concept NodeResolver = C::multi_field && requires(const C& c, node_view<space<2, double>>& n2,
                                                  node_view<space<3, double>>& n3) {
    c.resolve(n2);
    c.resolve(n3);
};

/// A contact policy: how bodies that share grid nodes interact.
/// - `multi_field`: one grid velocity field per body (true) or one shared field (false: bodies
///   stick where they meet, "no contact algorithm"; the grid then holds exactly one field).
/// - `required_fields`: field_list of per-particle state it needs (written by its
///   contact::ParticleHook, if it has one).
/// - a multi-field policy is either a contact::Law (the usual case) or a contact::NodeResolver,
///   not both.
template <class C>
concept Contact = requires {
    { C::multi_field } -> std::convertible_to<bool>;
    typename C::required_fields;
    requires FieldList<typename C::required_fields>;
} && (!C::multi_field || (Law<C> != NodeResolver<C>));

/// A law's optional friction coefficient (0 without one). The solver refuses a law whose
/// friction() is negative or not a number when it is built.
template <class C>
[[nodiscard]] double friction_of(const C& c) {
    if constexpr (requires { { c.friction() } -> std::convertible_to<double>; }) return double(c.friction());
    else return 0.0;
}

/// A law's own counters, kept right whatever runs in parallel: `tally` (default-constructible,
/// merged with +=), `count(tally&, pair, outcome) const` for every pair the law engaged, and
/// `record(const tally&)` (non-const), called once per contact pass after its nodes, serially.
/// The framework fills one tally per pass in node order (contact runs serially; run in
/// parallel, each thread would fill its own and they would merge in thread order), so the
/// policy's own members change only in `record`. solver::contact() reads them back.
template <class C, class S>
concept Counting = std::default_initializable<typename C::tally> &&
                   requires(C& c, const C& cc, typename C::tally& t, const pair_view<S>& p, const pair_outcome<S>& o) {
                       cc.count(t, p, o);
                       c.record(std::as_const(t));
                       t += std::as_const(t);
                   };

/// A law's optional per-particle hook, called once per step for every particle after the
/// step's last contact pass: `after_contact(particle, info) const` (contact::particle_contact),
/// where it may write the fields it declares in `required_fields`.
template <class C, class P, class S>
concept ParticleHook = requires(const C& c, const P& p, const particle_contact<S>& info) { c.after_contact(p, info); };

}  // namespace gimlet::contact
