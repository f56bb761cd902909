// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The solver's run-time options and its timings.

#include "gimlet/core/error.hpp"
#include "gimlet/core/space.hpp"

#include "gimlet/core/processes.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace gimlet {

/// Order of the stress update within a step (Bardenhagen 2002; Wallstedt & Guilkey 2008).
enum class update_scheme {
    musl,  ///< modified update stress last: stress from re-mapped particle velocities (default)
    usl,   ///< update stress last, from the updated grid velocities
    usf,   ///< update stress first, from the velocities of the particle-to-grid map
};

/// Run-time options of the step. Validated when the solver is built.
template <Space S>
struct solver_options {
    /// Order of the stress update within a step (default MUSL).
    update_scheme scheme = update_scheme::musl;
    /// PIC fraction alpha in [0, 1]: v_p = (1 - alpha) v_FLIP + alpha v_PIC (0 = pure FLIP, and
    /// nothing of the blend is computed). The kinetic energy the blend removes goes into the
    /// particles' internal energy, exactly in sum (docs/equations.md, "Damping transfer"; where
    /// particles are light, light_particle_ratio, they take no blend and no share of its heat,
    /// and the sum is short by their part).
    double pic_fraction = 0.0;
    /// Courant number C in (0, 1]: dt = C h / max_p (c_p + |v_p|) (docs/physics.md section 1, step 6).
    /// At most 0.7 with USL, which turns unstable between 0.70 and 0.72 (MUSL and USF are stable to 1).
    double cfl = 0.4;
    /// Nodes lighter than this fraction of the heaviest particle's mass are light nodes: their
    /// force is never divided by their mass (their velocity stays the mean of their particles'),
    /// and it goes back to the particles that exerted it, so momentum stays exact (see
    /// docs/equations.md, "Light nodes"). In [0, 1e-3].
    double mass_cutoff = 1e-12;
    /// A particle whose material is less dense than this fraction of the densest material with
    /// a nonzero weight on the nodes where it has one (in its own field; reference densities,
    /// m / V0) is a light particle: it takes the velocity of its nodes weighted by how much of
    /// the densest material each carries, and its velocity gradient the same way, and the
    /// momentum that changes goes back to the other particles of its nodes, so momentum stays
    /// exact; the kinetic energy it changes is not booked as heat (docs/equations.md, "Light
    /// particles"). Without it such a particle is flung by the accelerations of its dense
    /// neighbours' edge nodes. Density ratios above it (two materials in one field, densities a
    /// few times apart) are left to the transfer as it is, and particles of one material are
    /// never light against each other, whatever their sizes. 0 = off. In [0, 0.5]. Nothing of it
    /// runs in a scene whose least dense material is at least this fraction of its densest (of
    /// each body, with a multi-field contact, so never where each body has one material).
    double light_particle_ratio = 0.05;
    /// Iterations k towards the grid accelerations of the consistent mass matrix
    /// M_ij = sum_p m_p S_ip S_jp instead of the lumped m_i (docs/equations.md, "Consistent-mass
    /// accelerations"): a^(0) = f/m, a^(j+1) = a^(0) + a^(j) - (M a^(j))/m. The lumped mass makes
    /// the grid a dispersive lattice whose shocks trail grid-scale ringing; the consistent mass
    /// removes most of it. Momentum is kept. Each iteration costs a gather and a scatter over
    /// the stencils, and the grid's highest frequency rises by up to sqrt(k + 1), so
    /// cfl sqrt(k + 1) must stay <= 1 (in lasting tension, noise grows the faster the closer it
    /// is to 1: docs/equations.md, "Stability of the step in tension"); MUSL and USF only (USL is refused).
    /// 0 = the lumped mass (the default: nothing runs). In [0, 8] (4 iterations converge on a
    /// regular lattice). It keeps each particle's node entries as 32-bit numbers (4 bytes per
    /// stencil node: 36 in 2-D and 108 in 3-D with uGIMP), so the solver refuses it on a grid of
    /// more than 2^32 - 1 entries (fields x nodes).
    int consistent_mass_iterations = 0;
    /// Replace each particle's J = det F, before every material update, by the L2 projection of
    /// the particles' J onto the grid's functions (consistent_mass_iterations iterations of the
    /// consistent mass), its energy moved along the reference isentrope and the energy that move
    /// releases returned as heat (docs/equations.md, "Particle-scale state filters", (D)). It
    /// removes the particle-scale pattern a shock leaves that the grid's forces cannot see (the
    /// front peak, particles over-compressed in a collapse) and keeps what the grid resolves.
    /// Measured costs: it heats a freed slab's release (theta +3.2 % against +1.2 % without, USF)
    /// and adds heat to a collapse's hot spots; the 1-D front criteria hold under USF, not MUSL.
    /// Needs consistent_mass_iterations >= 1 (which also switches on the consistent-mass
    /// accelerations) and a material whose thermal policy has a const member
    /// reference_energy(double J) (J/kg on its reference isentrope; thermal::isentrope_temperature).
    /// Off by default.
    bool volume_filter = false;
    /// With multi-field contact, the most of a cell (in cells) two velocity fields may close on
    /// each other in one step the solver chooses (solver::step(), run_until): where fields
    /// sharing a node, their facing particle centres less than two cells apart there, approach at
    /// v, the step is at most contact_closure h / v. The contact decision is taken once a step
    /// on the gaps of the positions at its start; a pair that closes most of a cell in the step it engages
    /// takes that cell's compression in one step, which creates energy in strong impacts under
    /// every scheme (docs/equations.md, "Contact and the time step"). It shortens only the few
    /// steps of an approach faster than about contact_closure / cfl of the wave speed (a quarter
    /// at cfl 0.4). A step given to solver::step(dt) is taken as given: a loop of its own that
    /// wants the bound calls step() or step_at_most(dt). In [0, 1]; 0 = off.
    double contact_closure = 0.1;
    /// Upper bound on the time step (s), > 0.
    double max_time_step = std::numeric_limits<double>::infinity();
    /// Body force per unit mass (m/s^2), e.g. gravity.
    typename S::vector body_force = S::vector::Zero();
    /// OpenMP threads for the particle and node loops; 0 = the OpenMP default. Results do not
    /// depend on it: every reduction runs in a fixed order.
    int threads = 0;
    /// Sort the particles by grid cell before every step whose number (solver::steps()) is a
    /// multiple of this; 0 = never (the default). Particles that share nodes then sit close in
    /// memory, which keeps the transfers cache-friendly once the material has mixed. Sorting
    /// **permutes particle indices** (every field moves with its particle): an index held
    /// across such a step (by an observer, say) then names another particle. It is
    /// deterministic (a stable sort on the cell) and keyed on the step count, so a run resumed
    /// with solver::resume_at sorts at the same steps as the uninterrupted run.
    int sort_interval = 0;
    /// Spread each particle's volume change over a cell (a volumetric F-bar in rate form, after
    /// Coombs et al. 2018): the volumetric strain rate tr L of every particle is replaced by the
    /// volume-weighted mean over the particles of its body that share its stencil's first node
    /// (a cell-sized region: for the odd stencils of uGIMP, cpGIMP and the quadratic B-spline,
    /// the dual cell around a node), its deviatoric part kept; the forces take the region's mean
    /// stress to match. Two bodies are never averaged together. It keeps per-body, per-node sums,
    /// cleared every step. Off by default (see docs/equations.md).
    bool volumetric_average = false;
    /// The processes the run is split between (gimlet::mpi::make_ranks: the grid's slabs along
    /// its last axis, each process the particles of its own); null, the default: one process.
    /// Taken by a gimlet::distributed_solver; a plain gimlet::solver refuses them.
    /// Every process builds the same scene and runs the same calls; particle states, time steps,
    /// the conservation sums and hot_material are bitwise those of one process, for any number of
    /// them (docs/guide.md, "Many processes (MPI)", lists what is refused).
    std::shared_ptr<gimlet::processes> processes;

