// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Where bodies end along a line: the gap between two bodies' facing surfaces, and the walls of
/// a void inside one body with their closing speed. These give the reference paper's D (half
/// the gap between the impact surfaces) and its relative wall velocity of a collapsing cavity
/// (docs/reproduction.md defines both).
///
/// A body's surface is the edge of its outermost particle's domain: the particle centre plus
/// half its initial spacing V0^(1/dim) / 2 along the line. Only particles whose centres lie in a
/// strip around the line count: |x_k - a_k| <= strip_half_width for every axis k other than the
/// line's. The strip is not wrapped across periodic boundaries.
///
/// In an axisymmetric space (axisymmetric_space) a particle is a ring: its spacing is its uGIMP
/// domain's (fields::domain_half_width), and a line along r is the diameter through the axis,
/// which each ring in the strip crosses at r and at -r (a void around the axis then has walls at
/// -r_w and r_w: its chord is the diameter 2 r_w).
///
/// On many processes (solver_options::processes) every measurement here is the whole run's, bit
/// for bit one process's, on every process: each process's strip points go to every process,
/// joined in the particles' ordinal order (solver::ordinal), the order one process gathers them
/// in. Each is then collective: every process calls it, with the same lines.

#include "gimlet/core/detail/blocks.hpp"
#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/processes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace gimlet::diagnostics {

