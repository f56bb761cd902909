// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The solver's treatment of particles far less dense than their neighbours ("light particles";
/// solver_options::light_particle_ratio; docs/equations.md, "Light particles").
///
/// Where a dense particle has a tiny weight S at a node, the node's velocity increment
/// dt f_i / m_i grows as 1/sqrt(S) (GIMP's gradient at the edge of a support is not small where
/// the weight is). The dense particle reads it with weight S, harmlessly; a far less dense
/// particle on the same node reads it with weight O(1) and is flung (52-115 km/s in the sparse-cloud hard
/// case, det F down to 0). A light particle therefore reads each node by its reliability
/// k_i = m_i / rho_i^max (the volume of the node's densest material its mass amounts to), for
/// its velocity and for its velocity gradient, and the momentum it changes against FLIP goes back
/// to the non-light particles of its nodes, so momentum stays exact.

#include "gimlet/solver/solver.hpp"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

namespace gimlet {

// A particle's reference density m_p / V_p^0: what lightness compares. It is its material's
// density, so particles of one material are never light against each other, whatever their
// sizes (a mass test made a body seeded at 5 x 5 particles per cell light beside one seeded
// at 1, and its treatment then removed 9-16 % of the energy of their impact, where nothing
// was flung without it: docs/equations.md, "Light particles").
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
auto solver_core<S, Sh, M, Fields, MultiField, Part>::reference_density(std::size_t i) const -> real {
    return particles_.template column<fields::mass>()[i] / particles_.template column<fields::volume0>()[i];
}

// Whether any particle can be light: reference densities only change when the user touches the
// particles, and a particle is light only against a denser one on its stencil (in its field),
// so none can be where the least dense particle is at least theta times the densest: of the
// scene, or with a multi-field contact (whose fields never mix bodies) of each body. Then
// nothing below runs.
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
void solver_core<S, Sh, M, Fields, MultiField, Part>::check_light_possible() {
    const auto& body = particles_.template column<fields::body>();
    light_possible_ = false;
    if (particles_.size() == 0 || !(options_.light_particle_ratio > 0)) return;
    const std::size_t groups = multi_field ? materials_.size() : 1;
    std::vector<real> least(groups, std::numeric_limits<real>::infinity()), most(groups, real(0));
    for (std::size_t i = 0; i < particles_.size(); ++i) {
        const std::size_t g = multi_field ? std::size_t(body[i]) : 0;
        const real rho = reference_density(i);
        least[g] = std::min(least[g], rho);
        most[g] = std::max(most[g], rho);
    }
    for (std::size_t g = 0; g < groups; ++g)
        light_possible_ = light_possible_ || least[g] < real(options_.light_particle_ratio) * most[g];
}

// After the step's first scatter: per node entry (so per field), the largest reference density
// and the largest current density m_q / V_q of the particles with a nonzero weight there (both
// maxima, so the slab scatter's order does not matter); then p is light if
// rho0_p < theta max rho0, the maximum over the nodes where p has a nonzero weight. Then, at the
// nodes of the light particles' stencils, the mass of the particles that are not light,
// sum_q S_iq m_q (a sum of its own rather than m_i less the light mass, whose rounding would not
// cancel where the light mass dominates).
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
void solver_core<S, Sh, M, Fields, MultiField, Part>::find_light_particles() {
    light_list_.clear();
    if (!light_possible_) return;
    const auto& m = particles_.template column<fields::mass>();
    node_reference_density_.assign(grid_.entries(), real(0));
    node_densest_.assign(grid_.entries(), real(0));
    for_each_particle_by_slab([&](std::size_t q) {
        const real rho0 = reference_density(q), rho = m[q] / current_volume(particles_[q]);
        auto at = entries(q);
        stencils_[q].for_each([&](std::size_t node, real w, const vector&) {
            const std::size_t e = at(node);
            if (w > 0) {
                node_reference_density_[e] = std::max(node_reference_density_[e], rho0);
                node_densest_[e] = std::max(node_densest_[e], rho);
            }
        });
    });
    const auto n = static_cast<std::ptrdiff_t>(particles_.size());
    light_particle_.assign(particles_.size(), lightness::none);
    const real theta = real(options_.light_particle_ratio);
    detail::thread_shares shares(n, threads(), n >= parallel_threshold);
    GIMLET_OMP(parallel num_threads(shares.team()))
    for (auto claimed = shares.start(); shares.claim(claimed);)
        for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) {
            const auto q = static_cast<std::size_t>(k);
            real densest = 0;
            auto at = entries(q);
            stencils_[q].for_each([&](std::size_t node, real w, const vector&) {
                const std::size_t e = at(node);
                if (w > 0) densest = std::max(densest, node_reference_density_[e]);
            });
            light_particle_[q] = reference_density(q) < theta * densest ? lightness::light : lightness::none;
        }
    for (std::size_t q = 0; q < particles_.size(); ++q)
        if (light_particle_[q] != lightness::none) light_list_.push_back(q);
    if (light_list_.empty()) return;
    near_light_.assign(grid_.entries(), 0);
    for (std::size_t p : light_list_) {
        auto at = entries(p);
        stencils_[p].for_each([&](std::size_t node, real, const vector&) { near_light_[at(node)] = 1; });
    }
    node_heavy_mass_.assign(grid_.entries(), real(0));
    for_each_particle_by_slab([&](std::size_t q) {
        if (light_particle_[q] != lightness::none) return;
        auto at = entries(q);
        stencils_[q].for_each([&](std::size_t node, real w, const vector&) {
            const std::size_t e = at(node);
            if (near_light_[e]) node_heavy_mass_[e] += w * m[q];
        });
    });
}

