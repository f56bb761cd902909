// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// What a multi-field contact policy sees at one grid node where two or more velocity fields
/// have mass.

#include "gimlet/core/space.hpp"

#include <cstddef>
#include <cstdint>
#include <utility>

namespace gimlet::contact {

/// The normal two bodies share at a node, from a towards b, given their own outward unit
/// normals: (n^a - n^b)/|n^a - n^b| (Bardenhagen et al. 2000; zero if they coincide). The solver
/// measures the reach along it and the policies correct along it, so both use this one formula.
template <class Vector>
[[nodiscard]] Vector pair_normal(const Vector& normal_a, const Vector& normal_b) {
    const Vector d = normal_a - normal_b;
    const auto len = d.norm();
    return len > 0 ? Vector(d / len) : Vector(Vector::Zero());
}

/// The distance between the facing particle centres of fields a and b of a node along their
/// pair normal, from the node's count x count reaches (reach[a * count + b], node_view::reach):
/// -(reach_ab + reach_ba), the reference paper's R_i^pq (its section 2.2; docs/physics.md
/// section 3). The contact laws see it as node_view::gap; the solver's contact step reads it too.
template <class Real>
[[nodiscard]] Real facing_gap(const Real* reach, std::size_t count, std::size_t a, std::size_t b) noexcept {
    return -(reach[a * count + b] + reach[b * count + a]);
}

/// One node where several velocity fields have mass (above the solver's cut-off). A field is a
/// body, or with a multi_field::Partition part of one (the particles of a body on one side of a
/// closing void), so two fields of one body can touch. Arrays are indexed by the fields present
/// at this node, in increasing field id; "body a" below means the field at index a. A contact
/// law (contact::Law) never sees it: the framework does (multi_field/correct.hpp), and so does
/// a low-level policy (contact::NodeResolver), which corrects `momentum` itself.
template <Space S>
struct node_view {
    /// The scalar type of S.
    using real = typename S::real;
    /// A velocity or momentum: S::vector.
    using vector = typename S::vector;

    std::size_t count = 0;            ///< fields present (>= 2)
    const std::uint32_t* field = nullptr;  ///< their field ids (the body ids with one field per body)
    const std::uint32_t* body = nullptr;   ///< the body each field belongs to
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
    std::size_t node = 0;             ///< the node's index in the grid
    vector position = vector::Zero(); ///< the node's position (m)
    ///@{
    /// count x count, in/out, for a contact law with its own impulse (multi_field::correct):
    /// where the step's deciding pass engaged pair (a, b), a < b, the fractions of its normal
    /// approach and of its slip that the law's impulse removed, [a * count + b]. The step's later
    /// passes remove the same fractions of theirs: the law is not asked again. Null: not kept.
    real* normal_fraction = nullptr;
    real* slip_fraction = nullptr;
    ///@}

    /// Most fields at one node: their pairs must fit the 64-bit masks below. The solver stops a
    /// run with a numerical_error naming the node if more meet there.
    static constexpr std::size_t max_fields = 11;
    /// The bit of the pair of bodies a and b (in either order) in the masks below, at a node of
    /// `count` bodies; 0 if a == b.
    [[nodiscard]] static std::uint64_t pair_bit(std::size_t count, std::size_t a, std::size_t b) noexcept {
        if (a == b) return 0;
        if (a > b) std::swap(a, b);
        const std::size_t index = a * (2 * count - a - 1) / 2 + (b - a - 1);  // (0,1), (0,2), ..., (1,2), ...
        return std::uint64_t(1) << index;
    }
    /// The same at this node.
    [[nodiscard]] std::uint64_t pair_bit(std::size_t a, std::size_t b) const noexcept { return pair_bit(count, a, b); }
    /// In: pairs whose normal constraint must hold in this pass without testing whether they
    /// approach. They are the pairs this step's deciding pass engaged, seen again by a later pass
    /// (MUSL's re-mapping; USF's stress velocities and grid update): the velocities can look
    /// separating there, and dropping the constraint that the stress or the forces were computed
    /// with creates energy (docs/equations.md, Contact).
    std::uint64_t kept_pairs = 0;
    /// In: pairs the policy may engage if it finds them in contact: all in a deciding pass,
    /// none in the later passes of a step (a pair left free stays free).
    std::uint64_t open_pairs = ~std::uint64_t(0);
    /// Out: the pairs the policy corrected. The solver records them for the step's later
    /// passes; where a policy changes momenta without setting any, it records every pair.
    std::uint64_t engaged_pairs = 0;