namespace detail {

// A particle in the strip around a line: its coordinate along the line, half its initial
// spacing, and its velocity along the line.
struct strip_point {
    double coordinate;
    double half_spacing;
    double velocity;
    bool operator<(const strip_point& o) const noexcept { return coordinate < o.coordinate; }
};

template <class Solver>
void check_line(int axis, double strip_half_width) {
    // The message only where it is thrown: observers check their lines at every sample.
    if (!(axis >= 0 && axis < Solver::dim))
        require(false, "line axis", double(axis), "0 .. " + gimlet::detail::to_text(double(Solver::dim - 1)));
    require_positive("strip half-width (m)", strip_half_width);
}

// A line to gather a strip around: the particles of `body` whose centres lie within
// `half_width` of the line through `point` along `axis`.
template <class Vector>
struct strip_line {
    std::uint32_t body;
    int axis;
    Vector point;
    double half_width;
};

// On many processes: every process's points of each line, on every process, in the ordinal
// order of their particles (a ring's two points in the order it gives them): the sequence one
// process gathers. `mine[j]` is this process's points of line j, in its particles' order, and
// `ordinals[j]` their particles' ordinals. Collective.
inline std::vector<std::vector<strip_point>> strips_of_every_process(gimlet::processes& procs,
                                                                     const std::vector<std::vector<strip_point>>& mine,
                                                                     const std::vector<std::vector<std::uint64_t>>& ordinals) {
    struct record {
        std::uint64_t ordinal, line;
        strip_point point;
    };
    std::vector<record> flat;
    for (std::size_t j = 0; j < mine.size(); ++j)
        for (std::size_t k = 0; k < mine[j].size(); ++k) flat.push_back({ordinals[j][k], j, mine[j][k]});
    // A ring's two points share an ordinal and keep their order.
    std::vector<std::vector<strip_point>> out(mine.size());
    for (const record& r : gimlet::detail::in_ordinal_order(procs, flat)) out[std::size_t(r.line)].push_back(r.point);
    return out;
}

// The strips around several lines, in one pass over the particles: strips(s, lines)[j] holds
// the particles of the strip around lines[j], sorted by coordinate along its line. From 4096
// particles the strips are gathered on the solver's threads, a block of consecutive particles
// each, and each line's points joined in block order: the sequence the serial pass gathers, so
// the sort returns the same, and a line's strip is the same whatever other lines are asked. On
// many processes the points of every process are joined in ordinal order first
// (strips_of_every_process): the sequence one process gathers, and so one process's strips,
// on every process (std::sort orders equal coordinates by where they start, so the sequence
// must be one process's exactly). Collective there.
template <class Solver>
std::vector<std::vector<strip_point>> strips(const Solver& s, const std::vector<strip_line<typename Solver::vector>>& lines) {
    for (const auto& line : lines) check_line<Solver>(line.axis, line.half_width);
    gimlet::processes* procs = nullptr;
    if constexpr (requires { s.processes(); }) procs = s.processes();
    const auto& store = s.particles();
    const auto& x = store.template column<fields::position>();
    const auto& v = store.template column<fields::velocity>();
    const auto& b = store.template column<fields::body>();
    const auto& v0 = store.template column<fields::volume0>();
    const std::size_t n = store.size(), m = lines.size();
    const int threads = gimlet::detail::threads_of(s);
    const std::size_t blocks = gimlet::detail::observer_blocks(n, threads);
    std::vector<std::vector<strip_point>> found(blocks * m);  // block k's points of line j at k * m + j
    // On many processes, the particle of each point found (none are kept on one process).
    std::vector<std::vector<std::size_t>> found_at(procs ? blocks * m : 0);
    // Per body that a line names, the box outside which none of its lines' strips reaches (a
    // dimension along which one of its lines runs is open), so that most particles are passed
    // over with a test or two, whatever the number of lines. The box is widened by a second
    // half-width and a millionth of the coordinate, far more than the rounding of the exact
    // test below (in float or double), which still decides inside it: the points found are the
    // same. A line through a point that is not finite leaves its dimensions open.
    constexpr int dim = Solver::dim;
    using store_type = std::remove_cvref_t<decltype(store)>;
    constexpr bool axisymmetric = is_axisymmetric_v<typename store_type::space_type>;
    static_assert(!axisymmetric || store_type::template has<fields::domain_half_width>,
                  "gimlet::diagnostics: the surfaces of an axisymmetric solver need the particles' spacing, "
                  "fields::domain_half_width (uGIMP keeps it)");
    constexpr double unbounded = std::numeric_limits<double>::infinity();
    struct body_box {
        std::uint32_t body;
        std::array<double, dim> lo, hi;
        std::vector<std::size_t> lines;  // the body's lines, in increasing order
    };
    std::vector<body_box> boxes;
    for (std::size_t j = 0; j < m; ++j) {
        const auto& line = lines[j];
        auto box = std::find_if(boxes.begin(), boxes.end(), [&](const body_box& c) { return c.body == line.body; });
        if (box == boxes.end()) {
            box = boxes.insert(boxes.end(), body_box{line.body, {}, {}, {}});
            box->lo.fill(unbounded);
            box->hi.fill(-unbounded);
        }
        box->lines.push_back(j);
        for (int d = 0; d < dim; ++d) {
            const double centre = double(line.point[d]);
            // Open along the line, and where its point is not finite (a NaN point's strip takes
            // every particle, as the exact test does).
            if (d == line.axis || !std::isfinite(centre)) {
                box->lo[d] = -unbounded, box->hi[d] = unbounded;
                continue;
            }
            const double reach = 2 * line.half_width + 1e-6 * std::abs(centre);
            box->lo[d] = std::min(box->lo[d], centre - reach);
            box->hi[d] = std::max(box->hi[d], centre + reach);
        }
    }
    gimlet::detail::for_each_block(n, blocks, true, threads, [&](std::size_t k, std::size_t first, std::size_t last) {
        for (std::size_t i = first; i < last; ++i) {
            const body_box* box = nullptr;
            for (const auto& c : boxes)
                if (c.body == b[i]) box = &c;
            if (box == nullptr) continue;
            bool near = true;
            for (int d = 0; d < dim; ++d) {
                const double xd = double(x[i][d]);
                if (xd < box->lo[d] || xd > box->hi[d]) near = false;
            }
            if (!near) continue;
            for (const std::size_t j : box->lines) {
                const auto& line = lines[j];
                bool inside = true;
                for (int d = 0; d < Solver::dim; ++d)
                    if (d != line.axis && std::abs(double(x[i][d] - line.point[d])) > line.half_width) inside = false;
                if (!inside) continue;
                if constexpr (axisymmetric) {
                    // A ring's volume is per radian: its spacing is the uGIMP domain's. A line
                    // along r is the diameter through the axis: each ring crosses it twice.
                    const double half = double(store.template column<fields::domain_half_width>()[i][line.axis]);
                    found[k * m + j].push_back({double(x[i][line.axis]), half, double(v[i][line.axis])});
                    if (line.axis == 0) found[k * m + j].push_back({-double(x[i][0]), half, -double(v[i][0])});
                    if (procs) found_at[k * m + j].insert(found_at[k * m + j].end(), std::size_t(line.axis == 0 ? 2 : 1), i);
                } else {
                    const double half = 0.5 * std::pow(double(v0[i]), 1.0 / Solver::dim);
                    found[k * m + j].push_back({double(x[i][line.axis]), half, double(v[i][line.axis])});
                    if (procs) found_at[k * m + j].push_back(i);
                }
            }
        }
    });
    std::vector<std::vector<strip_point>> out(m);
    for (std::size_t j = 0; j < m; ++j) {
        out[j] = std::move(found[j]);
        for (std::size_t k = 1; k < blocks; ++k) out[j].insert(out[j].end(), found[k * m + j].begin(), found[k * m + j].end());
    }
    if constexpr (requires { s.processes(); })
        if (procs) {
            std::vector<std::vector<std::uint64_t>> ordinals(m);
            for (std::size_t j = 0; j < m; ++j)
                for (std::size_t k = 0; k < blocks; ++k)
                    for (const std::size_t i : found_at[k * m + j]) ordinals[j].push_back(s.ordinal(i));
            out = strips_of_every_process(*procs, out, ordinals);
        }
    for (auto& points : out) std::sort(points.begin(), points.end());
    return out;
}

// The particles of `body` in the strip around the line through `point` along `axis`, sorted
// by coordinate along the line (strips, for one line).
template <class Solver>
std::vector<strip_point> strip(const Solver& s, std::uint32_t body, int axis, const typename Solver::vector& point,
                               double strip_half_width) {
    return std::move(strips(s, {{body, axis, point, strip_half_width}})[0]);
}

// Mean velocity of the strip particles with coordinate in [lo, hi] (the wall particle is one).
inline double layer_velocity(const std::vector<strip_point>& pts, double lo, double hi) {
    double sum = 0;
    std::size_t n = 0;
    for (const auto& p : pts)
        if (p.coordinate >= lo && p.coordinate <= hi) sum += p.velocity, ++n;
    return n ? sum / double(n) : 0.0;
}

}  // namespace detail

