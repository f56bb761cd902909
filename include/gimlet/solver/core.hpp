// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// gimlet::solver_core: the particles, the grid and the named stages of a step, which the
/// schemes of gimlet::solver (solver/solver.hpp) call in their order.

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
#include "gimlet/shape/axisymmetric.hpp"
#include "gimlet/shape/concepts.hpp"
#include "gimlet/solver/health.hpp"
#include "gimlet/solver/options.hpp"
#include "gimlet/solver/seeding.hpp"
#include "gimlet/solver/setup_checks.hpp"
#include "gimlet/solver/slabs.hpp"
#include "gimlet/solver/stages/consistent_mass.hpp"
#include "gimlet/solver/stages/damping_transfer.hpp"
#include "gimlet/solver/stages/driven_particles.hpp"
#include "gimlet/solver/stages/field_choice.hpp"
#include "gimlet/solver/stages/light_particles.hpp"
#include "gimlet/solver/stages/volume_filter.hpp"
#include "gimlet/solver/stages/volumetric_average.hpp"
#include "gimlet/solver/time_step.hpp"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <concepts>
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
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
          FieldList ExtraFields = field_list<>, multi_field::Partition Part = multi_field::by_body,
          bool Distributed = false>
class solver;

/// A solver that runs on many processes (solver_options::processes): gimlet::solver with its
/// last parameter, Distributed, true. On one process (no processes given) it gives a plain
/// solver's bits; gimlet::solver itself refuses processes, so that in a program that never
/// splits its run the exchanges, the migration and the windows are constant branches that the
/// optimiser removes.
template <Space S, shape::Shape Sh, Material M, contact::Contact C = contact::single_field,
          FieldList ExtraFields = field_list<>, multi_field::Partition Part = multi_field::by_body>
using distributed_solver = solver<S, Sh, M, C, ExtraFields, Part, true>;

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
/// \tparam Distributed whether it runs on many processes (gimlet::distributed_solver).
template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part,
          bool Distributed = false>
class solver_core {
public:
    /// The space S (dimension and scalar type).
    using space_type = S;
    /// The scalar type of S.
    using real = typename S::real;
    /// A position or velocity: S::vector.
    using vector = typename S::vector;
    /// A Dim x Dim tensor: S::matrix.
    using matrix = typename S::matrix;
    /// A 3x3 tensor: S::tensor3.
    using tensor3 = typename S::tensor3;
    /// The shape-function policy Sh.
    using shape_type = Sh;
    /// The material type M.
    using material_type = M;
    /// The partition of bodies into velocity fields, Part.
    using partition_type = Part;
    /// The field_list of the particles, Fields.
    using particle_fields = Fields;
    /// The particle storage.
    using store_type = particle_store<S, particle_fields>;
    /// Number of axes, 2 or 3.
    static constexpr int dim = S::dim;
    /// True in an axisymmetric space (axisymmetric_space): rings per radian, the hoop terms.
    static constexpr bool axisymmetric = is_axisymmetric_v<S>;
    // The axisymmetric weights exist for the shapes the r-weighted integrals were derived for.
    static_assert(!axisymmetric || shape::has_axisymmetric_form<Sh>,
                  "gimlet::solver: in an axisymmetric_space the shape must be shape::ugimp or shape::linear, "
                  "whose r-weighted radial factors exist (shape::axisymmetric_form); cpgimp's deforming domain "
                  "and the B-splines have none yet");

    /// True if some particles may be driven (fields::driven in the particles' fields).
    static constexpr bool has_driven_particles = store_type::template has<fields::driven>;
    static_assert(store_type::template has<fields::driven> == store_type::template has<fields::driven_velocity>,
                  "gimlet::solver: fields::driven and fields::driven_velocity go together (stages::driven_particles)");

