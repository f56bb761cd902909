// SPDX-License-Identifier: MIT
// Radial return of strength::von_mises at a single material point (docs/physics.md section 4),
// driven through gimlet::update_material_point exactly as the solver drives it, in 2-D
// (plane strain) and 3-D, with the HMX shear modulus and yield stress.
//
// Two loadings keep the deviatoric strain-rate direction fixed, so the return is exact and the
// discrete algorithm must reproduce the continuum solution to round-off:
//  * uniaxial strain, L = diag(0, -r) (compression along y; 3-D: diag(0, -r, 0)), W = 0;
//  * pure shear with W = 0, L = [[0, r], [r, 0]] (symmetric, so D = L, W = 0). A simple shear
//    L = [[0, 2r], [0, 0]] has the same D but a spin W = [[0, r], [-r, 0]]: the Jaumann term
//    rotates the deviator away from D', the direction is no longer fixed and eps_p has no
//    simple closed form. The spin is an orthogonal rotation of s, so sigma_eq = Y must still
//    hold at every plastic step; that is checked separately.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
#include <vector>

namespace {

// ---- a thermal policy that records what the strength law returned (its dissipation) ---------
// update_material_point hands the strength law's return value to the thermal policy; recording
// it there checks the return value on the solver's own path.
struct last_dissipation {
    template <class S> using type = typename S::real;
    static constexpr const char* name = "last_dissipation";
};
struct dissipation_recorder {
    static constexpr bool enabled = true;
    using required_fields = gimlet::field_list<last_dissipation>;
    template <class P>
    void initialize(const P& p) const { p.template get<last_dissipation>() = 0; }
    template <class Real, class P>
    void update(const gimlet::point_step<Real>&, Real dissipated, const P& p) const {
        p.template get<last_dissipation>() = dissipated;
    }
};
static_assert(gimlet::thermal::Thermal<dissipation_recorder>);

using vm_material = gimlet::material<gimlet::strength::von_mises, gimlet::eos::linear, dissipation_recorder>;

const gimlet::presets::hmx_constants hmx{};
const double G = gimlet::elastic_moduli::from_young_poisson(hmx.young, hmx.poisson).shear;  // 4.748 GPa
const double K = gimlet::elastic_moduli::from_young_poisson(hmx.young, hmx.poisson).bulk;   // 7.91 GPa
const double Y0 = hmx.yield_stress;                                                         // 100 MPa

vm_material make_vm(double hardening) {
    return {hmx.density, gimlet::strength::von_mises{G, Y0, hardening}, gimlet::eos::linear{K}, dissipation_recorder{}};
}

// One material point in a store of its own, advanced by update_material_point.
template <int Dim, class M>
struct material_point {
    using S = gimlet::space<Dim>;
    using fields = gimlet::field_union_t<gimlet::core_fields<S>, typename M::required_fields>;
    using store_type = gimlet::particle_store<S, fields>;

    M mat;
    store_type store;
    std::size_t steps = 0;
    double time = 0;

