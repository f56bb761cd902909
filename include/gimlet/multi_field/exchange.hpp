// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The multi-field contact framework across the grid: which nodes several velocity fields share,
/// their normals and gaps, the contact passes of a step and the pairs each keeps
/// (docs/equations.md, Contact). The correction at one node is multi_field::correct
/// (correct.hpp); which field a particle's mass goes to at a node, multi_field::Partition
/// (partition.hpp).

#include "gimlet/contact/concepts.hpp"
#include "gimlet/contact/node.hpp"
#include "gimlet/core/describe.hpp"
#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/detail/shares.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/core/grid.hpp"
#include "gimlet/core/processes.hpp"
#include "gimlet/multi_field/correct.hpp"

#include <algorithm>
#include <cstring>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <span>
#include <utility>
#include <vector>

namespace gimlet::multi_field {

/// Which contact pass of a step this is. Each node records the pairs of fields the deciding
/// pass engaged (contact::node_view::engaged_pairs); later passes of the step keep them.
/// - `decide` (the grid update's pass in MUSL and USL): the policy decides freely, on the
///   velocities after the forces of the current stress.
/// - `remap` (MUSL, after re-mapping): the recorded pairs keep their normal constraint
///   (node_view::kept_pairs) and the others stay free, as in the grid update (engaging pairs
///   afresh there changes a 500 m/s cavity collapse's energy by 3e-7 of the start).
/// - `trial` (USF, before the stress update): the policy decides as in `decide`, on the
///   velocities the forces of the current stress would give (grid::force); then the pairs it
///   engaged are constrained on the velocities the stress update will use. So USF engages
///   contact where MUSL would, while the contact force is compressive, and not on the sign of
///   a start-of-step relative velocity, which chatters near release.
/// - `keep` (USF, after the grid update): the recorded pairs only, constraint kept, so the
///   forces work on the velocities that strained the material.
enum class pass { decide, remap, trial, keep };


/// The state of multi-field contact in a solver: per step the shared nodes, their fields'
/// normals (from the mass gradients there), each pair's normal and reach, and the pairs the
/// deciding pass engaged. Only resolve() depends on the contact policy, so solvers that differ
/// only in their law share the rest (gimlet::solver_core).
template <Space S>
class exchange {
public:
    /// The scalar type of S.
    using real = typename S::real;
    /// S::vector.
    using vector = typename S::vector;

    /// Whether two or more fields have mass above the cut-off at `node`, as the step's
    /// find_shared_nodes found it (call that first).
    [[nodiscard]] bool shared(std::size_t node) const noexcept { return shared_index_[node] >= 0; }