    /// \throws gimlet::invalid_parameter naming the first option outside its valid range, or a
    /// combination refused (USL with cfl > 0.7 or the consistent mass; volume_filter without the
    /// consistent mass; cfl above 1/sqrt(consistent_mass_iterations + 1)).
    void validate() const {
        require(pic_fraction >= 0.0 && pic_fraction <= 1.0, "pic_fraction", pic_fraction, "[0, 1]");
        require(cfl > 0.0 && cfl <= 1.0, "cfl (Courant number)", cfl, "(0, 1]");
        // USL turns unstable past about 0.707 (measured: docs/equations.md, "One explicit step", step 6).
        if (scheme == update_scheme::usl)
            require(cfl <= 0.7, "cfl (Courant number) with the USL scheme", cfl,
                    "(0, 0.7] (USL turns unstable between 0.70 and 0.72 in 2-D and 3-D; MUSL and USF are stable to 1)");
        require(mass_cutoff >= 0.0 && mass_cutoff <= 1e-3, "mass_cutoff", mass_cutoff, "[0, 1e-3]");
        require(light_particle_ratio >= 0.0 && light_particle_ratio <= 0.5, "light_particle_ratio",
                light_particle_ratio, "[0, 0.5] (0 = off)");
        require(consistent_mass_iterations >= 0 && consistent_mass_iterations <= 8, "consistent_mass_iterations",
                consistent_mass_iterations, "[0, 8] (0 = lumped mass)");
        if (consistent_mass_iterations > 0 && scheme == update_scheme::usl)
            throw invalid_parameter("consistent_mass_iterations with the USL scheme", std::to_string(consistent_mass_iterations),
                                    "0 (USL is unstable above a Courant number of about 0.7 with the lumped mass already; "
                                    "use MUSL or USF with the consistent mass)");
        require(cfl * std::sqrt(1.0 + consistent_mass_iterations) <= 1.0,
                "cfl (Courant number, with consistent_mass_iterations = " + std::to_string(consistent_mass_iterations) + ")", cfl,
                "(0, 1/sqrt(consistent_mass_iterations + 1)]: the consistent mass raises the highest grid frequency by up to that factor");
        if (volume_filter && consistent_mass_iterations < 1)
            throw invalid_parameter("volume_filter (with consistent_mass_iterations = " + std::to_string(consistent_mass_iterations) + ")",
                                    "true", "false, or consistent_mass_iterations in [1, 8] (the filter's projection "
                                    "solves with the consistent mass; the lumped one smooths every field over two cells)");
        require(contact_closure >= 0.0 && contact_closure <= 1.0, "contact_closure (cells a step)", contact_closure,
                "[0, 1] (0 = off)");
        require(max_time_step > 0.0, "max_time_step (s)", max_time_step, "> 0");
        for (int d = 0; d < S::dim; ++d) require_finite("body_force component (m/s^2)", double(body_force[d]));
        require(threads >= 0, "threads", threads, ">= 0 (0 = OpenMP default)");
        require(sort_interval >= 0, "sort_interval (steps)", sort_interval, ">= 0 (0 = never sort)");
    }
};

