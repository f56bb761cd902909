// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The volume filter (solver_options::volume_filter; docs/equations.md, "Particle-scale state
/// filters", (D)): before every material update, each particle's J = det F is replaced by the
/// L2 projection of the particles' J onto the grid's functions.
///
/// Why. Each particle's J changes only through the grid's velocity gradient, and the nodal
/// forces see the particles' stresses only through their sums over each node's support. A shock
/// leaves the particle rows of its plateau with different J, e and stress (at rest, 500 m/s:
/// sigma_yy 3.4-4.4 GPa from row to row) that no force can see or remove: the front-peak and
/// over-compression of docs/equations.md. The projection keeps what the grid can represent and
/// removes what it cannot:
///   c = M^-1 sum_p S_ip m_p J_p  (M the consistent mass matrix, k = consistent_mass_iterations
///                                 iterations of consistent_mass.hpp's scheme from the lumped
///                                 projection c0_i = sum_p S_ip m_p J_p / m_i),
///   J_p <- sum_i S_ip c_i  (over the nodes above the mass cut-off, the weights renormalised).
/// A lumped projection (k = 0) would smooth every field over about two cells (a shock front's
/// rise 3.7 -> 7.1 cells at 300 m/s); the consistent one leaves a resolved gradient nearly alone.
/// F is scaled by (J_new / J)^(1/dim).
///
/// The energy. Each particle keeps its thermal energy above the reference isentrope:
/// e <- e + e_s(J_new) - e_s(J) (the material's thermal policy provides e_s: reference_energy).
/// Projecting e with J would not do: the L2 projection is not convex and left a particle 5 K
/// under the isentrope on a shock's first step. The isentrope is convex, so replacing J by its
/// projection lowers sum_p m_p e_s(J_p): that energy (what the pattern held) is returned as heat,
/// spread through the nodes where it was lost (the positive part of each node's loss, scaled so
/// that the total is the loss exactly): the internal energy sum_p m_p e_p is kept, and no
/// particle is cooled. Where the filter would raise the isentrope's energy in total (not seen:
/// the projection averages), the particles pay it from their own e as above and nothing is spread.
/// Every particle's and node's sum runs in a fixed order (slab by slab), so the results do not
/// depend on the thread count.

#include "gimlet/solver/solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace gimlet {

