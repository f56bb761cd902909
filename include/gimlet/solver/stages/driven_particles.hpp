// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The driven-particles stage: particles that move with a velocity the user prescribes
/// (fields::driven, fields::driven_velocity), and carry it to the nodes they weigh, as a loading
/// (docs/guide.md, "Driving particles").

#include "gimlet/core/describe.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/grid.hpp"
#include "gimlet/core/space.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace gimlet::stages {

/// The driven-particles stage. A particle whose fields::driven has bit d set moves along axis d
/// with component d of its fields::driven_velocity v_d: after every grid update that sets nodal
/// velocities (the momentum update, USF's start-of-step velocities, MUSL's re-map), component d
/// of each node (each field's entry) that such particles weigh takes their mass-weighted mean,
/// v_id = sum_p S_ip m_p v_dp / sum_p S_ip m_p over the particles driving d, the walls and the
/// axis applied after it; in the grid-to-particle pass the particle's component d takes
/// v_pd = v_dd and x_pd += dt v_dd (its other components update as any particle's). So a driven
/// layer imposes its motion on the material it touches, which strains from those nodal
/// velocities (the way NairnMPM's rigid particles set their nodes' velocities). The driven particles' own
/// material updates from the same nodal velocities. What the driven particles do on the body
/// is work from outside: the energy audit (diagnostics::conservation) does not count it.
///
/// Reads: the particles' flags, driven velocities and masses, the step's stencils and node
/// entries. Writes: the nodal velocities given, and its own sums. Compiled in only where the
/// particles carry fields::driven; without it the solver has no code of it.
///
/// \tparam S the space.
template <Space S>
class driven_particles {
public:
    /// The scalar type of S.
    using real = typename S::real;
    /// S::vector.
    using vector = typename S::vector;

    /// The driven particles' nodes in `vg` (one value per grid entry) take the driven velocity,
    /// then the walls (wall_pass::keep: the step's decisions hold). The sums run on one thread
    /// in particle order, so the result does not depend on the thread count.
    template <class Core>
    void impose(Core& c, std::vector<vector>& vg) {
        const auto& flag = c.particles_.template column<fields::driven>();
        const auto& vd = c.particles_.template column<fields::driven_velocity>();
        const auto& m = c.particles_.template column<fields::mass>();
        if (mass_.size() != vg.size()) {
            mass_.assign(vg.size(), vector::Zero());
            momentum_.assign(vg.size(), vector::Zero());
        }
        touched_.clear();
        for (std::size_t i = 0; i < flag.size(); ++i) {
            if (!flag[i]) continue;
            if (flag[i] >= (1u << S::dim))
                throw invalid_parameter(describe_particle(c.particles_[i], c.steps_, double(c.time_)) + ": driven",
                                        std::to_string(unsigned(flag[i])),
                                        "0 to " + std::to_string((1u << S::dim) - 1) +
                                            " (bit d drives the velocity component along axis d)");
            if (!vd[i].allFinite())
                throw invalid_parameter(describe_particle(c.particles_[i], c.steps_, double(c.time_)) +
                                            ": driven_velocity (m/s)",
                                        "not finite", "finite on every axis");
            vector driven = vector::Zero();  // 1 on the driven components
            for (int d = 0; d < S::dim; ++d) driven[d] = (flag[i] >> d) & 1u ? real(1) : real(0);
            auto at = c.entries(i);
            c.stencils_[i].for_each([&](std::size_t node, real w, const vector&) {
                const std::size_t e = at(node);
                if (!(w > 0)) return;
                if (mass_[e].isZero()) touched_.push_back(e);
                mass_[e] += w * m[i] * driven;
                momentum_[e] += w * m[i] * driven.cwiseProduct(vd[i]);
            });
        }
        for (const std::size_t e : touched_) {
            for (int d = 0; d < S::dim; ++d)
                if (mass_[e][d] > 0) vg[e][d] = momentum_[e][d] / mass_[e][d];
            mass_[e] = vector::Zero();
            momentum_[e] = vector::Zero();
        }
        if (!touched_.empty()) c.grid_.apply_walls(vg, wall_pass::keep);
    }

private:
    std::vector<vector> mass_;      // per grid entry and component, zero outside impose
    std::vector<vector> momentum_;  // per grid entry, zero outside impose
    std::vector<std::size_t> touched_;
};

}  // namespace gimlet::stages