/// Where the wall-clock time of a solver's steps went (s, summed over its steps): see
/// solver::timings(). Fused loops are counted where they end up.
///
/// Each phase sums the time of the stages the scheme times into it (solver/solver.hpp); the
/// moments between two stages are in none.
struct step_timings {
    double sort = 0;               ///< sorting particles by cell (solver_options::sort_interval)
    double particle_to_grid = 0;   ///< weights, slabs, clearing the grid, P2G of mass, momentum, forces (and mass gradients, reach)
    double grid_update = 0;        ///< nodal velocities, momentum update, walls
    double contact = 0;            ///< multi-field contact at nodes shared by bodies
    double grid_to_particle = 0;   ///< G2P velocity and position update (with MUSL's re-map to the grid)
    double material_update = 0;    ///< velocity gradient, constitutive update, checks
    ///@{
    /// Two parts of particle_to_grid, counted in it too (not in total() again), to tell what in
    /// it scales with the threads: each particle's weights and gradients at x^n, and grouping
    /// the particles into the scatter's slabs with the partition's per-step preparation
    /// (self-contact's split nodes) and the choice of fields. The rest of particle_to_grid is
    /// the clearing, the scatters, and the light particles' and shared nodes' searches.
    double weights = 0, slabs = 0;
    ///@}
    /// The time of the six phases above: sort through material_update (s).
    [[nodiscard]] double total() const noexcept {
        return sort + particle_to_grid + grid_update + contact + grid_to_particle + material_update;
    }
};

}  // namespace gimlet
