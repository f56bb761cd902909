// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The volumetric-averaging stage (solver_options::volumetric_average; docs/equations.md,
/// "Volumetric averaging"): each particle's volumetric strain rate and in-plane mean stress
/// replaced by its cell's volume-weighted means (B-bar), per body or field and cell.

#include "gimlet/core/fields.hpp"
#include "gimlet/core/space.hpp"
#include "gimlet/material/update.hpp"

#include <cstddef>
#include <vector>

namespace gimlet::stages {

/// The volumetric-averaging stage. The schemes call average_rates before each material update
/// and average_stress before each force map; the velocity gradient and the force map read the
/// cell means through averaged_rate and averaged_stress.
///
/// Reads: the particles' stresses, volumes, bodies and stencils, the number of bodies, the
/// step's node entries and fields (stages::field_choice::side), the grid velocities given, and
/// the light-particles stage's gradients. Writes: its own cell sums only. Chosen at run time
/// (solver_options::volumetric_average); off, the schemes do not call it, and the velocity
/// gradient and the force's stress test the option once per particle.
///
/// \tparam S the space.
template <Space S>
class volumetric_average {
public:
    /// The scalar type of S.
    using real = typename S::real;
    /// S::vector.
    using vector = typename S::vector;
    /// S::matrix.
    using matrix = typename S::matrix;
    /// Number of axes, 2 or 3.
    static constexpr int dim = S::dim;

    /// Per body (or field) and cell (cell_key), the sums of V_p tr(sigma_p)/dim and of V_p
    /// (averaged_stress).
    template <class Core>
    void average_stress(Core& c) {
        const std::size_t n = c.materials_.size() * Core::fields_per_body * c.grid_.size();
        cell_stress_.assign(n, real(0));
        cell_stress_volume_.assign(n, real(0));
        const auto& sig = c.particles_.template column<fields::stress>();
        c.for_each_particle_by_slab([&](std::size_t i) {
            const real v = current_volume(c.particles_[i]);
            const std::size_t k = cell_key(c, i);
            cell_stress_[k] += v * sig[i].trace() / real(dim);
            cell_stress_volume_[k] += v;
        });
    }

    /// Per body (or field) and cell (cell_key), the sums of V_p tr L_p and of V_p over its
    /// particles, with L_p from the velocities vg. A particle's cell lies in its own slab, so the
    /// slab colouring keeps the sums free of races and in a fixed order.
    template <class Core>
    void average_rates(Core& c, const std::vector<vector>& vg) {
        const std::size_t n = c.materials_.size() * Core::fields_per_body * c.grid_.size();
        cell_rate_.assign(n, real(0));
        cell_volume_.assign(n, real(0));
        c.for_each_particle_by_slab([&](std::size_t i) {
            real rate = 0;
            if (c.lights_.is_light(i)) {
                rate = c.lights_.velocity_gradient(c, i, vg).trace();
            } else {
                auto at = c.entries(i);
                c.stencils_[i].for_each([&](std::size_t node, real, const vector& g) { rate += vg[at(node)].dot(g); });
            }
            const real v = current_volume(c.particles_[i]);
            const std::size_t k = cell_key(c, i);
            cell_rate_[k] += v * rate;
            cell_volume_[k] += v;
        });
    }

    /// L with its volumetric rate replaced by its cell's mean.
    template <class Core>
    void averaged_rate(const Core& c, std::size_t i, matrix& L) const {
        const std::size_t k = cell_key(c, i);
        L.diagonal().array() += (cell_rate_[k] / cell_volume_[k] - L.trace()) / real(dim);
    }

    /// sigma with its in-plane mean stress tr(sigma)/dim replaced by its cell's volume-weighted
    /// mean (B-bar: the power the forces of V_p times this do on the grid velocities is then
    /// exactly the stress power of the averaged rates, sum_p V_p sigma_p : L-bar_p, so averaging
    /// creates no energy).
    template <class Core>
    [[nodiscard]] matrix averaged_stress(const Core& c, std::size_t i, const matrix& sig) const {
        const std::size_t k = cell_key(c, i);
        matrix out = sig;
        out.diagonal().array() += cell_stress_[k] / cell_stress_volume_[k] - sig.trace() / real(dim);
        return out;
    }

private:
    // The particle's body (or with a partition, its field at that node) and grid cell, as one
    // index: the first node of its stencil (a cell for a given shape) in its block of nodes. Two
    // bodies, or two fields of one body, are never averaged together.
    template <class Core>
    [[nodiscard]] static std::size_t cell_key(const Core& c, std::size_t i) {
        std::size_t flat = 0;
        for (int d = 0; d < dim; ++d) flat += std::size_t(c.stencils_[i].offset[d][0]);
        std::size_t block = c.particles_.template column<fields::body>()[i];
        if constexpr (Core::fields_per_body > 1) block = block * Core::fields_per_body + c.field_choice_.side(i, 0);
        return block * c.grid_.size() + flat;
    }

    // Per body (or field) and cell: sums of V tr(L) and V, and of V tr(sigma)/dim and V at the
    // forces' time.
    std::vector<real> cell_rate_, cell_volume_, cell_stress_, cell_stress_volume_;
};

}  // namespace gimlet::stages
