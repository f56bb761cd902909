// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The solver's transfers between particles and grid: P2G (mass, momentum, forces), the grid
/// momentum update, and G2P with the light nodes' forces and the damping transfer
/// (docs/physics.md section 1, steps 1-4; docs/equations.md).

#include "gimlet/solver/core.hpp"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <utility>
#include <vector>

namespace gimlet {

// ---- transfers ----------------------------------------------------------------------

// m_i = sum S_ip m_p, (mv)_i = sum S_ip m_p v_p and, with Forces,
// f_i = -sum V_p sigma_p G_ip + sum S_ip m_p b (docs/physics.md section 1, step 1) in one pass;
// in an axisymmetric space f_ir gains -sum V_p sigma_thetatheta T_ip (docs/equations.md,
// "Axisymmetric GIMP").
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
template <bool Forces>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::scatter() {
    const auto& m = particles_.template column<fields::mass>();
    const auto& v = particles_.template column<fields::velocity>();
    const vector b = options_.body_force.template cast<real>();
    const bool loaded = !b.isZero() || store_type::template has<fields::external_acceleration>;
    auto particle = [&](std::size_t i) {
        const real mp = m[i];
        const vector mv = mp * v[i];
        auto at = entries(i);
        matrix vs = matrix::Zero();
        vector mb = vector::Zero();
        if constexpr (Forces) {
            vs = force_stress(i);
            mb = mp * b;
            if constexpr (store_type::template has<fields::external_acceleration>)
                mb += mp * particles_.template column<fields::external_acceleration>()[i];
        }
        if constexpr (axisymmetric) {
            const real vh = Forces ? hoop_force_stress(i) : real(0);
            stencils_[i].for_each_hoop([&](std::size_t node, real w, const vector& g, real t) {
                const std::size_t e = at(node);
                grid_.mass[e] += w * mp;
                grid_.momentum[e] += w * mv;
                if constexpr (Forces) {
                    grid_.force[e] -= vs * g;
                    grid_.force[e][0] -= vh * t;
                    if (loaded) grid_.force[e] += w * mb;
                } else {
                    (void)g, (void)t, (void)vh;
                }
            });
            return;
        }
        stencils_[i].for_each([&](std::size_t node, real w, const vector& g) {
            const std::size_t e = at(node);
            grid_.mass[e] += w * mp;
            grid_.momentum[e] += w * mv;
            if constexpr (Forces) {
                grid_.force[e] -= vs * g;
                if (loaded) grid_.force[e] += w * mb;
            } else {
                (void)g;
            }
        });
    };
    if constexpr (Forces) for_each_particle_by_slab_into(particle, grid_.mass, grid_.momentum, grid_.force);
    else for_each_particle_by_slab_into(particle, grid_.mass, grid_.momentum);
}

// f_i = -sum V_p sigma_p G_ip + sum S_ip m_p b (docs/physics.md section 1, step 1), after USF's
// stress update.
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::map_forces() {
    const auto& m = particles_.template column<fields::mass>();
    const vector b = options_.body_force.template cast<real>();
    const bool loaded = !b.isZero() || store_type::template has<fields::external_acceleration>;
    auto particle = [&](std::size_t i) {
        const matrix vs = force_stress(i);
        vector mb = m[i] * b;
        if constexpr (store_type::template has<fields::external_acceleration>)
            mb += m[i] * particles_.template column<fields::external_acceleration>()[i];
        auto at = entries(i);
        if constexpr (axisymmetric) {
            const real vh = hoop_force_stress(i);
            stencils_[i].for_each_hoop([&](std::size_t node, real w, const vector& g, real t) {
                const std::size_t e = at(node);
                grid_.force[e] -= vs * g;
                grid_.force[e][0] -= vh * t;
                if (loaded) grid_.force[e] += w * mb;
            });
            return;
        }
        stencils_[i].for_each([&](std::size_t node, real w, const vector& g) {
            const std::size_t e = at(node);
            grid_.force[e] -= vs * g;
            if (loaded) grid_.force[e] += w * mb;
        });
    };
    for_each_particle_by_slab_into(particle, grid_.force);
}

// v_i = (mv)_i / m_i, a weighted mean of the particles' velocities, wherever m_i > 0
// (docs/physics.md section 1, step 2).
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::nodal_velocity(std::vector<vector>& out) {
    for_each_swept_entry([&](std::size_t i) {
        out[i] = grid_.mass[i] > 0 ? vector(grid_.momentum[i] / grid_.mass[i]) : vector::Zero();
    });
}

// The nodal arrays of the swept field slots are cleared every step (the others are empty
// already: swept_fields()); on a large grid that is memory-bound work a single thread would do
// while the others wait, so it is split between the threads.
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::clear_grid() {
    for_each_swept_entry([&](std::size_t e) { grid_.clear_entry(e); });
}

// `out` holds one value per grid entry; the slots not swept this step hold `value` already
// (the callers fill with zero, and nothing writes there while a slot is not swept).
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::fill_entries(std::vector<vector>& out, const vector& value) {
    assert(out.size() == grid_.entries());
    for_each_swept_entry([&](std::size_t e) { out[e] = value; });
}

// The entries of the field slots swept this step (swept_fields(): every slot, or each body's
// first ones), on many processes of the node rows this process's particles reach (window_: its
// slabs and the band above them; the rest of the grid is never written here): runs of up to
// `run` entries, handed to the threads in a fixed split. One loop for every case, so that each
// pass's body is compiled once.
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
template <class F>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::for_each_swept_entry(F&& f) {
    constexpr std::size_t run = 1024;
    const std::size_t nodes = grid_.size(), swept = swept_fields(), blocks = grid_.entries() / nodes;
    const std::pair<std::size_t, std::size_t> whole{0, nodes};
    const auto* ranges = window_.empty() ? &whole : window_.data();
    const std::size_t range_count = window_.empty() ? 1 : window_.size();
    runs_.clear();
    std::size_t entries = 0;
    for (std::size_t block = 0; block < blocks; ++block) {
        if (block % fields_per_body >= swept) continue;  // body * fields_per_body + field
        for (std::size_t r = 0; r < range_count; ++r)
            for (std::size_t e = block * nodes + ranges[r].first, end = block * nodes + ranges[r].second; e < end; e += run)
                runs_.push_back({e, std::min(end, e + run)}), entries += runs_.back().second - e;
    }
    const auto n = static_cast<std::ptrdiff_t>(runs_.size());
    detail::thread_shares shares(n, threads(), std::ptrdiff_t(entries) >= node_parallel_threshold);
    GIMLET_OMP(parallel num_threads(shares.team()))
    for (auto claimed = shares.start(); shares.claim(claimed);)
        for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k)
            for (std::size_t e = runs_[std::size_t(k)].first, last = runs_[std::size_t(k)].second; e < last; ++e) f(e);
}

