// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Self-contact: a body's two sides of a closing void or crack in separate velocity fields where
/// they meet, so the multi-field contact laws act on them as between bodies (docs/equations.md,
/// "Self-contact"; after the field-gradient partitioning of Homel & Herbold 2017, IJNME 109).

#include "gimlet/core/error.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/space.hpp"
#include "gimlet/multi_field/partition.hpp"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace gimlet {

namespace fields {
/// The outward normal of the body's surface near the particle in the reference configuration,
/// scaled by the body's surface field there: about 1 at a free surface, a third one particle row
/// in, exactly 0 from the third row (at 2 x 2 particles per cell). A feature one cell thick or
/// less (a plate of two particle rows) has no normal on a face whose opposite face lies within
/// a cell: the two faces' mass gradients cancel at the nodes between them. Set once by
/// multi_field::self_contact when the solver is built; carried by the material (the current
/// normal is cof(F) times it).
struct surface_normal {
    /// Per particle: an S::vector.
    template <class S> using type = typename S::vector;
    /// The field's name in output files and error messages.
    static constexpr const char* name = "surface_normal";
};
}  // namespace fields

namespace multi_field {

/// Splits each body into two velocity fields at the nodes where two of its own surfaces face
/// each other across a gap, and keeps one field everywhere else (docs/equations.md,
/// "Self-contact").
///
/// - At construction (`initialize`), each particle's surface normal is the body's mass gradient
///   sum_q m_q G_iq interpolated to it, scaled by the body's largest; below `surface_cutoff`
///   of that it is zero (the bulk). No neighbour search: two scatters over the grid.
/// - Each step (`prepare`), at each node and body: the reference direction e is the current
///   normal of the particle with the largest S_ip m_p |n_p| there. The particles whose normal
///   points along e (n . e > 1/2) have their front at the largest (x_p - x_i) . e, those
///   pointing against it (n . e < -1/2) at the smallest. The node is split only if both groups
///   are present and face each other across a gap: the second front lies beyond the first, and
///   no particle of the body lies in the middle half between them. Two faces of one ligament
///   point away from each other, so a jet or a thin strip stays one field; intact material just
///   beyond a slot's tip, which both faces reach, fills the space between them.
/// - At a split node every particle of the body goes by its side of the plane midway between
///   the fronts (field 0 behind the surface whose normal is e, field 1 beyond), so a particle
///   without a normal still has a side. A third surface at the node takes the side of the plane
///   it lies on: two fields at most per body and node, never a failure.
/// - `enabled = false` keeps one field per body everywhere (results as multi_field::by_body);
///   a scene without voids pays for `prepare` only.
/// - On many processes (solver_options::processes) the mass gradients are completed across
///   them in the one-process order, and at the nodes two processes share the reference
///   direction (the larger key, ties to the lower ordinal), the fronts (the farther) and a
///   particle in the gap (either's) are merged: the same split nodes and planes as one process.
struct self_contact {
    /// Keeps each particle's reference surface normal.
    using required_fields = field_list<fields::surface_normal>;
    /// Two fields per body: the two sides of a closing void.
    static constexpr std::size_t fields_per_body = 2;
    /// Its hooks complete their per-node arrays across processes (multi_field::Partition).
    static constexpr bool distributes = true;

    /// False: one field per body everywhere (as multi_field::by_body).
    bool enabled = true;
    /// Particles whose surface field is below this fraction of the body's largest are bulk; in
    /// (0, 1), checked when the solver is built (at 0 round-off gives bulk particles normals).
    double surface_cutoff = 0.05;

