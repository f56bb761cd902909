// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The explicit GIMP solver: policies composed at compile time into one step.

#include "gimlet/contact/concepts.hpp"
#include "gimlet/contact/node.hpp"
#include "gimlet/contact/single_field.hpp"
#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/detail/stencil.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/grid.hpp"
#include "gimlet/material/material.hpp"
#include "gimlet/core/material_point.hpp"
#include "gimlet/material/update.hpp"
#include "gimlet/core/particle_store.hpp"
#include "gimlet/multi_field/exchange.hpp"
#include "gimlet/scene/scene.hpp"
#include "gimlet/shape/concepts.hpp"
#include "gimlet/solver/health.hpp"
#include "gimlet/solver/options.hpp"
#include "gimlet/solver/seeding.hpp"
#include "gimlet/solver/slabs.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace gimlet {

/// The explicit GIMP/MPM solver (docs/physics.md section 1).
///
/// \tparam S  the space (dimension 2 = plane strain, or 3; float or double).
/// \tparam Sh the shape-function policy (shape::Shape).
/// \tparam M  the material bundle every body uses (gimlet::material<...>).
/// \tparam C  the contact policy (contact::Contact).
/// \tparam ExtraFields fields the user wants stored besides the policies' (their own tags for
///         observers, or fields::external_acceleration for a per-particle body force).
///
/// The particle store holds exactly the union of the fields the policies declare; a policy
/// that is off (thermal::none, viscosity::none) adds no field and its steps are compiled out.
template <Space S, shape::Shape Sh, Material M, contact::Contact C = contact::single_field,
          FieldList ExtraFields = field_list<>>
class solver {
public:
    using space_type = S;
    using real = typename S::real;
    using vector = typename S::vector;
    using matrix = typename S::matrix;
    using tensor3 = typename S::tensor3;
    using shape_type = Sh;
    using material_type = M;
    using contact_type = C;
    using particle_fields = field_union_t<core_fields<S>, typename Sh::required_fields, typename M::required_fields, typename C::required_fields, ExtraFields>;
    using store_type = particle_store<S, particle_fields>;
    static constexpr int dim = S::dim;

    static constexpr bool multi_field = C::multi_field;

private:
    using particle_ref = gimlet::particle_ref<store_type>;

public:

    /// Build the particles of a scene. Throws invalid_parameter for bad options, bodies outside
    /// the grid, overlapping bodies or a body with no particles.
    /// \param contact the contact policy's parameters (e.g. friction).
    explicit solver(const scene::scene<S, M>& sc, const solver_options<S>& options = {}, const C& contact = C{})
        : options_(options), grid_(sc.grid(), Sh::stencil), contact_(contact) {
        options_.validate();
        require(!sc.bodies().empty(), "number of bodies", 0.0, ">= 1");
        // USF strains with the start-of-step velocities, and a one-sided wall decided there and
        // again after the forces would work on other velocities than the strain saw: the bar of
        // tests/core/test_wall.cpp gained 8 % energy. Refused until the wall decides on USF's
        // trial velocities, as contact does.
        for (int d = 0; d < dim; ++d)
            if (sc.grid().bc[d] == boundary::wall && options_.scheme == update_scheme::usf)
                throw invalid_parameter("update scheme with a one-sided wall (boundary::wall) along " +
                                            std::string(detail::axis_name(d)),
                                        "usf", "musl or usl (USF with a one-sided wall creates energy)");
        for (const auto& b : sc.bodies()) materials_.push_back(b.material);
        detail::seed_particles(sc, grid_, particles_);
        real heaviest = 0;
        for (real m : particles_.template column<fields::mass>()) heaviest = std::max(heaviest, m);
        mass_cutoff_ = real(options_.mass_cutoff) * heaviest;
        if constexpr (multi_field) {
            // One velocity field per body (Bardenhagen et al. 2000); a single-field policy keeps one.
            grid_.set_field_count(materials_.size());
            exchange_.allocate(grid_.entries());
        }
        // Which components of a node's force the walls leave free (1) or take (0): the projection
        // apply_walls makes on velocities, for the forces of light nodes (grid_to_particles).
        wall_free_.assign(grid_.entries(), vector::Ones());
        grid_.apply_walls(wall_free_, wall_pass::none);  // a one-sided wall holds no force component for good
        slabs_.set_up(grid_.nodes(dim - 1), grid_.periodic(dim - 1));
    }

    /// Advance one step with the stable time step (CFL, capped by max_time_step). Returns dt.
    real step() {
        check_pending();  // a bad value set between steps is blamed on its particle, not on dt
        return step(stable_time_step());
    }

    /// Advance one step of the given size (s). Throws numerical_error if the run breaks down.
    real step(real dt) {
        require(std::isfinite(double(dt)) && dt > 0, "time step dt (s)", double(dt), "finite and > 0");
        advance(dt);
        return dt;
    }

