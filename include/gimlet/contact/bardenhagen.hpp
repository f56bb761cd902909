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

/// Bardenhagen, Guilkey, Roessig, Brackbill, Witzel & Foster (2000), "An improved contact
/// algorithm for the material point method and application to stress propagation in granular
/// material": each body maps its own velocity field; where bodies share a node and approach
/// each other, their normal velocities are set to the centre-of-mass one and the tangential
/// slip is resisted by Coulomb friction. Bodies separate freely. Contact starts as soon as two
/// bodies share a node, that is up to about two cells early: the reference paper's criticism,
/// which contact::distance answers.
class bardenhagen {
public:
    /// One velocity field per body (contact::Contact).
    static constexpr bool multi_field = true;
    /// It keeps no per-particle state.
    using required_fields = field_list<>;

    /// \param friction Coulomb coefficient mu >= 0 (0: frictionless; infinity: no slip).
    explicit bardenhagen(double friction = 0.0) : mu_(friction) {
        require(!std::isnan(friction) && friction >= 0.0, "contact friction coefficient mu", friction, ">= 0");
    }

    /// Every pair of bodies that shares a node (and approaches: the framework asks no other).
    template <Space S>
    [[nodiscard]] bool in_contact(const pair_view<S>&) const noexcept {
        return true;
    }

    /// mu, the Coulomb coefficient (contact::Law).
    [[nodiscard]] double friction() const noexcept { return mu_; }

private:
    double mu_;
};

static_assert(Contact<bardenhagen>);

}  // namespace gimlet::contact
