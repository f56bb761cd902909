// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The background grid: a uniform patch of nodes covering the domain plus a ghost layer, with a
/// boundary condition per axis. The patch has a global origin index so a later domain
/// decomposition can hand each rank a patch without changing the node arithmetic.

#include "gimlet/core/error.hpp"
#include "gimlet/core/space.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace gimlet {

/// Boundary condition on one axis of the grid.
enum class boundary {
    periodic,  ///< the domain wraps around; particles leaving one side enter the other
    slip,      ///< rigid frictionless wall: normal velocity zero at and beyond the boundary nodes
    fixed,     ///< rigid sticking wall: all velocity components zero at and beyond the boundary
    free,      ///< no condition; the grid simply ends (a particle reaching the end stops the run)
    wall,      ///< rigid one-sided wall: resists penetration only, so a body can rebound and leave;
               ///< frictionless unless grid_spec::wall_friction gives mu > 0
};

/// How a call to grid::apply_walls treats a one-sided `wall` (slip and fixed walls always act).
/// A step's decisions hold for its later passes, as contact's do: a node the wall stopped while
/// the forces acted stays stopped for the strain of that step, and a node it left free stays
/// free, or the stress would see other velocities than the momentum and the rebound would gain
/// energy (measured: +18 % for an elastic bar under MUSL).
enum class wall_pass {
    decide,  ///< stop a node moving into the wall and remember it for the step (adds to earlier marks)
    keep,    ///< stop the nodes this step marked, whichever way they move now; leave the rest
    trial,   ///< stop a node moving into the wall, remembering nothing
    none,    ///< leave every one-sided wall alone
};

/// Geometry of the domain: [lower, upper] per axis, cell size h, boundary per axis.
template <Space S>
struct grid_spec {
    /// The scalar type of S.
    using real = typename S::real;
    /// Lower corner of the domain (m).
    typename S::vector lower = S::vector::Zero();
    /// Upper corner of the domain (m); each extent upper - lower must be a whole number of cells.
    typename S::vector upper = S::vector::Ones();
    /// Cell size h (m), > 0, the same on every axis.
    real cell = real(0.1);
    /// Boundary per axis. Defaults to `free` on every axis: a body that reaches the end of the
    /// grid stops the run with an error naming the particle, rather than wrapping round to the
    /// other side (ask for `periodic` where that is meant).
    std::array<boundary, S::dim> bc = all_free();
    /// Coulomb friction mu >= 0 of a `wall` axis: where the wall stops a node's approach by dv_n,
    /// it takes at most mu dv_n off the tangential velocity (0: frictionless).
    std::array<double, S::dim> wall_friction{};

private:
    static constexpr std::array<boundary, S::dim> all_free() {
        std::array<boundary, S::dim> b{};
        b.fill(boundary::free);
        return b;
    }
};

namespace detail {
inline const char* axis_name(int d) { return d == 0 ? "x" : d == 1 ? "y" : "z"; }
}  // namespace detail

/// Node arithmetic and nodal fields of a uniform grid.
///
/// Node k along axis d (k may be negative: ghost nodes) sits at lower_d + k h. On a periodic axis
/// with N cells there are N distinct nodes and k wraps modulo N; on other axes nodes
/// k = -ghost .. N + ghost are stored.
template <Space S>
class grid {
public:
    /// The scalar type of S.
    using real = typename S::real;
    /// A position or velocity: S::vector.
    using vector = typename S::vector;
    /// Number of axes, 2 or 3.
    static constexpr int dim = S::dim;

