// SPDX-License-Identifier: MIT
// eos::mie_gruneisen with the paper's HMX constants (docs/physics.md sections 5 and 7): the Hugoniot
// reference curve in compression and tension, the energy term, continuity at eta = 0, the
// tangent bulk modulus against a finite-difference isentrope, the pressure-energy solve of a
// step, and the stop at the singularity eta = 1/s.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
#include <string>

using Catch::Matchers::Contains;

namespace {

using S = gimlet::space<2>;
using mg_standard = gimlet::eos::mie_gruneisen<gimlet::eos::energy_reference::internal_energy>;
using mg_paper = gimlet::eos::mie_gruneisen<gimlet::eos::energy_reference::plastic_work>;
using hmx_mat = gimlet::presets::hmx_material<>;

const gimlet::presets::hmx_constants hmx{};
const double rho0 = hmx.density, c0 = hmx.sound_speed, s = hmx.slope, Gamma = hmx.gruneisen;
const double K0 = rho0 * c0 * c0;  // 14.26 GPa

mg_standard standard() { return {rho0, c0, s, Gamma}; }
mg_paper paper() { return {rho0, c0, s, Gamma}; }

// A one-particle store with every field the HMX material needs (plastic_work included).
struct one_particle {
    using fields = gimlet::field_union_t<gimlet::core_fields<S>, hmx_mat::required_fields>;
    gimlet::particle_store<S, fields> store;
    one_particle() {
        auto p = store[store.add()];
        p.get<gimlet::fields::volume0>() = 1e-6;
        p.get<gimlet::fields::mass>() = rho0 * 1e-6;
        p.get<gimlet::fields::position>() = S::vector(0.0125, 0.0375);
    }
    [[nodiscard]] auto p() { return store[0]; }
};

// The state of a material point at J (density rho0 / J), with the end-of-step energy e_b less
// the pressure's work factor f (see point_step).
gimlet::point_step<double> state(double J, double e_b = 0, double f = 0) {
    gimlet::point_step<double> st;
    st.J = J;
    st.J_old = J;
    st.density0 = rho0;
    st.density = rho0 / J;
    st.energy_before_pressure = e_b;
    st.pressure_work_factor = f;
    return st;
}

}  // namespace

TEST_CASE("Mie-Grueneisen: Hugoniot pressure, compression and tension branches", "[verification][eos]") {
    const auto eos = standard();
    for (double eta : {0.01, 0.05, 0.1, 0.2, 0.3}) {
        INFO("eta = " << eta);
        const double J = 1 - eta;
        const double ph = rho0 * c0 * c0 * eta / ((1 - s * eta) * (1 - s * eta));
        // The same formula evaluated in another order: a few ulps (1e-13 relative).
        CHECK(eos.hugoniot_pressure(J) == Approx(ph).epsilon(1e-13));
        CHECK(eos.hugoniot_energy(J) == Approx(0.5 * ph * eta / rho0).epsilon(1e-13));
    }
    // Spot value: eta = 0.1 gives 14.26 GPa * 0.1 / 0.74^2 = 2.605 GPa.
    CHECK(eos.hugoniot_pressure(0.9) == Approx(2.6049e9).epsilon(1e-4));  // 5 digits quoted

    // Tension: rho0 c0^2 (V0/V - 1). 5 % tension (J = 1.05) is -0.679 GPa; the misprinted
    // rho0^2 c0^2 form would give -1.29e12 "Pa" (1900 times larger), so a GPa-scale magnitude
    // rules it out.
    for (double J : {1.0001, 1.01, 1.05, 1.2, 1.5}) {
        INFO("J = " << J);
        CHECK(eos.hugoniot_pressure(J) == Approx(rho0 * c0 * c0 * (1 / J - 1)).epsilon(1e-13));  // a few ulps
        CHECK(eos.hugoniot_pressure(J) < 0);
    }
    const double p5 = eos.hugoniot_pressure(1.05);
    CHECK(std::abs(p5) > 0.1e9);
    CHECK(std::abs(p5) < 10e9);
    CHECK(p5 == Approx(-0.6793e9).epsilon(1e-4));  // 4 digits quoted
    CHECK(std::abs(rho0 * rho0 * c0 * c0 * (1 / 1.05 - 1)) > 1e12);  // the misprint's value
    CHECK(std::abs(p5 - rho0 * rho0 * c0 * c0 * (1 / 1.05 - 1)) > 1e11);
}