    /// Advance to time `t_end` (s), calling each observer when it is due (see diagnostics/):
    /// read-only observers (every_time, every_steps) and writable hooks (between_steps).
    template <class... Observers>
    void run_until(real t_end, Observers&... observers) {
        require(std::isfinite(double(t_end)) && t_end >= time_, "end time (s)", double(t_end),
                "finite and >= the current time " + detail::to_text(double(time_)));
        check_pending();
        (observers.maybe_call(*this), ...);
        while (time_ < t_end) {
            check_pending();  // what a hook (diagnostics::between_steps) changed, before dt reads it
            const real dt = std::min(stable_time_step(), t_end - time_);
            advance(dt);
            if (t_end - time_ < real(1e-12) * t_end) time_ = t_end;  // no sliver step at the end
            (observers.maybe_call(*this), ...);
        }
    }

    /// dt = C h / max_p (c_p + |v_p|), c_p = sqrt((K + 4G/3) / rho) from the current state
    /// (docs/physics.md section 1, step 6), with c_p raised to the viscosity's signal speed where an
    /// artificial viscosity acts (viscosity::Viscosity).
    [[nodiscard]] real stable_time_step() const {
        const auto n = static_cast<std::ptrdiff_t>(particles_.size());
        real fastest = 0;
        // The guards met on the way (health_events), counted once the step is taken.
        std::uint64_t n0 = 0, n1 = 0, n2 = 0;
        std::ptrdiff_t f0 = n, f1 = n, f2 = n;
        GIMLET_OMP(parallel for schedule(dynamic, particle_chunk) reduction(max : fastest) reduction(+ : n0, n1, n2) reduction(min : f0, f1, f2) num_threads(threads()) if (n >= parallel_threshold))
        for (std::ptrdiff_t i = 0; i < n; ++i) {
            const auto p = particles_[static_cast<std::size_t>(i)];
            unsigned guards = 0;
            real c = longitudinal_wave_speed(p, materials_[p.template get<fields::body>()], guards);
            if (guards != 0) {
                if (guards & eos::guard::compression_capped) ++n0, f0 = std::min(f0, i);
                if (guards & eos::guard::negative_modulus) ++n1, f1 = std::min(f1, i);
                if (guards & eos::guard::no_wave_speed) ++n2, f2 = std::min(f2, i);
            }
            if constexpr (M::viscosity_type::enabled)
                c = materials_[p.template get<fields::body>()].viscosity.signal_speed(c, grid_.cell(), p);
            fastest = std::max(fastest, c + p.template get<fields::velocity>().norm());
        }
        pending_health_ = {steps_, true, {n0, n1, n2}, {f0, f1, f2}};
        real dt = real(options_.max_time_step);
        if (fastest > 0) dt = std::min(dt, real(options_.cfl) * grid_.cell() / fastest);
        return dt;
    }

    /// Longitudinal wave speed of particle p: sqrt((K + 4G/3) / rho).
    template <class P>
    [[nodiscard]] real wave_speed(const P& p) const {
        return longitudinal_wave_speed(p, materials_[p.template get<fields::body>()]);
    }

    /// Mutable access to the particles; the next step re-checks them before using them.
    [[nodiscard]] store_type& particles() noexcept {
        state_touched_ = true;
        pending_health_.valid = false;  // a time step computed before the change no longer applies
        return particles_;
    }
    [[nodiscard]] const store_type& particles() const noexcept { return particles_; }
    [[nodiscard]] const grid<S>& background_grid() const noexcept { return grid_; }
    [[nodiscard]] const std::vector<M>& materials() const noexcept { return materials_; }
    [[nodiscard]] const solver_options<S>& options() const noexcept { return options_; }
    /// The contact policy, with whatever it counted (contact::Counting).
    [[nodiscard]] const C& contact() const noexcept { return contact_; }
    [[nodiscard]] real time() const noexcept { return time_; }

    /// Set the clock of a run resumed from saved particles (io/checkpoint.hpp): the simulated
    /// time (s) and the number of steps already taken. The next step re-checks the particles.
    void resume_at(real t, std::uint64_t steps_taken) {
        require(std::isfinite(double(t)) && t >= 0, "resume time (s)", double(t), "finite and >= 0");
        time_ = t;
        steps_ = steps_taken;
        state_touched_ = true;
        pending_health_.valid = false;
    }
    [[nodiscard]] std::uint64_t steps() const noexcept { return steps_; }
    /// Wall-clock time per phase of the steps so far (see docs/performance.md).
    [[nodiscard]] const step_timings& timings() const noexcept { return timings_; }
    /// The silent guards that acted so far (health_events). A resumed run counts from its resume.
    [[nodiscard]] const health_events& health() const noexcept { return health_; }

private:
    using stencil_type = detail::stencil<S, Sh::stencil>;
    // Loops shorter than this run on one thread: below it, starting a team costs more than the
    // loop (and a team on a busy machine can stall the whole step).
    static constexpr std::ptrdiff_t parallel_threshold = 4096;
    // Particle loops hand out chunks of this many particles on demand rather than one fixed
    // share per thread: on a machine where another process holds a core, the thread that runs
    // takes over the chunks of the one that waits, instead of idling at the end of the loop.
    // Every particle's result is independent of which thread runs it, so this costs no
    // determinism.
    static constexpr int particle_chunk = 512;
    // The same for loops over grid nodes, whose bodies cost a few nanoseconds each, some 30
    // times less than a particle's: a team pays for itself only on large grids.
    static constexpr std::ptrdiff_t node_parallel_threshold = 32 * parallel_threshold;