    /// The nodes where two or more fields have mass above the cut-off, with each field's outward
    /// normal, each pair's normal and each field's furthest particle centre along it
    /// (contact::node_view::reach), from the positions at the start of the step. Only these
    /// nodes take part in contact, and the masses do not change within a step. mass[i] is
    /// particle i's mass, for the fields' mass gradients at these nodes. Field f belongs
    /// to body f / fields_per_body; entries_of(i) gives particle i's entry chooser: called with
    /// each node of its stencil in turn, the index of the field entry its mass went to there
    /// (field * nodes + node). for_each_particle(rows, f) calls f(i) for every particle whose
    /// stencil reaches a node row r (of the last axis) with rows[r] != 0 (it may call it for
    /// others too), never for two particles that share a node at once, and for those of each
    /// node in the scatter's order: the mass gradients are sums in that order.
    ///
    /// The pass over every node runs in blocks of nodes, on `threads` threads where `parallel`:
    /// each block counts its shared nodes, fields and pairs, the blocks' offsets follow in node
    /// order, and each block fills its part. The arrays are those of one pass in node order,
    /// whatever the thread count.
    ///
    /// On many processes (`on`), each finds the nodes of its own rows and bands (whose masses
    /// the scatter completed on both sides, so both find the same shared nodes there):
    /// for_each_particle(rows, f, array) then completes the mass gradients' sums in the bands
    /// (a nodal array, the scatter's exchange), and the reaches, maxima, are swapped per band.
    /// `window`: the node ranges this process's particles reach, increasing and apart (its rows
    /// and the band above), outside which every node is empty here: the node passes visit these
    /// only. Empty: the whole grid.
    template <class Stencils, class Masses, class Entries, class ForEach>
    void find_shared_nodes(const grid<S>& grid, real cutoff, std::uint64_t step, double time, const Stencils& stencils,
                           const Masses& mass, std::size_t fields_per_body, const Entries& entries_of, ForEach&& for_each_particle,
                           int threads = 1, bool parallel = false, gimlet::processes* on = nullptr,
                           std::span<const std::pair<std::size_t, std::size_t>> window = {}) {
        window_.assign(window.begin(), window.end());
        // On many processes a node with too many fields on one stops all before the exchanges below.
        if (on) on->together([&] { count_shared(grid, cutoff, step, time, threads, parallel); });
        else count_shared(grid, cutoff, step, time, threads, parallel);
        list_shared(grid, cutoff, fields_per_body, threads, parallel);
        shared_reach_.assign(shared_pair_normal_.size(), -std::numeric_limits<real>::infinity());
        normal_fraction_.assign(shared_pair_normal_.size(), real(1));
        slip_fraction_.assign(shared_pair_normal_.size(), real(0));
        engaged_.assign(shared_.size(), 0);
        // (On many processes every process takes part in the exchanges below, shared nodes or not.)
        if (shared_.empty() && !on) return;
        // The node rows of the last axis that hold a shared node: for_each_particle may skip
        // the particles whose stencils reach none of them.
        const auto rows = static_cast<std::size_t>(grid.nodes(S::dim - 1));
        shared_row_.assign(rows, 0);
        for (const shared_node& sn : shared_) shared_row_[std::size_t(grid.layer(sn.node))] = 1;
        sum_mass_gradients(grid, stencils, mass, entries_of, for_each_particle, on != nullptr);
        normals(threads, parallel);
        reaches(grid, stencils, entries_of, for_each_particle);
        if (on) combine_reaches(*on);
    }

