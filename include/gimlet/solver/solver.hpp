// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The explicit GIMP solver: policies composed at compile time into one step, and the step's
/// three schemes (MUSL, USL, USF) as sequences of the named stages of gimlet::solver_core
/// (solver/core.hpp; the stages' own state under solver/stages/).

#include "gimlet/contact/check.hpp"
#include "gimlet/contact/concepts.hpp"
#include "gimlet/contact/node.hpp"
#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/detail/shares.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/multi_field/exchange.hpp"
#include "gimlet/scene/scene.hpp"
#include "gimlet/solver/core.hpp"
#include "gimlet/solver/distributed.hpp"
#include "gimlet/solver/options.hpp"
#include "gimlet/solver/particle_passes.hpp"
#include "gimlet/solver/transfers.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>

namespace gimlet {

/// The explicit GIMP/MPM solver (docs/physics.md section 1).
///
/// \tparam S  the space (dimension 2 = plane strain, or 3; float or double).
/// \tparam Sh the shape-function policy (shape::Shape).
/// \tparam M  the material bundle every body uses (gimlet::material<...>).
/// \tparam C  the contact policy (contact::Contact).
/// \tparam ExtraFields fields the user wants stored besides the policies' (their own tags for
///         observers, or fields::external_acceleration for a per-particle body force).
/// \tparam Part with multi-field contact, how each body is divided among velocity fields at the
///         nodes (multi_field::Partition; default one field per body).
/// \tparam Distributed true where the run may be split between processes
///         (solver_options::processes; gimlet::distributed_solver names it): false compiles
///         one process's step alone and refuses processes.
///
/// The particle store holds exactly the union of the fields the policies declare; a policy
/// that is off (thermal::none, viscosity::none) adds no field and its steps are compiled out.
/// All but the contact policy's part of a step is gimlet::solver_core, which solvers that differ
/// only in their law share; the schemes below call its stages in their order.
template <Space S, shape::Shape Sh, Material M, contact::Contact C, FieldList ExtraFields, multi_field::Partition Part,
          bool Distributed>
class solver
    : public solver_core<S, Sh, M, solver_fields_t<S, Sh, M, C, ExtraFields, Part>, C::multi_field, Part, Distributed> {
    using core = solver_core<S, Sh, M, solver_fields_t<S, Sh, M, C, ExtraFields, Part>, C::multi_field, Part, Distributed>;

public:
    using typename core::real;
    /// The contact policy C.
    using contact_type = C;
    /// The solver_core this solver derives from.
    using core_type = core;
    // A policy's optional members in a form the solver would skip (an after_contact that is not
    // const, say) stop the build with the checker's sentence instead.
    static_assert(contact::check<C>());

    /// Build the particles of a scene. Throws invalid_parameter for bad options, bodies outside
    /// the grid, overlapping bodies or a body with no particles.
    /// \param sc the scene: the grid and the bodies.
    /// \param options the solver's options (solver_options).
    /// \param contact the contact policy's parameters (e.g. friction).
    /// \param partition the partition's parameters (multi_field::Partition).
    explicit solver(const scene::scene<S, M>& sc, const solver_options<S>& options = {}, const C& contact = C{},
                    const Part& partition = Part{})
        : core(sc, options, partition, friction(contact)), contact_(contact) {}

    /// Advance one step with the stable time step (CFL, capped by max_time_step), shortened
    /// with multi-field contact while fields close in on each other
    /// (solver_options::contact_closure). Returns the step taken.
    real step() {
        this->check_pending();  // a bad value set between steps is blamed on its particle, not on dt
        return advance(this->stable_time_step(), true);
    }

    /// Advance one step as step() does, of at most `dt_max` (s): a loop of its own that stops at
    /// given times keeps the contact's shortening this way (step(dt) would not). Returns the
    /// step taken.
    real step_at_most(real dt_max) {
        require(std::isfinite(double(dt_max)) && dt_max > 0, "largest time step dt_max (s)", double(dt_max), "finite and > 0");
        this->check_pending();
        return advance(std::min(this->stable_time_step(), dt_max), true);
    }

    /// Advance one step of the given size (s), as given. Throws numerical_error if the run
    /// breaks down.
    real step(real dt) {
        require(std::isfinite(double(dt)) && dt > 0, "time step dt (s)", double(dt), "finite and > 0");
        return advance(dt, false);
    }

    /// Advance to time `t_end` (s), calling each observer when it is due (see diagnostics/):
    /// read-only observers (every_time, every_steps) and writable hooks (between_steps).
    template <class... Observers>
    void run_until(real t_end, Observers&... observers) {
        require(std::isfinite(double(t_end)) && t_end >= this->time_, "end time (s)", double(t_end),
                "finite and >= the current time " + detail::to_text(double(this->time_)));
        this->check_pending();
        (observers.maybe_call(*this), ...);
        while (this->time_ < t_end) {
            this->check_pending();  // what a hook (diagnostics::between_steps) changed, before dt reads it
            advance(std::min(this->stable_time_step(), t_end - this->time_), true);
            // No sliver step from rounding at the end. (Where the contact's step shortens the last
            // step, the rest is taken as one more step.)
            if (t_end - this->time_ < real(1e-12) * t_end) this->time_ = t_end;
            (observers.maybe_call(*this), ...);
        }
    }

    /// The contact policy, with whatever it counted (contact::Counting).
    [[nodiscard]] const C& contact() const noexcept { return contact_; }

private:
    using typename core::particle_ref;

    static std::optional<double> friction(const C& contact) {
        if constexpr (contact::Law<C>) return contact::friction_of(contact);
        else return (void)contact, std::nullopt;
    }

    // One step of the chosen scheme, of dt, or (`chosen`: the solver chose dt) shorter where
    // contact_closure asks; returns the step taken. Not a template, so that an explicit
    // instantiation of the solver compiles the step; defined below the class.
    real advance(real dt, bool chosen);

    // ---- the schemes ------------------------------------------------------------------------
    //
    // Each a sequence of the core's stages, each stage timed by the scheme into the phase of
    // step_timings it belongs to. `dt` is the step's size from the contact's shortening
    // (closing_limited, right after the P2G) on; nothing before it reads dt.

    // MUSL (Sulsky et al. 1995): P2G, grid update, contact, G2P, the particles' new momenta
    // re-mapped to the grid (docs/physics.md section 1, step 4), contact again (keeping the grid
    // update's pairs), and the stress from the re-mapped velocities.
    real musl_step(real dt, bool chosen) {
        auto& t = this->timings_;
        begin_step();
        grid_update_and_contact(dt, chosen);
        core::timed(t.grid_to_particle, [&] {
            this->grid_to_particles(dt, true);  // with the re-map's scatter
            this->remapped_velocities();
        });
        core::timed(t.contact, [&] { resolve_contact(multi_field::pass::remap, dt); });
        end_step(dt, true);
        return dt;
    }

    // USL: P2G, grid update, contact, G2P, and the stress from the updated grid velocities.
    real usl_step(real dt, bool chosen) {
        auto& t = this->timings_;
        begin_step();
        grid_update_and_contact(dt, chosen);
        core::timed(t.grid_to_particle, [&] { this->grid_to_particles(dt, false); });
        end_step(dt, true);
        return dt;
    }

    // USF: P2G of mass and momentum (with contact, of the current stress's forces too: they
    // decide where contact acts in this step), the stress from the start-of-step velocities,
    // then its forces, grid update, contact and G2P.
    real usf_step(real dt, bool chosen) {
        auto& t = this->timings_;
        begin_step();
        core::timed(t.particle_to_grid, [&] { scatter_and_search(true); });
        if (chosen) dt = closing_limited(dt);
        core::timed(t.grid_update, [&] { this->start_of_step_velocities(); });
        // The stress sees the same contact as the momentum update, or it would strain the
        // bodies through each other: this pass decides where contact acts in this step.
        core::timed(t.contact, [&] {
            resolve_contact(multi_field::pass::trial, dt);
            if constexpr (C::multi_field) this->clear_forces();
        });
        core::timed(t.material_update, [&] { update_stress(dt); });
        core::timed(t.particle_to_grid, [&] {
            if (this->options_.volumetric_average) this->average_mean_stress();
            this->map_forces();
        });
        core::timed(t.grid_update, [&] { this->update_grid_momentum(dt, false); });
        // USF keeps the decision its stress was computed with: releasing a node there, or
        // engaging one the stress saw free, makes the forces work on other velocities than the
        // ones that strained the material (an energy source: Bardenhagen contact from a gap
        // then rebounds with 1.8x the energy it came in with).
        core::timed(t.contact, [&] { resolve_contact(multi_field::pass::keep, dt); });
        core::timed(t.grid_to_particle, [&] { this->grid_to_particles(dt, false); });
        end_step(dt, false);
        return dt;
    }

    // ---- the schemes' shared parts ------------------------------------------------------------

    // What every scheme does first: the checks of what changed between steps, the weights at
    // x^n, the particles sorted by cell when due, the slabs of the scatter and the step's
    // fields, an empty grid.
    void begin_step() {
        auto& t = this->timings_;
        core::timed(t.material_update, [&] { this->check_step_start(); });  // the phase of finish_step's checks
        // The weights are recomputed from the positions every step, even though the previous
        // step's last pass could have computed them: a caller may change positions through a
        // reference to the store kept from an earlier particles() call, which no flag sees.
        core::timed(t.particle_to_grid, [&] { this->compute_stencils(); }, &t.weights);
        // On many processes, each particle to the process of its stencil's slab.
        if constexpr (Distributed)
            if (this->processes()) core::timed(t.particle_to_grid, [&] { this->migrate(); }, &t.slabs);
        core::timed(t.sort, [&] {
            if (!this->sort_due()) return;
            this->sort_by_cell();
            if constexpr (Distributed)
                if (this->processes()) this->renumber();
        });
        core::timed(t.particle_to_grid, [&] { this->group_into_slabs(); }, &t.slabs);
        core::timed(t.particle_to_grid, [&] { this->start_grid(); });
    }

    // P2G of mass, momentum and forces (USF's first: its forces only with contact), then the
    // searches that read the nodal masses: the light particles and the nodes several fields
    // share.
    void scatter_and_search(bool usf) {
        if (usf) this->scatter_for_usf();
        else this->scatter_all();
        this->find_light_particles();
        if constexpr (C::multi_field) this->find_shared_nodes();
    }

    // The step dt, or shorter where fields approaching each other at a shared node would close
    // by more than solver_options::contact_closure of a cell in it: the contact decision is
    // taken once a step, on the gaps of the positions at its start, and a pair engaged after
    // closing most of a cell in one step takes that cell's compression in one step, which
    // creates energy under every scheme (docs/equations.md, "Contact and the time step"). Read
    // after the P2G, before anything uses dt.
    real closing_limited(real dt) const {
        if constexpr (C::multi_field) {
            if (!(this->options_.contact_closure > 0)) return dt;
            real speed = this->exchange_.closing_speed(this->grid_, real(2) * this->grid_.cell());
            if (auto* p = this->processes()) speed = real(p->max(double(speed)));  // a maximum: exact in any order
            if (speed > 0) dt = std::min(dt, real(this->options_.contact_closure) * this->grid_.cell() / speed);
        }
        return dt;
    }

    // What MUSL and USL do first: P2G of mass, momentum and forces, the grid momentum update,
    // and the contact pass that decides where contact acts in this step (dt shortened first,
    // where the solver chose it: closing_limited).
    void grid_update_and_contact(real& dt, bool chosen) {
        auto& t = this->timings_;
        core::timed(t.particle_to_grid, [&] { scatter_and_search(false); });
        if (chosen) dt = closing_limited(dt);
        core::timed(t.grid_update, [&] { this->update_grid_momentum(dt, true); });
        core::timed(t.contact, [&] { resolve_contact(multi_field::pass::decide, dt); });
    }

    // What comes before every stress update: the volume filter, then the cells' mean rates
    // (they weight the rates with the volumes).
    void before_stress() {
        this->filter_volumes();
        if (this->options_.volumetric_average) this->average_volumetric_rates();
    }

    // The stress update from the grid velocities (USF's, before its forces).
    void update_stress(real dt) {
        before_stress();
        this->update_material_points(dt);
    }

    // What every scheme does last: the contact policy's particle hook, and the particle pass
    // that updates the material (MUSL, USL) and checks every particle.
    void end_step(real dt, bool update_materials) {
        core::timed(this->timings_.material_update, [&] {
            contact_hook();
            if (update_materials) before_stress();
            this->finish_step(dt, update_materials);
        });
    }

    // ---- the contact policy's part of the step -------------------------------------------------

    // At every node several fields share, the policy's correction (multi_field::exchange); nothing
    // with single-field contact.
    void resolve_contact(multi_field::pass pass, real dt) {
        if constexpr (C::multi_field)
            this->exchange_.resolve(pass, this->grid_, contact_, dt, this->mass_cutoff_);
        else (void)pass, (void)dt;
    }

    // A contact policy's per-particle hook (contact::ParticleHook), after the step's last
    // contact pass.
    void contact_hook() {
        if constexpr (C::multi_field && contact::ParticleHook<C, particle_ref, S>) {
            const auto n = static_cast<std::ptrdiff_t>(this->particles_.size());
            detail::thread_shares shares(n, this->threads(), n >= core::parallel_threshold);
            GIMLET_OMP(parallel num_threads(shares.team()))
            for (auto claimed = shares.start(); shares.claim(claimed);)
                for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) {
                    const auto i = static_cast<std::size_t>(k);
                    const contact::particle_contact<S> info =
                        this->exchange_.contact_of(this->entries(i), this->stencils_[i], this->grid_.size());
                    contact_.after_contact(this->particles_[i], info);
                }
        }
    }

    C contact_;
};

// Not inline, so that an `extern template` declaration of the solver keeps it, and the step it
// leads to, out of a unit that only constructs and runs it (docs/performance.md, "Memory, the
// largest scene, compile time").
template <Space S, shape::Shape Sh, Material M, contact::Contact C, FieldList ExtraFields, multi_field::Partition Part,
          bool Distributed>
auto solver<S, Sh, M, C, ExtraFields, Part, Distributed>::advance(real dt, bool chosen) -> real {
    // The consistent mass's entry list serves this step only, however it ends.
    struct forget_list {
        decltype(core::consistent_mass_)& stage;
        ~forget_list() { stage.unlist(); }
    } const step_list{this->consistent_mass_};
    switch (this->options_.scheme) {
        case update_scheme::musl: dt = musl_step(dt, chosen); break;
        case update_scheme::usl: dt = usl_step(dt, chosen); break;
        case update_scheme::usf: dt = usf_step(dt, chosen); break;
    }
    this->field_choice_.completed();  // reached only when the step completes
    return dt;
}

}  // namespace gimlet