TEST_CASE("Mie-Grueneisen: on the Hugoniot energy the pressure is P_H", "[verification][eos]") {
    one_particle pt;
    auto p = pt.p();
    const auto eos = standard();
    const auto eos_paper = paper();
    for (double J : {0.7, 0.8, 0.9, 0.95, 0.99, 1.0, 1.01, 1.05, 1.2}) {
        INFO("J = " << J);
        const double ph = eos.hugoniot_pressure(J);
        // e = e_H, no pressure work in the step (f = 0): P = P_H + Gamma rho (e_H - e_H).
        const double e_h = eos.hugoniot_energy(J);
        p.get<gimlet::fields::specific_internal_energy>() = e_h;
        CHECK(eos.pressure(state(J, e_h, 0.0), p) == Approx(ph).margin(1e-9 * K0));  // round-off of P_H and e_H terms
        // The paper's form with w_p = 0 is exactly P_H; with w_p > 0 it adds Gamma rho w_p.
        p.get<gimlet::fields::plastic_work>() = 0;
        CHECK(eos_paper.pressure(state(J), p) == ph);
        p.get<gimlet::fields::plastic_work>() = 5e3;  // J/kg
        CHECK(eos_paper.pressure(state(J), p) == Approx(ph + Gamma * rho0 / J * 5e3).epsilon(1e-13));  // ulps
    }
}

TEST_CASE("Mie-Grueneisen: continuous at eta = 0, and K = rho0 c0^2 at rest", "[verification][eos]") {
    one_particle pt;
    auto p = pt.p();
    const auto eos = standard();
    const double d = 1e-9;
    CHECK(eos.hugoniot_pressure(1.0) == 0.0);
    // Both branches have slope rho0 c0^2 at eta = 0: P(1 -/+ d) = +/- K0 d (1 + O(d)), so the
    // secants from either side agree with K0 to O(d) = 1e-9 plus the round-off of 1 - J (ulp(1)/d
    // = 2e-7); tolerance 1e-6 relative.
    CHECK(eos.hugoniot_pressure(1 - d) / d == Approx(K0).epsilon(1e-6));
    CHECK(-eos.hugoniot_pressure(1 + d) / d == Approx(K0).epsilon(1e-6));
    // Tangent bulk modulus with e = e_H on both sides: K0 to O(d) (coefficients ~ 2s + Gamma).
    for (double J : {1 - d, 1 + d}) {
        p.get<gimlet::fields::specific_internal_energy>() = eos.hugoniot_energy(J);
        CHECK(eos.bulk_modulus(gimlet::point_state<double>{J, rho0 / J, rho0}, p) == Approx(K0).epsilon(1e-7));
    }
    // At rest exactly: K = rho0 c0^2 (exact arithmetic: J * P_H'(0) = K0).
    p.get<gimlet::fields::specific_internal_energy>() = 0;
    CHECK(eos.bulk_modulus(gimlet::point_state<double>{1.0, rho0, rho0}, p) == K0);

    // The longitudinal wave speed of HMX at rest: sqrt((rho0 c0^2 + 4G/3) / rho0) = 3292 m/s.
    const hmx_mat mat = gimlet::presets::make_hmx();
    const double G = mat.strength.shear_modulus();
    const double c_expected = std::sqrt((K0 + 4 * G / 3) / rho0);
    const double c = gimlet::longitudinal_wave_speed(p, mat);
    CHECK(c == Approx(c_expected).epsilon(1e-14));  // same arithmetic up to ulps
    CHECK(std::abs(c - 3290.0) < 5.0);             // docs/physics.md quotes 3.29 km/s (3 digits)
}

