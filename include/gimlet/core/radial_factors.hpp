// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// A node's radial factors for one axisymmetric particle: what a shape's axisymmetric form
/// (shape::axisymmetric_form) gives for each node of its stencil along r.

namespace gimlet {

/// A node's radial factors for one particle of an axisymmetric solver (axisymmetric_space): the
/// r-weighted weight S^r, the r-weighted mean of the shape's derivative G^r (1/m) and the hoop
/// factor T^r (1/m) (docs/equations.md, "Axisymmetric GIMP"). A node's weight, gradient and hoop
/// factor are these times the shape's factors along z.
template <class Real>
struct radial_factors {
    Real weight = 0;    ///< S^r = ∫ N_i r dr / ∫ r dr over the particle's domain
    Real gradient = 0;  ///< G^r = ∫ N_i' r dr / ∫ r dr (not dS^r/dr_p)
    Real hoop = 0;      ///< T^r = ∫ N_i dr / ∫ r dr (the r-weighted mean of N_i / r)
};

}  // namespace gimlet