    /// The surface normals at t = 0 (multi_field::Partition's initialize hook).
    template <class View>
    void initialize(View& view) {
        using store_t = std::remove_cvref_t<decltype(view.particles)>;
        using S = typename store_t::space_type;
        using vector = typename S::vector;
        using real = typename S::real;
        require(surface_cutoff > 0 && surface_cutoff < 1, "self_contact::surface_cutoff", surface_cutoff,
                "(0, 1): a fraction of the body's largest surface field");
        auto& ps = view.particles;
        const std::size_t nodes = view.grid.size(), n = ps.size();
        const auto& mass = ps.template column<fields::mass>();
        const auto& body = ps.template column<fields::body>();
        auto& normal = ps.template column<fields::surface_normal>();
        // Each body's mass gradient at the nodes: sum_q m_q G_iq points out of the body
        // (Bardenhagen et al. 2000, eq. 16).
        std::vector<vector> gradient(view.bodies * nodes, vector::Zero());
        view.across.for_each_particle_by_slab_into(
            [&](std::size_t i) {
                const std::size_t base = std::size_t(body[i]) * nodes;
                view.stencils[i].for_each(
                    [&](std::size_t node, real, const vector& g) { gradient[base + node] += mass[i] * g; });
            },
            gradient);
        std::vector<real> largest(view.bodies, real(0));
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t base = std::size_t(body[i]) * nodes;
            vector at = vector::Zero();
            view.stencils[i].for_each([&](std::size_t node, real w, const vector&) { at += w * gradient[base + node]; });
            normal[i] = at;
            largest[body[i]] = std::max(largest[body[i]], real(at.norm()));
        }
        for (auto& top : largest) top = real(view.across.max(double(top)));  // exact: a maximum
        for (std::size_t i = 0; i < n; ++i) {
            const real top = largest[body[i]];
            const real size = top > 0 ? real(normal[i].norm()) / top : real(0);
            normal[i] = size >= real(surface_cutoff) ? vector(normal[i] / top) : vector::Zero();
        }
    }

    /// The split nodes of this step (multi_field::Partition's prepare hook): the reference
    /// direction of each node and body (pass 1), the fronts of the surfaces facing along it and
    /// against it (pass 2), the candidates where a gap lies between them, and those whose gap
    /// holds no particle of the body (pass 3).
    template <class View>
    void prepare(const View& view) {
        using S = space_of<View>;
        const std::size_t nodes = view.grid.size(), entries = view.bodies * nodes;
        split_nodes_ = 0;
        if (!enabled) {
            split_.assign(entries, 0);
            split_rows_.assign(std::size_t(view.grid.nodes(S::dim - 1)), 0);
            return;
        }
        reset_entries(view, entries);
        reference_directions(view);
        fronts(view);
        // Every process looks for particles in the gaps if any has a candidate (its passes merge
        // the nodes they share).
        const bool any = view.across.any(find_candidates(view, entries));
        if (any) empty_gaps(view);
        count_split(view, entries, any);
    }

    /// Field 0 or 1 of the particle's body at `node` (multi_field::Partition).
    template <class P, class V>
    [[nodiscard]] std::size_t side(const P& p, std::size_t node, const V& node_position) const {
        const std::size_t e = std::size_t(p.template get<fields::body>()) * nodes_ + node;
        if (e >= split_.size() || !split_[e]) return 0;
        const auto& x = p.template get<fields::position>();
        // The particle's space's dimension (what prepare used), not a member set at run time: the
        // compiler then sees that the loop cannot read past node_position (g++ 12 with AVX-512
        // warns otherwise).
        constexpr int dims = P::space_type::dim;
        double along = 0;
        for (int d = 0; d < dims; ++d) {
            double off = double(x[d] - node_position[d]);
            const double len = grid_length_[std::size_t(d)];
            if (len > 0) {
                if (off > len / 2) off -= len;
                else if (off < -len / 2) off += len;
            }
            along += off * unit_[e * std::size_t(dims) + std::size_t(d)];
        }
        return along < 0.5 * (front_along_[e] + front_against_[e]) ? 0 : 1;
    }

    /// The rows of nodes along the last axis (grid::layer) that hold a split node this step
    /// (multi_field::Partition's optional split_rows()): side() is 0 at every other node.
    [[nodiscard]] const std::vector<std::uint8_t>& split_rows() const noexcept { return split_rows_; }

    /// Nodes (times bodies) split in the last step: zero where no two surfaces of a body face
    /// each other.
    [[nodiscard]] std::size_t split_nodes() const noexcept { return split_nodes_; }
    /// False when no node is split this step: every side is 0 (multi_field::Partition's
    /// optional splits(), which spares the solver asking side() particle by particle).
    [[nodiscard]] bool splits() const noexcept { return split_nodes_ > 0; }

private:
    template <class View>
    using space_of = typename std::remove_cvref_t<decltype(std::declval<const View&>().particles)>::space_type;
    static constexpr double none = -1;  // no reference particle at an entry yet
    static constexpr double inf = std::numeric_limits<double>::infinity();

    // |n0| where the particle has a normal, 0 in the bulk: the test needs no square root
    // (norm() is the root of squaredNorm(), so the two are zero together).
    template <class View>
    [[nodiscard]] static auto normal_size(const View& view, std::size_t i) {
        using real = typename space_of<View>::real;
        const real a2 = view.particles.template column<fields::surface_normal>()[i].squaredNorm();
        return a2 > 0 ? real(std::sqrt(a2)) : real(0);
    }