    // Where particle i's velocity field starts in the nodal arrays: its body's field with
    // multi-field contact, the only field otherwise (a compile-time zero).
    [[nodiscard]] std::size_t field_base(std::size_t i) const noexcept {
        if constexpr (multi_field) return std::size_t(particles_.template column<fields::body>()[i]) * grid_.size();
        else return (void)i, std::size_t(0);
    }

    [[nodiscard]] int threads() const noexcept {
        return options_.threads > 0 ? options_.threads : detail::default_threads();
    }

    // ---- the step -----------------------------------------------------------------------
    //
    // The phases of docs/physics.md section 1 are fused where their arithmetic allows it, so a step
    // makes few passes over the particles and the nodes: the weights, one scatter (mass,
    // momentum and forces; USF without contact maps its forces after the stress update, USF
    // with contact both), one node pass (v^n, momentum update, v^{n+1}), one
    // gather (with MUSL's re-map scatter), one node pass for MUSL, and one particle pass that
    // updates the material and checks the particle. Each quantity is computed
    // with the same operations as in the unfused order; only the order in which a node sums its
    // particles' contributions is the scatter's (see for_each_particle_by_slab).

    // Wall-clock time of the step's phases: lap(into) adds the time since the last lap.
    struct phase_clock {
        using clock = std::chrono::steady_clock;
        clock::time_point mark = clock::now();
        void operator()(double& into) {
            const auto now = clock::now();
            into += std::chrono::duration<double>(now - mark).count();
            mark = now;
        }
    };

    void advance(real dt) {
        phase_clock lap;
        begin_step(dt, lap);
        switch (options_.scheme) {
            case update_scheme::musl: musl_step(dt, lap); break;
            case update_scheme::usl: usl_step(dt, lap); break;
            case update_scheme::usf: usf_step(dt, lap); break;
        }
    }

    // What every scheme does first: the checks of what changed between steps, the weights at
    // x^n, the slabs of the scatter, an empty grid.
    void begin_step(real dt, phase_clock& lap) {
        check_pending();
        count_health();
        lap(timings_.material_update);  // where the checks are done in every other step
        // The weights are recomputed from the positions every step, even though the previous
        // step's last pass could have computed them: a caller may change positions through a
        // reference to the store kept from an earlier particles() call, which no flag sees.
        compute_stencils();
        lap(timings_.particle_to_grid);
        if (options_.sort_interval > 0 && steps_ % std::uint64_t(options_.sort_interval) == 0) sort_by_cell();
        lap(timings_.sort);
        dt_ = dt;
        slabs_.bucket();
        if (options_.volumetric_average) average_mean_stress();
        grid_.clear();
    }

    // MUSL (Sulsky et al. 1995): P2G, grid update, contact, G2P, the particles' new momenta
    // re-mapped to the grid, contact again (keeping the grid update's pairs), and the stress
    // from the re-mapped velocities.
    void musl_step(real dt, phase_clock& lap) {
        scatter<true>();
        if constexpr (multi_field) find_shared_nodes();
        lap(timings_.particle_to_grid);
        update_grid_momentum(dt, true);
        lap(timings_.grid_update);
        if constexpr (multi_field) resolve_contact(multi_field::pass::decide);
        lap(timings_.contact);
        grid_to_particles(dt, true);  // with the re-map's scatter (docs/physics.md section 1, step 4)
        nodal_velocity(grid_.velocity);
        grid_.apply_walls(grid_.velocity, wall_pass::keep);  // the grid update's decisions hold
        lap(timings_.grid_to_particle);
        if constexpr (multi_field) resolve_contact(multi_field::pass::remap);
        lap(timings_.contact);
        end_step(dt, true, lap);
    }

    // USL: P2G, grid update, contact, G2P, and the stress from the updated grid velocities.
    void usl_step(real dt, phase_clock& lap) {
        scatter<true>();
        if constexpr (multi_field) find_shared_nodes();
        lap(timings_.particle_to_grid);
        update_grid_momentum(dt, true);
        lap(timings_.grid_update);
        if constexpr (multi_field) resolve_contact(multi_field::pass::decide);
        lap(timings_.contact);
        grid_to_particles(dt, false);
        lap(timings_.grid_to_particle);
        end_step(dt, true, lap);
    }

