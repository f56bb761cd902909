// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The explicit GIMP solver: policies composed at compile time into one step.

#include "gimlet/contact/check.hpp"
#include "gimlet/contact/concepts.hpp"
#include "gimlet/contact/node.hpp"
#include "gimlet/contact/single_field.hpp"
#include "gimlet/core/detail/omp.hpp"
#include "gimlet/core/detail/shares.hpp"
#include "gimlet/core/detail/stencil.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/grid.hpp"
#include "gimlet/material/material.hpp"
#include "gimlet/core/material_point.hpp"
#include "gimlet/material/update.hpp"
#include "gimlet/core/particle_store.hpp"
#include "gimlet/multi_field/check.hpp"
#include "gimlet/multi_field/exchange.hpp"
#include "gimlet/multi_field/partition.hpp"
#include "gimlet/scene/scene.hpp"
#include "gimlet/shape/concepts.hpp"
#include "gimlet/solver/health.hpp"
#include "gimlet/solver/options.hpp"
#include "gimlet/solver/seeding.hpp"
#include "gimlet/solver/slabs.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <chrono>
#include <concepts>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace gimlet {

/// The fields a solver's particles store: the union of the core's, the shape's, the material's,
/// the contact policy's, the partition's and the user's (gimlet::solver's parameters).
template <Space S, shape::Shape Sh, Material M, contact::Contact C, FieldList ExtraFields, multi_field::Partition Part>
using solver_fields_t = field_union_t<core_fields<S>, typename Sh::required_fields, typename M::required_fields,
                                     typename C::required_fields, typename Part::required_fields, ExtraFields>;

template <Space S, shape::Shape Sh, Material M, contact::Contact C = contact::single_field,
          FieldList ExtraFields = field_list<>, multi_field::Partition Part = multi_field::by_body>
class solver;

/// Everything of gimlet::solver but its contact policy: the particles, the grid, the passes
/// of a step and the public members that read them. Solvers that differ only in their contact
/// law (with the same fields) share it, so a program compiles this part once for all its laws:
/// its members are the bulk of a solver type's code (docs/performance.md, "Memory, the largest
/// scene, compile time"). Use gimlet::solver; name this type only to compile it once
/// (`extern template class`).
///
/// \tparam Fields the particles' fields (solver_fields_t).
/// \tparam MultiField whether the contact policy keeps a velocity field per body
///         (contact::Contact's `multi_field`).
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
class solver_core {
public:
    using space_type = S;
    using real = typename S::real;
    using vector = typename S::vector;
    using matrix = typename S::matrix;
    using tensor3 = typename S::tensor3;
    using shape_type = Sh;
    using material_type = M;
    using partition_type = Part;
    using particle_fields = Fields;
    using store_type = particle_store<S, particle_fields>;
    static constexpr int dim = S::dim;

    static constexpr bool multi_field = MultiField;
    // A policy's optional members in a form the solver would skip stop the build with the
    // checker's sentence instead.
    static_assert(multi_field::check<Part>());
    static constexpr std::size_t fields_per_body = Part::fields_per_body;
    // Fields of one body that no contact keeps apart would pass through each other.
    static_assert(multi_field || fields_per_body == 1,
                  "gimlet::solver: a partition with several fields per body needs a multi-field contact policy");
    static_assert(fields_per_body <= 255, "gimlet::solver: a partition may have at most 255 fields per body");

private:
    // Only gimlet::solver builds, copies, destroys and reaches into a core: what was private in
    // the solver stays private, and a core is never a solver without its contact policy.
    template <Space, shape::Shape, Material, contact::Contact, FieldList, multi_field::Partition>
    friend class solver;

    using particle_ref = gimlet::particle_ref<store_type>;