    /// True if the grid keeps a velocity field per body (MultiField).
    static constexpr bool multi_field = MultiField;
    // A policy's optional members in a form the solver would skip stop the build with the
    // checker's sentence instead.
    static_assert(multi_field::check<Part>());
    /// Velocity fields per body (1 unless the partition splits bodies); at most 255.
    static constexpr std::size_t fields_per_body = Part::fields_per_body;
    // Fields of one body that no contact keeps apart would pass through each other.
    static_assert(multi_field || fields_per_body == 1,
                  "gimlet::solver: a partition with several fields per body needs a multi-field contact policy");
    static_assert(fields_per_body <= 255, "gimlet::solver: a partition may have at most 255 fields per body");

private:
    // Only gimlet::solver builds, copies, destroys and reaches into a core: what is private to
    // the solver stays private, and a core is never a solver without its contact policy.
    template <Space, shape::Shape, Material, contact::Contact, FieldList, multi_field::Partition, bool>
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
    /// artificial viscosity acts (viscosity::Viscosity). With multi-field contact, step() and
    /// run_until may take less while fields close in on each other
    /// (solver_options::contact_closure); step(dt) takes dt as given.
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
    /// The particles, read-only.
    [[nodiscard]] const store_type& particles() const noexcept { return particles_; }
    /// The background grid (node arithmetic and nodal fields).
    [[nodiscard]] const grid<S>& background_grid() const noexcept { return grid_; }
    /// The scene's materials, indexed by fields::body.
    [[nodiscard]] const std::vector<M>& materials() const noexcept { return materials_; }
    /// The options the solver was built with.
    [[nodiscard]] const solver_options<S>& options() const noexcept { return options_; }
    /// The threads the solver's parallel loops use: options().threads where it is positive,
    /// otherwise OpenMP's default (1 without OpenMP). An observer with a parallel pass of its
    /// own takes as many, as the library's diagnostics do.
    [[nodiscard]] int threads() const noexcept {
        return options_.threads > 0 ? options_.threads : detail::default_threads();
    }
    /// The partition of bodies into velocity fields (multi_field::Partition).
    [[nodiscard]] const Part& partition() const noexcept { return partition_; }
    /// Simulated time so far (s).
    [[nodiscard]] real time() const noexcept { return time_; }

    /// Set the clock of a run resumed from saved particles (io/checkpoint.hpp): the simulated
    /// time (s) and the number of steps already taken. The next step re-checks the particles.
    /// \throws gimlet::invalid_parameter if t is negative or not finite.
    void resume_at(real t, std::uint64_t steps_taken) {
        require(std::isfinite(double(t)) && t >= 0, "resume time (s)", double(t), "finite and >= 0");
        time_ = t;
        steps_ = steps_taken;
        state_touched_ = true;
        pending_health_.valid = false;
    }
    /// Steps taken so far (counting those before a resume).
    [[nodiscard]] std::uint64_t steps() const noexcept { return steps_; }
    /// How many particles the last step found light (solver_options::light_particle_ratio),
    /// those left to FLIP because no node of theirs had other mass included.
    [[nodiscard]] std::size_t light_particles() const noexcept { return lights_.count(); }
    /// Wall-clock time per phase of the steps so far (see docs/performance.md).
    [[nodiscard]] const step_timings& timings() const noexcept { return timings_; }
    /// The silent guards that acted so far (health_events). A resumed run counts from its resume.
    [[nodiscard]] const health_events& health() const noexcept { return health_; }

    /// Whether the solver can run on many processes (gimlet::distributed_solver).
    static constexpr bool distributed = Distributed;
    /// The processes the run is split between (solver_options::processes), or null: one process
    /// (always, for a solver that is not a distributed_solver: its many-process paths fold away).
    [[nodiscard]] gimlet::processes* processes() const noexcept {
        if constexpr (Distributed) return options_.processes.get();
        else return nullptr;
    }
    /// Particle i's number in the whole run: its index in one process's store, whatever the
    /// number of processes (the seeding order, renumbered where the particles are sorted).
    [[nodiscard]] std::uint64_t ordinal(std::size_t i) const noexcept { return ordinal_.empty() ? i : ordinal_[i]; }
    /// Every process's particles in ordinal order (one process's store) on the first process,
    /// none on the others; on one process, a copy of particles(). Collective.
    [[nodiscard]] store_type gathered_particles() const;
    /// Replace the particles by `whole`, the whole run's in ordinal order (every process passes
    /// the same): each process keeps those of its own slabs. The next step checks them.
    /// Collective.
    void replace_particles(store_type whole);

private:
    using stencil_type = detail::stencil<S, Sh::stencil>;
    // Every particle and node loop of the solver runs in detail::thread_shares' schedule: each
    // thread a fixed share, the same in every loop over the same items, and a thread done early
    // takes chunks of the shares not yet done; each slab pass likewise gives each thread the
    // same slabs of a colour. (The same thread number is the same thread in every parallel
    // region with GCC's and LLVM's runtimes; the OpenMP standard does not promise it.) So a
    // particle's data and a slab's nodes stay near one core, in its caches, from pass to pass
    // (binding the threads, OMP_PROC_BIND and OMP_PLACES, keeps each thread on its core):
    // shares handed out on demand move about half of them between the cores in every pass,
    // which on a 2-core host costs as much as the work. And a slow core (another job on it, a
    // busy neighbour of a virtual machine) or a share of costlier particles holds up the loop by
    // no more than the chunk its thread has claimed, where fixed shares alone wait for the whole
    // share (docs/performance.md, "How the step is organised for speed" and "How the step is organised for speed").
    // Every particle's result, and every node's sum (slab by slab, in particle order), is
    // independent of which thread runs it, so the schedule costs no determinism.
    //
    // Loops shorter than this run on one thread: below it, starting a team costs more than the
    // loop (and a team on a busy machine can stall the whole step).
    static constexpr std::ptrdiff_t parallel_threshold = 4096;
    // A threshold likewise for loops over grid nodes, whose bodies cost a few nanoseconds each:
    // a pass over 16,000 entries takes some 30 us, waking a sleeping thread a few
    // (docs/performance.md).
    static constexpr std::ptrdiff_t node_parallel_threshold = 4 * parallel_threshold;

