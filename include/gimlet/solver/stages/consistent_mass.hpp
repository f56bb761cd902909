// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The consistent-mass stage: the grid accelerations of the consistent mass matrix, approximated by k iterations
/// (solver_options::consistent_mass_iterations; docs/equations.md, "Consistent-mass
/// accelerations").
///
/// MPM divides the nodal forces by the lumped mass m_i = sum_p S_ip m_p. The consistent mass
/// M_ij = sum_p m_p S_ip S_jp is what the weak form gives; its rows sum to the lumped masses.
/// With the lumped mass the grid is a dispersive lattice: short waves run slower than long ones,
/// so a shock trails a train of grid-scale waves (the front overshoot of docs/equations.md).
/// With the consistent mass that lag is 3.4 times smaller for uGIMP (tests/solver/
/// test_consistent_mass.cpp), and the train goes.
/// The solve is the iteration
///   a^(0) = f / m,   a^(j+1) = a^(0) + a^(j) - (M a^(j)) / m,
/// whose fixed point solves M a = f where M is regular; the forces then become m a^(k). The
/// eigenvalues of m^-1 M lie in [0, 1] (non-negative weights; m - M is diagonally dominant):
/// modes at 1 converge at once, modes near 0 (a support with fewer particles than nodes) grow
/// like (k + 1) a^(0), never more, so the grid's highest frequency rises by at most
/// sqrt(k + 1) and the options require cfl sqrt(k + 1) <= 1 (MUSL and USF; not with USL, which
/// is unstable above a Courant number of about 0.7 already with the lumped mass). The
/// correction m a^(j) - M a^(j) sums to zero over the nodes (the columns of M sum to the
/// lumped masses), so momentum is kept; light nodes (mass_cutoff) take no part, and each
/// particle's share of M a is spread over its other nodes (below) so that this stays exact.
/// An entry at a node that two or more fields share (where contact may act) keeps its lumped
/// acceleration, and the particles that reach it take part with their lumped mass (M's diagonal),
/// so that M's columns still sum to the lumped masses and momentum stays exact. The contact law
/// sets such a node's velocity after the momentum update; coupled to its neighbours through M,
/// a field's edge node there would spread the free surface's acceleration, which the contact
/// then overrides, into the cell behind it (a 1-D impact through the distance contact would
/// read 37 % under the plateau pressure in the first cell at k = 4; docs/equations.md).

#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/detail/shares.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/space.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

/// The optional stages of a step (consistent mass, damping transfer, light particles, volume
/// filter, volumetric averaging) and the choice of velocity fields: classes that
/// gimlet::solver_core owns and calls in the order of its scheme.
namespace gimlet::stages {

/// The consistent-mass stage, called by the grid momentum update of every scheme before the
/// forces are applied.
///
/// Reads: the grid's masses and forces, the mass cut-off, the walls' free components, the swept
/// field slots, the shared nodes of multi-field contact, the particles' masses, the step's
/// stencils and node entries. Writes: the grid's forces, and the step's list of each particle's
/// node entries (list), which the step's later transfers read instead of choosing them again.
/// Chosen at run time (solver_options::consistent_mass_iterations; 0, the default and the only
/// value USL takes, returns at once).
///
/// \tparam S the space.
/// \tparam Nodes the nodes of a particle's stencil.
template <Space S, std::size_t Nodes>
class consistent_mass {
public:
    /// The scalar type of S.
    using real = typename S::real;
    /// S::vector.
    using vector = typename S::vector;

    /// Particle i's node entries in its stencil's order, once this step's first iteration has
    /// listed them; null before (and at 0 iterations).
    [[nodiscard]] const std::uint32_t* list(std::size_t i) const noexcept {
        return listed_ ? &entry_[i * Nodes] : nullptr;
    }
    /// The list serves one step: the step's end (however it ends) forgets it.
    void unlist() noexcept { listed_ = false; }