    /// Build the particles of a scene (gimlet::solver's constructor). `friction` is the contact
    /// law's Coulomb coefficient, checked where the options are (none for a policy that is not
    /// a contact::Law).
    solver_core(const scene::scene<S, M>& sc, const solver_options<S>& options, const Part& partition,
                std::optional<double> friction);
    solver_core(const solver_core&) = default;
    solver_core(solver_core&&) = default;
    solver_core& operator=(const solver_core&) = default;
    solver_core& operator=(solver_core&&) = default;
    ~solver_core();  // below the class, as the members the step reaches (extern template)

public:
    /// dt = C h / max_p (c_p + |v_p|), c_p = sqrt((K + 4G/3) / rho) from the current state
    /// (docs/physics.md section 1, step 6), with c_p raised to the viscosity's signal speed where an
    /// artificial viscosity acts (viscosity::Viscosity).
    [[nodiscard]] real stable_time_step() const;

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
    /// The threads the solver's parallel loops use: options().threads where it is positive,
    /// otherwise OpenMP's default (1 without OpenMP). An observer with a parallel pass of its
    /// own takes as many, as the library's diagnostics do.
    [[nodiscard]] int threads() const noexcept {
        return options_.threads > 0 ? options_.threads : detail::default_threads();
    }
    /// The partition of bodies into velocity fields (multi_field::Partition).
    [[nodiscard]] const Part& partition() const noexcept { return partition_; }
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
    /// How many particles the last step found light (solver_options::light_particle_ratio),
    /// those left to FLIP because no node of theirs had other mass included.
    [[nodiscard]] std::size_t light_particles() const noexcept { return light_list_.size(); }
    /// Wall-clock time per phase of the steps so far (see docs/performance.md).
    [[nodiscard]] const step_timings& timings() const noexcept { return timings_; }
    /// The silent guards that acted so far (health_events). A resumed run counts from its resume.
    [[nodiscard]] const health_events& health() const noexcept { return health_; }

private:
    using stencil_type = detail::stencil<S, Sh::stencil>;
    // Every particle and node loop of the solver runs in detail::thread_shares' schedule: each
    // thread a fixed share, the same in every loop over the same items, and a thread done early
    // takes chunks of the shares not yet done; each slab pass likewise gives each thread the
    // same slabs of a colour. (The same thread number is the same thread in every parallel
    // region with GCC's and LLVM's runtimes; the OpenMP standard does not promise it.) So a
    // particle's data and a slab's nodes stay near one core, in its caches, from pass to pass
    // (binding the threads, OMP_PROC_BIND and OMP_PLACES, keeps each thread on its core):
    // shares handed out on demand moved about half of them between the cores in every pass,
    // and on a 2-core host where that cost as much as the work, 2 threads ran the elastic step
    // no faster than 1. And a slow core (another job on it, a busy neighbour of a virtual
    // machine) or a share of costlier particles holds up the loop by no more than the chunk its
    // thread has claimed, where fixed shares alone waited for the whole share: on 16 cores
    // those ran at 0.59-1.06 of the rate of shares handed out on demand (docs/performance.md,
    // "Each thread its own particles" and "Shares that are taken over").
    // Every particle's result, and every node's sum (slab by slab, in particle order), is
    // independent of which thread runs it, so the schedule costs no determinism.
    //
    // Loops shorter than this run on one thread: below it, starting a team costs more than the
    // loop (and a team on a busy machine can stall the whole step).
    static constexpr std::ptrdiff_t parallel_threshold = 4096;
    // A threshold likewise for loops over grid nodes, whose bodies cost a few nanoseconds each: a
    // pass over 16,000 entries takes some 30 us, waking a sleeping thread a few. At 32 times the
    // particles' threshold the HMX scene's 79,000 entries ran serially; with this one its
    // 2-thread run took 0.90 of the time, whole process, and scenes of 20,000 entries lost
    // nothing (docs/performance.md).
    static constexpr std::ptrdiff_t node_parallel_threshold = 4 * parallel_threshold;

    // Where particle i's mass goes in the nodal arrays (fields x nodes) at each node of its
    // stencil: entries(i) gives a chooser, called with the stencil's nodes in their order
    // (stencil::for_each, for_each_offset: every node), that returns the index of the field entry. One field
    // per body: its body's block, whatever the node; one field in all: the only block (a
    // compile-time zero). With a partition: the side chosen at the start of the step
    // (choose_fields), node by node; once the consistent mass has listed the step's entries
    // (cm_listed_), read from that list instead (the same entries, without the side's arithmetic).
    struct fixed_entry {
        std::size_t base;
        [[nodiscard]] std::size_t operator()(std::size_t node) const noexcept { return base + node; }
    };
    struct chosen_entry {
        std::size_t base, nodes;
        const std::uint8_t* side;    // advanced node by node
        const std::uint32_t* list;   // the step's listed entries, or null
        [[nodiscard]] std::size_t operator()(std::size_t node) noexcept {
            if (list) {
#ifndef NDEBUG
                // The list holds what the sides give, node by node, only if every pass walks a
                // whole stencil in order (a pass that stopped part-way would shift the next one).
                assert(*list == base + std::size_t(*side) * nodes + node);
                ++side;
#endif
                return *list++;
            }
            return base + std::size_t(*side++) * nodes + node;
        }
    };
    [[nodiscard]] auto entries(std::size_t i) const noexcept {
        if constexpr (!multi_field) {
            return (void)i, fixed_entry{0};
        } else {
            const std::size_t body = particles_.template column<fields::body>()[i];
            if constexpr (fields_per_body == 1) return fixed_entry{body * grid_.size()};
            else
                return chosen_entry{body * fields_per_body * grid_.size(), grid_.size(), sides_[i].data(),
                                    cm_listed_ ? &cm_entry_[i * stencil_type::nodes] : nullptr};
        }
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
        // Adds the time since the last lap to `into`, and returns it.
        double operator()(double& into) {
            const auto now = clock::now();
            const double lap = std::chrono::duration<double>(now - mark).count();
            into += lap;
            mark = now;
            return lap;
        }
    };