    // The current normal: cof(F) n0 (Nanson), scaled back to |n0| = a, into current_. Each
    // particle with a normal (a > 0) writes its own entries in pass 1 (which does not read them),
    // and pass 2 and the reference directions read them. A bulk particle's entries are neither
    // written nor read: passes 1 and 2 skip it after one test.
    template <class View>
    void set_current_normal(const View& view, std::size_t i, typename space_of<View>::real a) {
        using S = space_of<View>;
        const auto& F = view.particles.template column<fields::deformation_gradient>();
        const auto& normal0 = view.particles.template column<fields::surface_normal>();
        const typename S::matrix inv_t = F[i].inverse().transpose();
        typename S::vector c = inv_t * normal0[i];
        const typename S::real len = c.norm();
        c = len > 0 && std::isfinite(double(len)) ? typename S::vector(c * (a / len)) : S::vector::Zero();
        for (int d = 0; d < S::dim; ++d) current_[i * std::size_t(S::dim) + std::size_t(d)] = double(c[d]);
    }

    template <class S>
    [[nodiscard]] typename S::vector current_normal(std::size_t i) const {
        typename S::vector c;
        for (int d = 0; d < S::dim; ++d) c[d] = typename S::real(current_[i * std::size_t(S::dim) + std::size_t(d)]);
        return c;
    }

    // The reference direction e of a node and body, normalised by the first particle of pass 2
    // that reaches it (pass 2 reaches every entry pass 1 set, and only those) rather than at every
    // one: the passes by slab give one thread at a time a particle's nodes. Pass 3 and the split
    // nodes' planes read it at the candidates, which pass 2 has reached.
    template <class S>
    [[nodiscard]] typename S::vector unit(std::size_t e, [[maybe_unused]] std::size_t n) {
        constexpr int dim = S::dim;
        typename S::vector ref;
        if (!unit_set_[e]) {
            // Pass 1 set it wherever pass 2 asks (finite masses); an entry whose reference is
            // another process's has its direction set already (merge_reference_directions).
            assert(best_particle_[e] < n);
            ref = current_normal<S>(best_particle_[e]).normalized();
            for (int d = 0; d < dim; ++d) unit_[e * std::size_t(dim) + std::size_t(d)] = double(ref[d]);
            unit_set_[e] = 1;
        }
        for (int d = 0; d < dim; ++d) ref[d] = typename S::real(unit_[e * std::size_t(dim) + std::size_t(d)]);
        return ref;
    }

    // Every entry without a reference particle, fronts or direction.
    template <class View>
    void reset_entries(const View& view, std::size_t entries) {
        constexpr int dim = space_of<View>::dim;
        current_.resize(view.particles.size() * std::size_t(dim));
        best_.resize(entries), best_particle_.resize(entries);
        front_along_.resize(entries), front_against_.resize(entries);
        unit_.resize(entries * std::size_t(dim)), unit_set_.resize(entries);
        view.for_each_index(entries, [&](std::size_t e) {
            best_[e] = none, best_particle_[e] = std::numeric_limits<std::size_t>::max();
            front_along_[e] = -inf, front_against_[e] = inf;
            unit_set_[e] = 0;
        });
    }

    // Pass 1: each particle's current normal, and the reference direction of each node and body
    // (largest S m |n|, ties to the lower particle index, so the choice does not depend on the
    // order of the sum).
    template <class View>
    void reference_directions(const View& view) {
        using S = space_of<View>;
        using real = typename S::real;
        const std::size_t nodes = view.grid.size();
        const auto& mass = view.particles.template column<fields::mass>();
        const auto& body = view.particles.template column<fields::body>();
        view.for_each_particle_by_slab([&](std::size_t i) {
            const real a = normal_size(view, i);
            if (!(a > 0)) return;
            set_current_normal(view, i, a);
            const std::size_t base = std::size_t(body[i]) * nodes;
            view.stencils[i].for_each([&](std::size_t node, real w, const typename S::vector&) {
                if (!(w > 0)) return;
                const std::size_t e = base + node;
                const double key = double(w * mass[i] * a);
                if (key > best_[e] || (key == best_[e] && i < best_particle_[e])) best_[e] = key, best_particle_[e] = i;
            });
        });
        merge_reference_directions(view);
    }

