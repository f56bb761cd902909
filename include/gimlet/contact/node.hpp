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
    /// count x count, row a: how far body a's particle centres that map to this node reach
    /// towards body b, measured from the node along the pair's normal n_ab (pair_normal):
    /// reach[a * count + b] = max_p (x_p - x_i) . n_ab. Since n_ba = -n_ab, the gap between the
    /// facing particle centres of a and b along n_ab is gap(a, b) = -(reach_ab + reach_ba).
    const real* reach = nullptr;
    real cell = 0;                    ///< h
    real dt = 0;                      ///< time step

    // Pairs of bodies at the node, for the masks below: (a, b) with a < b in the node's order
    // has bit pair_bit(a, b). With more than 11 bodies, the pairs past the 64th have no bit and
    // count as open and never kept.
    [[nodiscard]] std::uint64_t pair_bit(std::size_t a, std::size_t b) const noexcept {
        const std::size_t index = a * (2 * count - a - 1) / 2 + (b - a - 1);
        return index < 64 ? std::uint64_t(1) << index : 0;
    }
    /// In: pairs whose normal constraint must hold in this pass without testing whether they
    /// approach. They are the pairs this step's deciding pass engaged, seen again by a later pass
    /// (MUSL's re-mapping; USF's stress velocities and grid update): the velocities can look
    /// separating there, and dropping the constraint that the stress or the forces were computed
    /// with creates energy (docs/equations.md, Contact).
    std::uint64_t kept_pairs = 0;
    /// In: pairs the policy may engage if it finds them in contact (the deciding pass: all;
    /// MUSL's re-mapping: those not kept; USF's grid update: none).
    std::uint64_t open_pairs = ~std::uint64_t(0);
    /// Out: the pairs the policy corrected. The solver records them for the step's later
    /// passes; where a policy changes momenta without setting any, it records every pair.
    std::uint64_t engaged_pairs = 0;

    /// The normal shared by bodies a and b, from a towards b: (n^a - n^b)/|n^a - n^b| (zero if
    /// their normals coincide).
    [[nodiscard]] vector pair_normal(std::size_t a, std::size_t b) const {
        const vector d = normal[a] - normal[b];
        const real len = d.norm();
        return len > real(0) ? vector(d / len) : vector::Zero();
    }
    /// Distance between the facing particle centres of bodies a and b along their pair normal
    /// (the reference paper's R_i^pq, its section 2.2; PHYSICS.md section 3).
    [[nodiscard]] real gap(std::size_t a, std::size_t b) const noexcept {
        return -(reach[a * count + b] + reach[b * count + a]);
    }
    [[nodiscard]] bool kept(std::size_t a, std::size_t b) const noexcept { return kept_pairs & pair_bit(a, b); }
    [[nodiscard]] bool open(std::size_t a, std::size_t b) const noexcept {
        const std::uint64_t bit = pair_bit(a, b);
        return bit == 0 || (open_pairs & bit);
    }
};

}  // namespace gimlet::contact