    /// At every node shared by two or more fields, let the contact policy correct the fields'
    /// momenta (docs/physics.md section 3), then refresh their velocities and the walls.
    template <contact::Contact C>
    void resolve(pass pass, grid<S>& grid, C& contact, real dt, real cutoff) {
        const std::size_t nodes = grid.size();
        tally_type<C> pass_tally{};
        tally_type<C>* tally = &pass_tally;
        const bool trial = pass == pass::trial, deciding = trial || pass == pass::decide;
        if (trial) {
            // v + dt f / m with the walls, as MUSL and USL decide after the grid update.
            trial_velocity_.resize(grid.entries());  // (zero outside the window, where nothing has mass)
            for (std::size_t base = 0; base < grid.entries(); base += nodes)
                for_window_nodes(0, nodes, [&](std::size_t node) {
                    const std::size_t e = base + node;
                    trial_velocity_[e] = grid.mass[e] > cutoff
                                             ? vector(grid.velocity_old[e] + dt * grid.force[e] / grid.mass[e])
                                             : vector::Zero();
                });
            grid.apply_walls(trial_velocity_, wall_pass::trial);
        }
        for (std::size_t s = 0; s < shared_.size(); ++s) {
            if (pass == pass::keep && engaged_[s] == 0) continue;
            const shared_node& sn = shared_[s];
            const std::size_t k = sn.count;
            m_.resize(k), p_.resize(k), p_before_.resize(k);
            auto load = [&](const std::vector<vector>& velocity) {
                for (std::size_t j = 0; j < k; ++j) {
                    const std::size_t e = shared_field_[sn.first_field + j] * nodes + sn.node;
                    m_[j] = grid.mass[e];
                    p_[j] = grid.mass[e] * velocity[e];  // after walls
                }
            };
            load(trial ? trial_velocity_ : grid.velocity);
            std::copy(p_.begin(), p_.end(), p_before_.begin());
            contact::node_view<S> view{k,
                                       shared_field_.data() + sn.first_field,
                                       shared_owner_.data() + sn.first_field,
                                       m_.data(),
                                       p_.data(),
                                       shared_normal_.data() + sn.first_field,
                                       shared_reach_.data() + sn.first_pair,
                                       grid.cell(),
                                       dt};
            view.node = sn.node;
            view.position = grid.node_position(sn.node);
            view.normal_fraction = normal_fraction_.data() + sn.first_pair;
            view.slip_fraction = slip_fraction_.data() + sn.first_pair;
            if (!deciding) {
                view.kept_pairs = engaged_[s];
                view.open_pairs = 0;
            }
            resolve_node(view, contact, tally);
            if (deciding) {
                std::uint64_t pairs = view.engaged_pairs;
                // A user policy that corrects without saying which pairs: all of them.
                for (std::size_t j = 0; j < k && pairs == 0; ++j)
                    if (p_[j] != p_before_[j]) pairs = ~std::uint64_t(0);
                engaged_[s] = pairs;
            }
            if (trial) {
                if (engaged_[s] == 0) continue;
                load(grid.velocity);
                view.kept_pairs = engaged_[s];
                view.open_pairs = 0;
                view.engaged_pairs = 0;
                resolve_node(view, contact, tally);
            }
            for (std::size_t j = 0; j < k; ++j) {
                const std::size_t e = shared_field_[sn.first_field + j] * nodes + sn.node;
                grid.velocity[e] = p_[j] / m_[j];
            }
        }
        grid.apply_walls(grid.velocity, pass == pass::remap ? wall_pass::keep : wall_pass::decide);
        if constexpr (counting<C>) contact.record(std::as_const(pass_tally));
        else (void)tally;
    }

    /// The fastest approach, (v_a - v_b) . n_ab > 0, of two fields at a node they share whose
    /// facing particle centres are less than `within` apart along the pair's normal
    /// (contact::node_view::gap), from the nodes' P2G momenta (the step's v^n); 0 where none
    /// approaches. The largest over the nodes, so the same for any thread count.
    [[nodiscard]] real closing_speed(const grid<S>& grid, real within) const {
        const std::size_t nodes = grid.size();
        real fastest = 0;
        for (const shared_node& sn : shared_) {
            const std::size_t k = sn.count;
            for (std::size_t a = 0; a + 1 < k; ++a) {
                const std::size_t ea = shared_field_[sn.first_field + a] * nodes + sn.node;
                for (std::size_t b = a + 1; b < k; ++b) {
                    const std::size_t eb = shared_field_[sn.first_field + b] * nodes + sn.node;
                    if (!(contact::facing_gap(shared_reach_.data() + sn.first_pair, k, a, b) < within)) continue;
                    const vector relative = grid.momentum[ea] / grid.mass[ea] - grid.momentum[eb] / grid.mass[eb];
                    fastest = std::max(fastest, relative.dot(shared_pair_normal_[sn.first_pair + a * k + b]));
                }
            }
        }
        return fastest;
    }

    /// What contact did to a particle with stencil `st` and entry chooser `entry` (as in
    /// find_shared_nodes) in this step (contact::particle_contact): whether a node of its
    /// stencil held an engaged pair of its field there, and its weight on those nodes.
    template <class Stencil, class Entry>
    [[nodiscard]] contact::particle_contact<S> contact_of(Entry entry, const Stencil& st, std::size_t nodes) const {
        contact::particle_contact<S> info;
        st.for_each([&](std::size_t node, real w, const vector&) {
            const std::size_t e = entry(node);  // asked at every node, in order
            const std::ptrdiff_t s = shared_index_[node];
            if (s < 0 || engaged_[std::size_t(s)] == 0) return;
            const std::size_t field = (e - node) / nodes;
            const shared_node& sn = shared_[std::size_t(s)];
            std::size_t a = 0;
            while (a < sn.count && shared_field_[sn.first_field + a] != field) ++a;
            if (a == sn.count) return;
            for (std::size_t b = 0; b < sn.count; ++b)
                if (engaged_[std::size_t(s)] & contact::node_view<S>::pair_bit(sn.count, a, b)) {
                    info.engaged = true;
                    info.weight += w;
                    return;
                }
        });
        return info;
    }

private:
    static constexpr std::size_t node_block = 4096;  // the node passes' blocks of nodes
    static constexpr std::size_t max_k = contact::node_view<S>::max_fields;