    explicit material_point(const M& m) : mat(m) {
        auto p = store[store.add()];
        p.template get<gimlet::fields::volume0>() = 1e-6;  // m^2 (per unit thickness) or m^3
        p.template get<gimlet::fields::mass>() = mat.density * 1e-6;
        if constexpr (M::thermal_type::enabled) mat.thermal.initialize(p);
    }
    [[nodiscard]] auto p() { return store[0]; }
    void step(const typename S::matrix& L, double dt) {
        gimlet::update_material_point(mat, p(), L, dt, 1e-3, steps++, time);  // cell: no viscosity here
        time += dt;
    }
    [[nodiscard]] Eigen::Matrix3d dev() { return gimlet::strength::deviator<double>(gimlet::stress3(p())); }
    [[nodiscard]] double sigma_eq() {
        const Eigen::Matrix3d s = dev();
        return std::sqrt(1.5 * s.cwiseProduct(s).sum());
    }
    [[nodiscard]] double eps_p() { return p().template get<gimlet::fields::plastic_strain>(); }
    [[nodiscard]] double w_p() { return p().template get<gimlet::fields::plastic_work>(); }
    [[nodiscard]] double density() { return p().template get<gimlet::fields::mass>() / gimlet::current_volume(p()); }
    // s_zz: the zz stress less its pressure part (2-D: the stress_zz field; 3-D: sigma(2, 2)).
    [[nodiscard]] double s_zz() {
        double szz;
        if constexpr (Dim == 2) szz = p().template get<gimlet::fields::stress_zz>();
        else szz = p().template get<gimlet::fields::stress>()(2, 2);
        return szz + gimlet::mean_pressure(p());
    }
};

// Uniaxial strain along y, monotone, then elastic unloading.
//
// Analytic solution (small increments, rate form, W = 0). With e = int r dt the compressive
// (logarithmic) strain, D' = r diag(1, -2, 1)/3, so the elastic deviator is
// s = (2 G e / 3) diag(1, -2, 1) and sigma_eq = sqrt(3/2 s:s) = 2 G e: yield at e_y = Y0 / (2G).
// Beyond it the flow is along the fixed direction diag(1, -2, 1); the equivalent total strain
// rate is sqrt(2/3 D':D') = 2r/3, so consistency sigma_eq' = 3G (2r/3 - eps_p') = H eps_p' gives
//     eps_p' = 2 G r / (3G + H),   eps_p(e) = (2 G e - Y0) / (3G + H)   for e >= e_y,
// and s = (Y/3) diag(1, -2, 1) with Y = Y0 + H eps_p: s_zz = s_xx = Y/3 != 0 in plane strain.
// The discrete radial return reproduces this exactly: every trial step adds 2G de to sigma_eq
// along the same direction, so each plastic step returns d eps_p = 2 G de / (3G + H), and the
// step that crosses yield returns (2 G e_{n+1} - Y0)/(3G + H).
// Plastic work per unit mass: w = int Y d eps_p / rho, rho = rho0 / J, J = exp(-e):
//     w = (k / rho0) int_{e_y}^{e} (Y0 + H k (x - e_y)) exp(-x) dx,   k = 2G / (3G + H),
//       = (k / rho0) [ (A + B + B e_y) exp(-e_y) - (A + B + B e) exp(-e) ],  A = Y0 - H k e_y, B = H k.
template <int Dim>
void check_uniaxial_strain(double H) {
    using S = gimlet::space<Dim>;
    material_point<Dim, vm_material> mp(make_vm(H));
    const double rate = 1e4, dt = 1e-9, de = rate * dt;  // 1e-5 strain per step
    typename S::matrix L = S::matrix::Zero();
    L(1, 1) = -rate;
    const int n_load = 3000;  // e = 0.03, about 3 e_y
    const double e_y = Y0 / (2 * G);

    std::vector<double> eps{0.0}, rho{mp.density()};
    double returned_sum = 0;
    int plastic_steps = 0;
    for (int n = 1; n <= n_load; ++n) {
        const double eps_old = mp.eps_p();
        mp.step(L, dt);
        const double e = n * de;
        eps.push_back(mp.eps_p());
        rho.push_back(mp.density());
        returned_sum += mp.p().template get<last_dissipation>();
        if (mp.eps_p() == 0) {
            // Elastic: sigma_eq = 2 G e; round-off of n additions (tolerance 1e-11 relative).
            CHECK(mp.sigma_eq() == Approx(2 * G * e).epsilon(1e-11));
            CHECK(mp.s_zz() == Approx(2 * G * e / 3).epsilon(1e-11));
            CHECK(e < e_y * (1 + 1e-12));
            continue;
        }
        ++plastic_steps;
        const double Y = Y0 + H * mp.eps_p();
        // On the yield surface to round-off: the return scales s by Y/sigma_eq*, then P is added
        // and removed again (P/Y <= 3, so a few ulps of Y; tolerance 1e-12 relative).
        CHECK(mp.sigma_eq() == Approx(Y).epsilon(1e-12));
        // The step's increment (crossing step included) against the closed form.
        const double d_expected = (eps_old > 0 ? 2 * G * de : 2 * G * e - Y0) / (3 * G + H);
        // sigma_eq* - Y is a difference of ~1e8 Pa values (~1e5 Pa apart) and the increment a
        // difference of ~1e-2 values (~7e-6 apart): ~1e-12 relative expected; tolerance 1e-10.
        CHECK(mp.eps_p() - eps_old == Approx(d_expected).epsilon(1e-10));
        REQUIRE(e > e_y * (1 - 1e-12));
    }
    REQUIRE(plastic_steps > 1000);

    // Accumulated eps_p against the analytic uniaxial-strain value (round-off of 3000 additions).
    const double e_end = n_load * de;
    const double eps_exact = (2 * G * e_end - Y0) / (3 * G + H);
    CHECK(mp.eps_p() == Approx(eps_exact).epsilon(1e-10));

    // Plane strain carries s_zz: non-zero, and equal to s_xx = Y/3 on the yield surface.
    const double Y_end = Y0 + H * mp.eps_p();
    const Eigen::Matrix3d s = mp.dev();
    CHECK(std::abs(mp.s_zz()) > 0.3 * Y_end);
    CHECK(mp.s_zz() == Approx(Y_end / 3).epsilon(1e-12));  // round-off, as sigma_eq above
    CHECK(s(0, 0) == Approx(Y_end / 3).epsilon(1e-12));
    CHECK(s(1, 1) == Approx(-2 * Y_end / 3).epsilon(1e-12));

    // Plastic work (a) against the quadrature of the recorded history, int Y d eps_p / rho with Y
    // linear in eps_p (trapezoid in Y is exact) and the end-of-step density of each step (the
    // density the library's update sees); round-off of 3000 additions: 1e-12 relative.
    double w_history = 0;
    for (std::size_t k = 1; k < eps.size(); ++k)
        w_history += 0.5 * ((Y0 + H * eps[k - 1]) + (Y0 + H * eps[k])) * (eps[k] - eps[k - 1]) / rho[k];
    CHECK(mp.w_p() == Approx(w_history).epsilon(1e-12));
    // (b) the dissipation returned by each update (recorded by the thermal policy) sums to the
    // field: the same additions in the same order, so round-off only (1e-13 relative).
    CHECK(returned_sum == Approx(mp.w_p()).epsilon(1e-13));
    // (c) against the continuum integral: the end-of-step density is a first-order quadrature
    // of int d eps_p / rho in time, low by about de/2 = 5e-6 relative; tolerance 1e-5.
    {
        const double k = 2 * G / (3 * G + H), A = Y0 - H * k * e_y, B = H * k;
        const double w_exact = k / hmx.density *
                               ((A + B + B * e_y) * std::exp(-e_y) - (A + B + B * e_end) * std::exp(-e_end));
        CHECK(mp.w_p() == Approx(w_exact).epsilon(1e-5));
    }

    // Elastic unloading: reverse the strain rate for a strain of 0.01 (< Y/G, no reverse yield).
    // Every step is elastic: eps_p and w_p are frozen exactly, sigma_eq = Y_end - 2 G e_unload
    // (round-off of the additions, 1e-9 of Y absolute as sigma_eq falls towards 5 MPa).
    const double eps_frozen = mp.eps_p(), w_frozen = mp.w_p();
    for (int n = 1; n <= 1000; ++n) {
        mp.step(-L, dt);
        CHECK(mp.eps_p() == eps_frozen);
        CHECK(mp.w_p() == w_frozen);
        CHECK(mp.p().template get<last_dissipation>() == 0.0);
        CHECK(mp.sigma_eq() < Y_end);
        CHECK(std::abs(mp.sigma_eq() - (Y_end - 2 * G * n * de)) < 1e-9 * Y_end);
    }
}

// Pure shear with W = 0: L = [[0, r], [r, 0]]. s_xy = 2 G g (g = r t), sigma_eq = sqrt(3) |s_xy|,
// yield at g_y = Y0 / (2 sqrt(3) G); the equivalent total strain rate is sqrt(2/3 D:D) = 2r/sqrt(3),
// so eps_p' = 2 sqrt(3) G r / (3G + H) and eps_p(g) = (2 sqrt(3) G g - Y0) / (3G + H).
template <int Dim>
void check_pure_shear(double H) {
    using S = gimlet::space<Dim>;
    material_point<Dim, vm_material> mp(make_vm(H));
    const double rate = 1e4, dt = 1e-9, dg = rate * dt;
    typename S::matrix L = S::matrix::Zero();
    L(0, 1) = L(1, 0) = rate;
    const int n_load = 2000;
    int plastic_steps = 0;
    for (int n = 1; n <= n_load; ++n) {
        mp.step(L, dt);
        if (mp.eps_p() == 0) {
            CHECK(mp.sigma_eq() == Approx(std::sqrt(3.0) * 2 * G * n * dg).epsilon(1e-11));  // round-off
            continue;
        }
        ++plastic_steps;
        CHECK(mp.sigma_eq() == Approx(Y0 + H * mp.eps_p()).epsilon(1e-12));  // round-off
    }
    REQUIRE(plastic_steps > 500);
    // det F = 1 for this L (det(I + h) = det(I - h) = 1 - (r dt/2)^2): no pressure, no s_zz.
    // P = K (1 - J) with J off by the round-off of 2000 matrix products (~1e-13): |P| < 1e-12 K.
    CHECK(std::abs(gimlet::mean_pressure(mp.p())) < 1e-12 * K);
    CHECK(std::abs(mp.s_zz()) < 1e-12 * Y0);
    const double eps_exact = (2 * std::sqrt(3.0) * G * n_load * dg - Y0) / (3 * G + H);
    CHECK(mp.eps_p() == Approx(eps_exact).epsilon(1e-10));  // round-off of 2000 additions
}

// Simple shear L = [[0, 2r], [0, 0]] (spin W = [[0, r], [-r, 0]]): the Jaumann rotation is
// orthogonal, so the return still lands on the yield surface at every plastic step.
template <int Dim>
void check_simple_shear(double H) {
    using S = gimlet::space<Dim>;
    material_point<Dim, vm_material> mp(make_vm(H));
    typename S::matrix L = S::matrix::Zero();
    L(0, 1) = 2e4;
    double eps_old = 0;
    int plastic_steps = 0;
    for (int n = 1; n <= 20000; ++n) {  // shear strain 0.4: the stress axes rotate visibly
        mp.step(L, 1e-9);
        CHECK(mp.eps_p() >= eps_old);
        eps_old = mp.eps_p();
        if (mp.eps_p() == 0) continue;
        ++plastic_steps;
        CHECK(mp.sigma_eq() == Approx(Y0 + H * mp.eps_p()).epsilon(1e-12));  // round-off
    }
    REQUIRE(plastic_steps > 10000);
}

// One step from a known, non-coaxial, elastic state: trial s* = s^n + 2 G dt D' (W = 0),
// then d eps_p = (sigma_eq* - Y^n)/(3G + H), s = s* (Y^n + H d eps_p)/sigma_eq*,
// d w_p = (Y^n + Y^{n+1})/2 d eps_p / rho^{n+1}.
template <int Dim>
void check_single_step(double H) {
    using S = gimlet::space<Dim>;
    material_point<Dim, vm_material> mp(make_vm(H));
    auto p = mp.p();
    const double eps0 = 0.01, Yn = Y0 + H * eps0, P0 = 50e6;
    Eigen::Matrix3d sn;
    if constexpr (Dim == 2) sn << 30, 20, 0, 20, -10, 0, 0, 0, -20;
    else sn << 30, 20, -5, 20, -10, 8, -5, 8, -20;
    sn *= 1e6;
    p.template get<gimlet::fields::plastic_strain>() = eps0;
    const Eigen::Matrix3d sigma_n = sn - P0 * Eigen::Matrix3d::Identity();
    p.template get<gimlet::fields::stress>() = gimlet::in_plane<Dim>(sigma_n);
    if constexpr (Dim == 2) p.template get<gimlet::fields::stress_zz>() = sigma_n(2, 2);
    const double eq_n = std::sqrt(1.5 * sn.cwiseProduct(sn).sum());
    REQUIRE(eq_n < Yn);  // a known elastic state

    typename S::matrix L;
    if constexpr (Dim == 2) L << -3e3, 1e3, 1e3, 2e3;
    else L << -3e3, 1e3, 0, 1e3, 2e3, -2e3, 0, -2e3, 4e3;
    const double dt = 1e-5;  // one large step: trial about 3 Y
    const Eigen::Matrix3d D = gimlet::embed3<double, Dim>(L);  // symmetric: W = 0
    const Eigen::Matrix3d trial = sn + 2 * G * dt * gimlet::strength::deviator<double>(D);
    const double eq_trial = std::sqrt(1.5 * trial.cwiseProduct(trial).sum());
    REQUIRE(eq_trial > 1.1 * Yn);  // a plastic step
    const double d_eps = (eq_trial - Yn) / (3 * G + H);
    const Eigen::Matrix3d s_expected = trial * (Yn + H * d_eps) / eq_trial;

    mp.step(L, dt);
    CHECK(mp.eps_p() - eps0 == Approx(d_eps).epsilon(1e-12));            // round-off
    CHECK((mp.dev() - s_expected).norm() < 1e-12 * Yn);                  // round-off (P/Y ~ 1)
    CHECK(mp.sigma_eq() == Approx(Yn + H * d_eps).epsilon(1e-12));       // round-off
    const double dw = 0.5 * (Yn + Yn + H * d_eps) * d_eps / mp.density();
    CHECK(mp.w_p() == Approx(dw).epsilon(1e-12));                        // round-off
    CHECK(mp.p().template get<last_dissipation>() == Approx(dw).epsilon(1e-12));
}

}  // namespace

