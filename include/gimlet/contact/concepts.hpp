// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The contact contract.

#include "gimlet/core/fields.hpp"

#include <concepts>

namespace gimlet::contact {

/// A contact policy decides how bodies that share grid nodes interact.
///
/// - `multi_field`: whether the grid carries one velocity field per body (true) or one shared
///   field (false: bodies stick where they meet, "no contact algorithm"). A single-field
///   policy makes the solver allocate and map exactly one field.
/// - `fields`: field_list of the per-particle state it needs.
template <class C>
concept Contact = requires {
    { C::multi_field } -> std::convertible_to<bool>;
    typename C::required_fields;
    requires FieldList<typename C::required_fields>;
};

}  // namespace gimlet::contact