    // At the nodes two processes share, the reference particle of the two with the larger key,
    // ties to the lower ordinal (within a process, indices run in ordinal order), as one process
    // picks it among them all; its direction travels, as the first particle of pass 2 would set
    // it. One process: nothing to merge.
    template <class View>
    void merge_reference_directions(const View& view) {
        using S = space_of<View>;
        constexpr int dim = S::dim;
        struct reference {
            double key = none;
            std::uint64_t ordinal = std::numeric_limits<std::uint64_t>::max();
            double unit[dim] = {};
        };
        const std::size_t n = view.particles.size();
        const auto mine = [&](std::size_t e) {
            reference r;
            if (best_[e] == none) return r;
            r.key = best_[e], r.ordinal = view.across.ordinal(best_particle_[e]);
            const typename S::vector u = unit<S>(e, n);
            for (int d = 0; d < dim; ++d) r.unit[d] = double(u[d]);
            return r;
        };
        view.across.merge_shared(view.bodies, mine, [&](std::size_t e, const reference& theirs) {
            const std::uint64_t ours =
                best_[e] == none ? std::numeric_limits<std::uint64_t>::max() : view.across.ordinal(best_particle_[e]);
            if (!(theirs.key > best_[e] || (theirs.key == best_[e] && theirs.ordinal < ours))) return;
            best_[e] = theirs.key, best_particle_[e] = std::numeric_limits<std::size_t>::max() - 1;  // another process's
            for (int d = 0; d < dim; ++d) unit_[e * std::size_t(dim) + std::size_t(d)] = theirs.unit[d];
            unit_set_[e] = 1;
        });
    }

    // Pass 2: the fronts of the particles facing along e and against it. (The nodes' positions
    // from the stencil, as grid::node_position gives them.)
    template <class View>
    void fronts(const View& view) {
        using S = space_of<View>;
        using real = typename S::real;
        using vector = typename S::vector;
        const std::size_t nodes = view.grid.size(), n = view.particles.size();
        const auto& body = view.particles.template column<fields::body>();
        view.for_each_particle_by_slab([&](std::size_t i) {
            const real a = normal_size(view, i);
            if (!(a > 0)) return;
            const vector c = current_normal<S>(i) / a;
            const std::size_t base = std::size_t(body[i]) * nodes;
            const vector x = view.particles.template column<fields::position>()[i];
            view.stencils[i].for_each_node_position(view.grid, [&](std::size_t node, real w, const vector& at) {
                if (!(w > 0)) return;
                const std::size_t e = base + node;
                const vector ref = unit<S>(e, n);
                const double facing = double(c.dot(ref));
                const double along = double(view.grid.offset_from(x, at).dot(ref));
                if (facing > 0.5) front_along_[e] = std::max(front_along_[e], along);
                if (facing < -0.5) front_against_[e] = std::min(front_against_[e], along);
            });
        });
        // The nodes two processes share: the farther fronts of the two (a maximum and a minimum).
        struct pair {
            double along, against;
        };
        view.across.merge_shared(
            view.bodies, [&](std::size_t e) { return pair{front_along_[e], front_against_[e]}; },
            [&](std::size_t e, const pair& theirs) {
                front_along_[e] = std::max(front_along_[e], theirs.along);
                front_against_[e] = std::min(front_against_[e], theirs.against);
            });
    }

    // A node is a candidate where both fronts exist and the surface facing against e lies beyond
    // the one facing along it: a gap between two faces, not the two faces of a ligament. Whether
    // there is any.
    template <class View>
    bool find_candidates(const View& view, std::size_t entries) {
        split_.resize(entries);
        std::atomic<bool> candidates{false};
        view.for_each_index(entries, [&](std::size_t e) {
            split_[e] = front_along_[e] > -inf && front_against_[e] < inf && front_against_[e] > front_along_[e];
            if (split_[e]) candidates.store(true, std::memory_order_relaxed);
        });
        return candidates.load();
    }