TEST_CASE("von Mises: uniaxial strain, perfectly plastic (H = 0), plane strain", "[verification][strength]") {
    check_uniaxial_strain<2>(0.0);
}
TEST_CASE("von Mises: uniaxial strain, linear hardening (H > 0), plane strain", "[verification][strength]") {
    check_uniaxial_strain<2>(1e9);
}
TEST_CASE("von Mises: uniaxial strain, H = 0 and H > 0, 3-D", "[verification][strength]") {
    check_uniaxial_strain<3>(0.0);
    check_uniaxial_strain<3>(1e9);
}

TEST_CASE("von Mises: pure shear (W = 0), H = 0 and H > 0, 2-D and 3-D", "[verification][strength]") {
    check_pure_shear<2>(0.0);
    check_pure_shear<2>(1e9);
    check_pure_shear<3>(0.0);
    check_pure_shear<3>(1e9);
}

TEST_CASE("von Mises: simple shear with spin stays on the yield surface", "[verification][strength]") {
    check_simple_shear<2>(0.0);
    check_simple_shear<2>(1e9);
    check_simple_shear<3>(1e9);
}

TEST_CASE("von Mises: one plastic step from a known elastic state matches the closed form", "[verification][strength]") {
    check_single_step<2>(0.0);
    check_single_step<2>(1e9);
    check_single_step<3>(0.0);
    check_single_step<3>(1e9);
}