    /// f <- m a^(k) (the file's comment), k = solver_options::consistent_mass_iterations.
    template <class Core>
    void apply(Core& c) {
        const int iterations = c.options_.consistent_mass_iterations;
        if (iterations <= 0) return;
        lumped_accelerations(c);
        // What the iterations share, found in the first: each particle's node entries in its
        // stencil's order (the partition's choice of field made once, not once per iteration), its
        // weight on the nodes above the cut-off, and how its share is scattered (scatter_kind). The
        // solver refuses the consistent mass on a grid whose entries do not fit 32 bits.
        listed_ = false;  // entries(i) chooses through the sides until the list is written (unlist() at the step's end too)
        entry_.resize(c.particles_.size() * Nodes);
        heavy_.resize(c.particles_.size());
        kind_.resize(c.particles_.size());
        for (int it = 0; it < iterations; ++it) {
            // M a starts from zero: cleared by lumped_accelerations for the first iteration, and by
            // next_iterate for the others (one pass, and one parallel region, fewer each).
            if (it == 0) {
                multiply_listing(c);
                // The rest of the step's passes (the gather, MUSL's re-map, the velocity gradient)
                // read their entries from the list too (Core::entries).
                listed_ = true;
            } else {
                multiply_listed(c);
            }
            next_iterate(c, it + 1 == iterations);
        }
    }

private:
    // Whether entry e keeps its lumped acceleration (an entry at a node two or more fields share;
    // none in a single-field solver, which pays nothing for the flags).
    template <class Core>
    [[nodiscard]] bool shared_entry(std::size_t e) const {
        if constexpr (Core::multi_field) return lumped_[e] != 0;
        else return (static_cast<void>(e), false);
    }

    // a^(0): the lumped accelerations. Light nodes (mass_cutoff) keep their forces and take no
    // part; a component a fixed or slip wall holds has none (the walls' free components). An
    // entry at a node where two or more fields are above the cut-off (the shared nodes of
    // multi-field contact, which the step's find_shared_nodes has found) keeps a^(0) through the
    // iteration. The pass runs in blocks of `block` entries and notes the blocks that hold an
    // entry above the cut-off: the iterations' node passes visit those blocks only. Everywhere
    // else the passes do nothing (no mass, so no update and no force), and M a is neither written
    // nor read there: the grid's empty room costs this one pass a step, not k + 1. This pass still
    // writes a^(0) in every block of the swept field slots, light entries included: the
    // particles' gathers read a at every node of their stencils. The slots the step does not
    // sweep (Core::swept_fields: self-contact's second fields where nothing splits) hold no
    // particle's node, so it skips them too, and on many processes so are the rows outside the
    // process's window (Core::window_holds).
    template <class Core>
    void lumped_accelerations(Core& c) {
        const std::size_t ne = c.grid_.entries();
        const bool parallel_nodes = static_cast<std::ptrdiff_t>(ne) >= Core::node_parallel_threshold;
        first_.resize(ne);
        accel_.resize(ne);
        product_.resize(ne);
        if constexpr (Core::multi_field) lumped_.resize(ne);  // written below where read
        const std::size_t grid_nodes = c.grid_.size();
        const std::size_t blocks = (ne + block - 1) / block;
        block_heavy_.resize(blocks);
        detail::thread_shares shares(static_cast<std::ptrdiff_t>(blocks), c.threads(), parallel_nodes);
        GIMLET_OMP(parallel num_threads(shares.team()))
        for (auto claimed = shares.start(); shares.claim(claimed);)
            for (std::ptrdiff_t b = claimed.first, end = claimed.last; b < end; ++b) {
                bool heavy = false;
                const std::size_t first = std::size_t(b) * block, last = std::min(ne, first + block);
                // A block within a field slot the step does not sweep has no mass.
                const std::size_t field = first / grid_nodes;
                const bool unswept = field == (last - 1) / grid_nodes && field % Core::fields_per_body >= c.swept_fields();
                // On many processes, a block outside the rows this process's particles reach has
                // no mass here and is never read.
                const bool outside = !c.window_holds(first, last);
                for (std::size_t e = first; e < last && !unswept && !outside; ++e) {
                    const real m = c.grid_.mass[e];
                    heavy = heavy || m > c.mass_cutoff_;
                    first_[e] = m > c.mass_cutoff_ ? vector(c.wall_free_[e].cwiseProduct(c.grid_.force[e] / m)) : vector::Zero();
                    accel_[e] = first_[e];
                    if constexpr (Core::multi_field) lumped_[e] = m > c.mass_cutoff_ && c.exchange_.shared(e % grid_nodes);
                }
                block_heavy_[std::size_t(b)] = heavy;
                // The first iteration's M a starts from zero in the blocks the iterations visit (only
                // there: the product's pages elsewhere stay untouched).
                if (heavy)
                    for (std::size_t e = first; e < last; ++e) product_[e] = vector::Zero();
            }
        blocks_.clear();
        for (std::size_t b = 0; b < blocks; ++b)
            if (block_heavy_[b]) blocks_.push_back(static_cast<std::uint32_t>(b));
    }