    // Pass 3 (only if there is a candidate): a gap is empty. A particle of the body lying in the
    // middle half between the fronts means material there, as just beyond the tip of a slot,
    // where both faces reach a node of the intact material ahead: no split (split_ 2).
    template <class View>
    void empty_gaps(const View& view) {
        using S = space_of<View>;
        using real = typename S::real;
        using vector = typename S::vector;
        const std::size_t nodes = view.grid.size(), n = view.particles.size();
        const auto& body = view.particles.template column<fields::body>();
        auto empty_gap = [&](std::size_t i) {
            const std::size_t base = std::size_t(body[i]) * nodes;
            const vector x = view.particles.template column<fields::position>()[i];
            view.stencils[i].for_each([&](std::size_t node, real w, const vector&) {
                const std::size_t e = base + node;
                if (!(w > 0) || split_[e] != 1) return;
                const double quarter = 0.25 * (front_against_[e] - front_along_[e]);
                const vector ref = unit<S>(e, n);
                const double along = double(view.grid.offset_from_node(node, x).dot(ref));
                if (along > front_along_[e] + quarter && along < front_against_[e] - quarter) split_[e] = 2;
            });
        };
        // Only the particles whose stencils can reach a candidate's row of nodes (of the last
        // axis) have anything to do here, where the view can skip the others (the solver's can:
        // partition_view).
        if constexpr (requires { view.for_each_particle_by_slab(candidate_rows_, empty_gap); }) {
            flag_rows(view.grid, nodes, [&](std::size_t e) { return split_[e] == 1; }, candidate_rows_);
            view.for_each_particle_by_slab(candidate_rows_, empty_gap);
        } else {
            view.for_each_particle_by_slab(empty_gap);
        }
        // The nodes two processes share: a particle in the gap on either is in it.
        view.across.merge_shared(
            view.bodies, [&](std::size_t e) { return split_[e]; },
            [&](std::size_t e, std::uint8_t theirs) {
                if (theirs == 2) split_[e] = 2;
            });
    }

    // The split nodes: the candidates left (without a candidate every entry is 0 already). A
    // split node's plane is its reference direction (unit_) and the midpoint of its fronts, both
    // kept until the next prepare, where side() reads them, with the grid's node count and
    // periodic lengths stored here. The rows of nodes (of the last axis) that hold a split node:
    // the solver asks side() only of the particles whose stencils can reach one (split_rows()).
    template <class View>
    void count_split(const View& view, std::size_t entries, bool any) {
        constexpr int dim = space_of<View>::dim;
        const std::size_t nodes = view.grid.size();
        // The split entries this process holds, and those of the nodes it owns (each node is one
        // process's): their sum over the processes counts every split node once.
        std::atomic<std::size_t> held{0}, owned{0};
        if (any) {
            view.for_each_index(entries, [&](std::size_t e) {
                if (split_[e] != 1) {
                    split_[e] = 0;
                    return;
                }
                held.fetch_add(1, std::memory_order_relaxed);
                if (view.across.owns(e % nodes)) owned.fetch_add(1, std::memory_order_relaxed);
            });
        }
        split_nodes_ = std::size_t(view.across.sum(owned.load()));
        if (held.load() > 0) flag_rows(view.grid, nodes, [&](std::size_t e) { return split_[e] != 0; }, split_rows_);
        else split_rows_.assign(std::size_t(view.grid.nodes(dim - 1)), 0);
        nodes_ = nodes;
        grid_length_.assign(std::size_t(dim), 0.0);
        for (int d = 0; d < dim; ++d) {
            grid_length_[std::size_t(d)] = view.grid.periodic(d) ? double(view.grid.spec().upper[d] - view.grid.spec().lower[d]) : 0.0;
        }
    }

    // rows[r] = whether some body's entry at a node of row r (grid::layer, the last axis) has
    // flagged(entry): the nodes of a row are a run of stride(dim - 1) consecutive indices, so
    // the rows are read in order, without a division per entry.
    template <class Grid, class Flagged>
    void flag_rows(const Grid& g, std::size_t nodes, Flagged&& flagged, std::vector<std::uint8_t>& rows) const {
        const int last = Grid::dim - 1;
        const auto count = static_cast<std::size_t>(g.nodes(last)), run = static_cast<std::size_t>(g.stride(last));
        rows.assign(count, 0);
        for (std::size_t base = 0; base < split_.size(); base += nodes)
            for (std::size_t r = 0; r < count; ++r)
                for (std::size_t k = r * run, end = k + run; k < end && !rows[r]; ++k) rows[r] = flagged(base + k);
    }

    std::size_t nodes_ = 0, split_nodes_ = 0;
    std::vector<double> current_, best_, front_along_, front_against_, unit_, grid_length_;
    std::vector<std::size_t> best_particle_;
    std::vector<std::uint8_t> split_, candidate_rows_, split_rows_, unit_set_;
};

}  // namespace multi_field
}  // namespace gimlet