template <Space S, shape::Shape Sh, Material M, contact::Contact C, FieldList ExtraFields, multi_field::Partition Part>
void solver<S, Sh, M, C, ExtraFields, Part>::filter_volumes() {
    if constexpr (has_reference_isentrope) {
        if (!options_.volume_filter) return;
        const int iterations = options_.consistent_mass_iterations;  // >= 1 (solver_options::validate)
        const std::size_t ne = grid_.entries();
        const auto nodes = static_cast<std::ptrdiff_t>(ne);
        [[maybe_unused]] const bool parallel_nodes = nodes >= node_parallel_threshold;  // read by the OpenMP pragmas only
        const auto n = static_cast<std::ptrdiff_t>(particles_.size());
        const auto& mass = particles_.template column<fields::mass>();
        auto& F = particles_.template column<fields::deformation_gradient>();
        auto& e = particles_.template column<fields::specific_internal_energy>();
        const auto& body = particles_.template column<fields::body>();
        vf_first_.resize(ne);
        vf_value_.resize(ne);
        vf_product_.resize(ne);
        vf_particle_.resize(particles_.size());

        // Scatters value(i) * (particle i's weight at the node) / (its weight on nodes above the
        // cut-off) to the nodes above the cut-off, slab by slab; each particle's sum over the
        // nodes is then value(i) exactly.
        auto scatter = [&](std::vector<real>& out, auto&& value) {
            std::fill(out.begin(), out.end(), real(0));
            for_each_particle_by_slab([&](std::size_t i) {
                const real share = value(i);
                auto at = entries(i);
                stencils_[i].for_each([&](std::size_t node, real w, const vector&) {
                    const std::size_t k = at(node);
                    if (grid_.mass[k] > mass_cutoff_) out[k] += w * share;
                });
            });
        };
        // sum_i S_ip c_i over the nodes above the cut-off, divided by the particle's weight there
        // (its own value where it reaches none), for every particle.
        auto gather = [&](const std::vector<real>& c, auto&& own) {
            GIMLET_OMP(parallel for schedule(dynamic, particle_chunk) num_threads(threads()) if (n >= parallel_threshold))
            for (std::ptrdiff_t k = 0; k < n; ++k) {
                const auto i = static_cast<std::size_t>(k);
                auto at = entries(i);
                real sum = 0, heavy = 0;
                stencils_[i].for_each([&](std::size_t node, real w, const vector&) {
                    const std::size_t j = at(node);
                    if (grid_.mass[j] > mass_cutoff_) sum += w * c[j], heavy += w;
                });
                vf_particle_[i] = heavy > 0 ? sum / heavy : own(i);
            }
        };
        // Each particle's weight on the nodes above the cut-off.
        vf_heavy_.resize(particles_.size());
        GIMLET_OMP(parallel for schedule(dynamic, particle_chunk) num_threads(threads()) if (n >= parallel_threshold))
        for (std::ptrdiff_t k = 0; k < n; ++k) {
            const auto i = static_cast<std::size_t>(k);
            auto at = entries(i);
            real heavy = 0;
            stencils_[i].for_each([&](std::size_t node, real w, const vector&) {
                if (grid_.mass[at(node)] > mass_cutoff_) heavy += w;
            });
            vf_heavy_[i] = heavy;
        }
        const auto& heavy = vf_heavy_;
        // m_p J_p over the particle's weight on the nodes above the cut-off, so that the lumped
        // projection c0_i is the mass-weighted mean of the J of the particles reaching node i.
        std::vector<real>& share = vf_share_;
        share.resize(particles_.size());
        GIMLET_OMP(parallel for schedule(dynamic, particle_chunk) num_threads(threads()) if (n >= parallel_threshold))
        for (std::ptrdiff_t k = 0; k < n; ++k) {
            const auto i = static_cast<std::size_t>(k);
            share[i] = heavy[i] > 0 ? mass[i] * F[i].determinant() / heavy[i] : real(0);
        }
        scatter(vf_first_, [&](std::size_t i) { return share[i]; });
        // The node masses above the cut-off, as the same renormalised shares see them.
        scatter(vf_product_, [&](std::size_t i) { return heavy[i] > 0 ? mass[i] / heavy[i] : real(0); });
        vf_mass_ = vf_product_;
        GIMLET_OMP(parallel for schedule(static) num_threads(threads()) if (parallel_nodes))
        for (std::ptrdiff_t k = 0; k < nodes; ++k) {
            const auto j = static_cast<std::size_t>(k);
            vf_first_[j] = vf_mass_[j] > 0 ? vf_first_[j] / vf_mass_[j] : real(0);
            vf_value_[j] = vf_first_[j];
        }
        // c^(j+1) = c0 + c^(j) - (M c^(j)) / m: M c is a gather to the particles and a scatter
        // of m_p (S c)_p back (consistent_mass.hpp).
        for (int it = 0; it < iterations; ++it) {
            gather(vf_value_, [&](std::size_t) { return real(0); });
            // m_p (S c)_p, scattered with the renormalised weights
            scatter(vf_product_, [&](std::size_t i) { return heavy[i] > 0 ? mass[i] * vf_particle_[i] / heavy[i] : real(0); });
            GIMLET_OMP(parallel for schedule(static) num_threads(threads()) if (parallel_nodes))
            for (std::ptrdiff_t k = 0; k < nodes; ++k) {
                const auto j = static_cast<std::size_t>(k);
                if (vf_mass_[j] > 0) vf_value_[j] = vf_first_[j] + vf_value_[j] - vf_product_[j] / vf_mass_[j];
            }
        }
        // The new J, F scaled to it, e moved along the isentrope; each particle's loss
        // m_p (e_s(J) - e_s(J_new)), to be returned as heat.
        gather(vf_value_, [&](std::size_t i) { return real(F[i].determinant()); });
        std::ptrdiff_t bad = n;
        GIMLET_OMP(parallel for schedule(dynamic, particle_chunk) reduction(min : bad) num_threads(threads()) if (n >= parallel_threshold))
        for (std::ptrdiff_t k = 0; k < n; ++k) {
            const auto i = static_cast<std::size_t>(k);
            const real j_old = F[i].determinant(), j_new = vf_particle_[i];
            share[i] = 0;
            if (!(std::isfinite(j_new) && j_new > 0)) {
                bad = std::min(bad, k);
                continue;
            }
            if (j_new == j_old) continue;
            const auto& thermal = materials_[body[i]].thermal;
            double es_old = 0, es_new = 0;
            try {  // e_s throws beyond the isentrope's singular compression
                es_old = thermal.reference_energy(double(j_old));
                es_new = thermal.reference_energy(double(j_new));
            } catch (const invalid_parameter&) {
                bad = std::min(bad, k);
                continue;
            }
            F[i] *= std::pow(j_new / j_old, real(1) / real(dim));
            e[i] += real(es_new - es_old);
            share[i] = mass[i] * real(es_old - es_new);
        }
        if (bad < n) {
            const auto i = static_cast<std::size_t>(bad);
            fail(i, "the volume filter projected J = " + detail::to_text(double(F[i].determinant())) + " to " +
                        detail::to_text(double(vf_particle_[i])) +
                        ", outside the reference isentrope's range (J > 0, and J > 1 - 1/s for Mie-Grueneisen)");
        }
        // The heat: the losses through the nodes, the positive part of each node's sum scaled to
        // the total loss, back to the particles by mass.
        scatter(vf_product_, [&](std::size_t i) { return heavy[i] > 0 ? share[i] / heavy[i] : real(0); });
        real total = 0, positive = 0;
        for (std::size_t j = 0; j < ne; ++j) {
            total += vf_product_[j];
            positive += std::max(vf_product_[j], real(0));
        }
        // Particles that reach no node above the cut-off lose nothing (their J is kept).
        if (!(total > 0 && positive > 0)) return;
        const real scale = total / positive;
        GIMLET_OMP(parallel for schedule(static) num_threads(threads()) if (parallel_nodes))
        for (std::ptrdiff_t k = 0; k < nodes; ++k) {
            const auto j = static_cast<std::size_t>(k);
            vf_value_[j] = vf_mass_[j] > 0 ? std::max(vf_product_[j], real(0)) * scale / vf_mass_[j] : real(0);
        }
        gather(vf_value_, [&](std::size_t) { return real(0); });
        GIMLET_OMP(parallel for schedule(static) num_threads(threads()) if (n >= parallel_threshold))
        for (std::ptrdiff_t k = 0; k < n; ++k) {
            // sum_i S_ip h_i over the particle's weight on the nodes above the cut-off
            e[static_cast<std::size_t>(k)] += vf_particle_[static_cast<std::size_t>(k)];
        }
    }
}

}  // namespace gimlet