// v_i^n = (mv)_i / m_i (with_old_velocity; USF has it already), the forces of the consistent
// mass if asked (stages/consistent_mass.hpp), (mv)_i += dt f_i,
// v_i^{n+1} = (mv)_i / m_i, then the walls (docs/physics.md section 1, step 2). A node under the
// mass cut-off keeps v_i^n: its force is never divided by its mass, it goes back to the
// particles that exerted it (grid_to_particles).
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::update_grid_momentum(real dt, bool with_old_velocity) {
    consistent_mass_.apply(*this);  // solver_options::consistent_mass_iterations; nothing at 0
    for_each_swept_entry([&](std::size_t i) {
        const real mi = grid_.mass[i];
        if (with_old_velocity) grid_.velocity_old[i] = mi > 0 ? vector(grid_.momentum[i] / mi) : vector::Zero();
        if (mi > mass_cutoff_) {
            grid_.momentum[i] += dt * grid_.force[i];
            grid_.velocity[i] = grid_.momentum[i] / mi;
        } else {
            grid_.velocity[i] = grid_.velocity_old[i];
        }
    });
    grid_.apply_walls(grid_.velocity);
    if constexpr (has_driven_particles) driven_.impose(*this, grid_.velocity);  // stages/driven_particles.hpp
}