    // f(node) for the nodes of [first, last) in the window (find_shared_nodes), in increasing order.
    template <class F>
    void for_window_nodes(std::size_t first, std::size_t last, F&& f) const {
        if (window_.empty()) {
            for (std::size_t node = first; node < last; ++node) f(node);
            return;
        }
        for (const auto& [a, b] : window_)
            for (std::size_t node = std::max(first, a), end = std::min(last, b); node < end; ++node) f(node);
    }

    // The fields above the cut-off at a node, in field order (at most max_k + 1 written to out);
    // returns how many there are.
    static std::size_t fields_at(const grid<S>& grid, real cutoff, std::size_t node, std::uint32_t* out) {
        const std::size_t nodes = grid.size(), fields_n = grid.field_count();
        std::size_t k = 0;
        for (std::size_t f = 0; f < fields_n; ++f)
            if (grid.mass[f * nodes + node] > cutoff) {
                if (k <= max_k) out[k] = static_cast<std::uint32_t>(f);
                ++k;
            }
        return k;
    }

    // Each block of nodes counts its shared nodes, fields and pairs, and marks the nodes shared
    // (shared_index_ 0) or not (-1); then the blocks' counts become their offsets, in node
    // order. A node shared by more than max_k fields stops the run (the lowest such node, as a
    // serial pass would stop at).
    void count_shared(const grid<S>& grid, real cutoff, std::uint64_t step, double time, int threads, bool parallel) {
        const std::size_t nodes = grid.size(), fields_n = grid.field_count();
        const std::size_t blocks = (nodes + node_block - 1) / node_block;
        if (shared_index_.size() != nodes) shared_index_.assign(nodes, -1);  // outside the window for good
        block_count_.assign(blocks, {});
        const auto blocks_n = static_cast<std::ptrdiff_t>(blocks);
        gimlet::detail::thread_shares count_shares(blocks_n, threads, parallel);
        GIMLET_OMP(parallel num_threads(count_shares.team()))
        for (auto claimed = count_shares.start(); count_shares.claim(claimed);)
            for (std::ptrdiff_t b = claimed.first, end = claimed.last; b < end; ++b) {
                block_counts& c = block_count_[std::size_t(b)];
                std::uint32_t ids[max_k + 1];
                const std::size_t first = std::size_t(b) * node_block;
                for_window_nodes(first, std::min(nodes, first + node_block), [&](std::size_t node) {
                    const std::size_t k = fields_at(grid, cutoff, node, ids);
                    shared_index_[node] = k < 2 ? -1 : 0;
                    if (k < 2) return;
                    if (k > max_k) {
                        c.too_many = std::min(c.too_many, node);
                        return;
                    }
                    ++c.nodes, c.fields += k, c.pairs += k * k;
                });
            }
        block_counts total{};
        for (block_counts& c : block_count_) {
            if (c.too_many < nodes) {
                std::uint32_t ids[max_k + 1];
                const std::size_t k = fields_at(grid, cutoff, c.too_many, ids);
                std::string list;
                for (std::size_t f = 0; f < fields_n; ++f)
                    if (grid.mass[f * nodes + c.too_many] > cutoff) list += (list.empty() ? "" : ", ") + std::to_string(f);
                throw numerical_error("gimlet: step " + std::to_string(step) + " (t = " +
                                      gimlet::detail::to_text(time) + " s): grid node at " +
                                      gimlet::detail::format_position(grid.node_position(c.too_many)) + " is shared by " +
                                      std::to_string(k) + " velocity fields (" + list + "); multi-field contact handles at most " +
                                      std::to_string(max_k) + " at one node");
            }
            const block_counts start{total.nodes, total.fields, total.pairs, nodes};
            total.nodes += c.nodes, total.fields += c.fields, total.pairs += c.pairs;
            c = start;  // the block's offsets from here on
        }
        shared_.resize(total.nodes), shared_field_.resize(total.fields), shared_owner_.resize(total.fields);
        shared_normal_.resize(total.fields), shared_pair_normal_.resize(total.pairs);
    }

