// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The update of one material point from its velocity gradient: deformation gradient, then the
/// constitutive policies (docs/physics.md section 1, step 5; section 4). The solver calls it for every
/// particle; tests call it directly to check a single material point.

#include "gimlet/core/describe.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/lanes.hpp"
#include "gimlet/material/material.hpp"
#include "gimlet/core/material_point.hpp"
#include "gimlet/core/space.hpp"
#include "gimlet/eos/concepts.hpp"
#include "gimlet/strength/jaumann.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>
#include <type_traits>

namespace gimlet {

/// Full 3x3 Cauchy stress of particle p (plane strain: sigma_zz from its own field).
template <class P>
[[nodiscard]] auto stress3(const P& p) {
    using S = typename P::space_type;
    using real = typename S::real;
    typename S::tensor3 s;
    if constexpr (S::dim == 2) {
        // Entry by entry into the result: built by embed3 and moved, the tensor is stored by
        // g++ 12 in 8-byte halves and read back in 16-byte loads that straddle them, which the
        // CPU cannot forward from its store buffer (docs/performance.md, "How the step is organised for speed").
        const auto& a = p.template get<fields::stress>();
        s(0, 0) = a(0, 0), s(1, 0) = a(1, 0), s(2, 0) = real(0);
        s(0, 1) = a(0, 1), s(1, 1) = a(1, 1), s(2, 1) = real(0);
        s(0, 2) = real(0), s(1, 2) = real(0), s(2, 2) = p.template get<fields::stress_zz>();
    } else {
        s = p.template get<fields::stress>();
    }
    return s;
}

/// Mean pressure -tr(sigma)/3 of particle p (Pa, compression positive).
template <class P>
[[nodiscard]] auto mean_pressure(const P& p) {
    using real = typename P::space_type::real;
    return -stress3(p).trace() / real(3);
}

/// Current volume J V^0 of particle p (per radian in an axisymmetric space).
template <class P>
[[nodiscard]] auto current_volume(const P& p) {
    return jacobian(p) * p.template get<fields::volume0>();
}

/// The state a policy needs between steps: J, current and reference density.
template <Material M, class P>
[[nodiscard]] auto point_state_of(const P& p, const M& mat) {
    using real = typename P::space_type::real;
    point_state<real> st;
    st.J = jacobian(p);
    st.density0 = real(mat.density);
    st.density = p.template get<fields::mass>() / (st.J * p.template get<fields::volume0>());
    return st;
}

/// Longitudinal wave speed sqrt((K + 4G/3) / rho) from the EOS tangent bulk modulus and the
/// strength's shear modulus (docs/physics.md section 1, step 6). `guards` gains the eos::guard bits of
/// the silent guards that acted: the EOS's own (if its bulk_modulus reports them) and
/// eos::guard::no_wave_speed where (K + 4G/3)/rho is not positive (the speed is then 0).
template <Material M, class P>
[[nodiscard]] auto longitudinal_wave_speed(const P& p, const M& mat, unsigned& guards) {
    using real = typename P::space_type::real;
    const point_state<real> st = point_state_of(p, mat);
    real k;
    if constexpr (requires { mat.eos.bulk_modulus(st, p, guards); }) k = mat.eos.bulk_modulus(st, p, guards);
    else k = mat.eos.bulk_modulus(st, p);
    const real g = mat.strength.shear_modulus(st, p);
    const real c2 = (k + real(4) / real(3) * g) / st.density;
    if (!(c2 > 0)) guards |= eos::guard::no_wave_speed;
    return std::sqrt(std::max(real(0), c2));
}
/// Longitudinal wave speed of particle p (m/s), as above, without reporting the guards.
template <Material M, class P>
[[nodiscard]] auto longitudinal_wave_speed(const P& p, const M& mat) {
    unsigned ignored = 0;
    return longitudinal_wave_speed(p, mat, ignored);
}

namespace detail {
// update_material_point, with the hoop rate L_thetatheta of an axisymmetric particle (ignored
// otherwise).
template <Material M, class P>
void update_point(const M& mat, const P& p, const typename P::space_type::matrix& L,
                  typename P::space_type::real hoop_rate, typename P::space_type::real dt,
                  typename P::space_type::real cell, std::size_t step, double time) {
    using S = typename P::space_type;
    constexpr bool axisymmetric = is_axisymmetric_v<S>;
    using real = typename S::real;
    using matrix = typename S::matrix;
    using tensor3 = typename S::tensor3;
    constexpr int dim = S::dim;

    matrix& F = p.template get<fields::deformation_gradient>();
    const real j_old = jacobian(p);
    // The old stress and its deviator first, well before the strength policy reads them: built
    // entry by entry, they reach memory in 8-byte stores, and a 16-byte load of two of them
    // right after (g++ pairs entries in the rotation) waits for the stores to drain
    // (store-to-load forwarding fails). Computed after F, the wait would be 13-15 % of
    // bench_lanes' update (docs/performance.md, "How the step is organised for speed").
    const tensor3 sigma_old = stress3(p);
    tensor3 s = strength::deviator(sigma_old);
    // The midpoint (Cayley) form of F' = L F (Hughes & Winget 1980, eq. 14; docs/physics.md
    // section 1, step 5). Unlike the forward-Euler (I + dt L) F, it keeps det F = 1 exactly under
    // a rigid spin, so a rotating body gains no spurious pressure; both are first-order consistent.
    const matrix half = real(0.5) * dt * L;
    if constexpr (dim == 2) {
        // The same map with the 2x2 inverse written out: inv(I - A) = adj(I - A) / det(I - A).
        const real m00 = real(1) - half(0, 0), m01 = -half(0, 1), m10 = -half(1, 0), m11 = real(1) - half(1, 1);
        const real inv_det = real(1) / (m00 * m11 - m10 * m01);
        const real i00 = m11 * inv_det, i01 = -m01 * inv_det, i10 = -m10 * inv_det, i11 = m00 * inv_det;
        const matrix b = (matrix::Identity() + half) * F;
        F(0, 0) = i00 * b(0, 0) + i01 * b(1, 0);
        F(1, 0) = i10 * b(0, 0) + i11 * b(1, 0);
        F(0, 1) = i00 * b(0, 1) + i01 * b(1, 1);
        F(1, 1) = i10 * b(0, 1) + i11 * b(1, 1);
    } else {
        F = (matrix::Identity() - half).inverse() * ((matrix::Identity() + half) * F);
    }
    if constexpr (axisymmetric) {
        // The same map on the hoop entry: L is block-diagonal (L_rtheta = L_ztheta = 0).
        real& hoop = p.template get<fields::hoop_stretch>();
        const real h = real(0.5) * dt * hoop_rate;
        hoop = (real(1) + h) * hoop / (real(1) - h);
    } else {
        (void)hoop_rate;
    }

    point_step<real> st;
    static_cast<point_state<real>&>(st) = point_state_of(p, mat);
    if constexpr (is_lanes<real>) {
        // Two particles at once (update_material_points_2): a particle that would stop the run
        // leaves the pair to the one-at-a-time update, which names it.
        if (!(finite_lanes(st.J) && st.J > real(0)).all()) return p.reject();
    } else {
        if (!std::isfinite(st.J))
            throw numerical_error(describe_particle(p, step, time) +
                                  ": velocity gradient is not finite (a non-finite value reached its nodes)");
        if (!(st.J > 0))
            throw numerical_error(describe_particle(p, step, time) + ": det F = " +
                                  detail::to_text(double(st.J)) + " <= 0 (inverted particle)");
    }
    st.dt = dt;
    st.J_old = j_old;
    st.step = step;
    st.time = time;
    if constexpr (dim == 2) {
        // Plane strain: only the in-plane entries of D and W (point_step's are zero already).
        // Axisymmetric: D_thetatheta is the hoop rate, and the spin is in-plane.
        st.plane_strain = !axisymmetric;
        if constexpr (axisymmetric) st.D(2, 2) = hoop_rate;
        const real shear = real(0.5) * (L(0, 1) + L(1, 0)), spin = real(0.5) * (L(1, 0) - L(0, 1));
        st.D(0, 0) = L(0, 0);
        st.D(1, 1) = L(1, 1);
        st.D(0, 1) = st.D(1, 0) = shear;
        st.W(1, 0) = spin;
        st.W(0, 1) = -spin;
    } else {
        st.D = real(0.5) * (L + L.transpose());
        st.W = real(0.5) * (L - L.transpose());
    }
    st.length = cell;

    const real dissipated = mat.strength.update(st, s, p);
    real q = 0;
    if constexpr (M::viscosity_type::enabled) {
        // The wave speed costs the EOS's tangent modulus and a square root (a `pow` for
        // Mie-Grueneisen in compression). A viscosity that declares `lazy_sound_speed` takes it
        // as a callable and asks for it only where q needs it, from the particle as it is then
        // (what the policy wrote to it before asking included); any other is given the number
        // (viscosity::Viscosity).
        const auto speed = [&] { return longitudinal_wave_speed(p, mat); };
        if constexpr (viscosity::lazy_sound_speed<typename M::viscosity_type>) q = mat.viscosity.pressure(st, speed, p);
        else q = mat.viscosity.pressure(st, speed(), p);
    }
    // Stress power per unit mass, midpoint in time (docs/physics.md section 1): de = dt v_mid sigma:D,
    // with sigma^{n+1} = s - (P + q) I and the midpoint specific volume
    // v_mid = (v^n + v^{n+1}) / 2 = (1 + J^n / J^{n+1}) / (2 rho^{n+1}): with the end-of-step
    // v alone, de = -P dv is first-order short in the step's strain (7 % on a shock's landing
    // step), and an isentrope loses that much heat per cycle (docs/equations.md). The part
    // without P^{n+1} is known before the EOS is called; the rest is
    // -pressure_work_factor * P^{n+1}.
    real& e = p.template get<fields::specific_internal_energy>();
    const real v_mid = real(0.5) * (real(1) + j_old / st.J) / st.density;
    const tensor3 known = real(0.5) * minus_identity(tensor3(sigma_old + s), q);
    real power;  // known : D
    if constexpr (axisymmetric)
        power = (known(0, 0) * st.D(0, 0) + known(1, 1) * st.D(1, 1)) + (known(1, 0) * st.D(1, 0) + known(0, 1) * st.D(0, 1)) +
                known(2, 2) * st.D(2, 2);
    else if constexpr (dim == 2)  // D_zz = 0 in plane strain; the terms summed as the 3x3 sum pairs them
        power = (known(0, 0) * st.D(0, 0) + known(1, 1) * st.D(1, 1)) + (known(1, 0) * st.D(1, 0) + known(0, 1) * st.D(0, 1));
    else
        power = known.cwiseProduct(st.D).sum();
    st.energy_before_pressure = e + dt * v_mid * power;
    st.pressure_work_factor = real(0.5) * dt * st.D.trace() * v_mid;
    // The stored elastic shear energy s:s / (4 G rho) (linear elasticity of the deviator): in e,
    // but not heat (docs/equations.md, thermal::isentrope_temperature). Computed only for a
    // thermal policy or an EOS that reads it (eos::reads_shear_energy).
    if constexpr (M::thermal_type::enabled || eos::reads_shear_energy<typename M::eos_type>) {
        const real shear = mat.strength.shear_modulus(static_cast<const point_state<real>&>(st), p);
        st.shear_energy = shear > 0 ? s.squaredNorm() / (real(4) * shear * st.density) : real(0);
    }
    const real pres = mat.eos.pressure(st, p);
    if constexpr (is_lanes<real>) {
        if (!finite_lanes(pres).all()) return p.reject();
    } else if (!std::isfinite(pres)) {
        throw numerical_error(describe_particle(p, step, time) + ": the EOS returned a non-finite pressure");
    }
    const tensor3 sigma_new = minus_identity(s, pres + q);
    e = st.energy_before_pressure - st.pressure_work_factor * pres;
    if constexpr (M::thermal_type::enabled) mat.thermal.update(st, dissipated, p);
    else (void)dissipated;
    p.template get<fields::stress>() = in_plane<dim>(sigma_new);
    if constexpr (dim == 2) p.template get<fields::stress_zz>() = sigma_new(2, 2);
}
}  // namespace detail

/// Advance particle p over dt given its velocity gradient L:
/// F <- (I - dt L/2)^-1 (I + dt L/2) F, then s from the strength law, P from the EOS, q from the
/// viscosity (over the grid cell size `cell`), sigma = s - (P + q) I,
/// e += dt v_mid sigma_mid : D, and the thermal update.
/// Throws numerical_error (naming particle, position and step) if F inverts.
template <Material M, class P>
void update_material_point(const M& mat, const P& p,
                           const typename P::space_type::matrix& L,
                           typename P::space_type::real dt, typename P::space_type::real cell,
                           std::size_t step, double time) {
    static_assert(!is_axisymmetric_v<typename P::space_type>,
                  "gimlet::update_material_point: an axisymmetric particle needs its hoop rate L_thetatheta "
                  "(the overload that takes it after L)");
    detail::update_point(mat, p, L, typename P::space_type::real(0), dt, cell, step, time);
}

/// update_material_point for an axisymmetric particle (axisymmetric_space): L is the (r, z)
/// velocity gradient and `hoop_rate` L_thetatheta = sum v_ir T_ip (docs/equations.md,
/// "Axisymmetric GIMP"), which stretches the hoop entry of F by the same midpoint map and enters
/// D as D_thetatheta (the volumetric rate, the plastic flow and the stress power see it).
template <Material M, class P>
void update_material_point(const M& mat, const P& p, const typename P::space_type::matrix& L,
                           typename P::space_type::real hoop_rate, typename P::space_type::real dt,
                           typename P::space_type::real cell, std::size_t step, double time) {
    static_assert(is_axisymmetric_v<typename P::space_type>,
                  "gimlet::update_material_point: a hoop rate is for an axisymmetric particle only");
    detail::update_point(mat, p, L, hoop_rate, dt, cell, step, time);
}

/// Whether the solver may update two particles of material M at once (update_material_points_2):
/// plane strain in double, a strength and an EOS that are lane_safe, no thermal policy, no
/// viscosity and no EOS that reads the shear energy (the update's own code for those branches
/// on values).
template <Material M, class S>
inline constexpr bool lanes_capable = [] {
    if constexpr (GIMLET_HAS_LANES && S::dim == 2 && !is_axisymmetric_v<S> && std::is_same_v<typename S::real, double>)
        return lane_safe<typename M::strength_type> && lane_safe<typename M::eos_type> && !M::thermal_type::enabled &&
               !M::viscosity_type::enabled && !eos::reads_shear_energy<typename M::eos_type>;
    else
        return false;
}();

#if GIMLET_HAS_LANES
namespace detail {
/// Two plane-strain particles as one particle handle whose scalar is lanes2: copies of the
/// fields the material update reads and writes (update_material_points_2 loads and stores
/// them). A lane_safe policy reads nothing through its handle.
struct lane_space2 {
    static constexpr int dim = 2;
    using real = lanes2;
    using vector = Eigen::Matrix<lanes2, 2, 1>;
    using matrix = Eigen::Matrix<lanes2, 2, 2>;
    using tensor3 = Eigen::Matrix<lanes2, 3, 3>;
};
struct particle_pair {
    using space_type = lane_space2;
    mutable lane_space2::matrix F, stress;
    mutable lanes2 stress_zz, energy;
    lanes2 mass, volume0;  // read only: the update writes neither, and neither is stored back
    mutable bool rejected = false;
    void reject() const noexcept { rejected = true; }
    template <class Field>
    [[nodiscard]] auto& get() const noexcept {
        if constexpr (std::is_same_v<Field, fields::deformation_gradient>) return F;
        else if constexpr (std::is_same_v<Field, fields::stress>) return stress;
        else if constexpr (std::is_same_v<Field, fields::stress_zz>) return stress_zz;
        else if constexpr (std::is_same_v<Field, fields::specific_internal_energy>) return energy;
        else if constexpr (std::is_same_v<Field, fields::mass>) return mass;
        else if constexpr (std::is_same_v<Field, fields::volume0>) return volume0;
        else static_assert(sizeof(Field) == 0, "a lane_safe policy reads no field through its particle handle");
    }
};
}  // namespace detail

/// update_material_point for particles a and b of one material at once, two lanes of one
/// vector (lanes_capable<M>): the same operations on each particle as its own update, so the
/// same bits. Returns false, having written nothing, where either particle would stop the run
/// (det F not positive or not finite, a non-finite pressure): the caller then updates them one
/// at a time, which stops with the message that names the particle.
template <Material M, class P>
[[nodiscard]] bool update_material_points_2(const M& mat, const P& a, const P& b, const typename P::space_type::matrix& La,
                                            const typename P::space_type::matrix& Lb, double dt, double cell,
                                            std::size_t step, double time) {
    static_assert(lanes_capable<M, typename P::space_type>);
    using matrix2 = detail::lane_space2::matrix;
    auto pack = [](const auto& x, const auto& y) {
        matrix2 r;
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) r(i, j) = lanes2(x(i, j), y(i, j));
        return r;
    };
    detail::particle_pair pair;
    pair.F = pack(a.template get<fields::deformation_gradient>(), b.template get<fields::deformation_gradient>());
    pair.stress = pack(a.template get<fields::stress>(), b.template get<fields::stress>());
    pair.stress_zz = lanes2(a.template get<fields::stress_zz>(), b.template get<fields::stress_zz>());
    pair.energy = lanes2(a.template get<fields::specific_internal_energy>(), b.template get<fields::specific_internal_energy>());
    pair.mass = lanes2(a.template get<fields::mass>(), b.template get<fields::mass>());
    pair.volume0 = lanes2(a.template get<fields::volume0>(), b.template get<fields::volume0>());
    update_material_point(mat, pair, pack(La, Lb), lanes2(dt), lanes2(cell), step, time);
    if (pair.rejected) return false;
    auto unpack = [](const matrix2& r, auto& x, auto& y) {
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) x(i, j) = r(i, j)[0], y(i, j) = r(i, j)[1];
    };
    unpack(pair.F, a.template get<fields::deformation_gradient>(), b.template get<fields::deformation_gradient>());
    unpack(pair.stress, a.template get<fields::stress>(), b.template get<fields::stress>());
    a.template get<fields::stress_zz>() = pair.stress_zz[0];
    b.template get<fields::stress_zz>() = pair.stress_zz[1];
    a.template get<fields::specific_internal_energy>() = pair.energy[0];
    b.template get<fields::specific_internal_energy>() = pair.energy[1];
    return true;
}
#endif

}  // namespace gimlet