    /// \param spec  the domain; validated (cell > 0, extent a whole number of cells, ...).
    /// \param ghost ghost nodes beyond each non-periodic boundary (the shape stencil width).
    grid(const grid_spec<S>& spec, int ghost) : spec_(spec), ghost_(ghost) {
        require_positive("grid cell size h (m)", double(spec.cell));
        std::size_t count = 1;
        for (int d = 0; d < dim; ++d) {
            const std::string ax = detail::axis_name(d);
            require_finite("grid lower bound " + ax + " (m)", double(spec.lower[d]));
            require_finite("grid upper bound " + ax + " (m)", double(spec.upper[d]));
            const double extent = double(spec.upper[d]) - double(spec.lower[d]);
            require(extent > 0, "grid extent along " + ax + " (upper - lower, m)", extent, "> 0");
            const double n = extent / double(spec.cell);
            const double nr = std::round(n);
            require(nr >= 1 && std::abs(n - nr) <= 1e-6 * nr,
                    "grid extent along " + ax + " in cells ((upper - lower) / h)", n,
                    "a whole number >= 1 (make the extent a multiple of the cell size)");
            // Node offsets and strides are int: a grid of more nodes cannot be indexed.
            constexpr double most = double(std::numeric_limits<int>::max());
            require(nr + 1 + 2 * ghost <= most, "grid extent along " + ax + " in cells ((upper - lower) / h)", n,
                    "at most " + std::to_string(std::numeric_limits<int>::max() - 1 - 2 * ghost) +
                        " (node indices are int)");
            cells_[d] = static_cast<int>(nr);
            periodic_[d] = spec.bc[d] == boundary::periodic;
            require(std::isfinite(spec.wall_friction[d]) && spec.wall_friction[d] >= 0,
                    "wall friction mu along " + ax, spec.wall_friction[d], "finite and >= 0");
            require(spec.wall_friction[d] == 0 || spec.bc[d] == boundary::wall, "wall friction mu along " + ax,
                    spec.wall_friction[d], "0 unless that axis is a one-sided wall (boundary::wall)");
            if (periodic_[d]) {
                require(cells_[d] >= ghost, "periodic grid cells along " + ax, cells_[d],
                        ">= " + std::to_string(ghost) + " (the shape stencil width)");
                nodes_[d] = cells_[d];
                offset_[d] = 0;
            } else {
                nodes_[d] = cells_[d] + 1 + 2 * ghost;
                offset_[d] = ghost;
            }
            stride_[d] = static_cast<int>(count);
            require(double(count) * double(nodes_[d]) <= double(std::numeric_limits<int>::max()), "grid node count",
                    double(count) * double(nodes_[d]), "at most 2147483647 (node indices are int)");
            count *= static_cast<std::size_t>(nodes_[d]);
        }
        if constexpr (is_axisymmetric_v<S>) {
            // The radial weights put node 0 on the axis and drop the nodes beyond it
            // (shape/detail/axisymmetric_gimp.hpp).
            require(spec.lower[0] == 0, "grid lower bound r (m) of an axisymmetric grid", double(spec.lower[0]),
                    "0 (the axis of symmetry is the grid's first column of nodes)");
            if (periodic_[0])
                throw invalid_parameter("boundary along r of an axisymmetric grid", "periodic",
                                        "slip, fixed, free or wall (it applies at the outer radius; the axis "
                                        "holds v_r = 0 itself)");
        }
        size_ = count;
        inv_cell_ = real(1) / spec.cell;
        set_field_count(1);
    }

    /// Number of velocity fields the grid carries (1, or one per body for multi-field contact).
    /// Field f of node n is entry f * size() + n of every nodal array.
    void set_field_count(std::size_t fields) {
        fields_ = fields;
        const std::size_t total = fields_ * size_;
        mass.assign(total, real(0));
        momentum.assign(total, vector::Zero());
        force.assign(total, vector::Zero());
        velocity.assign(total, vector::Zero());
        velocity_old.assign(total, vector::Zero());
        stopped_.assign(total, std::uint8_t(0));
    }
    /// Number of velocity fields per node (see set_field_count()).
    [[nodiscard]] std::size_t field_count() const noexcept { return fields_; }
    /// Entries of every nodal array: field_count() * size().
    [[nodiscard]] std::size_t entries() const noexcept { return fields_ * size_; }

