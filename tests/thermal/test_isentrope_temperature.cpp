// SPDX-License-Identifier: MIT
// thermal::isentrope_temperature with the paper's HMX constants: T(V, e) from the reference
// isentrope of the Mie-Grueneisen EOS. Checked against the Walsh-Christian Hugoniot temperature
// (thermal::hugoniot_heating, an independent derivation), an independent Simpson integration of
// the isentrope, a slow compression and release through the material-point update, the entropy a
// shock leaves on release, and the stop when a particle's energy falls below the isentrope.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>

namespace {

using Catch::Matchers::Contains;

const gimlet::presets::hmx_constants hmx{};
const double rho0 = hmx.density, c0 = hmx.sound_speed, s = hmx.slope, Gamma = hmx.gruneisen, cv = hmx.specific_heat,
             T0 = hmx.temperature, K0 = rho0 * c0 * c0;

gimlet::thermal::isentrope_temperature make_thermal() { return {rho0, c0, s, Gamma, cv, T0}; }

double hugoniot_pressure(double j) {
    const double eta = 1 - j;
    return eta >= 0 ? K0 * eta / ((1 - s * eta) * (1 - s * eta)) : K0 * (1 / j - 1);
}
double hugoniot_energy(double j) { return 0.5 * hugoniot_pressure(j) * (1 - j) / rho0; }

// e_s(J) by composite Simpson in J on d(J^Gamma e_s)/dJ = J^Gamma (-P_H / rho0 + Gamma e_H / J):
// the same ODE as the policy's, written from the EOS and integrated another way.
double simpson_reference_energy(double j, int n = 20000) {
    auto g = [](double x) { return std::pow(x, Gamma) * (-hugoniot_pressure(x) / rho0 + Gamma * hugoniot_energy(x) / x); };
    const double h = (j - 1) / n;
    double sum = g(1) + g(j);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * g(1 + i * h);
    return sum * h / 3 * std::pow(j, -Gamma);
}

// A 3-D material point of strength-free Mie-Grueneisen matter, driven by a prescribed velocity
// gradient through gimlet::update_material_point, as the solver drives it.
using S3 = gimlet::space<3>;
template <class Thermal>
using fluid = gimlet::material<gimlet::strength::none, gimlet::eos::mie_gruneisen<>, Thermal>;

template <class Thermal>
struct driven_point {
    using fields = gimlet::field_union_t<gimlet::core_fields<S3>, typename fluid<Thermal>::required_fields>;
    gimlet::particle_store<S3, fields> store;
    fluid<Thermal> mat;
    std::size_t step = 0;
    explicit driven_point(const Thermal& th) : mat{rho0, gimlet::strength::none{}, gimlet::eos::mie_gruneisen<>{rho0, c0, s, Gamma}, th} {
        auto p = store[store.add()];
        p.template get<gimlet::fields::volume0>() = 1e-9;
        p.template get<gimlet::fields::mass>() = rho0 * 1e-9;
        mat.thermal.initialize(p);
    }
    [[nodiscard]] auto p() { return store[0]; }
    [[nodiscard]] double J() { return p().template get<gimlet::fields::deformation_gradient>().determinant(); }
    [[nodiscard]] double T() { return p().template get<gimlet::fields::temperature>(); }
    // Hydrostatic volumetric strain rate `rate` (1/s) until J passes `target`.
    void ramp(double rate, double target, double dt) {
        const S3::matrix L = S3::matrix::Identity() * (rate / 3);
        while (rate < 0 ? J() > target : J() < target) {
            gimlet::update_material_point(mat, p(), L, dt, 1e-3, step, double(step) * dt);  // no viscosity
            ++step;
        }
    }
};

}  // namespace