/// The gap along a line between the surface of `lower` facing larger coordinates and the
/// surface of `upper` facing smaller ones.
struct surface_gap_result {
    bool found = false;           ///< both bodies have particles in the strip
    double lower_surface = 0;     ///< m: the lower body's largest particle centre + half spacing
    double upper_surface = 0;     ///< m: the upper body's smallest particle centre - half spacing
    /// m: upper_surface - lower_surface. Negative when the domains overlap (bodies in contact
    /// and compressed: the domains keep their initial size while the centres close in).
    [[nodiscard]] double gap() const noexcept { return upper_surface - lower_surface; }
};

/// The gap between body `lower` and body `upper` along the line through `point` parallel to
/// axis `axis`, from the particles within `strip_half_width` (m) of the line.
template <class Solver>
[[nodiscard]] surface_gap_result surface_gap(const Solver& s, std::uint32_t lower, std::uint32_t upper, int axis,
                                             const typename Solver::vector& point, double strip_half_width) {
    const auto both = detail::strips(s, {{lower, axis, point, strip_half_width}, {upper, axis, point, strip_half_width}});
    const auto& lo = both[0];
    const auto& hi = both[1];
    surface_gap_result r;
    if (lo.empty() || hi.empty()) return r;
    r.found = true;
    r.lower_surface = -std::numeric_limits<double>::infinity();
    for (const auto& p : lo) r.lower_surface = std::max(r.lower_surface, p.coordinate + p.half_spacing);
    r.upper_surface = std::numeric_limits<double>::infinity();
    for (const auto& p : hi) r.upper_surface = std::min(r.upper_surface, p.coordinate - p.half_spacing);
    return r;
}