    // M a = sum_p S_ip m_p (sum_j S_jp a_j): each particle gathers from a^(j) and scatters its
    // share into the product in one pass (on many processes completed in the bands, in the
    // one-process order: a band's heavy nodes are heavy on both sides, so both clear them), slab by slab (a fixed summation order whatever the
    // thread count; a^(j) is only read in the pass, so the gathers see the same values in any
    // order). Each particle's share is scattered over its nodes above the cut-off only, its
    // weights there renormalised to one: sum_i (M a)_i is then sum_p m_p a_p = sum_j m_j a_j
    // exactly, and the correction keeps momentum where a particle also reaches a light node.
    // The first iteration finds each particle's entries through the partition's chooser and
    // records them, with its weight on the heavy nodes and its kind.
    template <class Core>
    void multiply_listing(Core& c) {
        c.for_each_particle_by_slab_into([&](std::size_t i) {
            auto at = c.entries(i);
            std::uint32_t* out = &entry_[i * Nodes];
            vector ap = vector::Zero();
            real heavy = 0;     // the particle's weight on nodes above the mass cut-off
            bool held = false;  // whether it reaches a shared node's entry
            bool all_heavy = true;
            c.stencils_[i].for_each([&](std::size_t node, real w, const vector&) {
                const std::size_t e = at(node);
                *out++ = static_cast<std::uint32_t>(e);
                ap += w * accel_[e];
                if (c.grid_.mass[e] > c.mass_cutoff_) heavy += w;
                else all_heavy = false;
                held = held || shared_entry<Core>(e);
            });
            heavy_[i] = heavy;
            kind_[i] = held ? kind_held : all_heavy ? kind_all_heavy : kind_some_light;
            scatter_listed(c, i, ap);
        }, product_);
    }

    // The same sums from the lists, with the same operands in the same order (a held particle
    // scatters without its gathered sum).
    template <class Core>
    void multiply_listed(Core& c) {
        c.for_each_particle_by_slab_into([&](std::size_t i) {
            vector ap = vector::Zero();
            if (kind_[i] != kind_held) {
                const std::uint32_t* listed = &entry_[i * Nodes];
                c.stencils_[i].for_each([&](std::size_t, real w, const vector&) { ap += w * accel_[*listed++]; });
            }
            scatter_listed(c, i, ap);
        }, product_);
    }

