// SPDX-License-Identifier: MIT
// thermal::hugoniot_heating with the paper's HMX constants (docs/physics.md sections 6 and 7):
// the Walsh-Christian shock temperature against an independent RK4 integration of the same
// ODE, plastic-work heating, and the irreversible (isentropic-on-expansion) variant.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

namespace {

using S = gimlet::space<2>;
template <gimlet::thermal::expansion X>
using heating = gimlet::thermal::hugoniot_heating<X>;
constexpr auto paper_form = gimlet::thermal::expansion::hugoniot;
constexpr auto irreversible = gimlet::thermal::expansion::isentropic;

const gimlet::presets::hmx_constants hmx{};
const double rho0 = hmx.density, V0 = 1 / rho0, c0 = hmx.sound_speed, s = hmx.slope, Gamma = hmx.gruneisen,
             cv = hmx.specific_heat, T0 = hmx.temperature;

template <gimlet::thermal::expansion X = paper_form>
heating<X> make_heating() {
    return {rho0, c0, s, Gamma, cv, T0};
}

// One particle carrying a temperature, advanced by the policy's update as the solver does.
struct heated_point {
    using fields = gimlet::field_union_t<gimlet::core_fields<S>, gimlet::field_list<gimlet::fields::temperature>>;
    gimlet::particle_store<S, fields> store;
    heated_point() { store.add(); }
    [[nodiscard]] auto p() { return store[0]; }
    [[nodiscard]] double T() { return p().get<gimlet::fields::temperature>(); }
    // Advance from J_old to J_new with `dissipated` J/kg of plastic work.
    template <class H>
    void update(const H& h, double j_old, double j_new, double dissipated = 0) {
        gimlet::point_step<double> st;
        st.J_old = j_old;
        st.J = j_new;
        st.density0 = rho0;
        st.density = rho0 / j_new;
        h.update(st, dissipated, p());
    }
    // Advance from J = j0 to j1 in n equal increments of J.
    template <class H>
    void ramp(const H& h, double j0, double j1, int n) {
        for (int k = 0; k < n; ++k) update(h, j0 + (j1 - j0) * k / n, j0 + (j1 - j0) * (k + 1) / n);
    }
};

// dT/dV = s c0^2 (V0 - V)^2 / (c_v [(s - 1) V0 - s V]^3) - (Gamma / V) T, written out here
// independently of the library.
double rhs(double V, double T) {
    const double d = (s - 1) * V0 - s * V;
    return s * c0 * c0 * (V0 - V) * (V0 - V) / (cv * d * d * d) - Gamma / V * T;
}

// Classical RK4 from (V_a, T_a) to V_b in n steps.
double rk4(double Va, double Ta, double Vb, int n) {
    const double h = (Vb - Va) / n;
    double V = Va, T = Ta;
    for (int k = 0; k < n; ++k) {
        const double k1 = rhs(V, T);
        const double k2 = rhs(V + h / 2, T + h / 2 * k1);
        const double k3 = rhs(V + h / 2, T + h / 2 * k2);
        const double k4 = rhs(V + h, T + h * k3);
        T += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
        V = Va + (k + 1) * h;
    }
    return T;
}

// The shocked compression of a symmetric impact at relative speed 2v (particle-velocity jump
// v): U_s = c0 + s v, mass conservation rho0 U_s = rho (U_s - v) gives eta = 1 - V/V0 = v / U_s.
double shocked_eta(double v) { return v / (c0 + s * v); }

}  // namespace

TEST_CASE("Hugoniot heating: shock temperature against an independent RK4 integration", "[verification][thermal]") {
    const auto h = make_heating();
    // Simpson's rule over one increment [V1, V0] errs by at most (V0 - V1)^5 max|f''''| / 2880
    // in the integral of f = a(V) V^Gamma, i.e. by that over V1^Gamma in T. Evaluated offline
    // (sympy, f'''' sampled on 2001 points of [V1, V0]): 3.14e-3 K for v = 150 m/s and
    // 0.143 K for v = 300 m/s. Over n equal increments the bound is (V0 - V1)^5 / n^4 times the
    // same constant: bound_1 / n^4.
    struct impact {
        double v, simpson_bound_1;
    };
    for (const impact imp : {impact{150.0, 3.2e-3}, impact{300.0, 0.143}}) {
        const double v = imp.v;
        const double eta = shocked_eta(v);
        const double J1 = 1 - eta;
        INFO("v = " << v << " m/s, eta = " << eta);
        // Reference: RK4 with 1e5 steps. Its truncation error is O(dV^4) with dV < 1e-6 V0,
        // negligible; its round-off over 1e5 steps is ~1e-11 K. Halving the steps changes it
        // by less than 1e-10 K.
        const double T_ref = rk4(V0, T0, J1 * V0, 100000);
        CHECK(std::abs(T_ref - rk4(V0, T0, J1 * V0, 50000)) < 1e-10);

        // The policy through its update, in n increments as a simulation would advance it.
        // Tolerance: Simpson's bound for n increments plus 1e-10 K for the round-off of the
        // reference and of T over the increments.
        double T_100 = 0;
        for (int n : {50, 100, 200}) {
            INFO(n << " increments");
            heated_point q;
            h.initialize(q.p());
            REQUIRE(q.T() == T0);
            q.ramp(h, 1.0, J1, n);
            CHECK(std::abs(q.T() - T_ref) < imp.simpson_bound_1 / std::pow(n, 4) + 1e-10);
            if (n == 100) T_100 = q.T();
        }

        // One increment: Simpson over the whole compression, within the single-step bound.
        heated_point one;
        h.initialize(one.p());
        one.update(h, 1.0, J1);
        CHECK(std::abs(one.T() - T_ref) < imp.simpson_bound_1);

        std::printf("Hugoniot heating, HMX, v = %5.1f m/s: eta = %.5f, P_H = %.3f GPa, T = %.3f K "
                    "(RK4 reference %.6f K; 100 increments %.6f K; one increment %.6f K). "
                    "Paper: bulk shocked HMX ~310 K at 300 m/s.\n",
                    v, eta, rho0 * c0 * c0 * eta / ((1 - s * eta) * (1 - s * eta)) * 1e-9, T_100, T_ref,
                    T_100, one.T());
    }
}