TEST_CASE("isentrope temperature: the reference isentrope against an independent integration", "[thermal][verification]") {
    const auto th = make_thermal();
    CHECK(th.reference_energy(1.0) == 0.0);
    for (const double j : {0.62, 0.65, 0.7, 0.8, 0.876, 0.95, 0.999, 1.001, 1.1, 1.5, 2.5, 3.5}) {
        INFO("J = " << j);
        const double want = simpson_reference_energy(j);
        // To 1e-8 relative, and absolutely to c_v times a millionth of a kelvin near J = 1 where
        // e_s itself vanishes.
        CHECK(th.reference_energy(j) == Approx(want).epsilon(1e-8).margin(cv * 1e-6));
        // The isentrope's pressure is -rho0 de_s/dJ: a central difference of the table.
        const double h = 1e-6;
        const double slope = (th.reference_energy(j + h) - th.reference_energy(j - h)) / (2 * h);
        CHECK(th.reference_pressure(j) == Approx(-rho0 * slope).epsilon(1e-6));
    }
    CHECK(th.isentrope(0.8) == Approx(T0 * std::pow(0.8, -Gamma)));
    CHECK_THROWS_AS(th.reference_energy(1 - 1 / s), gimlet::invalid_parameter);
}

TEST_CASE("isentrope temperature: the reference isentrope is the EOS's own, on and off the table",
          "[thermal][verification]") {
    // de_s/dJ = -P(J, e_s) / rho0 with P from eos::mie_gruneisen's Hugoniot (P_H, e_H) and
    // Gamma rho = Gamma rho0 / J, integrated by RK4 from e_s(1) = 0 in x = ln(J - (1 - 1/s)).
    // The table spans 1 - s eta = 0.01 (J = 0.6192) to J = 3.003; 0.617 and 3.5 lie beyond it.
    const gimlet::eos::mie_gruneisen<> eos{rho0, c0, s, Gamma};
    const auto th = make_thermal();
    const double j_sing = 1 - 1 / s;
    auto slope = [&](double x, double e) {  // de/dx
        const double j = j_sing + std::exp(x);
        const double p = eos.hugoniot_pressure(j) + Gamma * rho0 / j * (e - eos.hugoniot_energy(j));
        return -p / rho0 * (j - j_sing);
    };
    for (const double target : {0.617, 0.63, 0.7, 0.9, 1.2, 2.0, 3.5}) {
        const int n = 20000;
        const double x0 = std::log(1 - j_sing), x1 = std::log(target - j_sing), h = (x1 - x0) / n;
        double e = 0, x = x0;
        for (int k = 0; k < n; ++k, x = x0 + k * h) {
            const double k1 = slope(x, e), k2 = slope(x + h / 2, e + h / 2 * k1), k3 = slope(x + h / 2, e + h / 2 * k2),
                         k4 = slope(x + h, e + h * k3);
            e += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
        }
        INFO("J = " << target);
        CHECK(th.reference_energy(target) == Approx(e).epsilon(1e-8).margin(cv * 1e-6));
    }
}

TEST_CASE("isentrope temperature: the update's tabulated T_s is T0 J^-Gamma to 1e-12, exact off the table",
          "[thermal][verification]") {
    // The particle update interpolates T_s in the reference table's cell: cubic Hermite in
    // x = ln(J - J_sing) with exact slopes, whose error is at most dx^4 / 384 times the largest
    // |d^4 T_s / dx^4| (the Hermite remainder). With w = (J - J_sing) / J that derivative is T_s
    // times Gamma^4 w^4 + 6 Gamma^3 w^4 - 6 Gamma^3 w^3 + 11 Gamma^2 w^4 - 18 Gamma^2 w^3
    // + 7 Gamma^2 w^2 + 6 Gamma w^4 - 12 Gamma w^3 + 7 Gamma w^2 - Gamma w, at most 0.566 in size
    // on the table for Gamma = 1.1 (at J = 2.41); dx = ln(100) / 1024, so the bound is 6.03e-13
    // of T_s. temperature() computes T_s exactly, so the two differ by that and rounding.
    driven_point<gimlet::thermal::isentrope_temperature> pt(make_thermal());
    const auto& th = pt.mat.thermal;
    const double j_sing = 1 - 1 / s;
    double worst = 0;
    auto difference = [&](double j, double heat) {
        const double e_th = th.reference_energy(j) + cv * heat;
        gimlet::point_step<double> st;
        st.J = j;
        pt.p().get<gimlet::fields::specific_internal_energy>() = e_th;
        th.update(st, 0.0, pt.p());
        const double want = th.temperature(j, e_th);
        return std::abs(pt.T() - want) / want;
    };
    // The table's 1,430 cells, from the compressed end (1 - s eta = 0.01) to J = 3, at 14,337
    // points uniform in x (about ten a cell, at varying places in each).
    const double x0 = std::log(0.01 / s), x3 = std::log(3.0 - j_sing);
    const int points = 7 * 1024 * 2;
    int bad = 0;
    for (int k = 0; k <= points; ++k) {
        const double j = j_sing + std::exp(x0 + (x3 - x0) * k / points);
        for (const double heat : {0.0, 500.0}) {
            const double d = difference(j, heat);
            worst = std::max(worst, d);
            bad += !(d <= 1e-12);
        }
    }
    INFO("worst relative difference " << worst);
    CHECK(bad == 0);
    CHECK(worst > 0);  // the update does interpolate (an exact T_s would read 0 everywhere)
    // Off the table, at both ends, T_s is computed exactly: the same value to rounding.
    for (const double j : {j_sing + 0.004 / s, 3.5, 10.0}) {
        INFO("J = " << j);
        CHECK(difference(j, 300.0) <= 1e-14);
    }
}

