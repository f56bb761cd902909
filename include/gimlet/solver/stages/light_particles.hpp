// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The light-particles stage: particles far less dense than their neighbours ("light particles";
/// solver_options::light_particle_ratio; docs/equations.md, "Light particles").
///
/// Where a dense particle has a tiny weight S at a node, the node's velocity increment
/// dt f_i / m_i grows as 1/sqrt(S) (GIMP's gradient at the edge of a support is not small where
/// the weight is). The dense particle reads it with weight S, harmlessly; a far less dense
/// particle on the same node reads it with weight O(1) and is flung (52-115 km/s, det F down
/// to 0, in the sparse cloud of tests/robustness/test_hard_cases.cpp, "near-empty nodes"). A
/// light particle therefore reads each node by its reliability
/// k_i = m_i / rho_i^max (the volume of the node's densest material its mass amounts to), for
/// its velocity and for its velocity gradient, and the momentum it changes against FLIP goes back
/// to the non-light particles of its nodes, so momentum stays exact.

#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/detail/shares.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/material_point.hpp"
#include "gimlet/core/space.hpp"
#include "gimlet/material/update.hpp"
#include "gimlet/solver/stages/damping_transfer.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace gimlet::stages {

/// The light-particles stage. Called by every scheme after its first scatter (find), by G2P
/// before its pass (move), and by the velocity gradient and volumetric averaging (is_light,
/// velocity_gradient).
///
/// Reads: the particles' mass, volume0, current volume, body and velocity, the number of bodies,
/// the step's stencils and node entries, the grid's mass and velocities, the light nodes' forces
/// (Core::on_light_node, Core::light_node_change), the options' light_particle_ratio and the
/// damping transfer's fraction.
/// Writes: the light particles' position and velocity (move); its own per-node and
/// per-particle state, read by G2P (heavy_mass, momentum) and the velocity gradient.
/// Chosen at run time (solver_options::light_particle_ratio, and whether any particle can be
/// light at all: check_possible()); off, it costs a test a step, and one per particle in the velocity
/// gradient.
///
/// \tparam S the space.
template <Space S>
class light_particles {
public:
    /// The scalar type of S.
    using real = typename S::real;
    /// S::vector.
    using vector = typename S::vector;
    /// S::matrix.
    using matrix = typename S::matrix;

    /// How many particles the last step found light.
    [[nodiscard]] std::size_t count() const noexcept { return list_.size(); }
    /// Whether any particle can be light (check_possible's answer).
    [[nodiscard]] bool possible() const noexcept { return possible_; }
    /// Whether particle i is light this step.
    [[nodiscard]] bool is_light(std::size_t i) const { return !list_.empty() && lightness_[i] != lightness::none; }
    /// Whether particle i takes the nodes' reliability-weighted velocity this step (move), not FLIP's.
    [[nodiscard]] bool moved(std::size_t i) const { return lightness_[i] == lightness::light; }
    /// Whether particle i hands back a share of the momentum the light particles changed (momentum).
    [[nodiscard]] bool returns_momentum(std::size_t i) const { return lightness_[i] == lightness::none; }
    /// The mass of node entry e from particles that are not light (at the light particles' nodes).
    [[nodiscard]] real heavy_mass(std::size_t e) const { return node_heavy_mass_[e]; }
    /// The momentum the light particles changed at node entry e (move).
    [[nodiscard]] const vector& momentum(std::size_t e) const { return light_momentum_[e]; }