    // USF: P2G of mass and momentum, the stress from the start-of-step velocities, then its
    // forces, grid update, contact and G2P.
    void usf_step(real dt, phase_clock& lap) {
        // With contact it also maps the forces of the current stress: they decide where contact
        // acts in this step (multi_field::pass::trial).
        if constexpr (multi_field) scatter<true>();
        else scatter<false>();
        if constexpr (multi_field) find_shared_nodes();
        lap(timings_.particle_to_grid);
        nodal_velocity(grid_.velocity_old);
        grid_.velocity = grid_.velocity_old;
        grid_.apply_walls(grid_.velocity);
        lap(timings_.grid_update);
        // The stress sees the same contact as the momentum update, or it would strain the
        // bodies through each other: this pass decides where contact acts in this step.
        if constexpr (multi_field) {
            resolve_contact(multi_field::pass::trial);
            std::fill(grid_.force.begin(), grid_.force.end(), vector::Zero());
        }
        lap(timings_.contact);
        if (options_.volumetric_average) average_volumetric_rates(grid_.velocity);
        update_material_points(dt, grid_.velocity);
        lap(timings_.material_update);
        if (options_.volumetric_average) average_mean_stress();
        map_forces();
        lap(timings_.particle_to_grid);
        update_grid_momentum(dt, false);
        lap(timings_.grid_update);
        // USF keeps the decision its stress was computed with: releasing a node there, or
        // engaging one the stress saw free, makes the forces work on other velocities than the
        // ones that strained the material (an energy source: Bardenhagen contact from a gap
        // rebounded with 1.8x the energy it came in with).
        if constexpr (multi_field) resolve_contact(multi_field::pass::keep);
        lap(timings_.contact);
        grid_to_particles(dt, false);
        lap(timings_.grid_to_particle);
        end_step(dt, false, lap);
    }

    // What every scheme does last: the contact policy's particle hook, and the particle pass
    // that updates the material (MUSL, USL) and checks every particle.
    void end_step(real dt, bool update_materials, phase_clock& lap) {
        if constexpr (multi_field) contact_hook();
        if (update_materials && options_.volumetric_average) average_volumetric_rates(grid_.velocity);
        finish_step(dt, update_materials);
        lap(timings_.material_update);
    }

    // Weights at x^n of every particle.
    void compute_stencils() {
        const auto n = static_cast<std::ptrdiff_t>(particles_.size());
        stencils_.resize(particles_.size());
        slabs_.resize(particles_.size());
        GIMLET_OMP(parallel for schedule(dynamic, particle_chunk) num_threads(threads()) if (n >= parallel_threshold))
        for (std::ptrdiff_t i = 0; i < n; ++i) compute_stencil(static_cast<std::size_t>(i));
    }

    // The stencil of particle i, computed once and shared by every transfer of the step, and
    // the slab its scatter belongs to.
    void compute_stencil(std::size_t i) {
        const auto p = particles_[i];
        auto& st = stencils_[i];
        st.template compute_with<Sh>(grid_, p.template get<fields::position>(), Sh::half_width(p, grid_.cell()));
        slabs_.assign(i, st.last_row);
    }

    // f(i) for every particle, slab by slab and colour by colour (detail::slab_schedule): every
    // node sums its particles' contributions in an order fixed by the grid and the particle
    // order, whatever the thread count. f must not throw.
    template <class F>
    void for_each_particle_by_slab(F&& f) {
        slabs_.for_each(std::ptrdiff_t(particles_.size()) >= parallel_threshold, threads(), std::forward<F>(f));
    }

    // ---- transfers ----------------------------------------------------------------------

    // m_i = sum S_ip m_p, (mv)_i = sum S_ip m_p v_p and, with Forces,
    // f_i = -sum V_p sigma_p G_ip + sum S_ip m_p b (docs/physics.md section 1, step 1) in one pass.
    template <bool Forces>
    void scatter() {
        const auto& m = particles_.template column<fields::mass>();
        const auto& v = particles_.template column<fields::velocity>();
        [[maybe_unused]] auto& mass_gradient = exchange_.mass_gradient();
        if constexpr (multi_field) std::fill(mass_gradient.begin(), mass_gradient.end(), vector::Zero());
        const vector b = options_.body_force.template cast<real>();
        const bool loaded = !b.isZero() || store_type::template has<fields::external_acceleration>;
        for_each_particle_by_slab([&](std::size_t i) {
            const real mp = m[i];
            const vector mv = mp * v[i];
            const std::size_t base = field_base(i);
            matrix vs = matrix::Zero();
            vector mb = vector::Zero();
            if constexpr (Forces) {
                vs = force_stress(i);
                mb = mp * b;
                if constexpr (store_type::template has<fields::external_acceleration>)
                    mb += mp * particles_.template column<fields::external_acceleration>()[i];
            }
            stencils_[i].for_each([&](std::size_t node, real w, const vector& g) {
                const std::size_t e = base + node;
                grid_.mass[e] += w * mp;
                grid_.momentum[e] += w * mv;
                // G is the gradient with respect to the particle position, so sum m_p G_ip points
                // out of the body (docs/physics.md section 3; Bardenhagen et al. 2000, eq. 16).
                if constexpr (multi_field) mass_gradient[e] += mp * g;
                if constexpr (Forces) {
                    grid_.force[e] -= vs * g;
                    if (loaded) grid_.force[e] += w * mb;
                } else {
                    (void)g;
                }
            });
        });
    }

