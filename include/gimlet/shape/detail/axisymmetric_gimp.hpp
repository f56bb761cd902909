// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The radial factors of axisymmetric uGIMP: the building block of a 2-D axisymmetric solver
/// (x -> r, y -> z), where every integral over a particle's domain carries the weight r.

#include "gimlet/core/radial_factors.hpp"
#include "gimlet/shape/detail/gimp_kernel.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace gimlet::shape::detail {

using gimlet::radial_factors;

/// The radial factors of the node at `r_i` >= 0 for a uGIMP particle centred at `r_p` > 0 of
/// half-width `half` (m) on cells of `h` (m), the linear hat N_i(r) = max(0, 1 - |r - r_i| / h).
///
/// The axisymmetric weak form per radian (Nairn & Guilkey 2015, Int. J. Numer. Meth. Engng 101;
/// NairnMPM's GIMP technical note, eqs 5.5, 5.8, 5.9) averages over the particle's domain with
/// the weight r: S_ip = ∫ χ_p N_i r dA / ∫ χ_p r dA, G_ip = ∫ χ_p ∇N_i r dA / ∫ χ_p r dA and
/// T_ip = ∫ χ_p N_i dA / ∫ χ_p r dA. On a box domain these separate into these radial factors
/// times the planar ones along z. The velocity gradient is L_rr = Σ v_ir G^r S^z,
/// L_zz = Σ v_iz S^r dS^z/dz and L_θθ = Σ v_ir T^r S^z, which is exact (a, a, b) for nodal
/// velocities (a r, b z) only with these three choices: T^r = S^r / r_p, or G^r = dS^r/dr_p,
/// would make L_θθ or L_rr wrong by a factor 1 ± l²/(3ρ²).
///
/// In cell units (s = (r_p - r_i)/h, a = |s|, σ = sign s, l = half/h, ρ = r_p/h), unclipped:
///   a < l:            S = 1 - (s² + l²)/(2l) + s(s² - 3l²)/(6lρ),
///                     hG = -s/l - (l² - s²)/(2lρ),           hT = (1 - (s² + l²)/(2l))/ρ;
///   l <= a <= 1 - l:  S = 1 - a - σl²/(3ρ),  hG = -σ,         hT = (1 - a)/ρ;
///   1 - l < a < 1+l:  with q = 1 + l - a, S = q²/(4l) (1 - σ(3l - q)/(3ρ)),
///                     hG = -σq/(2l) + q(2l - q)/(4lρ),        hT = q²/(4lρ);
///   beyond:           0.
/// The planar uGIMP factor plus an O(l²/ρ) correction; T^r is the planar weight over r_p.
/// A domain that reaches the axis (ρ < l) is clipped to [0, r_p + half] (as NairnMPM's and
/// Uintah's axisymmetric GIMP do); with b = ρ + l <= 1 only the nodes at r = 0 and r = h
/// weigh: S = 1 - 2b/3 and 2b/3, hG = -1 and +1, hT = 2/b - 1 and 1. Each factor is
/// continuous in r_p, across the clip too.
/// \pre 0 < half <= h/2, r_p > 0, r_i >= 0 on the grid (r_i = k h).
template <class Real>
[[nodiscard]] radial_factors<Real> axisymmetric_gimp_radial(Real r_p, Real r_i, Real half, Real h) noexcept {
    radial_factors<Real> f;
    const Real l = half / h, rho = r_p / h, s = (r_p - r_i) / h;
    if (rho < l) {
        // The domain reaches the axis: clipped to [0, r_p + half], nodes r = 0 and r = h.
        const Real b = rho + l;
        const Real k = r_i / h;
        if (k < Real(0.5)) {
            f.weight = Real(1) - Real(2) * b / Real(3);
            f.gradient = Real(-1) / h;
            f.hoop = (Real(2) / b - Real(1)) / h;
        } else if (k < Real(1.5)) {
            f.weight = Real(2) * b / Real(3);
            f.gradient = Real(1) / h;
            f.hoop = Real(1) / h;
        }
        return f;
    }
    const Real a = std::abs(s), sigma = s < Real(0) ? Real(-1) : Real(1);
    if (a < l) {
        const Real planar = Real(1) - (s * s + l * l) / (Real(2) * l);
        f.weight = planar + s * (s * s - Real(3) * l * l) / (Real(6) * l * rho);
        f.gradient = (-s / l - (l * l - s * s) / (Real(2) * l * rho)) / h;
        f.hoop = planar / (rho * h);
    } else if (a <= Real(1) - l) {
        f.weight = Real(1) - a - sigma * l * l / (Real(3) * rho);
        f.gradient = -sigma / h;
        f.hoop = (Real(1) - a) / (rho * h);
    } else if (a < Real(1) + l) {
        const Real q = Real(1) + l - a;
        f.weight = q * q / (Real(4) * l) * (Real(1) - sigma * (Real(3) * l - q) / (Real(3) * rho));
        f.gradient = (-sigma * q / (Real(2) * l) + q * (Real(2) * l - q) / (Real(4) * l * rho)) / h;
        f.hoop = q * q / (Real(4) * l * rho * h);
    }
    return f;
}

/// The radial factors of the node at `r_i` for a point particle (linear MPM) at `r_p` > 0 on cells
/// of `h`: the particle's domain shrinks to its centre, so S^r = N_i(r_p), G^r = N_i'(r_p) and
/// T^r = N_i(r_p) / r_p (the l -> 0 limit of axisymmetric_gimp_radial; NairnMPM's and Uintah's
/// axisymmetric linear shapes). At a node, N_i' takes the side away from the axis, as the
/// planar linear shape does.
template <class Real>
[[nodiscard]] radial_factors<Real> axisymmetric_linear_radial(Real r_p, Real r_i, Real h) noexcept {
    radial_factors<Real> f;
    const Real s = (r_p - r_i) / h, a = std::abs(s);
    if (a < Real(1)) {
        f.weight = Real(1) - a;
        f.gradient = (s < Real(0) ? Real(1) : Real(-1)) / h;
        f.hoop = f.weight / r_p;
    } else if (s == Real(-1)) {
        f.gradient = Real(1) / h;  // the particle on the node below: the slope from the right
    }
    return f;
}

/// The radial factors of a uGIMP particle at `r_p` > 0 (m) of half-width `half` <= h/2 for its
/// stencil along r, the axis at r = 0 and node k at r = k h: `first` is the stencil's first node,
/// and `f[a]` node first + a's factors (axisymmetric_gimp_radial); a node beyond the axis
/// (k < 0) has none.
template <class Real>
void axisymmetric_gimp_radial_stencil(Real r_p, Real half, Real h, int& first,
                                      std::array<radial_factors<Real>, gimp_stencil>& f) noexcept {
    (void)locate<gimp_stencil>(r_p / h, first);
    for (int a = 0; a < gimp_stencil; ++a) {
        const int k = first + a;
        f[a] = k < 0 ? radial_factors<Real>{} : axisymmetric_gimp_radial(r_p, Real(k) * h, half, h);
    }
}

}  // namespace gimlet::shape::detail
