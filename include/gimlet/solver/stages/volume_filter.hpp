// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The volume-filter stage (solver_options::volume_filter; docs/equations.md, "Particle-scale state
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
/// Each body is projected on its own (and with a multi-field contact each velocity field): two
/// bodies are never averaged together.
///
/// The energy. Each particle keeps its thermal energy above the reference isentrope:
/// e <- e + e_s(J_new) - e_s(J) (the material's thermal policy provides e_s: reference_energy).
/// Projecting e with J would not do: the L2 projection is not convex and leaves a particle 5 K
/// under the isentrope on a shock's first step. That move changes sum_p m_p e_s(J_p); where a
/// pattern is removed it lowers it (the isentrope is convex), and that energy is returned as
/// heat through the nodes where it was released: each node's sum of the particles' releases, the
/// parts of the same sign as the total scaled so that they sum to the total exactly, gathered
/// back per unit mass. The internal energy sum_p m_p e_p is kept. When the total is a release no
/// particle is cooled; when it is a gain (possible: with k >= 1 the projection's weights are not
/// all positive), the gain is taken back as heat from where it appeared, and a particle taken
/// under its isentrope stops the next material update (the e_th < e_s check).
/// The heat is scaled over the whole grid, so a release at one place and a gain at another
/// offset each other. A particle whose e_s(J) or e_s(J_new) its thermal policy refuses stops the
/// run before anything is changed. Every sum runs in a fixed order (slab by slab), so the results
/// do not depend on the thread count.

#include "gimlet/core/error.hpp"
#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/detail/shares.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/space.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

namespace gimlet::stages {

/// The volume-filter stage, called before every material update (before the cell averages of
/// volumetric averaging, which weight the rates with the volumes).
///
/// Reads: the grid's masses, the mass cut-off, consistent_mass_iterations, the particles'
/// masses, bodies, deformation gradients, stencils and node entries, and the materials'
/// reference isentropes. Writes: the particles' deformation gradients and internal energies. Chosen at run time (solver_options::volume_filter; off, it returns at once) and
/// compiled only for a material whose thermal policy provides the reference isentrope.
///
/// \tparam S the space.
template <Space S>
class volume_filter {
public:
    /// The scalar type of S.
    using real = typename S::real;
    /// S::vector.
    using vector = typename S::vector;

    /// J_p <- the projection of J onto the grid, e moved along the isentrope (the file's comment).
    template <class Core>
    void apply(Core& c) {
        if constexpr (Core::has_reference_isentrope) {
            if (!c.options_.volume_filter) return;
            // J is projected per body (key_base): with a single field, one block of node entries
            // per body; with multi-field contact each body's fields have entries of their own.
            const std::size_t nk = Core::multi_field ? c.grid_.entries() : c.grid_.entries() * c.materials_.size();
            first_.resize(nk);
            value_.resize(nk);
            product_.resize(nk);
            mass_.resize(nk);
            particle_.resize(c.particles_.size());
            heavy_.resize(c.particles_.size());
            weights_on_heavy_nodes(c);
            project(c);
            check_projection(c);
            move_along_isentrope(c);
            return_heat(c);
        }
    }

private:
    // Each particle's weight on the nodes above the mass cut-off (the weights below are
    // renormalised by it, so that a particle's weights over those nodes sum to one).
    template <class Core>
    void weights_on_heavy_nodes(Core& c) {
        const auto n = static_cast<std::ptrdiff_t>(c.particles_.size());
        detail::thread_shares shares(n, c.threads(), n >= Core::parallel_threshold);
        GIMLET_OMP(parallel num_threads(shares.team()))
        for (auto claimed = shares.start(); shares.claim(claimed);)
            for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) {
                const auto i = static_cast<std::size_t>(k);
                auto at = c.entries(i);
                real w_heavy = 0;
                c.stencils_[i].for_each([&](std::size_t node, real w, const vector&) {
                    if (c.grid_.mass[at(node)] > c.mass_cutoff_) w_heavy += w;
                });
                heavy_[i] = w_heavy;
            }
    }

    // Where particle `body`'s keys start: node entry e of a body is key key_base + e. With a
    // single field every body reaches the same entries, so each has a block of its own; with
    // multi-field contact a body's entries are its own already.
    template <class Core>
    [[nodiscard]] static std::size_t key_base(std::uint32_t body, std::size_t entries) noexcept {
        return Core::multi_field ? 0 : std::size_t(body) * entries;
    }