// ---- light nodes -------------------------------------------------------------------
//
// The FLIP update gives particle p the acceleration f_i / m_i of each node with weight S_ip,
// which conserves momentum exactly: sum_p S_ip m_p f_i / m_i = f_i. A node under the mass
// cut-off is never divided by, so its force would be dropped, and momentum lost with it
// (6.7e-9 of a fragment's |m v| in the sparse cloud of tests/robustness/test_hard_cases.cpp,
// "near-empty nodes"; 1e-12 of a body's in a 700 m/s cavity collapse, where the GIMP gradient
// at a support's edge is not small where the weight is). Each particle takes back its own part
// of it instead, dv_p += dt f_ip / m_p with f_ip = S_ip m_p b - V_p sigma_p G_ip, as far as the
// walls leave it free: sum_p m_p dv_p = dt f_i, and f_ip / m_p = S_ip b - sigma_p G_ip / rho_p
// is bounded by the particle's own state (docs/equations.md, "Light nodes").

// Whether node entry e, with particle weight w and gradient g, is a light node of the
// particle's (a stencil node it neither weighs nor pushes is not).
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
bool solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::on_light_node(std::size_t e, real w, const vector& g) const {
    return !(grid_.mass[e] > mass_cutoff_) && (w != 0 || !g.isZero());
}

// dt f_ip / m_p summed over particle i's light nodes, as far as the walls leave it free.
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
auto solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::light_node_change(std::size_t i, real dt) const -> vector {
    const auto& m = particles_.template column<fields::mass>();
    const matrix vs = force_stress(i);
    vector mb = m[i] * options_.body_force.template cast<real>();
    if constexpr (store_type::template has<fields::external_acceleration>)
        mb += m[i] * particles_.template column<fields::external_acceleration>()[i];
    vector own = vector::Zero();
    auto at = entries(i);
    if constexpr (axisymmetric) {
        const real vh = hoop_force_stress(i);
        stencils_[i].for_each_hoop([&](std::size_t node, real w, const vector& g, real t) {
            const std::size_t e = at(node);
            if (grid_.mass[e] > mass_cutoff_) return;
            vector f = w * mb - vs * g;
            f[0] -= vh * t;
            own += wall_free_[e].cwiseProduct(f);
        });
        return dt / m[i] * own;
    }
    stencils_[i].for_each([&](std::size_t node, real w, const vector& g) {
        const std::size_t e = at(node);
        if (!(grid_.mass[e] > mass_cutoff_)) own += wall_free_[e].cwiseProduct(w * mb - vs * g);
    });
    return dt / m[i] * own;
}