    // Each block fills its part of the shared nodes' arrays from its offsets: the node, its
    // fields and their bodies (field / fields_per_body), the normals' sums cleared.
    void list_shared(const grid<S>& grid, real cutoff, std::size_t fields_per_body, int threads, bool parallel) {
        const std::size_t nodes = grid.size();
        const auto blocks_n = static_cast<std::ptrdiff_t>(block_count_.size());
        gimlet::detail::thread_shares fill_shares(blocks_n, threads, parallel);
        GIMLET_OMP(parallel num_threads(fill_shares.team()))
        for (auto claimed = fill_shares.start(); fill_shares.claim(claimed);)
            for (std::ptrdiff_t b = claimed.first, end = claimed.last; b < end; ++b) {
                block_counts at = block_count_[std::size_t(b)];
                const std::size_t first_node = std::size_t(b) * node_block;
                for_window_nodes(first_node, std::min(nodes, first_node + node_block), [&](std::size_t node) {
                    if (shared_index_[node] < 0) return;
                    const std::size_t first = at.fields;
                    const std::size_t k = fields_at(grid, cutoff, node, shared_field_.data() + first);
                    shared_index_[node] = static_cast<std::ptrdiff_t>(at.nodes);
                    shared_[at.nodes] = {node, first, k, at.pairs};
                    for (std::size_t j = 0; j < k; ++j) {
                        shared_owner_[first + j] = static_cast<std::uint32_t>(shared_field_[first + j] / fields_per_body);
                        shared_normal_[first + j] = vector::Zero();  // the mass gradient's sum (sum_mass_gradients)
                    }
                    ++at.nodes, at.fields += k, at.pairs += k * k;
                });
            }
    }

    // Each shared field's mass gradient sum_p m_p G_ip, at the shared nodes only (the only place
    // it is read): summed into shared_normal_ by the particles that reach a shared row, slab by
    // slab as the scatter visits them, so each node's sum has the scatter's terms in the
    // scatter's order, whatever the thread count. G is the gradient with respect to the particle
    // position, so the sum points out of the body (docs/physics.md section 3; Bardenhagen et al.
    // 2000, eq. 16). `across` (many processes): the same sums into a nodal array (field x node)
    // whose bands the scatter's exchange completes in the one-process order, then copied to the
    // shared fields.
    template <class Stencils, class Masses, class Entries, class ForEach>
    void sum_mass_gradients(const grid<S>& grid, const Stencils& stencils, const Masses& mass, const Entries& entries_of,
                            ForEach& for_each_particle, bool across) {
        const std::size_t nodes = grid.size();
        if (across && gradient_.size() != grid.entries()) gradient_.assign(grid.entries(), vector::Zero());
        else if (across)  // (zero outside the window for good)
            for (std::size_t base = 0; base < grid.entries(); base += nodes)
                for_window_nodes(0, nodes, [&](std::size_t node) { gradient_[base + node] = vector::Zero(); });
        auto particle = [&](std::size_t i) {
            auto entry = entries_of(i);
            const real mp = mass[i];
            stencils[i].for_each([&](std::size_t node, real, const vector& g) {
                const std::size_t e = entry(node);  // asked at every node, in order
                const std::ptrdiff_t s = shared_index_[node];
                if (s < 0) return;
                const shared_node& sn = shared_[std::size_t(s)];
                const std::size_t field = (e - node) / nodes;
                for (std::size_t a = 0; a < sn.count; ++a)
                    if (shared_field_[sn.first_field + a] == field) {
                        (across ? gradient_[e] : shared_normal_[sn.first_field + a]) += mp * g;
                        return;
                    }  // else below the cut-off at this node
            });
        };
        if (!across) return for_each_particle(shared_row_, particle);
        for_each_particle(shared_row_, particle, gradient_);
        for (const shared_node& sn : shared_)
            for (std::size_t a = 0; a < sn.count; ++a)
                shared_normal_[sn.first_field + a] = gradient_[shared_field_[sn.first_field + a] * nodes + sn.node];
    }

