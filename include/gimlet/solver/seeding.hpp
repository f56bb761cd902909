// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Seeding: the particles of a scene's bodies (docs/physics.md section 2).

#include "gimlet/core/describe.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/grid.hpp"
#include "gimlet/scene/scene.hpp"

#include <array>
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <string>

namespace gimlet::detail {

/// One particle of `body` at x, of lattice spacing delta: its volume delta^dim (per radian in an
/// axisymmetric space: delta^2 r_p, the ring's volume over 2 pi), mass, velocity,
/// body id, GIMP half-width delta/2 (where the shape keeps one) and the thermal policy's initial state.
template <Space S, class M, class Store>
void add_particle(Store& particles, const scene::body<S, M>& body, std::uint32_t id, const typename S::vector& x,
                  typename S::real delta) {
    using real = typename S::real;
    using vector = typename S::vector;
    const std::size_t i = particles.add();
    auto p = particles[i];
    real vol;
    if constexpr (is_axisymmetric_v<S>) vol = delta * delta * x[0];
    else vol = std::pow(delta, real(S::dim));
    p.template get<fields::position>() = x;
    p.template get<fields::velocity>() = body.velocity;
    p.template get<fields::volume0>() = vol;
    p.template get<fields::mass>() = real(body.material.density) * vol;
    p.template get<fields::body>() = id;
    if constexpr (Store::template has<fields::domain_half_width>)
        p.template get<fields::domain_half_width>() = vector::Constant(delta / real(2));
    if constexpr (M::thermal_type::enabled) body.material.thermal.initialize(p);
}


/// What seed_particles does with each batch by default: keeps it.
struct keep_every_particle {
    template <class Store>
    void operator()(Store&, std::size_t) const noexcept {}
};

/// The most particles seed_particles seeds before it hands them to its batch hook.
inline constexpr std::size_t seed_batch = std::size_t(1) << 16;

/// Fill `particles` with the particles of the scene's bodies: one at the centre of every cell of
/// a sub-cell lattice (particles_per_cell per axis) aligned with the grid that lies inside the
/// body, body by body in the scene's order.
///
/// `batch(particles, first)` is called after every seed_batch particles of a body and at the end
/// of each body (then possibly with no particle after `first`): the batch is the particles from
/// index `first` on, all of one body, in seeding order. The hook may drop any of them (resize the
/// store after moving the kept ones forward, in order) and must leave the particles before
/// `first` as they are and add none; what it throws goes through. A process keeping those of its
/// own slabs so holds no more than its own particles and one batch.
///
/// Throws invalid_parameter for a body outside the grid, two overlapping bodies, or a body with
/// no particle (seeded, whether kept or not).
template <Space S, class M, class Store, class Batch = keep_every_particle>
void seed_particles(const scene::scene<S, M>& sc, const grid<S>& grid, Store& particles, Batch&& batch = {}) {
    using real = typename S::real;
    using vector = typename S::vector;
    constexpr int dim = S::dim;
    const auto& gs = sc.grid();
    const auto& bodies = sc.bodies();
    for (std::uint32_t b = 0; b < bodies.size(); ++b) {
        const auto& body = bodies[b];
        const real delta = gs.cell / real(body.particles_per_cell);
        // Particles sit at the centres of a sub-cell lattice aligned with the grid, so bodies
        // whose edges lie on grid lines are filled exactly.
        std::array<long, dim> lo{}, hi{};
        for (int d = 0; d < dim; ++d) {
            const std::string ax = detail::axis_name(d);
            require(body.lower[d] >= gs.lower[d] - real(1e-9) * gs.cell &&
                        body.upper[d] <= gs.upper[d] + real(1e-9) * gs.cell,
                    "extent of " + body.name + " along " + ax + " (m, from " +
                        detail::to_text(double(body.lower[d])) + ")",
                    double(body.upper[d]),
                    "inside the grid [" + detail::to_text(double(gs.lower[d])) + ", " +
                        detail::to_text(double(gs.upper[d])) + "]");
            lo[d] = static_cast<long>(std::floor((body.lower[d] - gs.lower[d]) / delta));
            hi[d] = static_cast<long>(std::ceil((body.upper[d] - gs.lower[d]) / delta));
        }
        std::size_t first = particles.size(), seeded = 0;
        std::array<long, dim> j = lo;
        while (true) {
            vector x;
            for (int d = 0; d < dim; ++d) x[d] = gs.lower[d] + (real(j[d]) + real(0.5)) * delta;
            if (grid.inside(x) && body.contains(x)) {
                for (std::uint32_t o = 0; o < b; ++o)
                    if (bodies[o].contains(x))
                        throw invalid_parameter("bodies", body.name + " and " + bodies[o].name,
                                                "non-overlapping (they share the point " +
                                                    format_position(x) + ")");
                add_particle(particles, body, b, x, delta);
                ++seeded;
                if (particles.size() - first >= seed_batch) batch(particles, first), first = particles.size();
            }
            int d = 0;
            while (d < dim && ++j[d] >= hi[d]) j[d] = lo[d], ++d;
            if (d == dim) break;
        }
        batch(particles, first);
        require(seeded > 0, "particle count of " + body.name, 0.0,
                ">= 1 (the region holds no particle-lattice point: too small for the cell, "
                "or its cavity removes all of it)");
    }
}

}  // namespace gimlet::detail