// FLIP velocity update with the damping blend, and x_p += dt sum S_ip v_i^{n+1}
// (docs/physics.md section 1, step 3), with the light nodes' forces above. With remap (MUSL),
// each particle's new momentum is scattered back to the grid in the same pass (docs/physics.md
// section 1, step 4): the gather reads grid velocities only and the scatter writes grid
// momenta only.
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::grid_to_particles(real dt, bool remap) {
    // Particles far lighter than their neighbours first (stages/light_particles.hpp): they take their
    // velocities here, and the others take back the momentum they changed below.
    // The pass is compiled twice: a scene without light particles runs the plain one.
    if (lights_.count() == 0) grid_to_particles_pass<false>(dt, remap);
    else grid_to_particles_pass<true>(dt, remap);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
template <bool Lights>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::grid_to_particles_pass(real dt, bool remap) {
    auto& x = particles_.template column<fields::position>();
    auto& v = particles_.template column<fields::velocity>();
    auto& energy = particles_.template column<fields::specific_internal_energy>();
    const auto& m = particles_.template column<fields::mass>();
    const real alpha = damping_transfer::fraction(*this);  // stages/damping_transfer.hpp
    const bool damping = alpha > 0;
    if constexpr (Lights) lights_.move(*this, dt);
    // MUSL's re-map of particle i's new momentum.
    auto scatter_momentum = [&](std::size_t i) {
        const vector mv = m[i] * v[i];
        auto at = entries(i);
        stencils_[i].for_each([&](std::size_t node, real w, const vector&) { grid_.momentum[at(node)] += w * mv; });
    };
    auto update = [&](std::size_t i) {
        const auto& st = stencils_[i];
        if (Lights && lights_.moved(i)) {
            if (remap) scatter_momentum(i);
            return;
        }
        // A driven particle moves with its prescribed velocity along its driven axes
        // (stages/driven_particles.hpp); a fully driven one needs nothing else.
        [[maybe_unused]] unsigned driven = 0;
        [[maybe_unused]] vector x_before;
        if constexpr (has_driven_particles) {
            driven = particles_.template column<fields::driven>()[i];
            if (driven == (1u << dim) - 1) {
                v[i] = particles_.template column<fields::driven_velocity>()[i];
                x[i] += dt * v[i];
                if (remap) scatter_momentum(i);
                return;
            }
            x_before = x[i];
        }
        vector v_pic = vector::Zero(), dv = vector::Zero(), old = vector::Zero();  // old: S v^n, for the blend
        bool light = false;
        auto at = entries(i);  // one chooser per pass over the stencil
        st.for_each([&](std::size_t node, real w, const vector& g) {
            const std::size_t e = at(node);
            v_pic += w * grid_.velocity[e];
            dv += w * (grid_.velocity[e] - grid_.velocity_old[e]);
            if (damping) old += w * grid_.velocity_old[e];
            light = light || on_light_node(e, w, g);
        });
        vector change = vector::Zero();
        if (light) {
            // Rare: only particles on a light node pay for this pass. Into the PIC velocity
            // too, which then sums to the nodes' momenta exactly.
            change = light_node_change(i, dt);
            dv += change;
            v_pic += change;
        }
        if constexpr (axisymmetric) {
            // A ring's domain midpoint moves with the plain shape's interpolation (a linear
            // field's value at r_p; the r-weighted one would move it with its ring's centroid, and
            // a ring converging on the axis would reach it before its hoop stretch stopped it:
            // docs/equations.md, "Axisymmetric GIMP").
            vector u = change;
            auto at_position = entries(i);
            st.for_each_position([&](std::size_t node, real cr, real cz) {
                const vector& vi = grid_.velocity[at_position(node)];
                u[0] += cr * vi[0];
                u[1] += cz * vi[1];
            });
            x[i] += dt * u;
        } else {
            x[i] += dt * v_pic;
        }
        const vector v_flip = v[i] + dv;
        if (!damping) {
            v[i] = v_flip;
        } else {
            damping_transfer::blend(*this, i, alpha, old, v_pic, change, v_flip, v[i], energy[i]);
        }
        if (Lights && lights_.returns_momentum(i)) {
            // Its share of the momentum the light particles changed at its nodes:
            // dv_q = -sum_i S_iq P_i / m_i^N (docs/equations.md, "Light particles").
            vector back = vector::Zero();
            auto at_back = entries(i);
            st.for_each([&](std::size_t node, real w, const vector&) {
                const std::size_t e = at_back(node);
                const real heavy = lights_.heavy_mass(e);
                if (heavy > 0) back += w / heavy * lights_.momentum(e);
            });
            v[i] -= back;
        }
        if constexpr (has_driven_particles) {
            if (driven) {
                const vector& vd = particles_.template column<fields::driven_velocity>()[i];
                for (int d = 0; d < dim; ++d)
                    if ((driven >> d) & 1u) v[i][d] = vd[d], x[i][d] = x_before[d] + dt * vd[d];
            }
        }
        if (remap) scatter_momentum(i);
    };
    if (remap) {
        fill_entries(grid_.momentum, vector::Zero());
        for_each_particle_by_slab_into(update, grid_.momentum);
    } else {
        const auto n = static_cast<std::ptrdiff_t>(particles_.size());
        detail::thread_shares shares(n, threads(), n >= parallel_threshold);
        GIMLET_OMP(parallel num_threads(shares.team()))
        for (auto claimed = shares.start(); shares.claim(claimed);)
            for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) update(static_cast<std::size_t>(k));
    }
}

}  // namespace gimlet