    /// The normal shared by bodies a and b, from a towards b: (n^a - n^b)/|n^a - n^b| (zero if
    /// their normals coincide).
    [[nodiscard]] vector pair_normal(std::size_t a, std::size_t b) const {
        return contact::pair_normal(normal[a], normal[b]);
    }
    /// Distance between the facing particle centres of bodies a and b along their pair normal
    /// (the reference paper's R_i^pq, its section 2.2; docs/physics.md section 3).
    [[nodiscard]] real gap(std::size_t a, std::size_t b) const noexcept { return facing_gap(reach, count, a, b); }
    /// True if pair (a, b) is in kept_pairs.
    [[nodiscard]] bool kept(std::size_t a, std::size_t b) const noexcept { return kept_pairs & pair_bit(a, b); }
    /// True if pair (a, b) is in open_pairs.
    [[nodiscard]] bool open(std::size_t a, std::size_t b) const noexcept { return open_pairs & pair_bit(a, b); }
};

/// What a contact law (contact::Law) sees of one pair of velocity fields a and b at one grid
/// node (two bodies, or two fields of one body: contact::node_view): read only. Its velocities are those of this pass at this moment (after the forces and the walls,
/// and after the corrections of the node's earlier pairs).
template <Space S>
struct pair_view {
    /// The scalar type of S.
    using real = typename S::real;
    /// A velocity or normal: S::vector.
    using vector = typename S::vector;

    std::size_t node = 0;              ///< the node's index in the grid
    vector position = vector::Zero();  ///< the node's position (m)
    ///@{
    std::uint32_t field_a = 0, field_b = 0;  ///< the two fields' ids (field_a < field_b)
    ///@}
    ///@{
    std::uint32_t body_a = 0, body_b = 0;    ///< the bodies they belong to (equal in self-contact)
    ///@}
    ///@{
    real mass_a = 0, mass_b = 0;       ///< their nodal masses m_i^a, m_i^b
    ///@}
    ///@{
    vector velocity_a = vector::Zero(), velocity_b = vector::Zero();  ///< their nodal velocities
    ///@}
    vector normal = vector::Zero();    ///< unit normal from a towards b (contact::pair_normal)
    /// Distance between the facing particle centres of a and b along `normal` (the reference
    /// paper's R_i^pq, its section 2.2): h/2 when 2 x 2 particles per cell touch.
    real gap = 0;
    real cell = 0;                     ///< h
    real dt = 0;                       ///< time step

    /// (v_a - v_b) . n: positive while a and b approach each other along the normal.
    [[nodiscard]] real approach() const { return (velocity_a - velocity_b).dot(normal); }
    /// The tangential part of v_a - v_b.
    [[nodiscard]] vector slip() const {
        const vector rel = velocity_a - velocity_b;
        return rel - rel.dot(normal) * normal;
    }
    /// m_a m_b / (m_a + m_b): the impulse (m_a m_b / (m_a + m_b)) * approach() stops the approach.
    [[nodiscard]] real reduced_mass() const { return mass_a * mass_b / (mass_a + mass_b); }
};

/// What the framework did to one pair at a node (for a law's counters, contact::Counting).
template <Space S>
struct pair_outcome {
    /// The momentum this correction gave body a (body b took the opposite), after the
    /// projection onto the dissipative set: the correction where the law engaged the pair. (Under
    /// USF that correction is measured on the velocities the current stress's forces would give,
    /// and what is applied is the constraint that holds the pair; where three or more bodies
    /// meet, later sweeps add to it.)
    typename S::vector impulse = S::vector::Zero();
};

/// What the framework tells a contact law's per-particle hook (contact::ParticleHook) about one
/// particle after the step's last contact pass.
template <Space S>
struct particle_contact {
    /// Whether a node of the particle's stencil holds a pair of its body that was in contact.
    bool engaged = false;
    /// The particle's weight on those nodes, sum of S_ip (in [0, 1]).
    typename S::real weight = 0;
};

}  // namespace gimlet::contact