    /// Whether any particle can be light: reference densities only change when the user touches
    /// the particles, and a particle is light only against a denser one on its stencil (in its
    /// field), so none can be where the least dense particle is at least theta times the densest:
    /// of the scene, or with a multi-field contact (whose fields never mix bodies) of each body.
    /// Where none can be, find() returns at once and no particle is light.
    template <class Core>
    void check_possible(const Core& c) {
        const auto& particles = c.particles_;
        const auto& body = particles.template column<fields::body>();
        possible_ = false;
        // (On many processes every process goes on to the reductions below, particles or not.)
        if ((particles.size() == 0 && !c.processes()) || !(c.options_.light_particle_ratio > 0)) return;
        const std::size_t groups = Core::multi_field ? c.materials_.size() : 1;
        std::vector<real> least(groups, std::numeric_limits<real>::infinity()), most(groups, real(0));
        for (std::size_t i = 0; i < particles.size(); ++i) {
            const std::size_t g = Core::multi_field ? std::size_t(body[i]) : 0;
            const real rho = reference_density(particles, i);
            least[g] = std::min(least[g], rho);
            most[g] = std::max(most[g], rho);
        }
        // On many processes, over every process's particles (exact: minima and maxima).
        if (auto* p = c.processes())
            for (std::size_t g = 0; g < groups; ++g) least[g] = real(p->min(double(least[g]))), most[g] = real(p->max(double(most[g])));
        for (std::size_t g = 0; g < groups; ++g)
            possible_ = possible_ || least[g] < real(c.options_.light_particle_ratio) * most[g];
    }