    // One step of the scheme. `law` holds the contact policy's part of it, called only with
    // multi-field contact: law.resolve(pass), the policy's correction at the shared nodes, and
    // law.hook(), its per-particle hook after the step's last contact pass. gimlet::solver
    // passes its own (solver::law_passes), so the rest of the step is compiled once for every
    // law.
    template <class Law>
    void advance(real dt, Law&& law) {
        phase_clock lap;
        // The consistent mass's entry list serves this step only, however it ends.
        struct unlist {
            bool& listed;
            ~unlist() { listed = false; }
        } const step_lists{cm_listed_};
        begin_step(dt, lap);
        switch (options_.scheme) {
            case update_scheme::musl: musl_step(dt, lap, law); break;
            case update_scheme::usl: usl_step(dt, lap, law); break;
            case update_scheme::usf: usf_step(dt, lap, law); break;
        }
        // Reached only when the step completes: a step that stopped part-way may have left
        // values in the later field slots, which the next step then sweeps.
        later_fields_empty_ = !split_now_;
    }

    // What every scheme does first: the checks of what changed between steps, the weights at
    // x^n, the slabs of the scatter, an empty grid.
    void begin_step(real dt, phase_clock& lap);  // below the class

    // What MUSL and USL do first: P2G of mass, momentum and forces, the grid momentum update,
    // and the contact pass that decides where contact acts in this step.
    template <class Law>
    void grid_update_and_contact(real dt, phase_clock& lap, Law& law) {
        scatter_all();
        find_light_particles();
        if constexpr (multi_field) find_shared_nodes();
        lap(timings_.particle_to_grid);
        update_grid_momentum(dt, true);
        lap(timings_.grid_update);
        if constexpr (multi_field) law.resolve(multi_field::pass::decide);
        lap(timings_.contact);
    }

    // MUSL (Sulsky et al. 1995): P2G, grid update, contact, G2P, the particles' new momenta
    // re-mapped to the grid, contact again (keeping the grid update's pairs), and the stress
    // from the re-mapped velocities.
    template <class Law>
    void musl_step(real dt, phase_clock& lap, Law& law) {
        grid_update_and_contact(dt, lap, law);
        grid_to_particles(dt, true);  // with the re-map's scatter (docs/physics.md section 1, step 4)
        nodal_velocity(grid_.velocity);
        grid_.apply_walls(grid_.velocity, wall_pass::keep);  // the grid update's decisions hold
        lap(timings_.grid_to_particle);
        if constexpr (multi_field) law.resolve(multi_field::pass::remap);
        lap(timings_.contact);
        end_step(dt, true, lap, law);
    }

    // USL: P2G, grid update, contact, G2P, and the stress from the updated grid velocities.
    template <class Law>
    void usl_step(real dt, phase_clock& lap, Law& law) {
        grid_update_and_contact(dt, lap, law);
        grid_to_particles(dt, false);
        lap(timings_.grid_to_particle);
        end_step(dt, true, lap, law);
    }

    // USF: P2G of mass and momentum, the stress from the start-of-step velocities, then its
    // forces, grid update, contact and G2P.
    template <class Law>
    void usf_step(real dt, phase_clock& lap, Law& law) {
        // With contact it also maps the forces of the current stress: they decide where contact
        // acts in this step (multi_field::pass::trial).
        scatter_for_usf();
        find_light_particles();
        if constexpr (multi_field) find_shared_nodes();
        lap(timings_.particle_to_grid);
        nodal_velocity(grid_.velocity_old);
        grid_.velocity = grid_.velocity_old;
        grid_.apply_walls(grid_.velocity);
        lap(timings_.grid_update);
        // The stress sees the same contact as the momentum update, or it would strain the
        // bodies through each other: this pass decides where contact acts in this step.
        if constexpr (multi_field) {
            law.resolve(multi_field::pass::trial);
            std::fill(grid_.force.begin(), grid_.force.end(), vector::Zero());
        }
        lap(timings_.contact);
        filter_volumes();  // before the cell averages: they weight the rates with the volumes
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
        if constexpr (multi_field) law.resolve(multi_field::pass::keep);
        lap(timings_.contact);
        grid_to_particles(dt, false);
        lap(timings_.grid_to_particle);
        end_step(dt, false, lap, law);
    }

    // What every scheme does last: the contact policy's particle hook, and the particle pass
    // that updates the material (MUSL, USL) and checks every particle.
    template <class Law>
    void end_step(real dt, bool update_materials, phase_clock& lap, Law& law) {
        if constexpr (multi_field) law.hook();
        if (update_materials) filter_volumes();
        if (update_materials && options_.volumetric_average) average_volumetric_rates(grid_.velocity);
        finish_step(dt, update_materials);
        lap(timings_.material_update);
    }

    // Weights at x^n of every particle.
    void compute_stencils() {
        const auto n = static_cast<std::ptrdiff_t>(particles_.size());
        stencils_.resize(particles_.size());
        slabs_.resize(particles_.size());
        detail::thread_shares shares(n, threads(), n >= parallel_threshold);
        GIMLET_OMP(parallel num_threads(shares.team()))
        for (auto claimed = shares.start(); shares.claim(claimed);)
            for (std::ptrdiff_t i = claimed.first, end = claimed.last; i < end; ++i) compute_stencil(static_cast<std::size_t>(i));
    }

    // The stencil of particle i, computed once and shared by every transfer of the step, and
    // the slab its scatter belongs to.
    void compute_stencil(std::size_t i) {
        const auto p = particles_[i];
        auto& st = stencils_[i];
        st.template compute_with<Sh>(grid_, p.template get<fields::position>(), Sh::half_width(p, grid_.cell()));
        slabs_.assign(i, st.first_row);
    }

