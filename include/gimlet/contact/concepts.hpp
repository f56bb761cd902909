// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The contact contract.

#include "gimlet/contact/node.hpp"
#include "gimlet/core/fields.hpp"

#include <concepts>

namespace gimlet::contact {

/// A contact policy decides how bodies that share grid nodes interact.
///
/// - `multi_field`: whether the grid carries one velocity field per body (true) or one shared
///   field (false: bodies stick where they meet, "no contact algorithm"). A single-field
///   policy makes the solver allocate and map exactly one field.
/// - `required_fields`: field_list of the per-particle state it needs.
/// - multi-field policies: `resolve(node)`, called at every node where two or more bodies have
///   mass, once to decide where contact acts (on the velocities the forces of the current
///   stress give, with the walls) and again where a later pass of the step must keep that decision
///   (node_view::kept_pairs; docs/equations.md, Contact). It corrects the bodies' nodal momenta
///   in `node.momentum` (contact::node_view) and should record the pairs it corrected in
///   `node.engaged_pairs` (the solver records every pair where it changed momenta without). A
///   correction that moves momentum between bodies without creating any conserves total
///   momentum.
template <class C>
concept Contact = requires {
    { C::multi_field } -> std::convertible_to<bool>;
    typename C::required_fields;
    requires FieldList<typename C::required_fields>;
} && (!C::multi_field || requires(const C& c, node_view<space<2, double>>& n2, node_view<space<3, double>>& n3) {
    c.resolve(n2);
    c.resolve(n3);
});

}  // namespace gimlet::contact