    // Particle i's share of M a, given its gathered sum_j S_jp a_j, scattered through its list.
    template <class Core>
    void scatter_listed(Core& c, std::size_t i, const vector& ap) {
        const auto& mass = c.particles_.template column<fields::mass>();
        const std::uint32_t* listed = &entry_[i * Nodes];
        const auto& st = c.stencils_[i];
        const real heavy = heavy_[i];
        if (kind_[i] == kind_held) {
            // A particle that reaches a shared node's entry takes part with its lumped mass
            // (M's diagonal): no entry of its stencil is coupled to another through it. (No
            // entry is shared in a single-field solver.)
            st.for_each([&](std::size_t, real w, const vector&) {
                const std::size_t e = *listed++;
                if (c.grid_.mass[e] > c.mass_cutoff_) product_[e] += vector(w * mass[i] * accel_[e]);
            });
            return;
        }
        // m_p a_p over its weight on the heavy nodes (renormalised; none where it reaches no
        // such node); only a particle that reaches a light node tests the nodes' masses.
        const vector share = heavy > 0 ? vector(mass[i] * ap / heavy) : vector::Zero();
        if (kind_[i] == kind_all_heavy) {
            st.for_each([&](std::size_t, real w, const vector&) { product_[*listed++] += vector(w * share); });
        } else {
            st.for_each([&](std::size_t, real w, const vector&) {
                const std::size_t e = *listed++;
                if (c.grid_.mass[e] > c.mass_cutoff_) product_[e] += vector(w * share);
            });
        }
    }

    // a^(j+1) from M a^(j), entry by entry, in the blocks that hold an entry above the cut-off
    // (split between the threads; each entry's work is its own, so the results do not depend on
    // how). After the last iteration, in the same pass, f <- f + m (a^(k) - a^(0)): m a^(k) where
    // a component is free, the force as it was where a wall holds it (the wall then sets that
    // velocity component) and at a shared node's entry (where a^(k) = a^(0)). Each entry's force
    // reads its own a^(k) only, so this is the separate pass after the iterations, fused.
    template <class Core>
    void next_iterate(Core& c, bool last) {
        const std::size_t ne = c.grid_.entries();
        const auto heavy_blocks = static_cast<std::ptrdiff_t>(blocks_.size());
        const bool parallel_heavy = heavy_blocks * std::ptrdiff_t(block) >= Core::node_parallel_threshold;
        detail::thread_shares shares(heavy_blocks, c.threads(), parallel_heavy);
        GIMLET_OMP(parallel num_threads(shares.team()))
        for (auto claimed = shares.start(); shares.claim(claimed);)
            for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) {
                const std::size_t first = std::size_t(blocks_[std::size_t(k)]) * block;
                for (std::size_t e = first, stop = std::min(ne, first + block); e < stop; ++e) {
                    const real m = c.grid_.mass[e];
                    if (m > c.mass_cutoff_ && !shared_entry<Core>(e))
                        accel_[e] = first_[e] + c.wall_free_[e].cwiseProduct(accel_[e] - product_[e] / m);
                    if (!last) product_[e] = vector::Zero();  // the next iteration's M a starts from zero
                    else if (m > c.mass_cutoff_) c.grid_.force[e] += m * (accel_[e] - first_[e]);
                }
            }
    }

    // Per node entry the lumped and the iterated accelerations and M a, and whether it keeps its
    // lumped acceleration (an entry at a node two or more fields share).
    std::vector<vector> first_, accel_, product_;
    std::vector<std::uint8_t> lumped_;
    // The blocks of `block` entries that hold an entry above the cut-off (found in the first node
    // pass; the iterations' node passes visit only those).
    static constexpr std::size_t block = 64;
    std::vector<std::uint8_t> block_heavy_;
    std::vector<std::uint32_t> blocks_;
    // Per particle, found in the first iteration and used by every one: its entries in stencil
    // order, its weight on the nodes above the cut-off, and how it scatters its share.
    enum scatter_kind : std::uint8_t { kind_all_heavy, kind_some_light, kind_held };
    std::vector<std::uint32_t> entry_;
    std::vector<real> heavy_;
    std::vector<std::uint8_t> kind_;
    bool listed_ = false;  // entry_ holds this step's entries (set after the first iteration)
};

}  // namespace gimlet::stages