    // Where particle i's mass goes in the nodal arrays (fields x nodes) at each node of its
    // stencil: entries(i) gives a chooser, called with the stencil's nodes in their order
    // (stencil::for_each, for_each_offset: every node), that returns the index of the field entry. One field
    // per body: its body's block, whatever the node; one field in all: the only block (a
    // compile-time zero). With a partition: the side chosen at the start of the step
    // (stages::field_choice), node by node; once the consistent mass has listed the step's
    // entries (stages::consistent_mass::list), read from that list instead (the same entries,
    // without the side's arithmetic).
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
                return chosen_entry{body * fields_per_body * grid_.size(), grid_.size(), field_choice_.sides(i),
                                    consistent_mass_.list(i)};
        }
    }

    // ---- the step's stages ---------------------------------------------------------------
    //
    // gimlet::solver's schemes (solver/solver.hpp) call these in their order, each timed by the
    // scheme. The phases of docs/physics.md section 1 are fused where their arithmetic allows
    // it, so a step makes few passes over the particles and the nodes: the weights, one scatter
    // (mass, momentum and forces; USF without contact maps its forces after the stress update,
    // USF with contact both), one node pass (v^n, momentum update, v^{n+1}), one gather (with
    // MUSL's re-map scatter), one node pass for MUSL, and one particle pass that updates the
    // material and checks the particle. Each quantity is computed with the same operations as
    // in the unfused order; only the order in which a node sums its particles' contributions is
    // the scatter's (see for_each_particle_by_slab).
    //
    // The stages the schemes call are defined below the class (here, in transfers.hpp and in
    // particle_passes.hpp), not inline: an explicit instantiation of the core compiles them, and
    // an `extern template` declaration keeps them out of a unit that runs a solver of another
    // contact law on a shared core (its schemes are compiled there; docs/performance.md, "Memory,
    // the largest scene, compile time").

    // Whether the material's thermal policy provides the reference isentrope's energy e_s(J)
    // (thermal::isentrope_temperature does), which the volume filter moves the energy along.
    static constexpr bool has_reference_isentrope = requires(const typename M::thermal_type& t) {
        { t.reference_energy(1.0) } -> std::convertible_to<double>;
    };

    // Wall-clock time of `f()`, added to `phase` (and to `part`, a part of that phase, if given).
    // On many processes a stage that throws on one throws on all (processes::together), with the
    // particle named by its ordinal, before any goes on to the next stage's exchanges.
    template <class F>
    void timed(double& phase, F&& f, double* part = nullptr) {
        using clock = std::chrono::steady_clock;
        const auto start = clock::now();
        run_stage(&call_stage<std::remove_reference_t<F>>, const_cast<void*>(static_cast<const void*>(std::addressof(f))));
        const double lap = std::chrono::duration<double>(clock::now() - start).count();
        phase += lap;
        if (part) *part += lap;
    }

    // The step's start: what changed between steps checked, and the guards of the time step this
    // step takes counted (count_health).
    void check_step_start();
    // Weights at x^n of every particle (from particle `first` on; the arrays sized to all).
    void compute_stencils(std::size_t first = 0);

    // The stencil of particle i, computed once and shared by every transfer of the step, and
    // the slab its scatter belongs to.
    void compute_stencil(std::size_t i) {
        const auto p = particles_[i];
        auto& st = stencils_[i];
        st.template compute_with<Sh>(grid_, p.template get<fields::position>(), Sh::half_width(p, grid_.cell()));
        slabs_.assign(i, st.first_row);
    }

    // Whether this step sorts the particles by cell first (solver_options::sort_interval).
    [[nodiscard]] bool sort_due() const noexcept {
        return options_.sort_interval > 0 && steps_ % std::uint64_t(options_.sort_interval) == 0;
    }
    // The particles into the scatter's slabs, the partition's preparation and the step's fields
    // (stages::field_choice).
    void group_into_slabs();
    // An empty grid (with volumetric averaging, the cells' mean stresses for the step's first
    // force map).
    void start_grid();
    // After the first scatter: the light particles (stages::light_particles), and the nodes
    // several fields share (multi_field::exchange) for the contact passes.
    void find_light_particles();
    void find_shared_nodes();  // below the class
    // USF's start-of-step grid velocities v^n (and v^{n+1} = v^n until the forces act), walls
    // applied; after USF's trial contact pass, the grid forces cleared for the force map.
    void start_of_step_velocities();
    void clear_forces();
    // MUSL: the nodal velocities of the re-mapped momenta, the grid update's wall decisions kept.
    void remapped_velocities();
    // Volumetric averaging (stages::volumetric_average), when solver_options::volumetric_average:
    // the cells' mean volumetric rates from the step's grid velocities, and their mean stresses.
    void average_volumetric_rates();
    void average_mean_stress();
    // The volume filter (stages::volume_filter), when solver_options::volume_filter.
    void filter_volumes();
    // What every scheme does last: the particle pass that updates the material (MUSL, USL) and
    // checks every particle, and the clock.
    void finish_step(real dt, bool update_materials);

    // f(i) for every particle, slab by slab and colour by colour (detail::slab_schedule): every
    // node sums its particles' contributions in an order fixed by the grid and the particle
    // order, whatever the thread count. f must not throw.
    template <class F>
    void for_each_particle_by_slab(F&& f) {
        slabs_.for_each(std::ptrdiff_t(particles_.size()) >= parallel_threshold, threads(), std::forward<F>(f));
    }
    // The same, for a pass that adds into the nodal arrays `arrays` (std::vectors over the grid's
    // entries): on many processes, the sums of the nodes two processes share are completed in
    // the one-process order (processes::after_colour).
    template <class F, class... Arrays>
    void for_each_particle_by_slab_into(F&& f, Arrays&... arrays) {
        slabs_.for_each(std::ptrdiff_t(particles_.size()) >= parallel_threshold, threads(), std::forward<F>(f),
                        fold_of(arrays...));
    }
    // The exchange of a slab pass that adds into `arrays` (none on one process).
    template <class... Arrays>
    [[nodiscard]] auto fold_of(Arrays&... arrays) {
        gimlet::processes* p = processes();
        return detail::fold_exchange<sizeof...(Arrays)>{p, {nodal_array::of(arrays, grid_.size(), p != nullptr)...}};
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
    // `arrays`: the nodal arrays the pass adds into, as for_each_particle_by_slab_into.
    template <class F, class... Arrays>
    void for_each_particle_by_slab_reaching(const std::vector<std::uint8_t>& rows, F&& f, Arrays&... arrays) {
        if constexpr (sizeof...(Arrays) == 0) {
            slabs_.for_each_reaching(rows, std::ptrdiff_t(particles_.size()) >= parallel_threshold, threads(), std::forward<F>(f));
        } else {
            slabs_.for_each_reaching(rows, std::ptrdiff_t(particles_.size()) >= parallel_threshold, threads(),
                                     std::forward<F>(f), fold_of(arrays...));
        }
    }

    // ---- transfers (solver/transfers.hpp): P2G, the grid update, G2P with the light nodes
    // and the damping transfer
    template <bool Forces>
    void scatter();
    // The scatters the step calls: mass, momentum and forces; USF's first, which maps the forces
    // too only with contact; USF's force map after the stress update.
    void scatter_all();
    void scatter_for_usf();
    void map_forces();
    void nodal_velocity(std::vector<vector>& out);
    void clear_grid();
    void fill_entries(std::vector<vector>& out, const vector& value);
    // f(e) for every grid entry of the field slots swept this step (stages::field_choice::swept),
    // split between the threads on a large grid; f(e) writes entry e only.
    template <class F>
    void for_each_swept_entry(F&& f);
    [[nodiscard]] std::size_t swept_fields() const noexcept { return field_choice_.swept(); }
    // v^n (with_old_velocity), the consistent mass's forces (stages::consistent_mass), the
    // momentum update and v^{n+1}, the walls.
    void update_grid_momentum(real dt, bool with_old_velocity);
    void grid_to_particles(real dt, bool remap);
    template <bool Lights>
    void grid_to_particles_pass(real dt, bool remap);
    [[nodiscard]] bool on_light_node(std::size_t e, real w, const vector& g) const;
    [[nodiscard]] vector light_node_change(std::size_t i, real dt) const;

    // ---- particle passes (solver/particle_passes.hpp): the material update, the step's last
    // pass, sorting
    void update_material_points(real dt);
    template <class After>
    std::ptrdiff_t material_pass(real dt, const std::vector<vector>& vg, bool update_materials, After&& after);
    void update_material_point(std::size_t i, real dt, const std::vector<vector>& vg);
    // With hoop_rate (axisymmetric space), L_thetatheta = sum v_ir T_ip there too.
    [[nodiscard]] matrix velocity_gradient(std::size_t i, const std::vector<vector>& vg, real* hoop_rate = nullptr) const;
    // How many particles the material passes update at once: two in the lanes of one vector
    // where the material allows it (lanes_capable, update_material_pair), else one.
    static constexpr std::ptrdiff_t material_group = lanes_capable<M, S> ? 2 : 1;
    [[nodiscard]] bool update_material_pair(std::size_t i, real dt, const std::vector<vector>& vg);
    [[nodiscard]] matrix force_stress(std::size_t i) const;
    // V_p sigma_thetatheta, the hoop stress's part of the radial force (axisymmetric space).
    [[nodiscard]] real hoop_force_stress(std::size_t i) const;
    void sort_by_cell();

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
    struct across_caller {
        solver_core* self;
        [[nodiscard]] std::uint64_t ordinal(std::size_t i) const noexcept { return self->ordinal(i); }
        template <class F, class... Arrays>
        void for_each_particle_by_slab_into(F&& f, Arrays&... arrays) const {
            self->for_each_particle_by_slab_into(std::forward<F>(f), arrays...);
        }
        template <class Get, class Merge>
        void merge_shared(std::size_t blocks, Get&& get, Merge&& merge) const {
            self->merge_shared(blocks, get, merge);
        }
        [[nodiscard]] double max(double x) const {
            auto* p = self->processes();
            return p ? p->max(x) : x;
        }
        [[nodiscard]] std::uint64_t sum(std::uint64_t n) const {
            auto* p = self->processes();
            return p ? p->sum(n) : n;
        }
        [[nodiscard]] bool any(bool flag) const {
            auto* p = self->processes();
            return p ? p->sum(std::uint64_t(flag)) > 0 : flag;
        }
        [[nodiscard]] bool owns(std::size_t node) const { return self->owns_node(node); }
    };
    template <class Store>
    using partition_view_type =
        multi_field::partition_view<Store, std::vector<stencil_type>, grid<S>, slab_caller, index_caller, across_caller>;
    template <class Store>
    [[nodiscard]] partition_view_type<Store> partition_view() {
        return {particles_, stencils_, grid_, materials_.size(), slab_caller{this}, index_caller{this}, across_caller{this}};
    }
    // At every node two processes both hold, in `blocks` blocks of the grid's nodes, entry e:
    // merge(e, the other process's get(e)) (partition_view's across.merge_shared).
    template <class Get, class Merge>
    void merge_shared(std::size_t blocks, Get& get, Merge& merge);
    // Whether node `node` counts as this process's: its row's slab is (always, on one process).
    [[nodiscard]] bool owns_node(std::size_t node) const;
    // Whether the partition has the optional prepare hook, asked each step (stages::field_choice;
    // multi_field::check, above, refuses one in a form this would miss). The view is a const
    // lvalue, so `prepare(const View&)` and a template `prepare(View&)` both take it.
    static constexpr bool partition_prepares = requires(Part& p, const partition_view_type<const store_type>& v) {
        p.prepare(v);
    };
    static constexpr bool partition_initializes = requires(Part& p, partition_view_type<store_type>& v) { p.initialize(v); };
    // What runs on many processes so far (detail::check_distributable refuses the rest).
    static constexpr bool distributable =
        !has_driven_particles && !axisymmetric &&
        ((!partition_prepares && !partition_initializes) || requires { requires Part::distributes; });

    // The guards of the time step this step takes (stable_time_step), into health_.
    void count_health() {
        if constexpr (Distributed)
            if (processes()) return count_health_across();
        pending_health_.commit(health_, steps_, [&](std::size_t i) {
            return describe_particle(particles_[i], steps_, double(time_));
        });
    }
    // The same on many processes: the counts summed, the first the lowest ordinal's.
    void count_health_across();

    // State set before the first step or changed between steps (by the user or a restart) is
    // checked before anything uses it, so a bad value is blamed on its own particle, not on a
    // neighbour or on the time step it would spoil.
    void check_pending() {
        if constexpr (Distributed)
            if (processes()) return check_pending_across();
        if (!state_touched_) return;
        check_particles();
        check_light_possible();  // the masses or volumes may have changed
        state_touched_ = false;
    }
    // The same on many processes: every process checks where any was touched, and a bad
    // particle on one stops all (together) before the collectives that follow.
    void check_pending_across() {
        if (many().max(state_touched_ ? 1.0 : 0.0) == 0) return;
        together([&] {
            require(particles_.size() == ordinal_.size(), "particles on this process after a change between steps",
                    double(particles_.size()),
                    std::to_string(ordinal_.size()) + ": particles are not added or removed on many processes");
            check_particles();
        });
        check_light_possible();
        state_touched_ = false;
    }

    // Whether any particle can be light (stages::light_particles::check_possible): out of the
    // class, as check_pending is reached from every unit that steps a solver.
    void check_light_possible();  // below the class

    // Stop on non-finite values, inverted particles or particles off the grid; report the
    // lowest-numbered offender so the message does not depend on the thread count.
    void check_particles();  // below the class

    [[nodiscard]] bool healthy(std::size_t i) const { return detail::particle_healthy(particles_[i], grid_); }
    [[nodiscard]] std::string problem(std::size_t i) const { return detail::particle_problem(particles_[i], grid_); }

    [[noreturn]] void fail(std::size_t i, const std::string& what) const {
        throw numerical_error(describe_particle(particles_[i], steps_, double(time_)) + ": " + what);
    }

    // ---- many processes (solver_options::processes) ---------------------------------------
    // A stage `f` run by timed(): on one process called, on many inside together(). Through a
    // function pointer that run_stage does not inline, so that each stage's body is compiled
    // once, not once for each branch (it would double the compile time of every solver).
    template <class F>
    static void call_stage(void* f) {
        (*static_cast<F*>(f))();
    }
    [[gnu::noinline]] void run_stage(void (*call)(void*), void* f) {
        if constexpr (Distributed)
            if (processes()) return together([&] { call(f); });
        call(f);
    }
    // f() on every process; where it throws on one, it throws on all, the message naming the
    // particle by its ordinal (describe_particle names it by its index in this process's store).
    void together(const std::function<void()>& f);
    // The processes, in the members that only a run on many processes reaches.
    [[nodiscard]] gimlet::processes& many() const noexcept { return *options_.processes; }
    // `message` with describe_particle's local index replaced by the particle's ordinal (into
    // *key where given).
    [[nodiscard]] std::string with_ordinal(const std::string& message, double* key = nullptr) const;
    // The particles of this process's slabs kept, in their order, their ordinals their indices.
    void keep_own_particles();
    // From particle `first` on, those of this process's slabs kept in order and the others
    // dropped; ordinal_ gains the kept ones' ordinals (`ordinal` for particle `first`, then on).
    void keep_own_from(std::size_t first, std::uint64_t ordinal);
    // Whether entries [first, last) hold one of the window's nodes (always, on one process).
    [[nodiscard]] bool window_holds(std::size_t first, std::size_t last) const noexcept {
        if (window_.empty()) return true;
        const std::size_t nodes = grid_.size();
        for (std::size_t e = first; e < last;) {
            const std::size_t base = e / nodes * nodes, a = e - base, b = std::min(last, base + nodes) - base;
            for (const auto& [lo, hi] : window_)
                if (a < hi && lo < b) return true;
            e = base + nodes;
        }
        return false;
    }
    // The scene's particles; on many processes those of this process's slabs, in seeding order,
    // each with its ordinal (its index in the whole seeding), kept batch by batch as they are
    // seeded, so that no process holds the whole scene.
    void seed(const scene::scene<S, M>& sc);
    // window_: this process's slabs' rows and the band above its last slab (wrapped on a
    // periodic axis).
    void set_window();
    // Particles whose stencils start in another process's slabs go there, each process's kept in
    // ordinal order (after compute_stencils).
    void migrate();
    // A particle's record for another process (its ordinal, then its columns' bytes): its size,
    // particle i's appended to `out` (`record`: the size), a record read into particle k of `to`;
    // particle i of `from` copied to particle k of `to`.
    [[nodiscard]] std::size_t record_bytes() const;
    void append_record(std::size_t i, std::size_t record, std::vector<std::byte>& out) const;
    static void read_record(const std::byte* record, store_type& to, std::size_t k);
    static void copy_particle(const store_type& from, std::size_t i, store_type& to, std::size_t k);
    // After a sort: the ordinals renumbered to the one-process order (sort_by_cell's keys are
    // ordered by slab, and each process owns consecutive slabs).
    void renumber();

    // The stages are friends: each reads and writes what its class comment lists.
    template <Space>
    friend class stages::light_particles;
    template <Space, std::size_t>
    friend class stages::consistent_mass;
    template <Space>
    friend class stages::volume_filter;
    template <Space>
    friend class stages::volumetric_average;
    template <std::size_t, std::size_t>
    friend class stages::field_choice;
    template <Space>
    friend class stages::driven_particles;
    template <Space>
    friend class stages::damping_transfer;
    // Stateless: G2P's blend of FLIP towards PIC (solver_options::pic_fraction).
    using damping_transfer = stages::damping_transfer<S>;

    // What the stages share: the scene's state, the step's weights and slabs, the grid.
    solver_options<S> options_;
    grid<S> grid_;
    std::vector<M> materials_;
    store_type particles_;
    std::vector<stencil_type> stencils_;
    // The scatter's slabs of node rows (for_each_particle_by_slab).
    detail::slab_schedule<std::max(Sh::stencil - 1, 1)> slabs_;
    real mass_cutoff_ = 0;
    std::vector<vector> wall_free_;  // per node entry: 1 where the walls leave a force component free
    Part partition_;
    multi_field::exchange<S> exchange_;  // multi-field contact only (empty otherwise)

    // The optional stages, each with its own state (solver/stages/).
    stages::field_choice<fields_per_body, stencil_type::nodes> field_choice_;
    stages::light_particles<S> lights_;
    stages::consistent_mass<S, stencil_type::nodes> consistent_mass_;
    stages::volume_filter<S> volume_filter_;
    stages::volumetric_average<S> volumetric_average_;
    [[no_unique_address]] std::conditional_t<has_driven_particles, stages::driven_particles<S>, detail::nothing> driven_;

    // The step's own state: the clock, the counters, the checks between steps.
    real time_ = 0;
    std::uint64_t steps_ = 0;
    step_timings timings_;
    health_events health_;
    mutable detail::pending_health pending_health_;  // stable_time_step's guards, until the step is taken
    std::vector<std::uint64_t> ordinal_;  // on many processes, each particle's ordinal (ordinal())
    // On many processes, the node ranges (of every field block) this process's particles reach,
    // increasing and apart: the node passes sweep these only (for_each_swept_entry, the shared
    // nodes' search, the consistent mass's first pass); and for_each_swept_entry's runs.
    std::vector<std::pair<std::size_t, std::size_t>> window_, runs_;
    bool state_touched_ = true;  // the scene's particles are checked before the first step
};