    // f_i = -sum V_p sigma_p G_ip + sum S_ip m_p b (docs/physics.md section 1, step 1), after USF's
    // stress update.
    void map_forces() {
        const auto& m = particles_.template column<fields::mass>();
        const vector b = options_.body_force.template cast<real>();
        const bool loaded = !b.isZero() || store_type::template has<fields::external_acceleration>;
        for_each_particle_by_slab([&](std::size_t i) {
            const matrix vs = force_stress(i);
            vector mb = m[i] * b;
            if constexpr (store_type::template has<fields::external_acceleration>)
                mb += m[i] * particles_.template column<fields::external_acceleration>()[i];
            const std::size_t base = field_base(i);
            stencils_[i].for_each([&](std::size_t node, real w, const vector& g) {
                grid_.force[base + node] -= vs * g;
                if (loaded) grid_.force[base + node] += w * mb;
            });
        });
    }

    // v_i = (mv)_i / m_i, a weighted mean of the particles' velocities, wherever m_i > 0
    // (docs/physics.md section 1, step 2).
    void nodal_velocity(std::vector<vector>& out) {
        const auto n = static_cast<std::ptrdiff_t>(grid_.entries());
        GIMLET_OMP(parallel for schedule(static) num_threads(threads()) if (n >= node_parallel_threshold))
        for (std::ptrdiff_t k = 0; k < n; ++k) {
            const auto i = static_cast<std::size_t>(k);
            out[i] = grid_.mass[i] > 0 ? vector(grid_.momentum[i] / grid_.mass[i]) : vector::Zero();
        }
    }

    // v_i^n = (mv)_i / m_i (with_old_velocity; USF has it already), (mv)_i += dt f_i,
    // v_i^{n+1} = (mv)_i / m_i, then the walls (docs/physics.md section 1, step 2). A node under the
    // mass cut-off keeps v_i^n: its force is never divided by its mass, it goes back to the
    // particles that exerted it (grid_to_particles).
    void update_grid_momentum(real dt, bool with_old_velocity) {
        const auto n = static_cast<std::ptrdiff_t>(grid_.entries());
        GIMLET_OMP(parallel for schedule(static) num_threads(threads()) if (n >= node_parallel_threshold))
        for (std::ptrdiff_t k = 0; k < n; ++k) {
            const auto i = static_cast<std::size_t>(k);
            const real mi = grid_.mass[i];
            if (with_old_velocity) grid_.velocity_old[i] = mi > 0 ? vector(grid_.momentum[i] / mi) : vector::Zero();
            if (mi > mass_cutoff_) {
                grid_.momentum[i] += dt * grid_.force[i];
                grid_.velocity[i] = grid_.momentum[i] / mi;
            } else {
                grid_.velocity[i] = grid_.velocity_old[i];
            }
        }
        grid_.apply_walls(grid_.velocity);
    }

    // ---- light nodes -------------------------------------------------------------------
    //
    // The FLIP update gives particle p the acceleration f_i / m_i of each node with weight S_ip,
    // which conserves momentum exactly: sum_p S_ip m_p f_i / m_i = f_i. A node under the mass
    // cut-off is never divided by, so its force would be dropped, and momentum lost with it
    // (6.7e-9 of a fragment's |m v| in the sparse-cloud hard case; 1e-12 of a body's in a
    // 700 m/s cavity collapse, where the GIMP gradient at a support's edge is not small where
    // the weight is). Each particle takes back its own part of it instead,
    // dv_p += dt f_ip / m_p with f_ip = S_ip m_p b - V_p sigma_p G_ip, as far as the walls leave
    // it free: sum_p m_p dv_p = dt f_i, and f_ip / m_p = S_ip b - sigma_p G_ip / rho_p is bounded
    // by the particle's own state (docs/equations.md, "Light nodes").

    // ---- the damping transfer (solver_options::pic_fraction) -----------------------------
    //
    // With S the grid-to-particle interpolation, the PIC velocity S v^{n+1} differs from the FLIP
    // velocity v_p + S (v^{n+1} - v^n) by d_p = v_p - S v^n, the part of the particle velocities
    // the grid cannot carry. The blend v_p' = v_FLIP - alpha d_p removes the kinetic energy
    // sum_p m_p (alpha d_p . v_FLIP - alpha^2 |d_p|^2 / 2), and each particle's internal energy
    // takes its share (docs/equations.md, "Damping transfer"). Writing v_FLIP = v_PIC + d_p, the
    // cross term sum_p m_p d_p . S v^{n+1} is not Galilean-invariant particle by particle (a body
    // at 700 m/s would heat and cool its particles by 700 |d_p|). Summed, it is
    // sum_i v_i^{n+1} . (m_i v_i^n - sum_j K_ij v_j^n), K_ij = sum_p S_ip m_p S_jp, and as K is
    // symmetric with rows summing to m_i (the weights sum to one), that is
    // sum_p m_p cov_p(v^{n+1}, v^n): the covariance of the new and old nodal velocities over the
    // particle's stencil, which is invariant, and close to their variance (so positive) at a
    // stable step. Each particle takes that share.

