// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The solver's particle passes: the material update (docs/physics.md section 1, step 5), the
/// stress the forces take, the step's last pass that updates and checks every particle, and the
/// sort by cell.

#include "gimlet/solver/core.hpp"

#include <algorithm>
#include <cstddef>
#include <exception>
#include <vector>

namespace gimlet {

// USF: L_p = sum v_i (x) G_ip, F update, then the constitutive policies (docs/physics.md
// section 1, step 5 and section 4: sigma = s - (P + q) I), before the forces are mapped.
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::update_material_points(real dt) {
    material_pass(dt, grid_.velocity, true, [](std::size_t) { return true; });
}

// Every particle's material update from the grid velocities vg (if update_materials), two at a
// time where the material allows it (update_material_pair), then after(i) for each particle
// whose update did not throw; after returns false for a broken particle. Returns the
// lowest-numbered broken particle (n if none); an update's error is thrown for the
// lowest-numbered particle once every particle is done, before the broken ones are reported
// (the order two separate passes would report them in).
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
template <class After>
std::ptrdiff_t solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::material_pass(real dt, const std::vector<vector>& vg,
                                                                     bool update_materials, After&& after) {
    const auto n = static_cast<std::ptrdiff_t>(particles_.size());
    std::ptrdiff_t failed = n, first_bad = n;
    std::exception_ptr error;
    const std::ptrdiff_t groups = (n + material_group - 1) / material_group;
    detail::thread_shares shares(groups, threads(), n >= parallel_threshold);
    GIMLET_OMP(parallel reduction(min : first_bad) num_threads(shares.team()))
    for (auto claimed = shares.start(); shares.claim(claimed);)
        for (std::ptrdiff_t g = claimed.first, end = claimed.last; g < end; ++g) {
            const std::ptrdiff_t first = g * material_group, last = std::min(n, first + material_group);
            const bool paired = update_materials && last - first == 2 && update_material_pair(static_cast<std::size_t>(first), dt, vg);
            for (std::ptrdiff_t k = first; k < last; ++k) {
                const auto i = static_cast<std::size_t>(k);
                if (update_materials && !paired) {
                    try {
                        update_material_point(i, dt, vg);
                    } catch (...) {
                        GIMLET_OMP(critical(gimlet_material_error))
                        if (k < failed) failed = k, error = std::current_exception();
                        continue;
                    }
                }
                if (!after(i)) first_bad = std::min(first_bad, k);
            }
        }
    if (error) std::rethrow_exception(error);
    return first_bad;
}

// The velocity gradient L_p = sum_i v_i (x) G_ip of particle i from the grid velocities vg
// (a light particle's from its reliable nodes), with volumetric averaging the cell's mean
// volumetric rate.
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
auto solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::velocity_gradient(
    std::size_t i, const std::vector<vector>& vg, [[maybe_unused]] real* hoop_rate) const -> matrix {
    matrix L = matrix::Zero();
    if (lights_.is_light(i)) {
        L = lights_.velocity_gradient(*this, i, vg, hoop_rate);
    } else if constexpr (axisymmetric) {
        // L_rr = sum v_ir G_r, L_zz = sum v_iz G_z, L_thetatheta = sum v_ir T_ip
        // (docs/equations.md, "Axisymmetric GIMP").
        real hoop = 0;
        auto at = entries(i);
        stencils_[i].for_each_hoop([&](std::size_t node, real, const vector& g, real t) {
            const vector& v = vg[at(node)];
            L.noalias() += v * g.transpose();
            hoop += v[0] * t;
        });
        if (hoop_rate) *hoop_rate = hoop;
    } else {
        auto at = entries(i);
        stencils_[i].for_each([&](std::size_t node, real, const vector& g) { L.noalias() += vg[at(node)] * g.transpose(); });
    }
    if (options_.volumetric_average) volumetric_average_.averaged_rate(*this, i, L);
    return L;
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::update_material_point(
    std::size_t i, real dt, const std::vector<vector>& vg) {
    auto p = particles_[i];
    const M& mat = materials_[p.template get<fields::body>()];
    if constexpr (axisymmetric) {
        real hoop = 0;
        const matrix L = velocity_gradient(i, vg, &hoop);
        gimlet::update_material_point(mat, p, L, hoop, dt, grid_.cell(), steps_, double(time_));
    } else {
        const matrix L = velocity_gradient(i, vg);
        gimlet::update_material_point(mat, p, L, dt, grid_.cell(), steps_, double(time_));
    }
}

// Particles i and i + 1 updated at once, in the two lanes of one vector (lanes_capable
// materials; gimlet::update_material_points_2): the same bits as one at a time. False, with
// nothing written, for two bodies or where either particle would stop the run: the caller
// then updates them one at a time, which names the particle.
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
bool solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::update_material_pair(
    std::size_t i, real dt, const std::vector<vector>& vg) {
#if GIMLET_HAS_LANES
    if constexpr (material_group == 2) {
        const auto& body = particles_.template column<fields::body>();
        if (body[i] != body[i + 1]) return false;
        // Whatever a policy throws for the pair is thrown again, for its particle, by the
        // one-at-a-time update (an exception must not leave an OpenMP loop).
        try {
            const matrix La = velocity_gradient(i, vg), Lb = velocity_gradient(i + 1, vg);
            return gimlet::update_material_points_2(materials_[body[i]], particles_[i], particles_[i + 1], La, Lb, dt,
                                                    grid_.cell(), steps_, double(time_));
        } catch (...) {
            return false;
        }
    }
#endif
    return (void)i, (void)dt, (void)vg, false;
}

// V_p sigma_p as the nodal forces take it: with volumetric averaging, the particle's in-plane
// mean stress replaced by its cell's volume-weighted mean (stages::volumetric_average).
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
auto solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::force_stress(std::size_t i) const -> matrix {
    const matrix& sig = particles_.template column<fields::stress>()[i];
    const real v = current_volume(particles_[i]);
    if (!options_.volumetric_average) return v * sig;
    return v * volumetric_average_.averaged_stress(*this, i, sig);
}

// V_p sigma_thetatheta (axisymmetric space): the hoop stress's share of the radial force,
// f_ir -= V_p sigma_thetatheta T_ip (docs/equations.md, "Axisymmetric GIMP").
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
auto solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::hoop_force_stress(std::size_t i) const -> real {
    if constexpr (axisymmetric) return current_volume(particles_[i]) * particles_.template column<fields::stress_zz>()[i];
    else return (void)i, real(0);
}

// The step's last particle pass: the constitutive update from the grid velocities (MUSL,
// USL), then what check_particles does (wrap, stop on a broken particle). A material error
// is reported before a failed check, each for the lowest-numbered particle, as two separate
// passes would report them.
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::finish_step(real dt, bool update_materials) {
    auto& x = particles_.template column<fields::position>();
    const std::ptrdiff_t first_bad = material_pass(dt, grid_.velocity, update_materials, [&](std::size_t i) {
        grid_.wrap(x[i]);
        return healthy(i);
    });
    ++steps_;
    time_ += dt;
    if (first_bad < std::ptrdiff_t(particles_.size()))
        fail(static_cast<std::size_t>(first_bad), problem(static_cast<std::size_t>(first_bad)));
}

// ---- sorting ------------------------------------------------------------------------

// Stable counting sort of the particles on the first node of their stencil (a cell of the
// grid), applied to every field and to the stencils.
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::sort_by_cell() {
    const std::size_t n = particles_.size(), cells = grid_.size();
    std::vector<std::size_t> start(cells + 1, 0), order(n);
    auto key = [&](std::size_t i) {
        int flat = 0;
        for (int d = 0; d < dim; ++d) flat += stencils_[i].offset[d][0];
        return static_cast<std::size_t>(flat);
    };
    for (std::size_t i = 0; i < n; ++i) ++start[key(i) + 1];
    for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
    for (std::size_t i = 0; i < n; ++i) order[start[key(i)]++] = i;
    auto permute = [&](auto& column) {
        auto old = column;
        for (std::size_t k = 0; k < n; ++k) column[k] = old[order[k]];
    };
    particles_.for_each_column([&](auto, auto& column) { permute(column); });
    permute(stencils_);
    permute(slabs_.slab_of());
}

}  // namespace gimlet