// A node's reliability k_i = m_i / rho_i^max (zero where no particle weighs it).
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
auto solver_core<S, Sh, M, Fields, MultiField, Part>::reliability(std::size_t e) const -> real {
    return node_densest_[e] > 0 ? grid_.mass[e] / node_densest_[e] : real(0);
}

// The mass of node entry e from particles that are not light (at the light particles' nodes).
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
auto solver_core<S, Sh, M, Fields, MultiField, Part>::heavy_mass(std::size_t e) const -> real {
    return node_heavy_mass_[e];
}

// A light particle's velocity gradient (instead of sum_i v_i (x) G_ip):
// L_p = sum_i (lambda_i v_i + (1 - lambda_i) vbar_p) (x) G_ip with lambda_i = k_i / max_j k_j and
// vbar_p = sum_i S_ip k_i v_i / sum_i S_ip k_i: a node that carries little of the densest
// material strains the particle by little (docs/equations.md, "Light particles").
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
auto solver_core<S, Sh, M, Fields, MultiField, Part>::light_velocity_gradient(
    std::size_t i, const std::vector<vector>& vg) const
    -> matrix {
    matrix L = matrix::Zero();
    real k_max = 0, k_sum = 0;
    vector mean = vector::Zero();
    auto at = entries(i);
    stencils_[i].for_each([&](std::size_t node, real w, const vector&) {
        const std::size_t e = at(node);
        const real k = reliability(e);
        if (w > 0) k_max = std::max(k_max, k);
        mean += w * k * vg[e];
        k_sum += w * k;
    });
    if (k_sum > 0) mean /= k_sum;
    auto at_grad = entries(i);
    stencils_[i].for_each([&](std::size_t node, real, const vector& g) {
        const std::size_t e = at_grad(node);
        const real lambda = k_max > 0 ? std::min(real(1), reliability(e) / k_max) : real(0);
        L.noalias() += (lambda * vg[e] + (1 - lambda) * mean) * g.transpose();
    });
    return L;
}

// Before the grid-to-particle pass, on one thread in index order: each light particle p takes
// v_p' = sum_i S_ip k_i v_i / sum_i S_ip k_i (the nodes' velocities after the grid update) as its
// velocity and for its position update. Its momentum change against the velocity the main pass
// would give it, D_p = m_p (v_p' - v_p^FLIP + alpha d_p) (FLIP with the damping blend), is split
// over its nodes in proportion to S_ip m_i^N (m^N: the non-light mass, heavy_mass) and summed
// per node in light_momentum_; grid_to_particles hands -light_momentum_ to the node's
// non-light particles in proportion to S_iq m_q. The kinetic energy this changes is not booked
// as heat, as the contact policies do not book theirs (docs/equations.md, "Light particles", says
// why and how much). Its FLIP velocity is the one grid_to_particles would give it, with its light
// nodes' forces. A light particle none of whose nodes has non-light mass keeps its FLIP velocity
// (there is nothing to return its momentum to): lightness::light_flip.
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
void solver_core<S, Sh, M, Fields, MultiField, Part>::move_light_particles(real dt) {
    auto& x = particles_.template column<fields::position>();
    auto& v = particles_.template column<fields::velocity>();
    const auto& m = particles_.template column<fields::mass>();
    light_momentum_.assign(grid_.entries(), vector::Zero());
    for (std::size_t p : light_list_) {
        vector v_flip = v[p], v_read = vector::Zero(), old = vector::Zero();
        real k_sum = 0, heavy_sum = 0;
        bool light_node = false;
        auto at = entries(p);
        stencils_[p].for_each([&](std::size_t node, real w, const vector& g) {
            const std::size_t e = at(node);
            v_flip += w * (grid_.velocity[e] - grid_.velocity_old[e]);
            old += w * grid_.velocity_old[e];
            light_node = light_node || on_light_node(e, w, g);
            const real k = reliability(e);
            v_read += w * k * grid_.velocity[e];
            k_sum += w * k;
            heavy_sum += w * heavy_mass(e);
        });
        if (light_node) v_flip += light_node_change(p, dt);
        if (!(k_sum > 0) || !(heavy_sum > 0)) {
            // Its nodes carry no material but its own: it moves as FLIP moves it.
            light_particle_[p] = lightness::light_flip;
            continue;
        }
        v_read /= k_sum;
        // Against the velocity the main pass would give it, with the damping blend
        // v_FLIP - alpha (v_p - S v^n): the blend keeps momentum only summed over all particles.
        const vector usual = v_flip - real(options_.pic_fraction) * (v[p] - old);
        const vector D = m[p] * (v_read - usual);
        auto at_share = entries(p);
        stencils_[p].for_each([&](std::size_t node, real w, const vector&) {
            const std::size_t e = at_share(node);
            light_momentum_[e] += D * (w * heavy_mass(e) / heavy_sum);
        });
        x[p] += dt * v_read;
        v[p] = v_read;
    }
}

}  // namespace gimlet