    // out_k = sum_p (S_ip / heavy_p) value(p) over the nodes above the cut-off, slab by slab.
    template <class Core, class Value>
    void scatter(Core& c, std::vector<real>& out, Value&& value) {
        const auto& body = c.particles_.template column<fields::body>();
        const std::size_t ne = c.grid_.entries();
        std::fill(out.begin(), out.end(), real(0));
        c.for_each_particle_by_slab([&](std::size_t i) {
            if (!(heavy_[i] > 0)) return;
            const real v = value(i) / heavy_[i];
            const std::size_t base = key_base<Core>(body[i], ne);
            auto at = c.entries(i);
            c.stencils_[i].for_each([&](std::size_t node, real w, const vector&) {
                const std::size_t k = at(node);
                if (c.grid_.mass[k] > c.mass_cutoff_) out[base + k] += w * v;
            });
        });
    }

    // particle_[p] = sum_i (S_ip / heavy_p) values_i over the nodes above the cut-off (own(p)
    // for a particle that reaches none).
    template <class Core, class Own>
    void gather(Core& c, const std::vector<real>& values, Own&& own) {
        const auto& body = c.particles_.template column<fields::body>();
        const std::size_t ne = c.grid_.entries();
        const auto n = static_cast<std::ptrdiff_t>(c.particles_.size());
        detail::thread_shares shares(n, c.threads(), n >= Core::parallel_threshold);
        GIMLET_OMP(parallel num_threads(shares.team()))
        for (auto claimed = shares.start(); shares.claim(claimed);)
            for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) {
                const auto i = static_cast<std::size_t>(k);
                if (!(heavy_[i] > 0)) {
                    particle_[i] = own(i);
                    continue;
                }
                const std::size_t base = key_base<Core>(body[i], ne);
                auto at = c.entries(i);
                real sum = 0;
                c.stencils_[i].for_each([&](std::size_t node, real w, const vector&) {
                    const std::size_t j = at(node);
                    if (c.grid_.mass[j] > c.mass_cutoff_) sum += w * values[base + j];
                });
                particle_[i] = sum / heavy_[i];
            }
    }

    // f(j) for every node entry of every body, split between the threads on a large grid.
    template <class Core, class F>
    void for_each_key(Core& c, F&& f) {
        const auto keys = static_cast<std::ptrdiff_t>(mass_.size());
        detail::thread_shares shares(keys, c.threads(), keys >= Core::node_parallel_threshold);
        GIMLET_OMP(parallel num_threads(shares.team()))
        for (auto claimed = shares.start(); shares.claim(claimed);)
            for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) f(static_cast<std::size_t>(k));
    }

    // The projection c into value_, and its values at the particles, the new J, into particle_
    // (a particle that reaches no node above the cut-off keeps its own J). First the masses as
    // the renormalised weights see them, and c0: the mass-weighted mean J of the particles
    // reaching each node. Then c^(j+1) = c0 + c^(j) - (M c^(j)) / m, M c a gather to the particles
    // and a scatter of m_p (S c)_p back (stages/consistent_mass.hpp); a uniform J is its fixed
    // point.
    template <class Core>
    void project(Core& c) {
        const auto& mass = c.particles_.template column<fields::mass>();
        const auto& F = c.particles_.template column<fields::deformation_gradient>();
        scatter(c, mass_, [&](std::size_t i) { return mass[i]; });
        scatter(c, first_, [&](std::size_t i) { return mass[i] * F[i].determinant(); });
        for_each_key(c, [&](std::size_t j) {
            first_[j] = mass_[j] > 0 ? first_[j] / mass_[j] : real(0);
            value_[j] = first_[j];
        });
        const int iterations = c.options_.consistent_mass_iterations;  // >= 1 (solver_options::validate)
        for (int it = 0; it < iterations; ++it) {
            gather(c, value_, [&](std::size_t) { return real(0); });
            scatter(c, product_, [&](std::size_t i) { return mass[i] * particle_[i]; });
            for_each_key(c, [&](std::size_t j) {
                if (mass_[j] > 0) value_[j] = first_[j] + value_[j] - product_[j] / mass_[j];
            });
        }
        gather(c, value_, [&](std::size_t i) { return real(F[i].determinant()); });
    }

    // Each particle's change of e_s from its J to the new J, into es_change_, checked before
    // anything changes: the first particle (lowest index) whose new J is not a positive number,
    // or whose e_s its thermal policy refuses, stops the run with the state as it was.
    template <class Core>
    void check_projection(Core& c) {
        const auto& F = c.particles_.template column<fields::deformation_gradient>();
        const auto& body = c.particles_.template column<fields::body>();
        const auto n = static_cast<std::ptrdiff_t>(c.particles_.size());
        es_change_.assign(c.particles_.size(), 0.0);
        std::ptrdiff_t failed = n;
        std::exception_ptr error;
        detail::thread_shares shares(n, c.threads(), n >= Core::parallel_threshold);
        GIMLET_OMP(parallel num_threads(shares.team()))
        for (auto claimed = shares.start(); shares.claim(claimed);)
            for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) {
                const auto i = static_cast<std::size_t>(k);
                const real j_old = F[i].determinant(), j_new = particle_[i];
                if (j_new == j_old) continue;
                try {
                    if (!(std::isfinite(j_new) && j_new > 0))
                        throw std::domain_error("not a positive number");
                    const auto& thermal = c.materials_[body[i]].thermal;
                    es_change_[i] = thermal.reference_energy(double(j_new)) - thermal.reference_energy(double(j_old));
                } catch (...) {
                    GIMLET_OMP(critical(gimlet_volume_filter_error))
                    if (k < failed) failed = k, error = std::current_exception();
                }
            }
        if (!error) return;
        const auto i = static_cast<std::size_t>(failed);
        std::string why;
        try {
            std::rethrow_exception(error);
        } catch (const std::exception& x) {
            why = x.what();
        } catch (...) {
            why = "an unknown exception";
        }
        c.fail(i, "the volume filter projected J = " + detail::to_text(double(F[i].determinant())) + " to " +
                      detail::to_text(double(particle_[i])) + ", which the reference isentrope refuses (" + why + ")");
    }

    // F scaled to the new J, e moved along the isentrope.
    template <class Core>
    void move_along_isentrope(Core& c) {
        auto& F = c.particles_.template column<fields::deformation_gradient>();
        auto& e = c.particles_.template column<fields::specific_internal_energy>();
        const auto n = static_cast<std::ptrdiff_t>(c.particles_.size());
        detail::thread_shares shares(n, c.threads(), n >= Core::parallel_threshold);
        GIMLET_OMP(parallel num_threads(shares.team()))
        for (auto claimed = shares.start(); shares.claim(claimed);)
            for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) {
                const auto i = static_cast<std::size_t>(k);
                if (es_change_[i] == 0.0) continue;
                const real j_old = F[i].determinant(), j_new = particle_[i];
                F[i] *= std::pow(j_new / j_old, real(1) / real(S::dim));
                e[i] += real(es_change_[i]);
            }
    }

    // The heat: each particle's release m_p (e_s(J) - e_s(J_new)) through the nodes; the node
    // sums of the total's sign, scaled to the total, back to the particles per unit mass
    // (sum_p m_p heat_p = total exactly).
    template <class Core>
    void return_heat(Core& c) {
        const auto& mass = c.particles_.template column<fields::mass>();
        auto& e = c.particles_.template column<fields::specific_internal_energy>();
        const std::size_t nk = product_.size();
        scatter(c, product_, [&](std::size_t i) { return -mass[i] * real(es_change_[i]); });
        real total = 0;
        for (std::size_t j = 0; j < nk; ++j) total += product_[j];
        auto counted = [&](real node_sum) { return node_sum != 0 && (node_sum > 0) == (total > 0); };
        real same_sign = 0;
        for (std::size_t j = 0; j < nk; ++j)
            if (counted(product_[j])) same_sign += product_[j];
        if (total == 0 || same_sign == 0) return;
        const real scale = total / same_sign;
        for_each_key(c, [&](std::size_t j) {
            value_[j] = mass_[j] > 0 && counted(product_[j]) ? product_[j] * scale / mass_[j] : real(0);
        });
        gather(c, value_, [&](std::size_t) { return real(0); });
        const auto n = static_cast<std::ptrdiff_t>(c.particles_.size());
        detail::thread_shares shares(n, c.threads(), n >= Core::parallel_threshold);
        GIMLET_OMP(parallel num_threads(shares.team()))
        for (auto claimed = shares.start(); shares.claim(claimed);)
            for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k)
                e[static_cast<std::size_t>(k)] += particle_[static_cast<std::size_t>(k)];
    }

    // Per key (key_base) the lumped projection of J, the iterate, M times it (and the
    // releases), the masses as the renormalised weights see them; per particle the gathered
    // values, the weight on the nodes above the cut-off and the change of e_s.
    std::vector<real> first_, value_, product_, mass_, particle_, heavy_;
    std::vector<double> es_change_;
};

}  // namespace gimlet::stages