/// A void inside one body, cut by a line: its two walls and how fast they approach each other.
struct void_chord_result {
    bool open = false;        ///< a void wider than the threshold crosses the line near the point
    double lower_wall = 0;    ///< m: domain edge of the wall at the smaller coordinate
    double upper_wall = 0;    ///< m: domain edge of the wall at the larger coordinate
    double lower_wall_velocity = 0;  ///< m/s along the line: mean over the wall's particle layer
    double upper_wall_velocity = 0;  ///< m/s along the line
    /// m: the void's length along the line (0 when closed).
    [[nodiscard]] double length() const noexcept { return open ? upper_wall - lower_wall : 0.0; }
    /// m/s: the rate at which the walls approach each other (positive while the void shrinks).
    [[nodiscard]] double closing_speed() const noexcept { return lower_wall_velocity - upper_wall_velocity; }
    /// m: the void's midpoint along the line.
    [[nodiscard]] double centre() const noexcept { return 0.5 * (lower_wall + upper_wall); }
};

namespace detail {

// void_chord's result from the strip around its line (`target` the point's coordinate along it).
inline void_chord_result chord(const std::vector<strip_point>& pts, double target, double min_width) {
    void_chord_result r;
    double best_distance = std::numeric_limits<double>::infinity();
    std::size_t best = 0;
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
        const double lo = pts[k].coordinate + pts[k].half_spacing;
        const double hi = pts[k + 1].coordinate - pts[k + 1].half_spacing;
        if (hi - lo <= min_width) continue;
        const double distance = target < lo ? lo - target : (target > hi ? target - hi : 0.0);
        if (distance < best_distance) best_distance = distance, best = k;
    }
    if (!std::isfinite(best_distance)) return r;
    r.open = true;
    const auto& below = pts[best];
    const auto& above = pts[best + 1];
    r.lower_wall = below.coordinate + below.half_spacing;
    r.upper_wall = above.coordinate - above.half_spacing;
    r.lower_wall_velocity = layer_velocity(pts, below.coordinate - 1.5 * below.half_spacing, below.coordinate);
    r.upper_wall_velocity = layer_velocity(pts, above.coordinate, above.coordinate + 1.5 * above.half_spacing);
    return r;
}

}  // namespace detail

/// The void of body `body` crossed by the line through `point` along `axis`: the gap between
/// consecutive particle domains in the strip that contains point[axis] (or, if none does, the
/// nearest one), provided it is wider than `min_width` (m). A wall's velocity is the mean over
/// the strip's particles within three quarters of a particle spacing of the wall particle,
/// behind it: the wall's own particle layer, not the next one (compression brings that no
/// closer than about 0.9 spacing).
template <class Solver>
[[nodiscard]] void_chord_result void_chord(const Solver& s, std::uint32_t body, int axis,
                                           const typename Solver::vector& point, double strip_half_width,
                                           double min_width) {
    require_positive("void threshold width (m)", min_width);
    return detail::chord(detail::strip(s, body, axis, point, strip_half_width), double(point[axis]), min_width);
}

/// A line for void_chords: the void of `body` crossed by the line through `point` along `axis`.
template <class Vector>
struct chord_line {
    /// The body whose void is cut.
    std::uint32_t body;
    /// The axis of the line: 0 (x), 1 (y) or 2 (z).
    int axis;
    /// A point of the line (m).
    Vector point;
};

/// void_chord along each of `lines`, in one pass over the particles rather than one a line:
/// result j is void_chord(s, lines[j].body, lines[j].axis, lines[j].point, strip_half_width,
/// min_width), bit for bit. For an observer that cuts the same state along several lines. No
/// lines: no pass over the particles, and no results.
template <class Solver>
[[nodiscard]] std::vector<void_chord_result> void_chords(const Solver& s,
                                                         const std::vector<chord_line<typename Solver::vector>>& lines,
                                                         double strip_half_width, double min_width) {
    require_positive("void threshold width (m)", min_width);
    require_positive("strip half-width (m)", strip_half_width);
    if (lines.empty()) return {};
    std::vector<detail::strip_line<typename Solver::vector>> around;
    for (const auto& line : lines) around.push_back({line.body, line.axis, line.point, strip_half_width});
    const auto pts = detail::strips(s, around);
    std::vector<void_chord_result> out;
    for (std::size_t j = 0; j < lines.size(); ++j) out.push_back(detail::chord(pts[j], double(lines[j].point[lines[j].axis]), min_width));
    return out;
}

}  // namespace gimlet::diagnostics