// The full HMX material (Mie-Grueneisen, bulk viscosity, heating): the EOS and q change only
// the pressure, so the deviatoric return is the same as above.
TEST_CASE("von Mises inside the HMX material: uniaxial strain stays on the yield surface", "[verification][strength]") {
    using M = gimlet::presets::hmx_material<>;
    material_point<2, M> mp(gimlet::presets::make_hmx());
    gimlet::space<2>::matrix L = gimlet::space<2>::matrix::Zero();
    L(1, 1) = -1e4;
    const double dt = 1e-9, de = 1e-5;
    for (int n = 1; n <= 3000; ++n) {
        mp.step(L, dt);
        if (mp.eps_p() == 0) continue;
        // Round-off relative to the pressure, which reaches ~0.5 GPa = 5 Y0 here.
        CHECK(mp.sigma_eq() == Approx(Y0).epsilon(1e-12));
    }
    CHECK(mp.eps_p() == Approx((2 * G * 3000 * de - Y0) / (3 * G)).epsilon(1e-10));  // as above
    CHECK(mp.s_zz() == Approx(Y0 / 3).epsilon(1e-12));
    // All plastic work became heat: the Hugoniot part is positive too, so T >= T0 + w_p / c_v.
    CHECK(mp.p().template get<gimlet::fields::temperature>() > hmx.temperature + mp.w_p() / hmx.specific_heat);
}