    // f(i) for every particle, slab by slab and colour by colour (detail::slab_schedule): every
    // node sums its particles' contributions in an order fixed by the grid and the particle
    // order, whatever the thread count. f must not throw.
    template <class F>
    void for_each_particle_by_slab(F&& f) {
        slabs_.for_each(std::ptrdiff_t(particles_.size()) >= parallel_threshold, threads(), std::forward<F>(f));
    }
    // Rows of nodes flagged for for_each_particle_by_slab_reaching (a partition's split_rows(),
    // or rows given to its view) must be one flag per row of the last axis: `what` names them.
    void require_row_flags(const std::vector<std::uint8_t>& rows, const char* what) const {
        const auto layers = static_cast<std::size_t>(grid_.nodes(dim - 1));
        require(rows.size() == layers, what, double(rows.size()),
                std::to_string(layers) + ": one flag per row of nodes along the last axis");
    }
    // The same as for_each_particle_by_slab, for the particles of the slabs whose stencils can
    // reach a node row flagged in `rows` (slab_schedule::for_each_reaching).
    template <class F>
    void for_each_particle_by_slab_reaching(const std::vector<std::uint8_t>& rows, F&& f) {
        slabs_.for_each_reaching(rows, std::ptrdiff_t(particles_.size()) >= parallel_threshold, threads(), std::forward<F>(f));
    }

    // ---- transfers (solver/transfers.hpp): P2G, the grid update, G2P with the light nodes
    // and the damping transfer
    template <bool Forces>
    void scatter();
    // The scatters the step calls, as members that are not templates, so that an explicit
    // instantiation of the core compiles them (the step that calls them is a template): mass,
    // momentum and forces; and USF's first, which maps the forces too only with contact.
    // (Defined below the class: an inline member would compile its scatter in every unit that
    // steps a solver of another law on a core declared `extern template`.)
    void scatter_all();
    void scatter_for_usf();
    void map_forces();
    void nodal_velocity(std::vector<vector>& out);
    void clear_grid();
    void fill_entries(std::vector<vector>& out, const vector& value);
    // f(e) for every grid entry of the field slots swept this step (swept_fields_), split
    // between the threads on a large grid; f(e) writes entry e only.
    template <class F>
    void for_each_swept_entry(F&& f);
    void update_grid_momentum(real dt, bool with_old_velocity);
    void consistent_mass_forces();  // solver/consistent_mass.hpp
    void filter_volumes();          // solver/volume_filter.hpp (solver_options::volume_filter)
    // Whether the material's thermal policy provides the reference isentrope's energy e_s(J)
    // (thermal::isentrope_temperature does), which the volume filter moves the energy along.
    static constexpr bool has_reference_isentrope = requires(const typename M::thermal_type& t) {
        { t.reference_energy(1.0) } -> std::convertible_to<double>;
    };
    void grid_to_particles(real dt, bool remap);
    template <bool Lights>
    void grid_to_particles_pass(real dt, bool remap);
    [[nodiscard]] bool on_light_node(std::size_t e, real w, const vector& g) const;
    [[nodiscard]] vector light_node_change(std::size_t i, real dt) const;

    // ---- particle passes (solver/particle_passes.hpp): the material update, volumetric
    // averaging, the step's last pass, sorting
    void update_material_points(real dt, const std::vector<vector>& vg);
    template <class After>
    std::ptrdiff_t material_pass(real dt, const std::vector<vector>& vg, bool update_materials, After&& after);
    void update_material_point(std::size_t i, real dt, const std::vector<vector>& vg);
    [[nodiscard]] matrix velocity_gradient(std::size_t i, const std::vector<vector>& vg) const;
    // How many particles the material passes update at once: two in the lanes of one vector
    // where the material allows it (lanes_capable, update_material_pair), else one.
    static constexpr std::ptrdiff_t material_group = lanes_capable<M, S> ? 2 : 1;
    [[nodiscard]] bool update_material_pair(std::size_t i, real dt, const std::vector<vector>& vg);
    [[nodiscard]] std::size_t cell_key(std::size_t i) const;
    [[nodiscard]] matrix force_stress(std::size_t i) const;
    void average_mean_stress();
    void average_volumetric_rates(const std::vector<vector>& vg);
    void finish_step(real dt, bool update_materials);
    void sort_by_cell();

    // Light particles (light_particles.hpp; solver_options::light_particle_ratio).
    [[nodiscard]] real reference_density(std::size_t i) const;
    void check_light_possible();
    void find_light_particles();
    [[nodiscard]] real reliability(std::size_t e) const;
    [[nodiscard]] real heavy_mass(std::size_t e) const;
    // Whether particle i is light this step (light_particle_ is only current when the list is not empty).
    [[nodiscard]] bool is_light(std::size_t i) const { return !light_list_.empty() && light_particle_[i] != lightness::none; }
    [[nodiscard]] matrix light_velocity_gradient(std::size_t i, const std::vector<vector>& vg) const;
    void move_light_particles(real dt);

    // ---- multi-field contact (multi_field::exchange) --------------------------------------