    /// The domain the grid was built from.
    [[nodiscard]] const grid_spec<S>& spec() const noexcept { return spec_; }
    /// Cell size h (m).
    [[nodiscard]] real cell() const noexcept { return spec_.cell; }
    /// 1 / h (1/m).
    [[nodiscard]] real inv_cell() const noexcept { return inv_cell_; }
    /// Number of cells along axis d.
    [[nodiscard]] int cells(int d) const noexcept { return cells_[d]; }
    /// Number of stored nodes along axis d: cells on a periodic axis, cells + 1 + 2 ghost otherwise.
    [[nodiscard]] int nodes(int d) const noexcept { return nodes_[d]; }
    /// True if axis d is periodic.
    [[nodiscard]] bool periodic(int d) const noexcept { return periodic_[d]; }
    /// Ghost nodes beyond each non-periodic boundary (the shape stencil width).
    [[nodiscard]] int ghost() const noexcept { return ghost_; }
    /// Number of stored nodes (the product of nodes(d) over the axes); one field's share of a nodal array.
    [[nodiscard]] std::size_t size() const noexcept { return size_; }

    /// Storage offset along axis d of node k (multiplied by the axis stride).
    [[nodiscard]] int axis_offset(int d, int k) const noexcept {
        int i = k + offset_[d];
        if (periodic_[d]) {
            i %= nodes_[d];
            if (i < 0) i += nodes_[d];
        }
        return i * stride_[d];
    }
    /// Storage offsets along axis d of the W consecutive nodes first, first + 1, ...: the same
    /// as axis_offset for each, with one wrap test per node instead of a division (positions
    /// are wrapped into the domain, so the division is only needed for a stencil starting
    /// outside it).
    /// Returns the storage index of node `first`.
    template <int W>
    int axis_offsets(int d, int first, int* out) const noexcept {
        int i = first + offset_[d];
        if (periodic_[d]) {
            const int n = nodes_[d];
            if (i < 0 || i >= n) {
                i %= n;
                i += i < 0 ? n : 0;
            }
            const int storage = i;
            for (int a = 0; a < W; ++a) {
                out[a] = i * stride_[d];
                i = i + 1 == n ? 0 : i + 1;
            }
            return storage;
        }
        for (int a = 0; a < W; ++a) out[a] = (i + a) * stride_[d];
        return i;
    }
    /// Distance between consecutive storage indices along axis d in the flat node index.
    [[nodiscard]] int stride(int d) const noexcept { return stride_[d]; }
    /// Position of the node stored at `index` (0 <= index < size()), for messages.
    [[nodiscard]] vector node_position(std::size_t index) const {
        vector x;
        for (int d = 0; d < dim; ++d) {
            x[d] = coordinate(d, static_cast<int>(index / std::size_t(stride_[d])) % nodes_[d]);
        }
        return x;
    }
    /// Position along axis d of the nodes whose storage offset along d is `storage` (a multiple
    /// of stride(d), as axis_offsets gives): node_position's component d, to the bit, for every
    /// node with that offset, from one division instead of two per axis and node.
    [[nodiscard]] real axis_position(int d, int storage) const noexcept {
        assert(storage % stride_[d] == 0);
        return coordinate(d, storage / stride_[d]);
    }
    /// x minus the position of the node stored at `index`, the nearest image along periodic axes.
    [[nodiscard]] vector offset_from_node(std::size_t index, const vector& x) const {
        return offset_from(x, node_position(index));
    }
    /// x minus a node's position `node_at` (node_position, or stencil::for_each_node_position's),
    /// the nearest image along periodic axes.
    [[nodiscard]] vector offset_from(const vector& x, const vector& node_at) const {
        vector d = x - node_at;
        for (int a = 0; a < dim; ++a) {
            if (!periodic_[a]) continue;
            const real len = spec_.upper[a] - spec_.lower[a];
            if (d[a] > len / 2) d[a] -= len;
            else if (d[a] < -len / 2) d[a] += len;
        }
        return d;
    }
    /// True if node k along axis d is stored (always on a periodic axis).
    [[nodiscard]] bool stored(int d, int k) const noexcept {
        return periodic_[d] || (k + offset_[d] >= 0 && k + offset_[d] < nodes_[d]);
    }
    /// Global node index along axis d of a storage index.
    [[nodiscard]] int node_of(int d, int storage) const noexcept { return storage - offset_[d]; }