// jaumann_rotate's plane-strain path (point_step::plane_strain, set by update_material_point in
// 2-D) must be the same rotation as the general 3x3 Cayley form, out-of-plane rows and columns
// included, for a symmetric or non-symmetric s, and keep the invariants: the 2-D hot path relies
// on it. (In the portable build the two agree to the bit: the path keeps the 3x3 form's operands
// and order; a -march=native build may contract them differently, hence a tolerance of 1e-15
// of the largest entry.)
TEST_CASE("Jaumann rotation: the plane-strain path equals the 3x3 form", "[verification][strength]") {
    using T3 = Eigen::Matrix3d;
    for (int k = 0; k < 50; ++k) {
        const double phase = 0.37 * k;
        T3 s;
        s << std::sin(phase), 0.3 * std::cos(2 * phase), 0.2 * std::sin(3 * phase),  //
            0.3 * std::cos(2 * phase), -0.7 * std::cos(phase), -0.1 * std::cos(5 * phase),  //
            0.2 * std::sin(3 * phase), -0.1 * std::cos(5 * phase), 0.4 * std::sin(7 * phase);
        if (k % 2 == 1) s(0, 1) += 0.05 * std::cos(11 * phase), s(2, 0) -= 0.03;  // non-symmetric
        s *= 1e9;
        gimlet::point_step<double> st;
        st.dt = 1e-8;
        const double spin = 1e7 * std::sin(1.3 * k) * (k % 7 == 0 ? 30.0 : 1.0);  // up to |dt W / 2| = 1.5
        st.W(1, 0) = spin;
        st.W(0, 1) = -spin;
        const T3 general = gimlet::strength::jaumann_rotate(st, s);
        st.plane_strain = true;
        const T3 planar = gimlet::strength::jaumann_rotate(st, s);
        CHECK((planar - general).cwiseAbs().maxCoeff() <= 1e-15 * s.cwiseAbs().maxCoeff());
        CHECK(std::abs(planar.squaredNorm() - s.squaredNorm()) <= 1e-14 * s.squaredNorm());
        CHECK(planar(2, 2) == s(2, 2));
    }
}