    /// After the step's first scatter: per node entry (so per field), the largest reference
    /// density and the largest current density m_q / V_q of the particles with a nonzero weight
    /// there (both maxima, so the slab scatter's order does not matter); then p is light if
    /// rho0_p < theta max rho0, the maximum over the nodes where p has a nonzero weight. Then, at
    /// the nodes of the light particles' stencils, the mass of the particles that are not light,
    /// sum_q S_iq m_q (a sum of its own rather than m_i less the light mass, whose rounding would
    /// not cancel where the light mass dominates).
    template <class Core>
    void find(Core& c) {
        list_.clear();
        if (!possible_) return;
        const auto& particles = c.particles_;
        const auto& stencils = c.stencils_;
        const auto& m = particles.template column<fields::mass>();
        const std::size_t entries = c.grid_.entries();
        node_reference_density_.assign(entries, real(0));
        node_densest_.assign(entries, real(0));
        c.for_each_particle_by_slab([&](std::size_t q) {
            const real rho0 = reference_density(particles, q), rho = m[q] / current_volume(particles[q]);
            auto at = c.entries(q);
            stencils[q].for_each([&](std::size_t node, real w, const vector&) {
                const std::size_t e = at(node);
                if (w > 0) {
                    node_reference_density_[e] = std::max(node_reference_density_[e], rho0);
                    node_densest_[e] = std::max(node_densest_[e], rho);
                }
            });
        });
        const auto n = static_cast<std::ptrdiff_t>(particles.size());
        lightness_.assign(particles.size(), lightness::none);
        const real theta = real(c.options_.light_particle_ratio);
        detail::thread_shares shares(n, c.threads(), n >= Core::parallel_threshold);
        GIMLET_OMP(parallel num_threads(shares.team()))
        for (auto claimed = shares.start(); shares.claim(claimed);)
            for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) {
                const auto q = static_cast<std::size_t>(k);
                real densest = 0;
                auto at = c.entries(q);
                stencils[q].for_each([&](std::size_t node, real w, const vector&) {
                    const std::size_t e = at(node);
                    if (w > 0) densest = std::max(densest, node_reference_density_[e]);
                });
                lightness_[q] = reference_density(particles, q) < theta * densest ? lightness::light : lightness::none;
                // A driven particle moves as it is told (stages::driven_particles), never as a light one.
                if constexpr (Core::has_driven_particles)
                    if (particles.template column<fields::driven>()[q]) lightness_[q] = lightness::none;
            }
        for (std::size_t q = 0; q < particles.size(); ++q)
            if (lightness_[q] != lightness::none) list_.push_back(q);
        if (list_.empty()) return;
        near_light_.assign(entries, 0);
        for (std::size_t p : list_) {
            auto at = c.entries(p);
            stencils[p].for_each([&](std::size_t node, real, const vector&) { near_light_[at(node)] = 1; });
        }
        node_heavy_mass_.assign(entries, real(0));
        c.for_each_particle_by_slab([&](std::size_t q) {
            if (lightness_[q] != lightness::none) return;
            auto at = c.entries(q);
            stencils[q].for_each([&](std::size_t node, real w, const vector&) {
                const std::size_t e = at(node);
                if (near_light_[e]) node_heavy_mass_[e] += w * m[q];
            });
        });
    }

    /// A light particle's velocity gradient (instead of sum_i v_i (x) G_ip):
    /// L_p = sum_i (lambda_i v_i + (1 - lambda_i) vbar_p) (x) G_ip with lambda_i = k_i / max_j k_j
    /// and vbar_p = sum_i S_ip k_i v_i / sum_i S_ip k_i: a node that carries little of the densest
    /// material strains the particle by little (docs/equations.md, "Light particles").
    template <class Core>
    [[nodiscard]] matrix velocity_gradient(const Core& c, std::size_t i, const std::vector<vector>& vg,
                                           [[maybe_unused]] real* hoop_rate = nullptr) const {
        matrix L = matrix::Zero();
        real k_max = 0, k_sum = 0;
        vector mean = vector::Zero();
        auto at = c.entries(i);
        c.stencils_[i].for_each([&](std::size_t node, real w, const vector&) {
            const std::size_t e = at(node);
            const real k = reliability(c, e);
            if (w > 0) k_max = std::max(k_max, k);
            mean += w * k * vg[e];
            k_sum += w * k;
        });
        if (k_sum > 0) mean /= k_sum;
        auto at_grad = c.entries(i);
        if constexpr (is_axisymmetric_v<S>) {
            // The hoop rate L_thetatheta = sum v_ir T_ip from the same blended velocities.
            real hoop = 0;
            c.stencils_[i].for_each_hoop([&](std::size_t node, real, const vector& g, real t) {
                const std::size_t e = at_grad(node);
                const real lambda = k_max > 0 ? std::min(real(1), reliability(c, e) / k_max) : real(0);
                const vector v = lambda * vg[e] + (1 - lambda) * mean;
                L.noalias() += v * g.transpose();
                hoop += v[0] * t;
            });
            if (hoop_rate) *hoop_rate = hoop;
            return L;
        }
        c.stencils_[i].for_each([&](std::size_t node, real, const vector& g) {
            const std::size_t e = at_grad(node);
            const real lambda = k_max > 0 ? std::min(real(1), reliability(c, e) / k_max) : real(0);
            L.noalias() += (lambda * vg[e] + (1 - lambda) * mean) * g.transpose();
        });
        return L;
    }

    /// Before the grid-to-particle pass, on one thread in index order: each light particle p takes
    /// v_p' = sum_i S_ip k_i v_i / sum_i S_ip k_i (the nodes' velocities after the grid update) as
    /// its velocity and for its position update. Its momentum change against the velocity the main
    /// pass would give it, D_p = m_p (v_p' - v_p^FLIP + alpha d_p) (FLIP with the damping blend),
    /// is split over its nodes in proportion to S_ip m_i^N (m^N: the non-light mass, heavy_mass)
    /// and summed per node (momentum); G2P hands -momentum(e) to the node's non-light particles in
    /// proportion to S_iq m_q. The kinetic energy this changes is not booked as heat, as the
    /// contact policies do not book theirs (docs/equations.md, "Light particles", says why and how
    /// much). Its FLIP velocity is the one G2P would give it, with its light nodes' forces
    /// (Core::on_light_node, Core::light_node_change). A light particle none of whose nodes has
    /// non-light mass keeps its FLIP velocity (there is nothing to return its momentum to):
    /// lightness::light_flip.
    template <class Core>
    void move(Core& c, real dt) {
        auto& x = c.particles_.template column<fields::position>();
        auto& v = c.particles_.template column<fields::velocity>();
        const auto& m = c.particles_.template column<fields::mass>();
        const auto& grid = c.grid_;
        light_momentum_.assign(grid.entries(), vector::Zero());
        for (std::size_t p : list_) {
            vector v_flip = v[p], v_read = vector::Zero(), old = vector::Zero();
            real k_sum = 0, heavy_sum = 0;
            bool light_node = false;
            auto at = c.entries(p);
            c.stencils_[p].for_each([&](std::size_t node, real w, const vector& g) {
                const std::size_t e = at(node);
                v_flip += w * (grid.velocity[e] - grid.velocity_old[e]);
                old += w * grid.velocity_old[e];
                light_node = light_node || c.on_light_node(e, w, g);
                const real k = reliability(c, e);
                v_read += w * k * grid.velocity[e];
                k_sum += w * k;
                heavy_sum += w * heavy_mass(e);
            });
            if (light_node) v_flip += c.light_node_change(p, dt);
            if (!(k_sum > 0) || !(heavy_sum > 0)) {
                // Its nodes carry no material but its own: it moves as FLIP moves it.
                lightness_[p] = lightness::light_flip;
                continue;
            }
            v_read /= k_sum;
            // Against the velocity the main pass would give it, with the damping blend
            // v_FLIP - alpha (v_p - S v^n): the blend keeps momentum only summed over all particles.
            const vector usual = v_flip - damping_transfer<S>::fraction(c) * (v[p] - old);
            const vector D = m[p] * (v_read - usual);
            auto at_share = c.entries(p);
            c.stencils_[p].for_each([&](std::size_t node, real w, const vector&) {
                const std::size_t e = at_share(node);
                light_momentum_[e] += D * (w * heavy_mass(e) / heavy_sum);
            });
            if constexpr (is_axisymmetric_v<S>) {
                // A ring's midpoint moves with the plain shape's interpolation (the nodes beyond
                // the axis mirrored: stencil::for_each_position), weighted by the same
                // reliabilities, the main pass's rule where every k_i is the same. The axis nodes'
                // v_r = 0 is a condition, not a mass's estimate: it counts as the most reliable
                // node's, or a light ring beside the axis would move with the shell's velocity
                // across it.
                real k_top = 0;
                auto at_top = c.entries(p);
                c.stencils_[p].for_each([&](std::size_t node, real, const vector&) {
                    k_top = std::max(k_top, reliability(c, at_top(node)));
                });
                vector u = vector::Zero(), k_plain = vector::Zero();
                auto at_position = c.entries(p);
                c.stencils_[p].for_each_position([&](std::size_t node, real cr, real cz) {
                    const std::size_t e = at_position(node);
                    const real k = reliability(c, e);
                    const real kr = grid.node_position(e % grid.size())[0] <= 0 ? k_top : k;
                    u[0] += cr * kr * grid.velocity[e][0];
                    u[1] += cz * k * grid.velocity[e][1];
                    k_plain[0] += cz * kr;
                    k_plain[1] += cz * k;
                });
                for (int d = 0; d < 2; ++d) x[p][d] += dt * (k_plain[d] > 0 ? u[d] / k_plain[d] : v_read[d]);
            } else {
                x[p] += dt * v_read;
            }
            v[p] = v_read;
        }
    }

