// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// What gimlet::solver's constructor refuses, by name (invalid_parameter), besides what the
/// options, the scene and the seeding check themselves.

#include "gimlet/core/error.hpp"
#include "gimlet/core/grid.hpp"
#include "gimlet/scene/scene.hpp"
#include "gimlet/solver/options.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace gimlet::detail {

/// Before the particles are seeded: the options, at least one body, no one-sided wall under USF,
/// and the contact law's Coulomb coefficient (`friction`, none for a policy that is not a
/// contact::Law).
template <class S, class M>
void check_setup(const scene::scene<S, M>& sc, const solver_options<S>& options, std::optional<double> friction) {
    options.validate();
    require(!sc.bodies().empty(), "number of bodies", 0.0, ">= 1");
    // USF strains with the start-of-step velocities, and a one-sided wall decided there and
    // again after the forces would work on other velocities than the strain saw: the bar of
    // tests/core/test_wall.cpp gains 8 % energy. Refused until the wall decides on USF's
    // trial velocities, as contact does.
    for (int d = 0; d < S::dim; ++d)
        if (sc.grid().bc[d] == boundary::wall && options.scheme == update_scheme::usf)
            throw invalid_parameter("update scheme with a one-sided wall (boundary::wall) along " +
                                        std::string(axis_name(d)),
                                    "usf", "musl or usl (USF with a one-sided wall creates energy)");
    if (friction)
        require(*friction >= 0.0, "contact law friction() (Coulomb coefficient mu)", *friction,
                ">= 0 (infinity: no slip)");
    if constexpr (is_axisymmetric_v<S>) {
        // The filters average over cells of the (r, z) plane, which are rings of different
        // volume per radian; neither is derived for that yet.
        if (options.volume_filter)
            throw invalid_parameter("volume_filter", "true", "false in an axisymmetric space (not derived for rings)");
        if (options.volumetric_average)
            throw invalid_parameter("volumetric_average", "true",
                                    "false in an axisymmetric space (not derived for rings)");
        // A uniform body force with a radial component is not axisymmetric.
        require(options.body_force[0] == 0, "body_force along r (m/s^2) in an axisymmetric space",
                double(options.body_force[0]), "0 (a body force acts along the axis z only)");
    }
}

/// Once the particles are seeded: the volume filter only for a material with a reference
/// isentrope, and the consistent mass only on a grid of at most 2^32 - 1 node entries
/// (`entries`: fields x nodes), whose particle entry lists are 32-bit.
template <class S>
void check_options_for(const solver_options<S>& options, bool has_reference_isentrope, std::size_t entries) {
    if (options.volume_filter && !has_reference_isentrope)
        throw invalid_parameter("volume_filter", "true",
                                "false for this material: the filter moves each particle's energy along the reference "
                                "isentrope, which its thermal policy does not provide (reference_energy(J); "
                                "thermal::isentrope_temperature does)");
    if (options.consistent_mass_iterations > 0 && entries > std::size_t(UINT32_MAX))
        throw invalid_parameter("consistent_mass_iterations (with a grid of " + std::to_string(entries) +
                                    " node entries, fields x nodes)",
                                std::to_string(options.consistent_mass_iterations),
                                "0 on a grid of more than 4294967295 node entries");
}

/// Processes given to a solver compiled for one process (gimlet::solver's Distributed false):
/// refused by name, pointing to gimlet::distributed_solver.
inline void refuse_processes_for_one_process_solver(bool given) {
    if (given)
        throw invalid_parameter("solver_options::processes with a gimlet::solver", "set",
                                "null: a solver that runs on many processes is a gimlet::distributed_solver "
                                "(gimlet::solver with its last parameter, Distributed, true)");
}

/// On many processes (solver_options::processes): what the distributed step does not do yet,
/// refused by name. `Unsupported`: driven particles, an axisymmetric space or a partition with
/// hooks that does not say it distributes (multi_field::Partition); `light_possible`: whether any particle can be
/// light (stages::light_particles), over the whole scene.
template <bool Unsupported, class S>
void check_distributable(const solver_options<S>& options, bool light_possible) {
    const std::string what = "on many processes (solver_options::processes), which do not distribute it yet";
    if constexpr (Unsupported)
        throw invalid_parameter("solver_options::processes with this solver", "set",
                                "null: driven particles, axisymmetric spaces and partitions with hooks that do not "
                                "say they distribute (multi_field::Partition's distributes) run on one process so far");
    if (options.volume_filter) throw invalid_parameter("volume_filter", "true", "false " + what);
    if (options.volumetric_average) throw invalid_parameter("volumetric_average", "true", "false " + what);
    if (light_possible)
        throw invalid_parameter("light_particle_ratio (with bodies whose densities differ by more than it)",
                                to_text(options.light_particle_ratio), "0 " + what + " (light particles)");
}

}  // namespace gimlet::detail