TEST_CASE("Mie-Grueneisen: bulk modulus is the isentropic -V dP/dV", "[verification][eos]") {
    one_particle pt;
    auto p = pt.p();
    const auto eos = standard();
    // P(J, e) from the EOS itself (energy form, no work factor).
    const auto P = [&](double J, double e) { return eos.pressure(state(J, e, 0.0), p); };
    for (double J : {0.97, 0.9, 0.8, 1.05}) {
        for (double excess : {0.0, 2e4, -1e4}) {  // e - e_H (J/kg)
            INFO("J = " << J << ", e - e_H = " << excess);
            const double e = eos.hugoniot_energy(J) + excess;
            p.get<gimlet::fields::specific_internal_energy>() = e;
            const double K = eos.bulk_modulus(gimlet::point_state<double>{J, rho0 / J, rho0}, p);
            // Central difference along the isentrope de = -P dV (V = J / rho0): e_{+/-} =
            // e - P(J, e) dV_{+/-}. The O(dV^2) error of that energy is the same on both sides
            // and cancels, so the secant is O(h^2): error C h^2 with C = P'''/(6 P') up to ~40
            // here (P_H' grows like (1 - s eta)^-3), i.e. <= 4e-9 at h = 1e-5; round-off
            // ~ ulp(P) / (h K) ~ 1e-11. Tolerance 1e-7 relative.
            const auto k_fd = [&](double h) {
                const double p0 = P(J, e);
                const double jp = J * (1 + h), jm = J * (1 - h);
                const double ep = e - p0 * (jp - J) / rho0, em = e - p0 * (jm - J) / rho0;
                return -J * (P(jp, ep) - P(jm, em)) / (jp - jm);  // -V dP/dV = -J dP/dJ
            };
            CHECK(K == Approx(k_fd(1e-5)).epsilon(1e-7));
            // The remaining discrepancy is the secant's own O(h^2) error, not a slip in K: it
            // shrinks 100-fold from h = 1e-4 to 1e-5 (compressed states, where it is far above
            // round-off; the ratio is 100 (1 + O(h^2)), round-off adds < 1 %).
            if (J < 1) {
                const double r = (K - k_fd(1e-4)) / (K - k_fd(1e-5));
                CHECK(r > 90);
                CHECK(r < 110);
            }
        }
    }
}

TEST_CASE("Mie-Grueneisen: pressure and end-of-step energy are solved together", "[verification][eos]") {
    one_particle pt;
    auto p = pt.p();
    const auto eos = standard();
    for (double J : {0.9, 0.98, 1.03}) {
        for (double f : {-2e-6, -1e-8, 3e-7}) {  // pressure_work_factor dt tr(D) / (2 rho) (m^3/kg)
            INFO("J = " << J << ", f = " << f);
            const double e_h = eos.hugoniot_energy(J);
            const double e_b = e_h + 1.5e4;
            const double pres = eos.pressure(state(J, e_b, f), p);
            // Self-consistency: P = P_H + Gamma rho (e - e_H) with e = e_b - f P. Round-off of the
            // solve, relative to the largest term (P_H or Gamma rho (e_b - e_H) ~ 35 MPa): 1e-12.
            const double rhs = eos.hugoniot_pressure(J) + Gamma * rho0 / J * (e_b - f * pres - e_h);
            const double scale = std::abs(eos.hugoniot_pressure(J)) + Gamma * rho0 / J * std::abs(e_b - e_h);
            CHECK(std::abs(pres - rhs) < 1e-12 * scale);
        }
    }
}