    void find_shared_nodes();  // below the class

    // What a partition's hooks see (multi_field::partition_view).
    struct slab_caller {
        solver_core* self;
        template <class F>
        void operator()(F&& f) const { self->for_each_particle_by_slab(std::forward<F>(f)); }
        template <class F>
        void operator()(const std::vector<std::uint8_t>& rows, F&& f) const {
            self->require_row_flags(rows, "rows given to for_each_particle_by_slab (their count)");
            self->for_each_particle_by_slab_reaching(rows, std::forward<F>(f));
        }
    };
    struct index_caller {
        solver_core* self;
        template <class F>
        void operator()(std::size_t count, F&& f) const {
            const auto n = static_cast<std::ptrdiff_t>(count);
            detail::thread_shares shares(n, self->threads(), n >= node_parallel_threshold);
            GIMLET_OMP(parallel num_threads(shares.team()))
            for (auto claimed = shares.start(); shares.claim(claimed);)
                for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) f(static_cast<std::size_t>(k));
        }
    };
    template <class Store>
    using partition_view_type =
        multi_field::partition_view<Store, std::vector<stencil_type>, grid<S>, slab_caller, index_caller>;
    template <class Store>
    [[nodiscard]] partition_view_type<Store> partition_view() {
        return {particles_, stencils_, grid_, materials_.size(), slab_caller{this}, index_caller{this}};
    }

    // The partition's side of every particle at every node of its stencil, from the
    // start-of-step state: the transfers of the whole step use them (entries).
    //
    // This member compiles only for a partition of several fields, and is called only under
    // `if constexpr`. It is a template because an explicit instantiation of the core
    // (docs/performance.md, "Memory, the largest scene, compile time") instantiates every member
    // that is not one: C++20 would skip a member whose `requires` fails, clang 14 does not.
    template <int = 0>
    void choose_fields() {
        const auto n = static_cast<std::ptrdiff_t>(particles_.size());
        sides_.resize(particles_.size());  // entries added are zero
        // A partition that says it splits nothing this step (multi_field::Partition's optional
        // splits(), asked once a step: split_now_) puts every particle in its body's first field
        // at once: every side 0, which they all still are after a step that split nothing (the
        // fill, one thread over a byte per stencil node of every particle, ran every such step:
        // about 0.1 ms at 216,000 particles in 2-D, a serial part of the step;
        // docs/performance.md).
        if (!split_now_) {
            if (!sides_zero_) std::fill(sides_.begin(), sides_.end(), std::array<std::uint8_t, stencil_type::nodes>{});
            sides_zero_ = true;
            return;
        }
        sides_zero_ = false;
        // Particle i's sides; false if the partition answered out of range.
        auto choose = [&](std::size_t i) {
            const auto p = particles_[i];
            std::size_t j = 0;
            bool ok = true;
            stencils_[i].for_each_node_position(grid_, [&](std::size_t node, real, const vector& at) {
                assert(at == grid_.node_position(node));
                const std::size_t side = partition_.side(std::as_const(p), node, at);
                ok = ok && side < fields_per_body;
                sides_[i][j++] = static_cast<std::uint8_t>(ok ? side : 0);
            });
            return ok;
        };
        // A partition that names the rows of nodes holding a node it splits
        // (multi_field::Partition's optional split_rows()) is asked only of the particles whose
        // stencils reach one; every other particle is in its body's first field at every node.
        const std::vector<std::uint8_t>* rows = nullptr;
        const int layers = grid_.nodes(dim - 1);
        if constexpr (requires(const Part& q) {
                          { q.split_rows() } -> std::same_as<const std::vector<std::uint8_t>&>;
                      }) {
            rows = &partition_.split_rows();
            require_row_flags(*rows, "the partition's split_rows() size");
        }
        // Whether particle i's stencil reaches a flagged row: its rows along the last axis start
        // at first_row and wrap only on a periodic axis (on a free one the stencil lies within the
        // grid's ghost nodes), as grid::layer numbers them.
        auto reaches = [&](std::size_t i) {
            for (int a = 0, r = stencils_[i].first_row; a < Sh::stencil; ++a, ++r) {
                if (r == layers) r = 0;
                if ((*rows)[std::size_t(r)]) return true;
            }
            return false;
        };
        std::ptrdiff_t first_bad = n;
        detail::thread_shares shares(n, threads(), n >= parallel_threshold);
        GIMLET_OMP(parallel reduction(min : first_bad) num_threads(shares.team()))
        for (auto claimed = shares.start(); shares.claim(claimed);)
            for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) {
                const auto i = static_cast<std::size_t>(k);
                if (rows && !reaches(i)) sides_[i] = {};
                else if (!choose(i)) first_bad = std::min(first_bad, k);
            }
        if (first_bad < n)
            fail(static_cast<std::size_t>(first_bad),
                 "the partition (multi_field::Partition::side) chose a field outside [0, " +
                     std::to_string(fields_per_body) + ") at a node of its stencil");
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
        check_light_possible();  // the masses or volumes may have changed
        state_touched_ = false;
    }

    // Stop on non-finite values, inverted particles or particles off the grid; report the
    // lowest-numbered offender so the message does not depend on the thread count.
    void check_particles();  // below the class

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
    // Volumetric averaging, per body (or field) and cell: sums of V tr(L) and V, and of V tr(sigma)/dim
    // and V at the forces' time.
    std::vector<real> cell_rate_, cell_volume_, cell_stress_, cell_stress_volume_;
    bool state_touched_ = true;  // the scene's particles are checked before the first step
    Part partition_;
    // Per particle and stencil node, the side of its body the partition chose this step
    // (fields_per_body > 1 only).
    std::vector<std::array<std::uint8_t, stencil_type::nodes>> sides_;
    bool sides_zero_ = true;  // every entry of sides_ is 0 (choose_fields)
    real dt_ = 0;
    // Light particles, this step (light_particles.hpp): none unless light_possible_. Per particle
    // its lightness, the light ones in index order, and per node entry the largest reference and
    // current densities, whether a light particle's stencil holds it, the mass of the particles
    // that are not light there and the momentum the light ones changed.
    enum class lightness : std::uint8_t {
        none,
        light,       // takes the nodes' reliability-weighted velocity
        light_flip,  // light, but no node of its has non-light mass: FLIP moves it
    };
    bool light_possible_ = false;
    std::vector<lightness> light_particle_;
    std::vector<std::size_t> light_list_;
    std::vector<real> node_reference_density_, node_densest_, node_heavy_mass_;
    std::vector<std::uint8_t> near_light_;
    std::vector<vector> light_momentum_;
    // Consistent-mass accelerations (consistent_mass.hpp; solver_options::consistent_mass_iterations):
    // per node entry the lumped and the iterated accelerations and M a, and whether it keeps its
    // lumped acceleration (an entry at a node two or more fields share).
    std::vector<vector> cm_first_, cm_accel_, cm_product_;
    std::vector<std::uint8_t> cm_lumped_;
    // The field slots of each body that the grid's node passes visit this step
    // (for_each_swept_entry). A body's later slots are skipped where the partition says it
    // splits nothing this step (its optional splits(): split_now_; a partition without it always
    // splits) and the later slots are empty: no mass, momentum, force, velocity or wall flag in
    // any of their entries, which is what a pass over them would leave. The first step to
    // complete without a split swept every slot, left them empty and sets later_fields_empty_;
    // nothing writes there until a step splits again. Self-contact's second fields, where
    // nothing splits, then cost no pass over the grid.
    std::size_t swept_fields_ = fields_per_body;
    bool split_now_ = true;
    bool later_fields_empty_ = false;
    // The blocks of cm_block entries that hold an entry above the cut-off (found in the first
    // node pass; the iterations' node passes visit only those).
    static constexpr std::size_t cm_block = 64;
    std::vector<std::uint8_t> cm_block_heavy_;
    std::vector<std::uint32_t> cm_blocks_;
    // Per particle, found in the first iteration and used by every one: its entries in stencil
    // order, its weight on the nodes above the cut-off, and how it scatters its share.
    enum cm_scatter : std::uint8_t { cm_all_heavy, cm_some_light, cm_held };
    std::vector<std::uint32_t> cm_entry_;
    std::vector<real> cm_heavy_;
    std::vector<std::uint8_t> cm_kind_;
    bool cm_listed_ = false;  // cm_entry_ holds this step's entries (set after the first iteration)
    // The volume filter (volume_filter.hpp): per body and node entry the lumped projection of J,
    // the iterate, M times it (and the releases), the masses as the renormalised weights see
    // them; per particle the gathered values, the weight on the nodes above the cut-off and the
    // change of e_s.
    std::vector<real> vf_first_, vf_value_, vf_product_, vf_mass_, vf_particle_, vf_heavy_;
    std::vector<double> vf_es_change_;
    multi_field::exchange<S> exchange_;  // multi-field contact only (empty otherwise)
    real time_ = 0;
    std::uint64_t steps_ = 0;
};

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
///
/// The particle store holds exactly the union of the fields the policies declare; a policy
/// that is off (thermal::none, viscosity::none) adds no field and its steps are compiled out.
/// All but the contact policy's part of a step is gimlet::solver_core, which solvers that differ
/// only in their law share.
template <Space S, shape::Shape Sh, Material M, contact::Contact C, FieldList ExtraFields, multi_field::Partition Part>
class solver : public solver_core<S, Sh, M, solver_fields_t<S, Sh, M, C, ExtraFields, Part>, C::multi_field, Part> {
    using core = solver_core<S, Sh, M, solver_fields_t<S, Sh, M, C, ExtraFields, Part>, C::multi_field, Part>;

public:
    using typename core::real;
    using contact_type = C;
    using core_type = core;
    // A policy's optional members in a form the solver would skip (an after_contact that is not
    // const, say) stop the build with the checker's sentence instead.
    static_assert(contact::check<C>());

