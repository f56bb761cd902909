// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// What the solver hands to the constitutive policies (strength, eos, viscosity, thermal) for
/// one particle: its kinematic state and, during an update, the step's rates. Tensors are 3x3
/// in both 2-D and 3-D: in plane strain the out-of-plane rows are zero in D and W, and the
/// stress carries sigma_zz (docs/physics.md section 4), so a law written once works in both.

#include "gimlet/core/fields.hpp"
#include "gimlet/core/particle_store.hpp"

#include <cstddef>

namespace gimlet {

/// J = det F of particle p: the in-plane determinant, times the hoop stretch F_thetatheta in an
/// axisymmetric space (plane strain has F_zz = 1).
template <class P>
[[nodiscard]] auto jacobian(const P& p) {
    if constexpr (is_axisymmetric_v<typename P::space_type>)
        return p.template get<fields::deformation_gradient>().determinant() * p.template get<fields::hoop_stretch>();
    else
        return p.template get<fields::deformation_gradient>().determinant();
}

/// The state of a material point between steps.
template <class Real>
struct point_state {
    Real J = 1;         ///< det F, current volume over reference volume
    Real density = 0;   ///< current density m_p / (J V_p^0)
    Real density0 = 0;  ///< reference density of the body's material
};

/// One constitutive update over a time step (docs/physics.md section 1, step 5).
template <class Real>
struct point_step : point_state<Real> {
    /// A 3x3 tensor of Real (plane strain carries the out-of-plane components).
    using tensor3 = Eigen::Matrix<Real, 3, 3>;
    Real dt = 0;               ///< time step
    Real J_old = 1;            ///< det F at the start of the step
    tensor3 D = tensor3::Zero();  ///< rate of deformation, sym(L)
    tensor3 W = tensor3::Zero();  ///< spin, skew(L)
    Real length = 0;           ///< grid cell size h: the length a shock is spread over, for viscosity
    /// Specific internal energy at the end of the step without the pressure's own work:
    /// e^n + dt v_mid sigma_mid' : D with sigma_mid' the midpoint stress less the end-of-step
    /// pressure and v_mid = (1/rho^n + 1/rho^{n+1}) / 2. The end-of-step energy is
    /// `energy_before_pressure - pressure_work_factor * P`, so an energy-dependent EOS can solve
    /// for P and e together (see eos::mie_gruneisen).
    Real energy_before_pressure = 0;
    /// dt tr(D) v_mid / 2: the share of the end-of-step pressure in the energy increment.
    Real pressure_work_factor = 0;
    /// The stored elastic shear energy per unit mass at the end of the step, s:s / (4 G rho)
    /// (J/kg; zero without shear stiffness), computed when the material has a thermal policy.
    /// It is part of e but not heat: the thermal part of the energy that a temperature from the
    /// state sees is e - shear_energy (docs/equations.md, thermal::isentrope_temperature).
    Real shear_energy = 0;
    std::size_t step = 0;      ///< step number, for error messages
    double time = 0;           ///< simulated time at the start of the step (s), for messages
    /// True in plane strain (2-D; set by update_material_point): D and W have no out-of-plane
    /// entries (the stress still has sigma_zz), so a law may take a cheaper path, as
    /// jaumann_rotate does. Leave it false when building a step by hand unless that holds.
    /// (Last, so positional initialisers written before it keep their meaning.)
    bool plane_strain = false;
};

/// The particle handle a policy sees in concept checks: a store holding the core fields plus
/// the policy's own. Real stores hold more (the union of every policy's fields).
template <int Dim, class Policy>
using archetype_particle = particle_ref<particle_store<
    space<Dim, double>, field_union_t<core_fields<space<Dim, double>>, typename Policy::required_fields>>>;

}  // namespace gimlet