    // FLIP velocity update with the damping blend, and x_p += dt sum S_ip v_i^{n+1}
    // (docs/physics.md section 1, step 3), with the light nodes' forces above. With remap (MUSL),
    // each particle's new momentum is scattered back to the grid in the same pass (docs/physics.md
    // section 1, step 4): the gather reads grid velocities only and the scatter writes grid
    // momenta only.
    void grid_to_particles(real dt, bool remap) {
        auto& x = particles_.template column<fields::position>();
        auto& v = particles_.template column<fields::velocity>();
        auto& energy = particles_.template column<fields::specific_internal_energy>();
        const auto& m = particles_.template column<fields::mass>();
        const real alpha = real(options_.pic_fraction);
        const bool damping = alpha > 0;
        const vector b = options_.body_force.template cast<real>();
        auto update = [&](std::size_t i) {
            vector v_pic = vector::Zero(), dv = vector::Zero();
            const std::size_t base = field_base(i);
            const auto& st = stencils_[i];
            bool light = false;
            st.for_each([&](std::size_t node, real w, const vector& g) {
                const std::size_t e = base + node;
                v_pic += w * grid_.velocity[e];
                dv += w * (grid_.velocity[e] - grid_.velocity_old[e]);
                // (A stencil node the particle neither weighs nor pushes is no light node of its.)
                light = light || (!(grid_.mass[e] > mass_cutoff_) && (w != 0 || !g.isZero()));
            });
            vector change = vector::Zero();
            if (light) {
                // Rare: only particles on a light node pay for this pass.
                const matrix vs = force_stress(i);
                vector mb = m[i] * b;
                if constexpr (store_type::template has<fields::external_acceleration>)
                    mb += m[i] * particles_.template column<fields::external_acceleration>()[i];
                vector own = vector::Zero();
                st.for_each([&](std::size_t node, real w, const vector& g) {
                    const std::size_t e = base + node;
                    if (!(grid_.mass[e] > mass_cutoff_)) own += wall_free_[e].cwiseProduct(w * mb - vs * g);
                });
                // Into the PIC velocity too, which then sums to the nodes' momenta exactly.
                change = dt / m[i] * own;
                dv += change;
                v_pic += change;
            }
            x[i] += dt * v_pic;
            const vector v_flip = v[i] + dv;
            if (!damping) {
                v[i] = v_flip;
            } else {
                vector old = vector::Zero();
                st.for_each([&](std::size_t node, real w, const vector&) { old += w * grid_.velocity_old[base + node]; });
                const vector fresh = v_pic - change;  // S v^{n+1}
                real cov = 0;  // centred, so no cancellation of |v|^2
                st.for_each([&](std::size_t node, real w, const vector&) {
                    cov += w * (grid_.velocity[base + node] - fresh).dot(grid_.velocity_old[base + node] - old);
                });
                const vector d = v_flip - v_pic;
                // The particle's share of sum_p m_p d_p . v_PIC (the light nodes' part is its own).
                const real cross = cov + d.dot(change);
                v[i] = v_flip - alpha * d;
                energy[i] += alpha * (cross + d.squaredNorm()) - real(0.5) * alpha * alpha * d.squaredNorm();
            }
            if (remap) {
                const vector mv = m[i] * v[i];
                st.for_each([&](std::size_t node, real w, const vector&) { grid_.momentum[base + node] += w * mv; });
            }
        };
        if (remap) {
            std::fill(grid_.momentum.begin(), grid_.momentum.end(), vector::Zero());
            for_each_particle_by_slab(update);
        } else {
            const auto n = static_cast<std::ptrdiff_t>(particles_.size());
            GIMLET_OMP(parallel for schedule(dynamic, particle_chunk) num_threads(threads()) if (n >= parallel_threshold))
            for (std::ptrdiff_t k = 0; k < n; ++k) update(static_cast<std::size_t>(k));
        }
    }

    // USF: L_p = sum v_i (x) G_ip, F update, then the constitutive policies (docs/physics.md
    // section 1, step 5 and section 4: sigma = s - (P + q) I), before the forces are mapped.
    void update_material_points(real dt, const std::vector<vector>& vg) {
        const auto n = static_cast<std::ptrdiff_t>(particles_.size());
        std::ptrdiff_t failed = n;
        std::exception_ptr error;
        GIMLET_OMP(parallel for schedule(dynamic, particle_chunk) num_threads(threads()) if (n >= parallel_threshold))
        for (std::ptrdiff_t k = 0; k < n; ++k) {
            try {
                update_material_point(static_cast<std::size_t>(k), dt, vg);
            } catch (...) {
                GIMLET_OMP(critical(gimlet_material_error))
                if (k < failed) failed = k, error = std::current_exception();
            }
        }
        if (error) std::rethrow_exception(error);
    }