TEST_CASE("Mie-Grueneisen: the singularity at eta = 1/s stops with a clear error, never inf/NaN", "[verification][eos]") {
    one_particle pt;
    auto p = pt.p();
    const auto eos = standard();
    const auto eos_paper = paper();
    // Close to eta = 1/s = 0.385 (J = 0.615) the EOS must throw, naming particle, eta and the
    // singularity.
    const double j_sing = 1 - 1 / s;
    for (double J : {j_sing + 1e-3, j_sing + 1e-6, j_sing}) {
        INFO("J = " << J);
        CHECK_THROWS_AS(eos.pressure(state(J), p), gimlet::numerical_error);
        CHECK_THROWS_WITH(eos.pressure(state(J), p), Contains("particle 0") && Contains("eta") && Contains("singular"));
        CHECK_THROWS_AS(eos_paper.pressure(state(J), p), gimlet::numerical_error);
        CHECK_THROWS_WITH(eos_paper.pressure(state(J), p), Contains("particle 0") && Contains("eta") && Contains("singular"));
    }

    // Fine sampling of J in (0.5, 1.5): finite, or numerical_error; never inf/NaN. The thrown
    // region is exactly the compressed side of the documented margin (1 - s eta <= 0.05).
    std::size_t finite = 0, thrown = 0;
    double lowest_finite = 2, highest_thrown = 0;
    for (int k = 1; k < 100000; ++k) {
        const double J = 0.5 + 1e-5 * k;
        p.get<gimlet::fields::specific_internal_energy>() = 0;
        p.get<gimlet::fields::plastic_work>() = 0;
        try {
            const double a = eos.pressure(state(J, 1e3, -1e-7), p);
            const double b = eos_paper.pressure(state(J), p);
            const double kb = eos.bulk_modulus(gimlet::point_state<double>{J, rho0 / J, rho0}, p);
            if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(kb)) FAIL("non-finite at J = " << J);
            ++finite;
            lowest_finite = std::min(lowest_finite, J);
        } catch (const gimlet::numerical_error&) {
            ++thrown;
            highest_thrown = std::max(highest_thrown, J);
        }
    }
    CHECK(finite + thrown == 99999);
    CHECK(thrown > 0);
    CHECK(highest_thrown < lowest_finite);
    CHECK(highest_thrown == Approx(1 - 0.95 / s).margin(1e-5));  // within one sample of the margin

    // Through the material-point update: uniaxial compression of an HMX particle until it
    // stops. Every pressure before that is finite; the error names the particle and eta.
    using P2 = gimlet::particle_store<S, gimlet::field_union_t<gimlet::core_fields<S>, hmx_mat::required_fields>>;
    P2 store;
    auto q = store[store.add()];
    q.get<gimlet::fields::volume0>() = 1e-6;
    q.get<gimlet::fields::mass>() = rho0 * 1e-6;
    const hmx_mat mat = gimlet::presets::make_hmx();
    mat.thermal.initialize(q);
    S::matrix L = S::matrix::Zero();
    L(1, 1) = -1e5;  // 1e-3 strain per step of 1e-8 s
    bool stopped = false;
    for (std::size_t step = 0; step < 2000 && !stopped; ++step) {
        try {
            gimlet::update_material_point(mat, q, L, 1e-8, 1e-3, step, 1e-8 * double(step));  // 1 mm cells
            REQUIRE(q.get<gimlet::fields::stress>().allFinite());
            REQUIRE(std::isfinite(q.get<gimlet::fields::stress_zz>()));
        } catch (const gimlet::numerical_error& err) {
            stopped = true;
            const std::string what = err.what();
            CHECK_THAT(what, Contains("particle 0") && Contains("eta") && Contains("singular") && Contains("step "));
            // It stopped at the margin, not before: 1 - s eta <= 0.05 within one step (1e-3).
            const double J = q.get<gimlet::fields::deformation_gradient>().determinant();
            CHECK(1 - s * (1 - J) <= 0.05);
            CHECK(1 - s * (1 - J) > 0.05 - s * 1e-3);
        }
    }
    CHECK(stopped);
}
