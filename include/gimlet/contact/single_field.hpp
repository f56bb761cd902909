// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// One grid velocity field for all bodies.

#include "gimlet/contact/concepts.hpp"

namespace gimlet::contact {

/// The "no contact algorithm" case of standard MPM (Sulsky et al. 1994): every body maps to the
/// same nodal velocity, so bodies interact as soon as their particles share nodes (up to about
/// two cells apart) and, once their particle domains meet, stick and cannot separate.
/// The grid holds a single field; no contact step runs.
struct single_field {
    /// One shared velocity field (contact::Contact).
    static constexpr bool multi_field = false;
    /// It keeps no per-particle state.
    using required_fields = field_list<>;
};

static_assert(Contact<single_field>);

}  // namespace gimlet::contact