    /// Build the particles of a scene. Throws invalid_parameter for bad options, bodies outside
    /// the grid, overlapping bodies or a body with no particles.
    /// \param contact the contact policy's parameters (e.g. friction).
    /// \param partition the partition's parameters (multi_field::Partition).
    explicit solver(const scene::scene<S, M>& sc, const solver_options<S>& options = {}, const C& contact = C{},
                    const Part& partition = Part{})
        : core(sc, options, partition, friction(contact)), contact_(contact) {}

    /// Advance one step with the stable time step (CFL, capped by max_time_step). Returns dt.
    real step() {
        this->check_pending();  // a bad value set between steps is blamed on its particle, not on dt
        return step(this->stable_time_step());
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
        require(std::isfinite(double(t_end)) && t_end >= this->time_, "end time (s)", double(t_end),
                "finite and >= the current time " + detail::to_text(double(this->time_)));
        this->check_pending();
        (observers.maybe_call(*this), ...);
        while (this->time_ < t_end) {
            this->check_pending();  // what a hook (diagnostics::between_steps) changed, before dt reads it
            const real dt = std::min(this->stable_time_step(), t_end - this->time_);
            advance(dt);
            if (t_end - this->time_ < real(1e-12) * t_end) this->time_ = t_end;  // no sliver step at the end
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

    // The step, with the contact policy's part of it (solver_core::advance). Not a template, so
    // that an explicit instantiation of the solver compiles the step; defined below the class.
    void advance(real dt);

    struct law_passes {
        solver& self;
        // At every node several fields share, the policy's correction (multi_field::exchange).
        // (An explicit instantiation of the solver compiles these two members for every policy:
        // hence the guards, although the step calls them only with multi-field contact.)
        void resolve(multi_field::pass pass) {
            if constexpr (C::multi_field)
                self.exchange_.resolve(pass, self.grid_, self.contact_, self.dt_, self.mass_cutoff_);
            else (void)pass;
        }
        // A contact policy's per-particle hook (contact::ParticleHook), after the step's last
        // contact pass.
        void hook() {
            if constexpr (C::multi_field && contact::ParticleHook<C, particle_ref, S>) {
                const auto n = static_cast<std::ptrdiff_t>(self.particles_.size());
                detail::thread_shares shares(n, self.threads(), n >= core::parallel_threshold);
                GIMLET_OMP(parallel num_threads(shares.team()))
                for (auto claimed = shares.start(); shares.claim(claimed);)
                    for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) {
                        const auto i = static_cast<std::size_t>(k);
                        const contact::particle_contact<S> info =
                            self.exchange_.contact_of(self.entries(i), self.stencils_[i], self.grid_.size());
                        self.contact_.after_contact(self.particles_[i], info);
                    }
            }
        }
    };

    C contact_;
};

// Members defined outside their class: not inline, so that an `extern template` declaration of
// the solver or its core keeps them, and the step they lead to, out of a unit that only
// constructs and runs it (docs/performance.md, "Memory, the largest scene, compile time").

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
solver_core<S, Sh, M, Fields, MultiField, Part>::solver_core(const scene::scene<S, M>& sc,
                                                             const solver_options<S>& options, const Part& partition,
                                                             std::optional<double> friction)
    : options_(options), grid_(sc.grid(), Sh::stencil), partition_(partition) {
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
    if (friction)
        require(*friction >= 0.0, "contact law friction() (Coulomb coefficient mu)", *friction,
                ">= 0 (infinity: no slip)");
    for (const auto& b : sc.bodies()) materials_.push_back(b.material);
    detail::seed_particles(sc, grid_, particles_);
    real heaviest = 0;
    for (real m : particles_.template column<fields::mass>()) heaviest = std::max(heaviest, m);
    mass_cutoff_ = real(options_.mass_cutoff) * heaviest;
    if (options_.volume_filter && !has_reference_isentrope)
        throw invalid_parameter("volume_filter", "true",
                                "false for this material: the filter moves each particle's energy along the reference "
                                "isentrope, which its thermal policy does not provide (reference_energy(J); "
                                "thermal::isentrope_temperature does)");
    check_light_possible();
    // One velocity field per body (Bardenhagen et al. 2000), or the partition's number of
    // them; a single-field policy keeps one.
    const std::size_t fields = multi_field ? materials_.size() * fields_per_body : 1;
    // The consistent mass lists each particle's node entries in 32 bits (consistent_mass.hpp):
    // refused, before the nodal arrays are allocated, on a grid with more entries.
    const std::size_t entries_wanted = grid_.size() * fields;
    if (options_.consistent_mass_iterations > 0 && entries_wanted > std::size_t(UINT32_MAX))
        throw invalid_parameter("consistent_mass_iterations (with a grid of " + std::to_string(entries_wanted) +
                                    " node entries, fields x nodes)",
                                std::to_string(options_.consistent_mass_iterations),
                                "0 on a grid of more than 4294967295 node entries");
    if constexpr (multi_field) grid_.set_field_count(fields);
    // Which components of a node's force the walls leave free (1) or take (0): the projection
    // apply_walls makes on velocities, for the forces of light nodes (grid_to_particles).
    wall_free_.assign(grid_.entries(), vector::Ones());
    grid_.apply_walls(wall_free_, wall_pass::none);  // a one-sided wall holds no force component for good
    slabs_.set_up(grid_.nodes(dim - 1), grid_.periodic(dim - 1));
    if constexpr (requires(Part& p, partition_view_type<store_type>& v) { p.initialize(v); }) {
        compute_stencils();
        slabs_.bucket();
        auto view = partition_view<store_type>();
        partition_.initialize(view);
    }
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
auto solver_core<S, Sh, M, Fields, MultiField, Part>::stable_time_step() const -> real {
    const auto n = static_cast<std::ptrdiff_t>(particles_.size());
    real fastest = 0;
    // The guards met on the way (health_events), counted once the step is taken.
    std::uint64_t n0 = 0, n1 = 0, n2 = 0;
    std::ptrdiff_t f0 = n, f1 = n, f2 = n;
    detail::thread_shares shares(n, threads(), n >= parallel_threshold);
    GIMLET_OMP(parallel reduction(max : fastest) reduction(+ : n0, n1, n2) reduction(min : f0, f1, f2) num_threads(shares.team()))
    for (auto claimed = shares.start(); shares.claim(claimed);)
        for (std::ptrdiff_t i = claimed.first, end = claimed.last; i < end; ++i) {
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

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
void solver_core<S, Sh, M, Fields, MultiField, Part>::check_particles() {
    const auto n = static_cast<std::ptrdiff_t>(particles_.size());
    auto& x = particles_.template column<fields::position>();
    std::ptrdiff_t first_bad = n;
    detail::thread_shares shares(n, threads(), n >= parallel_threshold);
    GIMLET_OMP(parallel reduction(min : first_bad) num_threads(shares.team()))
    for (auto claimed = shares.start(); shares.claim(claimed);)
        for (std::ptrdiff_t k = claimed.first, end = claimed.last; k < end; ++k) {
            const auto i = static_cast<std::size_t>(k);
            grid_.wrap(x[i]);
            if (!problem(i).empty()) first_bad = std::min(first_bad, k);
        }
    if (first_bad < n) fail(static_cast<std::size_t>(first_bad), problem(static_cast<std::size_t>(first_bad)));
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
void solver_core<S, Sh, M, Fields, MultiField, Part>::begin_step(real dt, phase_clock& lap) {
    check_pending();
    count_health();
    lap(timings_.material_update);  // where the checks are done in every other step
    // The weights are recomputed from the positions every step, even though the previous
    // step's last pass could have computed them: a caller may change positions through a
    // reference to the store kept from an earlier particles() call, which no flag sees.
    compute_stencils();
    timings_.weights += lap(timings_.particle_to_grid);
    if (options_.sort_interval > 0 && steps_ % std::uint64_t(options_.sort_interval) == 0) sort_by_cell();
    lap(timings_.sort);
    slabs_.bucket(std::ptrdiff_t(particles_.size()) >= parallel_threshold, threads());
    // Asked of any partition that has it, whatever its fields_per_body; the view is a const
    // lvalue, so `prepare(const View&)` and a template `prepare(View&)` both take it.
    if constexpr (requires(Part& p, const partition_view_type<const store_type>& v) { p.prepare(v); }) {
        const auto view = partition_view<const store_type>();
        partition_.prepare(view);
    }
    if constexpr (fields_per_body > 1) {
        split_now_ = true;
        if constexpr (requires(const Part& p) { { p.splits() } -> std::convertible_to<bool>; }) split_now_ = partition_.splits();
        swept_fields_ = split_now_ || !later_fields_empty_ ? fields_per_body : 1;
        if (split_now_) later_fields_empty_ = false;  // this step writes there, even if it stops part-way
        choose_fields();
    }
    timings_.slabs += lap(timings_.particle_to_grid);
    dt_ = dt;
    if (options_.volumetric_average) average_mean_stress();
    clear_grid();
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
void solver_core<S, Sh, M, Fields, MultiField, Part>::find_shared_nodes() {
    exchange_.find_shared_nodes(grid_, mass_cutoff_, steps_, double(time_), stencils_,
                                particles_.template column<fields::mass>(), fields_per_body,
                                [&](std::size_t i) { return entries(i); },
                                [&](const std::vector<std::uint8_t>& rows, auto&& f) {
                                    for_each_particle_by_slab_reaching(rows, f);
                                },
                                threads(),
                                std::ptrdiff_t(grid_.entries()) >= node_parallel_threshold);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
solver_core<S, Sh, M, Fields, MultiField, Part>::~solver_core() = default;

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
void solver_core<S, Sh, M, Fields, MultiField, Part>::scatter_all() {
    scatter<true>();
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part>
void solver_core<S, Sh, M, Fields, MultiField, Part>::scatter_for_usf() {
    if constexpr (multi_field) scatter<true>();
    else scatter<false>();
}

template <Space S, shape::Shape Sh, Material M, contact::Contact C, FieldList ExtraFields, multi_field::Partition Part>
void solver<S, Sh, M, C, ExtraFields, Part>::advance(real dt) {
    core::advance(dt, law_passes{*this});
}

}  // namespace gimlet

#include "gimlet/solver/consistent_mass.hpp"
#include "gimlet/solver/volume_filter.hpp"
#include "gimlet/solver/light_particles.hpp"
#include "gimlet/solver/particle_passes.hpp"
#include "gimlet/solver/transfers.hpp"