// Members defined outside their class: not inline, so that an `extern template` declaration of
// the core keeps them, and the stages they lead to, out of a unit that only constructs and runs
// a solver (docs/performance.md, "Memory, the largest scene, compile time").

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::solver_core(const scene::scene<S, M>& sc, const solver_options<S>& options, const Part& partition,
                         std::optional<double> friction)
    : options_(options), grid_(sc.grid(), Sh::stencil), partition_(partition) {
    if constexpr (!Distributed) detail::refuse_processes_for_one_process_solver(options_.processes != nullptr);
    detail::check_setup(sc, options_, friction);
    for (const auto& b : sc.bodies()) materials_.push_back(b.material);
    // One velocity field per body (Bardenhagen et al. 2000), or the partition's number of
    // them; a single-field policy keeps one.
    const std::size_t fields = multi_field ? materials_.size() * fields_per_body : 1;
    // Refused before the nodal arrays are allocated, and before the processes take this
    // solver's slabs (a processes object keeps the first solver's for good).
    detail::check_options_for(options_, has_reference_isentrope, grid_.size() * fields);
    if (processes()) detail::check_distributable<!distributable>(options_, false);  // light particles below
    slabs_.set_up(grid_.nodes(dim - 1), grid_.periodic(dim - 1));
    auto* p = processes();
    if constexpr (Distributed)
        if (p) {
            p->set_up(slabs_.layout(std::size_t(grid_.stride(dim - 1)), grid_.size()));
            set_window();
        }
    // A failure while seeding (a bad scene, no memory for a process's share) stops all.
    if (p) p->together([&] { seed(sc); });
    else seed(sc);
    real heaviest = 0;
    for (real m : particles_.template column<fields::mass>()) heaviest = std::max(heaviest, m);
    if (auto* p = processes()) heaviest = real(p->max(double(heaviest)));  // exact: the whole run's
    mass_cutoff_ = real(options_.mass_cutoff) * heaviest;
    check_light_possible();  // refused on many processes where any particle can be light
    if constexpr (multi_field) grid_.set_field_count(fields);
    // Which components of a node's force the walls leave free (1) or take (0): the projection
    // apply_walls makes on velocities, for the forces of light nodes (grid_to_particles).
    wall_free_.assign(grid_.entries(), vector::Ones());
    grid_.apply_walls(wall_free_, wall_pass::none);  // a one-sided wall holds no force component for good
    if constexpr (requires(Part& p, partition_view_type<store_type>& v) { p.initialize(v); }) {
        compute_stencils();
        slabs_.bucket();
        auto view = partition_view<store_type>();
        partition_.initialize(view);
    }
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::~solver_core() = default;

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
auto solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::stable_time_step() const -> real {
    const real dt = detail::stable_time_step(particles_, materials_, grid_, options_, threads(), parallel_threshold, steps_,
                                             pending_health_);
    // The least of the processes' steps: C h / max (c + |v|) rounds monotonically in the speed.
    if (auto* p = processes()) return real(p->min(double(dt)));
    return dt;
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::check_particles() {
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

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::check_step_start() {
    check_pending();
    count_health();
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::group_into_slabs() {
    slabs_.bucket(std::ptrdiff_t(particles_.size()) >= parallel_threshold, threads());
    field_choice_.prepare(*this);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::start_grid() {
    if (options_.volumetric_average) average_mean_stress();
    clear_grid();
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::find_light_particles() {
    lights_.find(*this);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::start_of_step_velocities() {
    nodal_velocity(grid_.velocity_old);
    grid_.velocity = grid_.velocity_old;
    grid_.apply_walls(grid_.velocity);
    if constexpr (has_driven_particles) driven_.impose(*this, grid_.velocity);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::clear_forces() {
    std::fill(grid_.force.begin(), grid_.force.end(), vector::Zero());
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::remapped_velocities() {
    nodal_velocity(grid_.velocity);
    grid_.apply_walls(grid_.velocity, wall_pass::keep);  // the grid update's decisions hold
    if constexpr (has_driven_particles) driven_.impose(*this, grid_.velocity);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::average_volumetric_rates() {
    volumetric_average_.average_rates(*this, grid_.velocity);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::average_mean_stress() {
    volumetric_average_.average_stress(*this);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::filter_volumes() {
    if constexpr (has_reference_isentrope) volume_filter_.apply(*this);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::compute_stencils(std::size_t first) {
    const auto n = static_cast<std::ptrdiff_t>(particles_.size() - first);
    stencils_.resize(particles_.size());
    slabs_.resize(particles_.size());
    detail::thread_shares shares(n, threads(), n >= parallel_threshold);
    GIMLET_OMP(parallel num_threads(shares.team()))
    for (auto claimed = shares.start(); shares.claim(claimed);)
        for (std::ptrdiff_t i = claimed.first, end = claimed.last; i < end; ++i)
            compute_stencil(first + static_cast<std::size_t>(i));
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::check_light_possible() {
    lights_.check_possible(*this);  // on many processes, over every process's particles
    // (Light particles are refused on many processes so far.)
    if (processes() && lights_.possible()) detail::check_distributable<false>(options_, true);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::find_shared_nodes() {
    exchange_.find_shared_nodes(grid_, mass_cutoff_, steps_, double(time_), stencils_,
                                particles_.template column<fields::mass>(), fields_per_body,
                                [&](std::size_t i) { return entries(i); },
                                [&](const std::vector<std::uint8_t>& rows, auto&& f, auto&... arrays) {
                                    for_each_particle_by_slab_reaching(rows, f, arrays...);
                                },
                                threads(),
                                std::ptrdiff_t(grid_.entries()) >= node_parallel_threshold, processes(), window_);
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::scatter_all() {
    scatter<true>();
}

template <Space S, shape::Shape Sh, Material M, FieldList Fields, bool MultiField, multi_field::Partition Part, bool Distributed>
void solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::scatter_for_usf() {
    if constexpr (multi_field) scatter<true>();
    else scatter<false>();
}

}  // namespace gimlet