TEST_CASE("isentrope temperature: on the Hugoniot it is the Walsh-Christian temperature", "[thermal][verification]") {
    // T(V, e_H(V)) against thermal::hugoniot_heating's integration of dT/dV along the Hugoniot
    // from T0 (PHYSICS of both: T ds = c_v dT + Gamma c_v T / V dV, de_H = T ds - P_H dV), in
    // steps of 1e-4 in J.
    const auto th = make_thermal();
    const gimlet::thermal::hugoniot_heating<> wc{rho0, c0, s, Gamma, cv, T0};
    double t_wc = T0, j = 1.0;
    for (const double eta : {0.05, 0.0852, 0.1238, 0.1535, 0.2, 0.246, 0.3}) {
        while (j > 1 - eta) {
            const double next = std::max(j - 1e-4, 1 - eta);
            t_wc = wc.advance(t_wc, j / rho0, next / rho0);
            j = next;
        }
        const double t = th.temperature(j, hugoniot_energy(j));
        std::printf("Hugoniot eta %.4f: T(V, e_H) = %.3f K, Walsh-Christian %.3f K\n", eta, t, t_wc);
        CHECK(t == Approx(t_wc).margin(0.01));
    }
}

TEST_CASE("isentrope temperature: a slow ramp follows the isentrope there and back", "[thermal][verification]") {
    // Hydrostatic compression at |tr D| = 1e3 1/s to eta = 0.2 and back, viscosity off: the
    // isentrope reads T0 (1/0.8)^Gamma = 383.5 K at the top and T0 at the end. The paper's
    // Walsh-Christian form (thermal::hugoniot_heating) gives every state the Hugoniot temperature
    // of its compression instead: 604.5 K at eta = 0.2.
    driven_point<gimlet::thermal::isentrope_temperature> ramp(make_thermal());
    ramp.ramp(-1e3, 0.8, 1e-8);
    const double j_top = ramp.J(), t_top = ramp.T();
    ramp.ramp(1e3, 1.0, 1e-8);
    std::printf("ramp: top J = %.6f T = %.3f K (isentrope %.3f K); back at J = %.6f T = %.6f K after %zu steps\n",
                j_top, t_top, T0 * std::pow(j_top, -Gamma), ramp.J(), ramp.T(), ramp.step);
    CHECK(t_top == Approx(T0 * std::pow(0.8, -Gamma)).margin(0.5));
    CHECK(ramp.T() == Approx(T0).margin(0.5));

    driven_point<gimlet::thermal::hugoniot_heating<>> paper(gimlet::thermal::hugoniot_heating<>{rho0, c0, s, Gamma, cv, T0});
    paper.ramp(-1e3, 0.8, 1e-8);
    std::printf("ramp, the paper's form: top T = %.3f K\n", paper.T());
    CHECK(paper.T() == Approx(604.5).margin(1.0));
}

