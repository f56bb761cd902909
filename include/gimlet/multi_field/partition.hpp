// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Velocity fields are not bodies: how a body's particles are divided among the grid's velocity
/// fields, node by node (docs/concepts.md, "Velocity fields").

#include "gimlet/core/fields.hpp"
#include "gimlet/core/material_point.hpp"
#include "gimlet/core/space.hpp"

#include <concepts>
#include <cstddef>

/// Multi-field contact's framework: how bodies are divided among velocity fields
/// (multi_field::Partition) and the contact passes at shared nodes.
namespace gimlet::multi_field {

/// How multi-field contact divides each body among velocity fields. Contact acts between fields
/// (contact::node_view), so a body split into several fields can touch itself where they meet:
/// the self-contact of a closing void.
/// - `fields_per_body` (k >= 1): body b owns the fields b k, ..., b k + k - 1 of every node.
/// - `required_fields`: field_list of the per-particle state it reads.
/// - with k > 1, `side(particle, node, position) const`: which of its body's k fields (an
///   index in [0, k)) the particle scatters to at grid node `node` at `position` (m). The solver
///   asks once per particle and stencil node at the start of each step, from the start-of-step
///   state, and every transfer of the step uses the answers; a side out of range stops the run,
///   naming the particle.
/// A node where one field has mass is what one velocity field would be, whatever its index:
/// splitting changes nothing until two fields of a body meet at a node.
///
/// Two optional hooks let a partition look at the grid (multi_field::self_contact uses both):
/// - `initialize(view)`: once, in the solver's constructor, with the particles writable (a
///   checkpoint loaded afterwards overwrites the fields it set with the saved ones);
/// - `prepare(view)`: at the start of every step (whatever fields_per_body), after the weights
///   and before the solver asks `side`, with the particles read-only (a partition keeps what it
///   learns in its own members).
/// Both get a multi_field::partition_view; write them as templates, `template <class View>
/// void prepare(const View& view)`. The solver calls a hook only if the partition has it, so a
/// hook with another name or a signature the solver cannot call is not an error: it is never
/// called. A third, `bool splits() const`, asked after `prepare`, may return false to say that
/// every side is 0 this step, so the solver need not ask `side` particle by particle; once a
/// step has completed with it false, the grid's node passes skip every body's fields past the
/// first while it stays false. Asked once a step (multi_field::check refuses a non-const one).
/// A fourth, `const std::vector<std::uint8_t>& split_rows() const`, asked after `prepare` on a
/// step that splits, names the rows of nodes along the last axis (grid::layer; one flag per
/// row, grid.nodes(dim - 1) of them, or the step stops with an error naming it) that hold a node
/// where `side` may answer other than 0: the solver then asks `side` only of the particles
/// whose stencils can reach a flagged row, and puts every other particle in its body's first
/// field.
/// Particle indices are those of the store at the time of the call: the solver renumbers the
/// particles when it sorts them (solver_options::sort_interval), so per-particle state belongs
/// in `required_fields`, not in members indexed by particle.
///
/// On many processes (solver_options::processes) each process holds its own particles only, so
/// a hook's per-node arrays see part of the particles at the nodes two processes share. A
/// partition with a hook runs there only if it says it completes them, `static constexpr bool
/// distributes = true`, through its view's `across` (multi_field::partition_view); the solver
/// refuses any other by name. A partition without hooks (its side() reads the particle alone)
/// runs on many processes as it is. The solver asks every process's splits() and splits where
/// any does.
template <class P>
concept Partition = requires {
    { P::fields_per_body } -> std::convertible_to<std::size_t>;
    typename P::required_fields;
    requires FieldList<typename P::required_fields>;
    requires P::fields_per_body >= 1;
} && (P::fields_per_body == 1 ||
      requires(const P& p, std::size_t node, const archetype_particle<2, P>& p2, const archetype_particle<3, P>& p3,
               const typename space<2, double>::vector& x2, const typename space<3, double>::vector& x3) {
          { p.side(p2, node, x2) } -> std::convertible_to<std::size_t>;
          { p.side(p3, node, x3) } -> std::convertible_to<std::size_t>;
      });

/// What a partition's optional hooks see: the particles (a particle_store, writable in
/// `initialize`), each particle's stencil at the current positions (`stencils[i].for_each(
/// f(node, S_ip, G_ip))`, nodes by storage index; `stencils[i].for_each_node_position(grid,
/// f(node, S_ip, x_i))` gives each node's position as grid.node_position does, without its
/// divisions), the grid (node_position, offset_from_node, offset_from, layer, nodes, size) and the
/// number of bodies. `for_each_particle_by_slab(f)` calls f(i) for every particle
/// in an order that lets f add into per-node arrays without races at the nodes of particle i's
/// own stencil (not at other nodes): every such node sums its particles' contributions in an
/// order fixed by the grid and the particle order, whatever the thread count (so results stay
/// thread-independent); `for_each_particle_by_slab(rows, f)` does the same for the particles
/// whose stencils can reach a row of nodes r of the last axis (grid.layer) with rows[r] != 0
/// (rows: a std::vector<std::uint8_t> of grid.nodes(dim - 1) flags, or it throws), and may skip
/// the others, in the same order. Neither may be called from inside f or another of the view's
/// loops (the rows' form keeps the slabs it visits in the solver). `for_each_index(count, f)` calls f(k) for every k in [0, count), split
/// between the solver's threads when count is large (a grid's entries): for per-node work
/// where f(k) writes only entry k. f must not throw.
///
/// `across` completes what crosses processes (solver_options::processes), so that a hook's
/// results are those of one process whatever their number; on one process each of its members
/// is the identity, at no cost. Every process calls its collective members (all but ordinal
/// and owns) alike, in the same order:
/// - `across.ordinal(i)`: particle i's index in the one-process run (i on one process), for a
///   choice between particles by index;
/// - `across.for_each_particle_by_slab_into(f, arrays...)`: for_each_particle_by_slab(f) for an
///   f that adds into `arrays` (std::vectors of whole blocks of grid.size() per-node values,
///   numbers or fixed-size Eigen vectors), each node's sums completed on every process that
///   holds it, in the one-process order;
/// - `across.merge_shared(blocks, get, merge)`: for per-node values combined in any order (a
///   maximum, a minimum, an or): at each node two processes both hold, in each of `blocks`
///   blocks of grid.size() entries, merge(e, theirs) with theirs the other process's get(e) (a
///   trivially copyable value); merge must leave both processes with the same value at e;
/// - `across.max(x)` (a double), `across.sum(n)` (a std::uint64_t), `across.any(flag)`: over
///   every process;
/// - `across.owns(node)`: whether the node counts as this process's (each node is one
///   process's), for a count over nodes.
template <class Store, class Stencils, class Grid, class BySlab, class ByIndex, class Across>
struct partition_view {
    /// The particles: writable in `initialize`, read-only in `prepare`.
    Store& particles;
    /// Each particle's stencil at the current positions, by particle index.
    const Stencils& stencils;
    /// The background grid.
    const Grid& grid;
    /// Number of bodies in the scene.
    std::size_t bodies;
    /// `for_each_particle_by_slab(f)` and `(rows, f)`: the race-free particle loops described above.
    BySlab for_each_particle_by_slab;
    /// `for_each_index(count, f)`: f(k) for k in [0, count), split between the solver's threads.
    ByIndex for_each_index;
    /// What crosses processes (ordinal, for_each_particle_by_slab_into, merge_shared, max, sum,
    /// any, owns), described above.
    Across across;
};

/// One velocity field per body (Bardenhagen et al. 2000): the default. A body never touches
/// itself; its particles share one field wherever they meet.
struct by_body {
    /// It reads no per-particle state.
    using required_fields = field_list<>;
    /// One field per body.
    static constexpr std::size_t fields_per_body = 1;
};

}  // namespace gimlet::multi_field