    // The reaches, maxima over each process's particles, combined over the bands' shared nodes
    // (the same nodes, fields and pairs in the same order on both processes of a band).
    void combine_reaches(gimlet::processes& on) {
        const auto bands = on.bands();
        auto in_band = [&](const shared_band& b, const shared_node& sn) { return sn.node >= b.first && sn.node < b.first + b.count; };
        std::vector<std::vector<std::byte>> mine(bands.size());
        for (std::size_t b = 0; b < bands.size(); ++b)
            for (const shared_node& sn : shared_) {
                if (!in_band(bands[b], sn)) continue;
                const std::size_t bytes = sn.count * sn.count * sizeof(real), at = mine[b].size();
                mine[b].resize(at + bytes);
                std::memcpy(mine[b].data() + at, shared_reach_.data() + sn.first_pair, bytes);
            }
        const auto theirs = on.swap(mine);
        for (std::size_t b = 0; b < bands.size(); ++b) {
            require(theirs[b].size() == mine[b].size(), "shared-node reaches passed between processes (bytes)",
                    double(theirs[b].size()), std::to_string(mine[b].size()) + ": the same shared nodes on both sides of a band");
            std::size_t at = 0;
            for (const shared_node& sn : shared_) {
                if (!in_band(bands[b], sn)) continue;
                for (std::size_t k = 0; k < sn.count * sn.count; ++k, at += sizeof(real)) {
                    real other;
                    std::memcpy(&other, theirs[b].data() + at, sizeof(real));
                    real& r = shared_reach_[sn.first_pair + k];
                    r = std::max(r, other);
                }
            }
        }
    }

    // The fields' unit normals and each pair's normal, node by node.
    void normals(int threads, bool parallel) {
        const auto shared_n = static_cast<std::ptrdiff_t>(shared_.size());
        gimlet::detail::thread_shares normal_shares(shared_n, threads, parallel && shared_n >= std::ptrdiff_t(node_block));
        GIMLET_OMP(parallel num_threads(normal_shares.team()))
        for (auto claimed = normal_shares.start(); normal_shares.claim(claimed);)
            for (std::ptrdiff_t s = claimed.first, end = claimed.last; s < end; ++s) {
                const shared_node& sn = shared_[std::size_t(s)];
                const std::size_t first = sn.first_field, k = sn.count;
                for (std::size_t j = 0; j < k; ++j) {
                    const vector g = shared_normal_[first + j];
                    const real len = g.norm();
                    shared_normal_[first + j] = len > real(0) ? vector(g / len) : vector::Zero();
                }
                // The policies correct along the same n_ab (contact::pair_normal); n_ba = -n_ab.
                for (std::size_t a = 0; a < k; ++a)
                    for (std::size_t b2 = 0; b2 < k; ++b2)
                        shared_pair_normal_[sn.first_pair + a * k + b2] =
                            a != b2 ? contact::pair_normal(shared_normal_[first + a], shared_normal_[first + b2]) : vector::Zero();
            }
    }

