// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The field-choice stage: with a partition of several fields per body (multi_field::Partition;
/// self-contact's is one), the partition's preparation for the step and its side of every
/// particle at every node of its stencil, from the start-of-step state; and which field slots
/// the grid's node passes visit this step.

#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/detail/shares.hpp"
#include "gimlet/core/space.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace gimlet::stages {

/// The field-choice stage, called at the start of every step once the particles are bucketed
/// into slabs (prepare), and told when a step completes (completed).
///
/// Reads: the particles, the step's stencils, the grid, the partition (its prepare, splits,
/// split_rows and side). Writes: the partition's own state (its prepare), the sides every
/// transfer of the step reads (Core::entries) and the swept slots every node pass reads.
/// Chosen at compile time: a partition of one field per body (multi_field::by_body) has nothing
/// to choose, and only its optional prepare is called. Then at run time: a partition of several
/// fields per body says each step whether it splits anything (splits(); self-contact's
/// `enabled`), and a step where it does not sweeps one slot per body.
///
/// \tparam FieldsPerBody the partition's fields per body.
/// \tparam Nodes the nodes of a particle's stencil.
template <std::size_t FieldsPerBody, std::size_t Nodes>
class field_choice {
public:
    /// The field slots of each body that the grid's node passes visit this step. A body's later
    /// slots are skipped where the partition says it splits nothing this step (its optional
    /// splits(); a partition without it always splits) and the later slots are empty: no mass,
    /// momentum, force, velocity or wall flag in any of their entries, which is what a pass over
    /// them would leave. The first step to complete without a split swept every slot and left
    /// them empty; nothing writes there until a step splits again. Self-contact's second fields,
    /// where nothing splits, then cost no pass over the grid.
    [[nodiscard]] std::size_t swept() const noexcept { return swept_; }
    /// Particle i's side (field of its body) at the j-th node of its stencil this step.
    [[nodiscard]] std::size_t side(std::size_t i, std::size_t j) const noexcept { return sides_[i][j]; }
    /// Particle i's sides, node by node in its stencil's order.
    [[nodiscard]] const std::uint8_t* sides(std::size_t i) const noexcept { return sides_[i].data(); }

    /// The partition's preparation (its optional prepare), then the step's sides.
    template <class Core>
    void prepare(Core& c) {
        using Part = typename Core::partition_type;
        using store_type = typename Core::store_type;
        // Asked of any partition that has it, whatever its fields_per_body (the core tells:
        // Core::partition_prepares).
        if constexpr (Core::partition_prepares) {
            const auto view = c.template partition_view<const store_type>();
            c.partition_.prepare(view);
        }
        if constexpr (FieldsPerBody > 1) {
            split_now_ = true;
            if constexpr (requires(const Part& p) {
                              { p.splits() } -> std::convertible_to<bool>;
                          })
            {
                split_now_ = c.partition_.splits();
                // Every process sweeps the same field slots (the nodes they share are summed
                // across them): a split on any is a split on all.
                if (auto* p = c.processes()) split_now_ = p->sum(std::uint64_t(split_now_)) > 0;
            }
            swept_ = split_now_ || !later_fields_empty_ ? FieldsPerBody : 1;
            if (split_now_) later_fields_empty_ = false;  // this step writes there, even if it stops part-way
            choose(c);
        }
    }

    /// Reached only when a step completes: a step that stopped part-way may have left values in
    /// the later field slots, which the next step then sweeps.
    void completed() noexcept { later_fields_empty_ = !split_now_; }

private:
    // The partition's side of every particle at every node of its stencil.
    template <class Core>
    void choose(Core& c) {
        using Part = typename Core::partition_type;
        using real = typename Core::real;
        using vector = typename Core::vector;
        const auto& particles = c.particles_;
        const auto& stencils = c.stencils_;
        const auto& grid = c.grid_;
        const auto n = static_cast<std::ptrdiff_t>(particles.size());
        sides_.resize(particles.size());  // entries added are zero
        // A partition that says it splits nothing this step puts every particle in its body's
        // first field at once: every side 0, which they all still are after a step that split
        // nothing, so the fill (one thread over a byte per stencil node of every particle, a
        // serial part of the step) runs only after a step that split.
        if (!split_now_) {
            if (!sides_zero_) std::fill(sides_.begin(), sides_.end(), std::array<std::uint8_t, Nodes>{});
            sides_zero_ = true;
            return;
        }
        sides_zero_ = false;
        // Particle i's sides; false if the partition answered out of range.
        auto choose_one = [&](std::size_t i) {
            const auto p = particles[i];
            std::size_t j = 0;
            bool ok = true;
            stencils[i].for_each_node_position(grid, [&](std::size_t node, real, const vector& at) {
                assert(at == grid.node_position(node));
                const std::size_t chosen = c.partition_.side(std::as_const(p), node, at);
                ok = ok && chosen < FieldsPerBody;
                sides_[i][j++] = static_cast<std::uint8_t>(ok ? chosen : 0);
            });
            return ok;
        };
        // A partition that names the rows of nodes holding a node it splits
        // (multi_field::Partition's optional split_rows()) is asked only of the particles whose
        // stencils reach one; every other particle is in its body's first field at every node.
        const std::vector<std::uint8_t>* rows = nullptr;
        const int layers = grid.nodes(Core::dim - 1);
        if constexpr (requires(const Part& q) {
                          { q.split_rows() } -> std::same_as<const std::vector<std::uint8_t>&>;
                      }) {
            rows = &c.partition_.split_rows();
            c.require_row_flags(*rows, "the partition's split_rows() size");
        }
        // Whether particle i's stencil reaches a flagged row: its rows along the last axis start
        // at first_row and wrap only on a periodic axis (on a free one the stencil lies within the
        // grid's ghost nodes), as grid::layer numbers them.
        auto reaches = [&](std::size_t i) {
            for (int a = 0, r = stencils[i].first_row; a < Core::shape_type::stencil; ++a, ++r) {
                if (r == layers) r = 0;
                if ((*rows)[std::size_t(r)]) return true;
            }
            return false;
        };
        std::ptrdiff_t first_bad = n;
        detail::thread_shares shares(n, c.threads(), n >= Core::parallel_threshold);
        GIMLET_OMP(parallel reduction(min : first_bad) num_threads(shares.team()))
        for (auto claimed = shares.start(); shares.claim(claimed);)
            for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) {
                const auto i = static_cast<std::size_t>(k);
                if (rows && !reaches(i)) sides_[i] = {};
                else if (!choose_one(i)) first_bad = std::min(first_bad, k);
            }
        if (first_bad < n)
            c.fail(static_cast<std::size_t>(first_bad),
                   "the partition (multi_field::Partition::side) chose a field outside [0, " +
                       std::to_string(FieldsPerBody) + ") at a node of its stencil");
    }

    // Per particle and stencil node, the side of its body the partition chose this step.
    std::vector<std::array<std::uint8_t, Nodes>> sides_;
    bool sides_zero_ = true;  // every entry of sides_ is 0
    std::size_t swept_ = FieldsPerBody;
    bool split_now_ = true;
    bool later_fields_empty_ = false;
};

}  // namespace gimlet::stages