    /// The storage index along the last axis of the node stored at `index` (the solver's
    /// scatter cuts the grid into slabs of such layers): unflatten(index)[dim - 1].
    [[nodiscard]] int layer(std::size_t index) const noexcept {
        assert(index < size_);  // a node index, not a field entry (those of field f start at f * size())
        return static_cast<int>(index / static_cast<std::size_t>(stride_[dim - 1]));
    }

    /// Multi-index (per-axis storage indices) of a flat node index.
    [[nodiscard]] std::array<int, dim> unflatten(std::size_t flat) const noexcept {
        std::array<int, dim> idx{};
        for (int d = 0; d < dim; ++d) {
            idx[d] = static_cast<int>(flat % static_cast<std::size_t>(nodes_[d]));
            flat /= static_cast<std::size_t>(nodes_[d]);
        }
        return idx;
    }
    /// Position of a node given its per-axis storage indices.
    [[nodiscard]] vector position(const std::array<int, dim>& idx) const noexcept {
        vector x;
        for (int d = 0; d < dim; ++d) x[d] = spec_.lower[d] + real(node_of(d, idx[d])) * spec_.cell;
        return x;
    }

    /// Zero the nodal fields before a particle-to-grid transfer.
    void clear() {
        std::fill(stopped_.begin(), stopped_.end(), std::uint8_t(0));
        std::fill(mass.begin(), mass.end(), real(0));
        std::fill(momentum.begin(), momentum.end(), vector::Zero());
        std::fill(force.begin(), force.end(), vector::Zero());
    }
    /// clear() of entry e alone (0 <= e < entries()), for a caller that splits the entries
    /// between threads.
    void clear_entry(std::size_t e) noexcept {
        stopped_[e] = 0;
        mass[e] = real(0);
        momentum[e] = vector::Zero();
        force[e] = vector::Zero();
    }

    /// Impose the wall conditions on nodal velocities (every field): on a slip or fixed axis, nodes at
    /// and beyond the boundary (k <= 0 or k >= N) lose the normal (slip) or every (fixed)
    /// component; on a `wall` axis they lose only a normal component that moves into the wall
    /// (with friction, the tangential velocity loses at most mu times that), as `pass` says
    /// (wall_pass). Ghost nodes beyond a wall belong to the rigid wall.
    ///
    /// Only the planes of nodes at and beyond each wall are visited (ghost + 1 per side), so the
    /// cost scales with the boundary, not with the grid.
    void apply_walls(std::vector<vector>& v, wall_pass pass = wall_pass::decide) {
        if constexpr (is_axisymmetric_v<S>) hold_axis(v);
        const bool one_sided = pass != wall_pass::none;
        for (int d = 0; d < dim; ++d) {
            const boundary b = spec_.bc[d];
            if (b != boundary::slip && b != boundary::fixed && !(b == boundary::wall && one_sided)) continue;
            const real mu = real(spec_.wall_friction[d]);
            // Storage index s holds node k = s - offset_d; k <= 0 and k >= N are wall nodes. In an
            // axisymmetric space the low end of r is the axis (hold_axis), not a wall.
            const int low_last = offset_[d], high_first = offset_[d] + cells_[d];
            const bool axis_side = is_axisymmetric_v<S> && d == 0;
            for (int s = axis_side ? high_first : 0; s < nodes_[d]; s = s == low_last ? high_first : s + 1) {
                const real into = s <= low_last ? real(-1) : real(1);  // the wall's side, along +d
                for_each_in_plane(d, s, [&](std::size_t n) {
                    for (std::size_t f = 0; f < fields_; ++f) {
                        const std::size_t i = f * size_ + n;
                        vector& e = v[i];
                        if (b == boundary::slip) e[d] = real(0);
                        else if (b == boundary::fixed) e.setZero();
                        else if (pass == wall_pass::keep) {
                            if (stopped_[i] & (1u << d)) stop_at_wall(e, d, into, mu);
                        } else if (e[d] * into > 0 || (pass == wall_pass::decide && (stopped_[i] & (1u << d)))) {
                            stop_at_wall(e, d, into, mu);
                            if (pass == wall_pass::decide) stopped_[i] |= std::uint8_t(1u << d);
                        }
                    }
                });
            }
        }
    }

