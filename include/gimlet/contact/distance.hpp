// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The reference paper's distance-switched contact.

#include "gimlet/contact/bardenhagen.hpp"

namespace gimlet::contact {

/// The reference paper's improved criterion (its section 2.2, equation R_i^pq <= L/2;
/// docs/physics.md section 3): the Bardenhagen et al. (2000) correction is applied at a node only
/// where the two bodies are close there, and only while they approach (the implied normal force
/// is compressive; when it would turn tensile the correction is dropped and the bodies separate).
///
/// **How the gap is measured.** At node i, bodies a and b share the normal
/// n_ab = (n^a - n^b)/|n^a - n^b| from their mass gradients (the one their correction uses).
/// Each body's particle centres that map to node i are projected on it, from the node, and the
/// furthest towards the other body is kept: reach_ab = max_{p in a} (x_p - x_i) . n_ab and
/// reach_ba = max_{q in b} (x_q - x_i) . (-n_ab). The distance between the facing particle
/// centres along n_ab is gap = -(reach_ab + reach_ba) (node_view::gap), the paper's R_i^pq.
/// Contact acts where gap <= h/2: touching bodies with 2x2 particles per cell have facing
/// centres exactly h/2 apart, so contact starts when the particle domains meet, not when the
/// bodies first share a node (up to two cells earlier). The paper prints the criterion with
/// max/min signs that do not make a distance; this is its meaning. Where three or more bodies
/// meet, each pair is measured along its own normal.
class distance {
public:
    /// One velocity field per body (contact::Contact).
    static constexpr bool multi_field = true;
    /// It keeps no per-particle state.
    using required_fields = field_list<>;

    /// \param friction Coulomb coefficient mu >= 0; \param gap_fraction the switching distance
    /// in cells (the paper's 1/2), in (0, 2].
    explicit distance(double friction = 0.0, double gap_fraction = 0.5) : mu_(friction), gap_(gap_fraction) {
        require(!std::isnan(friction) && friction >= 0.0, "contact friction coefficient mu", friction, ">= 0");
        require(gap_fraction > 0.0 && gap_fraction <= 2.0, "contact switching distance (cells)", gap_fraction,
                "(0, 2]");
    }

    /// In contact once the facing particle centres are within the switching distance.
    template <Space S>
    [[nodiscard]] bool in_contact(const pair_view<S>& pair) const noexcept {
        using real = typename S::real;
        // A small tolerance: touching bodies sit exactly at h/2 and must count as in contact.
        return pair.gap <= real(gap_) * pair.cell * (real(1) + real(1e-9));
    }

    /// mu, the Coulomb coefficient (contact::Law).
    [[nodiscard]] double friction() const noexcept { return mu_; }
    /// The switching distance, in cells.
    [[nodiscard]] double switching_distance() const noexcept { return gap_; }

private:
    double mu_, gap_;
};

static_assert(Contact<distance>);

}  // namespace gimlet::contact
