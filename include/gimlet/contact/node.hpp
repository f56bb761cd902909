// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// What a multi-field contact policy sees at one grid node shared by two or more bodies.

#include "gimlet/core/space.hpp"

#include <cstddef>
#include <cstdint>

namespace gimlet::contact {

/// One node where several bodies have mass (above the solver's cut-off). Arrays are indexed by
/// the bodies present at this node, in increasing body id.
template <Space S>
struct node_view {
    using real = typename S::real;
    using vector = typename S::vector;

    std::size_t count = 0;            ///< bodies present (>= 2)
    const std::uint32_t* body = nullptr;  ///< their body ids
    const real* mass = nullptr;       ///< m_i^b
    vector* momentum = nullptr;       ///< (mv)_i^b, in/out: the policy corrects it
    const vector* normal = nullptr;   ///< outward unit normal of each body: sum_p m_p G_ip, normalised
    /// Furthest particle centre of each body that maps to this node, measured from the node along
    /// that body's outward normal: max_p (x_p - x_i) . n^b. For two bodies A, B with
    /// n^B = -n^A, the gap between their facing particle centres is -(reach^A + reach^B).
    const real* reach = nullptr;
    real cell = 0;                    ///< h
    real dt = 0;                      ///< time step
    /// In: this step's deciding pass engaged the node and this is a later pass (MUSL's
    /// re-mapping; USF's stress velocities and grid update). The policy must keep its normal
    /// constraint without re-testing whether the bodies approach: the velocities can look
    /// separating there, and dropping the constraint the stress or forces were computed with
    /// creates energy (docs/equations.md, Contact).
    bool constrained = false;
    /// Out: the policy set this if it corrected the momenta.
    bool engaged = false;
};

}  // namespace gimlet::contact