    /// Wrap a position into the domain along periodic axes.
    void wrap(vector& x) const noexcept {
        for (int d = 0; d < dim; ++d) {
            if (!periodic_[d]) continue;
            const real len = spec_.upper[d] - spec_.lower[d];
            if (std::abs(x[d] - spec_.lower[d]) < real(1e6) * len) {
                if (x[d] < spec_.lower[d]) x[d] += len * std::ceil((spec_.lower[d] - x[d]) / len);
                if (x[d] >= spec_.upper[d]) x[d] -= len * std::floor((x[d] - spec_.lower[d]) / len);
            } else if (std::isfinite(x[d])) {
                // Far away, where a shift by whole periods rounds off by more than a period (at
                // 7e21 m, say) or overflows: the exact remainder.
                const real r = std::fmod(x[d] - spec_.lower[d], len);
                x[d] = spec_.lower[d] + (r < 0 ? r + len : r);
            }
            if (x[d] >= spec_.upper[d]) x[d] = spec_.lower[d];  // round-off at the seam
        }
    }
    /// True if x lies in the domain along every non-periodic axis.
    [[nodiscard]] bool inside(const vector& x) const noexcept {
        for (int d = 0; d < dim; ++d)
            if (!periodic_[d] && !(x[d] >= spec_.lower[d] && x[d] <= spec_.upper[d])) return false;
        return true;
    }

    // Nodal fields, field-major (see set_field_count).
    std::vector<real> mass;            ///< m_i
    std::vector<vector> momentum;      ///< (mv)_i
    std::vector<vector> force;         ///< f_i
    std::vector<vector> velocity;      ///< v_i after the momentum update (and BCs, contact)
    std::vector<vector> velocity_old;  ///< v_i^n = (mv)_i / m_i before the update (for FLIP)

private:
    // Coordinate d of the nodes with storage index i along axis d (node_position and
    // axis_position: one expression, so the two agree to the bit).
    [[nodiscard]] real coordinate(int d, int i) const noexcept { return spec_.lower[d] + real(i - offset_[d]) * spec_.cell; }

    // A node at a one-sided wall: its normal velocity stops; Coulomb friction takes at most mu
    // times the approach it stopped (none for a marked node now moving away) off its tangential
    // velocity.
    static void stop_at_wall(vector& e, int d, real into, real mu) {
        const real stopped = std::max(real(0), e[d] * into);
        e[d] = real(0);
        if (!(mu > 0)) return;
        const real slip = e.norm();
        if (slip > 0) e *= std::max(real(0), real(1) - mu * stopped / slip);
    }

    // The axis of an axisymmetric grid: v_r = 0 on the nodes at r = 0 (and the empty ones beyond,
    // which no particle weighs), whatever the boundary along r says of the outer radius.
    void hold_axis(std::vector<vector>& v) const {
        for (int s = 0; s <= offset_[0]; ++s)
            for_each_in_plane(0, s, [&](std::size_t n) {
                for (std::size_t f = 0; f < fields_; ++f) v[f * size_ + n][0] = real(0);
            });
    }

    // f(flat node index) for every node whose storage index along axis d is s.
    template <class F>
    void for_each_in_plane(int d, int s, F&& f) const {
        const auto inner = static_cast<std::size_t>(stride_[d]);
        const std::size_t block = inner * static_cast<std::size_t>(nodes_[d]);
        for (std::size_t outer = 0; outer < size_; outer += block)
            for (std::size_t j = 0; j < inner; ++j) f(outer + static_cast<std::size_t>(s) * inner + j);
    }

    grid_spec<S> spec_;
    int ghost_;
    std::array<int, dim> cells_{}, nodes_{}, offset_{}, stride_{};
    std::array<bool, dim> periodic_{};
    std::size_t size_ = 0;
    std::size_t fields_ = 1;
    std::vector<std::uint8_t> stopped_;  // per node entry: the axes whose one-sided wall stopped it this step
    real inv_cell_ = 1;
};

}  // namespace gimlet