    void update_material_point(std::size_t i, real dt, const std::vector<vector>& vg) {
        auto p = particles_[i];
        matrix L = matrix::Zero();
        const std::size_t base = field_base(i);
        stencils_[i].for_each([&](std::size_t node, real, const vector& g) { L.noalias() += vg[base + node] * g.transpose(); });
        if (options_.volumetric_average) {
            const std::size_t c = cell_key(i);
            L.diagonal().array() += (cell_rate_[c] / cell_volume_[c] - L.trace()) / real(dim);
        }
        gimlet::update_material_point(materials_[p.template get<fields::body>()], p, L, dt, grid_.cell(), steps_, double(time_));
    }

    // ---- volumetric averaging (solver_options::volumetric_average) ------------------------

    // The particle's body and grid cell, as one index: the first node of its stencil (a cell for
    // a given shape) in its body's block of nodes.
    [[nodiscard]] std::size_t cell_key(std::size_t i) const {
        std::size_t flat = 0;
        for (int d = 0; d < dim; ++d) flat += std::size_t(stencils_[i].offset[d][0]);
        return std::size_t(particles_.template column<fields::body>()[i]) * grid_.size() + flat;
    }

    // V_p sigma_p as the nodal forces take it: with volumetric averaging, the particle's in-plane
    // mean stress tr(sigma_p)/dim replaced by its cell's volume-weighted mean (B-bar: the power
    // these forces do on the grid velocities is then exactly the stress power of the averaged
    // rates, sum_p V_p sigma_p : L-bar_p, so averaging creates no energy).
    [[nodiscard]] matrix force_stress(std::size_t i) const {
        const matrix& sig = particles_.template column<fields::stress>()[i];
        const real v = current_volume(particles_[i]);
        if (!options_.volumetric_average) return v * sig;
        const std::size_t c = cell_key(i);
        matrix out = sig;
        out.diagonal().array() += cell_stress_[c] / cell_stress_volume_[c] - sig.trace() / real(dim);
        return v * out;
    }

    // Per body and cell, the sums of V_p tr(sigma_p)/dim and of V_p (force_stress).
    void average_mean_stress() {
        const std::size_t n = materials_.size() * grid_.size();
        cell_stress_.assign(n, real(0));
        cell_stress_volume_.assign(n, real(0));
        const auto& sig = particles_.template column<fields::stress>();
        for_each_particle_by_slab([&](std::size_t i) {
            const real v = current_volume(particles_[i]);
            const std::size_t c = cell_key(i);
            cell_stress_[c] += v * sig[i].trace() / real(dim);
            cell_stress_volume_[c] += v;
        });
    }

    // Per body and cell, the sums of V_p tr L_p and of V_p over its particles, with L_p from the
    // velocities vg. A particle's cell lies in its own slab, so the slab colouring keeps the sums
    // free of races and in a fixed order.
    void average_volumetric_rates(const std::vector<vector>& vg) {
        const std::size_t n = materials_.size() * grid_.size();
        cell_rate_.assign(n, real(0));
        cell_volume_.assign(n, real(0));
        for_each_particle_by_slab([&](std::size_t i) {
            real rate = 0;
            const std::size_t base = field_base(i);
            stencils_[i].for_each([&](std::size_t node, real, const vector& g) { rate += vg[base + node].dot(g); });
            const real v = current_volume(particles_[i]);
            const std::size_t c = cell_key(i);
            cell_rate_[c] += v * rate;
            cell_volume_[c] += v;
        });
    }

    // The step's last particle pass: the constitutive update from the grid velocities (MUSL,
    // USL), then what check_particles does (wrap, stop on a broken particle). A material error
    // is reported before a failed check, each for the lowest-numbered particle, as when the
    // passes were separate.
    void finish_step(real dt, bool update_materials) {
        const auto n = static_cast<std::ptrdiff_t>(particles_.size());
        auto& x = particles_.template column<fields::position>();
        std::ptrdiff_t failed = n, first_bad = n;
        std::exception_ptr error;
        GIMLET_OMP(parallel for schedule(dynamic, particle_chunk) reduction(min : first_bad) num_threads(threads()) if (n >= parallel_threshold))
        for (std::ptrdiff_t k = 0; k < n; ++k) {
            const auto i = static_cast<std::size_t>(k);
            if (update_materials) {
                try {
                    update_material_point(i, dt, grid_.velocity);
                } catch (...) {
                    GIMLET_OMP(critical(gimlet_material_error))
                    if (k < failed) failed = k, error = std::current_exception();
                    continue;
                }
            }
            grid_.wrap(x[i]);
            if (!healthy(i)) first_bad = std::min(first_bad, k);
        }
        if (error) std::rethrow_exception(error);
        ++steps_;
        time_ += dt;
        if (first_bad < n) fail(static_cast<std::size_t>(first_bad), problem(static_cast<std::size_t>(first_bad)));
    }