TEST_CASE("Hugoniot heating: plastic work heats by dw / c_v", "[verification][thermal]") {
    const auto h = make_heating();
    heated_point pt;
    h.initialize(pt.p());
    // No volume change: only the dissipated work acts. w = 3125 J/kg gives dT = 2.5 K, and
    // 300 + 2.5 is exact in binary, so the result is exact.
    pt.update(h, 0.95, 0.95, 3125.0);
    CHECK(pt.T() == T0 + 2.5);
    // An arbitrary amount: T0 + w / c_v to one rounding of the sum (1e-15 relative).
    heated_point q;
    h.initialize(q.p());
    const double w = 1234.5678;
    q.update(h, 1.0, 1.0, w);
    CHECK(q.T() == Approx(T0 + w / cv).epsilon(1e-15));
    // Both variants agree (the expansion switch does not touch dissipation).
    heated_point r;
    const auto hi = make_heating<irreversible>();
    hi.initialize(r.p());
    r.update(hi, 1.0, 1.0, w);
    CHECK(r.T() == q.T());
}

TEST_CASE("Hugoniot heating: the irreversible variant is isentropic on expansion only", "[verification][thermal]") {
    const auto hp = make_heating<paper_form>();
    const auto hi = make_heating<irreversible>();
    const double J1 = 1 - shocked_eta(300.0);

    // Compression: identical to the paper's form, increment by increment (same arithmetic).
    heated_point a, b;
    hp.initialize(a.p());
    hi.initialize(b.p());
    for (int k = 0; k < 100; ++k) {
        const double j0 = 1 - (1 - J1) * k / 100, j1 = 1 - (1 - J1) * (k + 1) / 100;
        a.update(hp, j0, j1);
        b.update(hi, j0, j1);
        REQUIRE(a.T() == b.T());
    }
    const double T_shocked = b.T();
    REQUIRE(T_shocked > T0);

    // Expansion back to V0 in 100 increments. Irreversible variant: only -(Gamma/V) T dV acts,
    // so T V^Gamma is constant: T_final = T_shocked (J1)^Gamma. Each increment multiplies by
    // (V_old/V_new)^Gamma; the product telescopes, leaving round-off of 100 pow calls
    // (tolerance 1e-13 relative).
    b.ramp(hi, J1, 1.0, 100);
    CHECK(b.T() == Approx(T_shocked * std::pow(J1, Gamma)).epsilon(1e-13));
    // At every intermediate volume as well.
    heated_point c;
    hi.initialize(c.p());
    c.ramp(hi, 1.0, J1, 100);
    for (int k = 0; k < 100; ++k) {
        const double j0 = J1 + (1 - J1) * k / 100, j1 = J1 + (1 - J1) * (k + 1) / 100;
        c.update(hi, j0, j1);
        CHECK(c.T() * std::pow(j1, Gamma) == Approx(T_shocked * std::pow(J1, Gamma)).epsilon(1e-13));
    }
    // It keeps shock heat: above T0 after release, and cooler than the shocked state.
    CHECK(b.T() > T0);
    CHECK(b.T() < T_shocked);

    // The paper's form retraces the same ODE on expansion: the RK4 integration back from the
    // shocked state (Simpson's bound for 100 increments, 0.143 K / 1e8, plus round-off: 1e-8 K
    // is generous), which returns to T0 (the ODE is reversible) up to the error of both legs.
    a.ramp(hp, J1, 1.0, 100);
    CHECK(std::abs(a.T() - rk4(J1 * V0, T_shocked, V0, 100000)) < 1e-8);
    CHECK(std::abs(a.T() - T0) < 1e-8);
    CHECK(b.T() > a.T() + 1.0);  // the variants differ by far more than round-off
}