TEST_CASE("isentrope temperature: release from a shock keeps its entropy", "[thermal][verification]") {
    // A particle on the Hugoniot of a symmetric impact at v (eta = v / (c0 + s v), e = e_H)
    // released slowly to J = 1: theta = T / T_s(V) is constant along an isentrope, so it lands at
    // theta T0 above T0, where the Walsh-Christian form returns to T0 exactly.
    for (const double v : {300.0, 500.0, 700.0}) {
        const double eta = v / (c0 + s * v), j = 1 - eta;
        const auto th = make_thermal();
        driven_point<gimlet::thermal::isentrope_temperature> pt(th);
        // Put the point on the Hugoniot: F = J^(1/3) I, e = e_H.
        auto p = pt.p();
        p.get<gimlet::fields::deformation_gradient>() = S3::matrix::Identity() * std::cbrt(j);
        p.get<gimlet::fields::specific_internal_energy>() = hugoniot_energy(j);
        // The oracle from the independent integration: T_H = T0 J^-Gamma + (e_H - e_s) / c_v.
        const double t_shock = T0 * std::pow(j, -Gamma) + (hugoniot_energy(j) - simpson_reference_energy(j)) / cv;
        const double theta = t_shock / (T0 * std::pow(j, -Gamma));
        pt.ramp(1e3, 1.0, 1e-8);
        const double landed = pt.T() * std::pow(pt.J(), Gamma);  // T / T_s(V) times T0
        std::printf("release from %3.0f m/s: shock T %.2f K, theta %.5f, landed %.2f K at J = %.6f "
                    "(isentropic release %.2f K)\n", v, t_shock, theta, pt.T(), pt.J(), theta * T0);
        CHECK(landed == Approx(theta * T0).margin(0.1));
        CHECK(pt.T() > T0 + 0.9 * (theta - 1) * T0);  // the shock's heat is kept (the paper's form: T0)
    }
}

TEST_CASE("isentrope temperature: energy below the isentrope stops the run, naming the particle", "[thermal][robustness]") {
    driven_point<gimlet::thermal::isentrope_temperature> pt(make_thermal());
    pt.ramp(-1e3, 0.99, 1e-8);
    // Corrupt the particle: take away 1 K worth of energy (the tolerance is 0.1 K).
    pt.p().get<gimlet::fields::specific_internal_energy>() -= cv;
    try {
        pt.ramp(-1e3, 0.98, 1e-8);
        FAIL("no numerical_error");
    } catch (const gimlet::numerical_error& e) {
        const std::string what = e.what();
        CHECK_THAT(what, Contains("particle 0") && Contains("below the reference isentrope") && Contains("step ") &&
                             Contains("cold_tolerance"));
    }
    // Within the tolerance it goes on, reading a temperature just below the isentrope's.
    driven_point<gimlet::thermal::isentrope_temperature> ok(make_thermal());
    ok.ramp(-1e3, 0.99, 1e-8);
    ok.p().get<gimlet::fields::specific_internal_energy>() -= 0.05 * cv;
    ok.ramp(-1e3, 0.98, 1e-8);
    CHECK(ok.T() < make_thermal().isentrope(ok.J()));
}

TEST_CASE("isentrope temperature: bad parameters are refused by name", "[thermal][robustness]") {
    using T = gimlet::thermal::isentrope_temperature;
    CHECK_THROWS_WITH(T(0, c0, s, Gamma, cv, T0), Contains("rho0"));
    CHECK_THROWS_WITH(T(rho0, -1, s, Gamma, cv, T0), Contains("c0"));
    CHECK_THROWS_WITH(T(rho0, c0, 1.0, Gamma, cv, T0), Contains("slope s"));
    CHECK_THROWS_WITH(T(rho0, c0, s, -0.1, cv, T0), Contains("Gamma"));
    CHECK_THROWS_WITH(T(rho0, c0, s, Gamma, 0, T0), Contains("c_v"));
    CHECK_THROWS_WITH(T(rho0, c0, s, Gamma, cv, std::nan("")), Contains("T0"));
    CHECK_THROWS_WITH(T(rho0, c0, s, Gamma, cv, T0, -1), Contains("cold_tolerance"));
}
