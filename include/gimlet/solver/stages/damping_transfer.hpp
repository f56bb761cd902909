// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The damping-transfer stage (solver_options::pic_fraction; docs/equations.md, "Damping
/// transfer"): G2P's FLIP velocity blended towards PIC's, and the kinetic energy the blend
/// removes handed to each particle's internal energy.
///
/// With S the grid-to-particle interpolation, the PIC velocity S v^{n+1} differs from the FLIP
/// velocity v_p + S (v^{n+1} - v^n) by d_p = v_p - S v^n, the part of the particle velocities
/// the grid cannot carry. The blend v_p' = v_FLIP - alpha d_p removes the kinetic energy
/// sum_p m_p (alpha d_p . v_FLIP - alpha^2 |d_p|^2 / 2), and each particle's internal energy
/// takes its share. Writing v_FLIP = v_PIC + d_p, the cross term sum_p m_p d_p . S v^{n+1} is
/// not Galilean-invariant particle by particle (a body at 700 m/s would heat and cool its
/// particles by 700 |d_p|). Summed, it is sum_i v_i^{n+1} . (m_i v_i^n - sum_j K_ij v_j^n),
/// K_ij = sum_p S_ip m_p S_jp, and as K is symmetric with rows summing to m_i (the weights sum
/// to one), that is sum_p m_p cov_p(v^{n+1}, v^n): the covariance of the new and old nodal
/// velocities over the particle's stencil, which is invariant, and close to their variance (so
/// positive) at a stable step. Each particle takes that share.

#include "gimlet/core/space.hpp"

#include <cstddef>

namespace gimlet::stages {

/// The damping-transfer stage. G2P asks fraction() once a pass and, where it is positive,
/// gathers S v^n beside its FLIP and PIC sums and calls blend() for each particle it moves; the
/// light-particles stage compares a light particle's velocity with the blended one (fraction()).
///
/// Reads: the options' pic_fraction, the particle's stencil and node entries, the grid's new and
/// old velocities. Writes: the particle's velocity and specific internal energy (blend). It
/// holds no state: the blend is a term of G2P's per-particle loop, where the stencil's
/// velocities are at hand; a pass of its own would read them again. Chosen at run time
/// (solver_options::pic_fraction > 0); off, G2P tests a flag per particle and per stencil node.
///
/// \tparam S the space.
template <Space S>
class damping_transfer {
public:
    /// The scalar type of S.
    using real = typename S::real;
    /// S::vector.
    using vector = typename S::vector;

    /// alpha, the share of the PIC velocity in the blend (0: off).
    template <class Core>
    [[nodiscard]] static real fraction(const Core& c) {
        return real(c.options_.pic_fraction);
    }

    /// Particle i's velocity v_FLIP - alpha d_p, d_p = v_FLIP - v_PIC, and its internal energy's
    /// share of the kinetic energy that removes: alpha (cross + |d_p|^2) - alpha^2 |d_p|^2 / 2,
    /// with cross its share of sum_p m_p d_p . v_PIC (the covariance above, plus d_p . change
    /// for the light nodes' part, which is its own). `old` is S v^n, `v_pic` S v^{n+1} + change,
    /// `change` the light nodes' velocity change (zero where it has none).
    template <class Core>
    static void blend(const Core& c, std::size_t i, real alpha, const vector& old, const vector& v_pic,
                      const vector& change, const vector& v_flip, vector& v, real& energy) {
        const vector fresh = v_pic - change;  // S v^{n+1}
        real cov = 0;  // centred, so no cancellation of |v|^2
        auto at = c.entries(i);
        c.stencils_[i].for_each([&](std::size_t node, real w, const vector&) {
            const std::size_t e = at(node);
            cov += w * (c.grid_.velocity[e] - fresh).dot(c.grid_.velocity_old[e] - old);
        });
        const vector d = v_flip - v_pic;
        const real cross = cov + d.dot(change);
        v = v_flip - alpha * d;
        energy += alpha * (cross + d.squaredNorm()) - real(0.5) * alpha * alpha * d.squaredNorm();
    }
};

}  // namespace gimlet::stages