    // Each pair's furthest particle centre along its normal (contact::node_view::reach). Particles
    // of one node are visited by one thread at a time (slab colouring), and a maximum does not
    // depend on the order: the result is the same for any thread count.
    template <class Stencils, class Entries, class ForEach>
    void reaches(const grid<S>& grid, const Stencils& stencils, const Entries& entries_of, ForEach& for_each_particle) {
        const std::size_t nodes = grid.size();
        for_each_particle(shared_row_, [&](std::size_t i) {
            auto entry = entries_of(i);
            stencils[i].for_each_offset(grid.cell(), [&](std::size_t node, real w, const vector& r) {
                const std::size_t e = entry(node);  // asked at every node, in order
                const std::ptrdiff_t s = shared_index_[node];
                if (s < 0 || !(w > real(0))) return;  // a node the particle does not weigh
                const std::size_t field = (e - node) / nodes;
                const shared_node& sn = shared_[std::size_t(s)];
                std::size_t a = 0;
                while (a < sn.count && shared_field_[sn.first_field + a] != field) ++a;
                if (a == sn.count) return;  // below the cut-off at this node
                for (std::size_t b = 0; b < sn.count; ++b) {
                    if (b == a) continue;
                    const std::size_t slot = sn.first_pair + a * sn.count + b;
                    shared_reach_[slot] = std::max(shared_reach_[slot], r.dot(shared_pair_normal_[slot]));
                }
            });
        });
    }

    // A contact law's counters (contact::Counting), or nothing.
    template <class C>
    static constexpr bool counts() {
        if constexpr (requires { typename C::tally; }) return contact::Counting<C, S>;
        else return false;
    }
    template <class C>
    static constexpr bool counting = counts<C>();
    struct no_tally {};
    template <class C>
    static auto tally_identity() {
        if constexpr (counting<C>) return std::type_identity<typename C::tally>{};
        else return std::type_identity<no_tally>{};
    }
    template <class C>
    using tally_type = typename decltype(tally_identity<C>())::type;

    // The policy's correction at one node: the framework's for a contact::Law, its own for a
    // contact::NodeResolver.
    template <class C>
    static void resolve_node(contact::node_view<S>& view, C& contact, tally_type<C>* tally) {
        if constexpr (contact::Law<C>) {
            if constexpr (counting<C>) multi_field::correct(view, contact, tally);
            else multi_field::correct(view, contact);
        } else {
            (void)tally;
            contact.resolve(view);
        }
    }

    // The nodes shared by two or more fields (find_shared_nodes) with, per shared node, its
    // fields, their bodies and their normals (shared_field_, shared_owner_, shared_normal_ from
    // first_field), its pairs' normals and reaches (count x count from first_pair) and the pairs
    // engaged by the step's deciding pass; scratch space for one node's masses and momenta.
    struct shared_node {
        std::size_t node, first_field, count, first_pair;
    };
    std::vector<std::ptrdiff_t> shared_index_;
    std::vector<std::uint8_t> shared_row_;  // per node row of the last axis: whether it has a shared node
    std::vector<shared_node> shared_;
    // Per block of nodes in find_shared_nodes: its shared nodes, fields and pairs (then its
    // offsets), and its first node shared by more fields than a node view holds.
    struct block_counts {
        std::size_t nodes = 0, fields = 0, pairs = 0, too_many = std::numeric_limits<std::size_t>::max();
    };
    std::vector<block_counts> block_count_;
    std::vector<std::uint32_t> shared_field_, shared_owner_;
    std::vector<vector> shared_normal_, shared_pair_normal_;
    std::vector<real> shared_reach_;
    // Per shared node and pair: what a law's impulse removed where the deciding pass engaged it
    // (contact::node_view::normal_fraction, slip_fraction).
    std::vector<real> normal_fraction_, slip_fraction_;
    std::vector<std::uint64_t> engaged_;
    std::vector<real> m_;
    std::vector<vector> p_, p_before_, trial_velocity_;
    std::vector<vector> gradient_;  // on many processes: the mass gradients per field and node
    std::vector<std::pair<std::size_t, std::size_t>> window_;  // find_shared_nodes's window
};

}  // namespace gimlet::multi_field