    // ---- sorting ------------------------------------------------------------------------

    // Stable counting sort of the particles on the first node of their stencil (a cell of the
    // grid), applied to every field and to the stencils.
    void sort_by_cell() {
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

    // ---- multi-field contact (multi_field::exchange) --------------------------------------

    void find_shared_nodes() {
        const std::size_t nodes = grid_.size();
        exchange_.find_shared_nodes(
            grid_, mass_cutoff_, steps_, double(time_), stencils_,
            [&](std::size_t i) { return static_cast<std::uint32_t>(field_base(i) / nodes); },
            [&](auto&& f) { for_each_particle_by_slab(f); });
    }

    void resolve_contact(multi_field::pass pass) { exchange_.resolve(pass, grid_, contact_, dt_, mass_cutoff_); }

    // A contact policy's per-particle hook (contact::ParticleHook), after the step's last
    // contact pass.
    void contact_hook() {
        if constexpr (multi_field && contact::ParticleHook<C, particle_ref, S>) {
            const auto n = static_cast<std::ptrdiff_t>(particles_.size());
            const std::size_t nodes = grid_.size();
            GIMLET_OMP(parallel for schedule(dynamic, particle_chunk) num_threads(threads()) if (n >= parallel_threshold))
            for (std::ptrdiff_t k = 0; k < n; ++k) {
                const auto i = static_cast<std::size_t>(k);
                const auto body = static_cast<std::uint32_t>(field_base(i) / nodes);
                const contact::particle_contact<S> info = exchange_.contact_of(body, stencils_[i]);
                contact_.after_contact(particles_[i], info);
            }
        }
    }

    // The guards of the time step this step takes (stable_time_step), into health_.
    void count_health() {
        pending_health_.commit(health_, steps_, [&](std::size_t i) {
            return describe_particle(particles_[i], steps_, double(time_));
        });
    }

    // State set before the first step or changed between steps (by the user or a restart) is
    // checked before anything uses it, so a bad value is blamed on its own particle, not on a
    // neighbour or on the time step it would spoil.
    void check_pending() {
        if (!state_touched_) return;
        check_particles();
        state_touched_ = false;
    }

    // Stop on non-finite values, inverted particles or particles off the grid; report the
    // lowest-numbered offender so the message does not depend on the thread count.
    void check_particles() {
        const auto n = static_cast<std::ptrdiff_t>(particles_.size());
        auto& x = particles_.template column<fields::position>();
        std::ptrdiff_t first_bad = n;
        GIMLET_OMP(parallel for schedule(dynamic, particle_chunk) reduction(min : first_bad) num_threads(threads()) if (n >= parallel_threshold))
        for (std::ptrdiff_t k = 0; k < n; ++k) {
            const auto i = static_cast<std::size_t>(k);
            grid_.wrap(x[i]);
            if (!problem(i).empty()) first_bad = std::min(first_bad, k);
        }
        if (first_bad < n) fail(static_cast<std::size_t>(first_bad), problem(static_cast<std::size_t>(first_bad)));
    }

    [[nodiscard]] bool healthy(std::size_t i) const { return detail::particle_healthy(particles_[i], grid_); }
    [[nodiscard]] std::string problem(std::size_t i) const { return detail::particle_problem(particles_[i], grid_); }

    [[noreturn]] void fail(std::size_t i, const std::string& what) const {
        throw numerical_error(describe_particle(particles_[i], steps_, double(time_)) + ": " + what);
    }

    solver_options<S> options_;
    grid<S> grid_;
    std::vector<M> materials_;
    store_type particles_;
    std::vector<stencil_type> stencils_;
    // The scatter's slabs of node rows (for_each_particle_by_slab).
    detail::slab_schedule<std::max(Sh::stencil - 1, 1)> slabs_;
    step_timings timings_;
    health_events health_;
    mutable detail::pending_health pending_health_;  // stable_time_step's guards, until the step is taken
    real mass_cutoff_ = 0;
    std::vector<vector> wall_free_;  // per node entry: 1 where the walls leave a force component free
    // Volumetric averaging, per body and cell: sums of V tr(L) and V, and of V tr(sigma)/dim
    // and V at the forces' time.
    std::vector<real> cell_rate_, cell_volume_, cell_stress_, cell_stress_volume_;
    bool state_touched_ = true;  // the scene's particles are checked before the first step
    C contact_;
    real dt_ = 0;
    multi_field::exchange<S, C> exchange_;  // multi-field contact only (empty otherwise)
    real time_ = 0;
    std::uint64_t steps_ = 0;
};

}  // namespace gimlet