private:
    // A particle's reference density m_p / V_p^0: what lightness compares. It is its material's
    // density, so particles of one material are never light against each other, whatever their
    // sizes (a mass test would make a body seeded at 5 x 5 particles per cell light beside one
    // seeded at 1, and its treatment would remove 9-16 % of the energy of their impact, where
    // nothing is flung without it: docs/equations.md, "Light particles").
    template <class Store>
    [[nodiscard]] static real reference_density(const Store& particles, std::size_t i) {
        return particles.template column<fields::mass>()[i] / particles.template column<fields::volume0>()[i];
    }

    // A node's reliability k_i = m_i / rho_i^max (zero where no particle weighs it).
    template <class Core>
    [[nodiscard]] real reliability(const Core& c, std::size_t e) const {
        return node_densest_[e] > 0 ? c.grid_.mass[e] / node_densest_[e] : real(0);
    }

    enum class lightness : std::uint8_t {
        none,
        light,       // takes the nodes' reliability-weighted velocity
        light_flip,  // light, but no node of its has non-light mass: FLIP moves it
    };
    // None unless possible_. Per particle its lightness (only current when the list is not
    // empty), the light ones in index order, and per node entry the largest reference and
    // current densities, whether a light particle's stencil holds it, the mass of the particles
    // that are not light there and the momentum the light ones changed.
    bool possible_ = false;
    std::vector<lightness> lightness_;
    std::vector<std::size_t> list_;
    std::vector<real> node_reference_density_, node_densest_, node_heavy_mass_;
    std::vector<std::uint8_t> near_light_;
    std::vector<vector> light_momentum_;
};

}  // namespace gimlet::stages
