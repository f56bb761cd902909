// SPDX-License-Identifier: MIT
// The analytic references of tests/support/spherical_shell.hpp checked against what defines
// them, not against their own formulas (docs/equations.md, "Spherical shells: Lame and
// Carroll-Holt"):
//  * Lame: the equilibrium equation by finite differences of the stresses, the two boundary
//    conditions, and the stresses from the displacement's strains by Hooke's law; the first
//    yield found on the elastic field; the incompressible limit against Carroll-Holt's elastic
//    phase;
//  * Carroll-Holt: the outer pressure from integrating the equilibrium equation with a
//    constitutive law (Simpson's rule), the distension from volumes integrated over the shell,
//    the mean-stress theorem and the compressibility error from the solid's integrated volume.
#include "spherical_shell.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace {

constexpr double pi = 3.14159265358979323846;

// Simpson's rule on [lo, hi] with n (even) intervals.
double simpson(const std::function<double(double)>& f, double lo, double hi, int n) {
    const double h = (hi - lo) / n;
    double sum = f(lo) + f(hi);
    for (int i = 1; i < n; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * f(lo + i * h);
    return sum * h / 3.0;
}

// Five-point central first derivative with step h (error of order h^4).
double derivative(const std::function<double(double)>& f, double x, double h) {
    return (f(x - 2.0 * h) - 8.0 * f(x - h) + 8.0 * f(x + h) - f(x + 2.0 * h)) / (12.0 * h);
}

// A shell of the HMX preset's moduli (docs/equations.md, "presets::make_hmx()"): G = 4.75 GPa,
// Y = 100 MPa, K = 14.3 GPa (rho0 c0^2), b/a = 3, pushed 1 um inward.
constexpr double shell_a = 2e-3;
constexpr double shell_b = 6e-3;
constexpr double hmx_bulk = 14.3e9;
constexpr double hmx_shear = 4.75e9;
constexpr double hmx_yield = 100e6;

std::vector<gimlet::test::lame_sphere> lame_cases() {
    return {gimlet::test::lame_sphere(shell_a, shell_b, -1e-6, hmx_bulk, hmx_shear),
            // nearly incompressible (nu = 0.4998) and pulled outward
            gimlet::test::lame_sphere(shell_a, shell_b, 2e-6, 2000.0 * hmx_shear, hmx_shear),
            // compressible (nu = 0.1), a thin shell
            gimlet::test::lame_sphere(5e-3, 5.5e-3, -3e-7, 0.55 * hmx_shear, hmx_shear)};
}

// Points across the wall, ends excluded by a margin of h.
std::vector<double> wall_points(double a, double b, double h) {
    std::vector<double> r;
    for (int i = 0; i <= 8; ++i) r.push_back(a + 2.0 * h + (b - a - 4.0 * h) * i / 8.0);
    return r;
}

}  // namespace

TEST_CASE("Lame sphere: the stresses satisfy radial equilibrium by finite differences", "[support]") {
    for (const auto& s : lame_cases()) {
        const double a = s.inner_radius(), b = s.outer_radius();
        const double h = 1e-3 * (b - a);
        for (const double r : wall_points(a, b, h)) {
            // d sigma_r / dr + 2 (sigma_r - sigma_theta) / r = 0, each term against sigma / r
            const double scale = std::abs(s.radial_stress(r)) + std::abs(s.hoop_stress(r));
            const double dsr = derivative([&](double x) { return s.radial_stress(x); }, r, h);
            const double residual = dsr + 2.0 * (s.radial_stress(r) - s.hoop_stress(r)) / r;
            CAPTURE(r, dsr, residual);
            CHECK(std::abs(dsr) * r > 1e-2 * scale);  // the terms themselves are not zero
            CHECK(std::abs(residual) * r < 1e-9 * scale);
        }
    }
}

TEST_CASE("Lame sphere: a traction-free cavity and the prescribed outer displacement", "[support]") {
    const double u_b[] = {-1e-6, 2e-6, -3e-7};
    const auto cases = lame_cases();
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const auto& s = cases[i];
        CHECK(std::abs(s.radial_stress(s.inner_radius())) < 1e-12 * std::abs(s.outer_pressure()));
        CHECK(s.displacement(s.outer_radius()) == Approx(u_b[i]).epsilon(1e-13));
        // inward displacement compresses: a positive outer pressure
        CHECK((u_b[i] < 0.0) == (s.outer_pressure() > 0.0));
    }
}

TEST_CASE("Lame sphere: Hooke's law on the strains of the displacement gives the stresses", "[support]") {
    const double bulk[] = {hmx_bulk, 2000.0 * hmx_shear, 0.55 * hmx_shear};
    const auto cases = lame_cases();
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const auto& s = cases[i];
        const double k = bulk[i], g = hmx_shear, lambda = k - 2.0 * g / 3.0;
        const double a = s.inner_radius(), b = s.outer_radius();
        const double h = 1e-4 * (b - a);
        for (const double r : wall_points(a, b, h)) {
            // lambda / G is up to 2000: lambda multiplies the derivative's error
            const double scale = std::abs(s.radial_stress(r)) + std::abs(s.hoop_stress(r));
            const double e_r = derivative([&](double x) { return s.displacement(x); }, r, h);
            const double e_t = s.displacement(r) / r;
            const double volumetric = e_r + 2.0 * e_t;
            const double sigma_r = lambda * volumetric + 2.0 * g * e_r;
            const double sigma_t = lambda * volumetric + 2.0 * g * e_t;
            CAPTURE(i, r);
            CHECK(std::abs(sigma_r - s.radial_stress(r)) < 1e-8 * scale);
            CHECK(std::abs(sigma_t - s.hoop_stress(r)) < 1e-8 * scale);
        }
    }
}

TEST_CASE("Lame sphere: first yield at the cavity at P = 2Y/(3 alpha), whatever K and G", "[support]") {
    for (const double b_over_a : {3.0, 1.5, 1.1}) {
        for (const double k_over_g : {0.55, 3.0, 2000.0}) {
            const gimlet::test::lame_sphere s(1.0, b_over_a, -1e-6, k_over_g * hmx_shear, hmx_shear);
            // the largest stress difference over the wall, found on a grid
            double largest = 0.0, where = 0.0;
            for (int i = 0; i <= 1000; ++i) {
                const double r = 1.0 + (b_over_a - 1.0) * i / 1000.0;
                const double d = std::abs(s.hoop_stress(r) - s.radial_stress(r));
                if (d > largest) { largest = d; where = r; }
            }
            // the field is linear in u_b: scale it until the largest difference is Y
            const double pressure_at_yield = s.outer_pressure() * hmx_yield / largest;
            const double alpha = gimlet::test::alpha_from_radii(1.0, b_over_a);
            CAPTURE(b_over_a, k_over_g);
            CHECK(where == 1.0);
            CHECK(pressure_at_yield ==
                  Approx(gimlet::test::carroll_holt_elastic_limit_pressure(hmx_yield, alpha)).epsilon(1e-12));
        }
    }
    // b/a = 3: alpha0 = 27/26, P_e = 52 Y / 81
    CHECK(gimlet::test::carroll_holt_elastic_limit_pressure(hmx_yield, 27.0 / 26.0) ==
          Approx(52.0 * hmx_yield / 81.0).epsilon(1e-14));
}

TEST_CASE("Lame sphere: the incompressible limit is Carroll-Holt's elastic phase", "[support]") {
    // Lame's solution is on the initial radii, Carroll-Holt's on the current ones: the two
    // small-strain forms differ by the order of the strain at the cavity, u(a)/a
    const double alpha0 = gimlet::test::alpha_from_radii(shell_a, shell_b);
    for (const double u_b : {-6e-8, -6e-10}) {
        const gimlet::test::lame_sphere s(shell_a, shell_b, u_b, 1e7 * hmx_shear, hmx_shear);
        const double strain = std::abs(s.displacement(shell_a)) / shell_a;
        const double alpha = gimlet::test::alpha_from_radii(shell_a + s.displacement(shell_a), shell_b + u_b);
        CAPTURE(u_b, strain);
        REQUIRE(alpha < alpha0);
        REQUIRE(alpha > gimlet::test::carroll_holt_alpha_first_yield(alpha0, hmx_shear, hmx_yield));
        CHECK(s.outer_pressure() ==
              Approx(gimlet::test::carroll_holt_static_pressure(alpha, alpha0, hmx_shear, hmx_yield))
                  .epsilon(5.0 * strain));
        // incompressible: the solid keeps its volume (to second order in the strain)
        CHECK(gimlet::test::inner_radius_incompressible(shell_a, shell_b, shell_b + u_b) ==
              Approx(shell_a + s.displacement(shell_a)).epsilon(5.0 * strain * strain + 1e-12));
    }
}

TEST_CASE("Carroll-Holt: the fully plastic pressure integrates the equilibrium equation", "[support]") {
    // fully plastic: sigma_theta - sigma_r = -Y, so the radial pressure p = -sigma_r has
    // dp/dr = 2Y/r, p(a) = 0; the outer pressure is its integral from a to b
    const double y = hmx_yield;
    for (const auto& radii : std::vector<std::pair<double, double>>{
             {1.0, 3.0}, {2e-3, 6e-3}, {1.0, std::cbrt(53.0)}, {1.0, 1.05}, {0.01, 1.0}}) {
        const double a = radii.first, b = radii.second;
        const double numeric = simpson([&](double r) { return 2.0 * y / r; }, a, b, 20000);
        const double alpha = gimlet::test::alpha_from_radii(a, b);
        CAPTURE(a, b, alpha);
        CHECK(gimlet::test::carroll_holt_fully_plastic_pressure(y, alpha) == Approx(numeric).epsilon(1e-9));
    }
    // b/a = 3: P = 2Y ln 3, about 2.197 Y
    CHECK(gimlet::test::carroll_holt_fully_plastic_pressure(y, 27.0 / 26.0) / y == Approx(2.1972245773).epsilon(1e-10));
}

TEST_CASE("Carroll-Holt: the distension from volumes integrated over the shell", "[support]") {
    const auto shell_volume = [](double a, double b) {
        return simpson([](double r) { return 4.0 * pi * r * r; }, a, b, 200);
    };
    const double a0 = shell_a, b0 = shell_b;
    CHECK(gimlet::test::alpha_from_radii(1.0, 3.0) == Approx(27.0 / 26.0).epsilon(1e-15));
    CHECK(gimlet::test::alpha_from_radii(0.0, 3.0) == 1.0);
    const double solid0 = shell_volume(a0, b0);
    // the whole sphere's volume over the solid's
    CHECK(gimlet::test::alpha_from_radii(a0, b0) == Approx(shell_volume(0.0, b0) / solid0).epsilon(1e-12));
    // collapse at constant solid volume, through alpha = (alpha0 + 1)/2 to near closure
    const double alpha0 = gimlet::test::alpha_from_radii(a0, b0);
    double previous = alpha0;
    for (int i = 1; i < 10; ++i) {
        const double b_closed = std::cbrt(b0 * b0 * b0 - a0 * a0 * a0);
        const double b = b0 + (b_closed - b0) * i / 10.0;
        const double a = gimlet::test::inner_radius_incompressible(a0, b0, b);
        CAPTURE(i, a, b);
        CHECK(shell_volume(a, b) == Approx(solid0).epsilon(1e-12));
        const double alpha = gimlet::test::alpha_from_radii(a, b);
        CHECK(alpha < previous);
        CHECK(alpha == Approx(shell_volume(0.0, b) / solid0).epsilon(1e-12));
        previous = alpha;
    }
    // the check's end, alpha = (alpha0 + 1)/2: b^3 = alpha (b0^3 - a0^3)
    const double alpha_end = 0.5 * (alpha0 + 1.0);
    const double b_end = std::cbrt(alpha_end * (b0 * b0 * b0 - a0 * a0 * a0));
    CHECK(gimlet::test::alpha_from_radii(gimlet::test::inner_radius_incompressible(a0, b0, b_end), b_end) ==
          Approx(alpha_end).epsilon(1e-12));
}

TEST_CASE("Carroll-Holt: the static phases integrate the incompressible elastic-plastic field", "[support]") {
    // At alpha, the solid volume s = b^3 - a^3 (over 4 pi / 3) fixed, a^3 = s (alpha - 1),
    // b^3 = s alpha; the incompressible displacement u = C / r^2 with 3C = s (alpha - alpha0), so
    // |eps_theta - eps_r| = 3|C| / r^3, |sigma_theta - sigma_r| = min(2G 3|C| / r^3, Y) (the
    // deviator's direction is fixed: monotonic loading), and p = -sigma_r integrates 2|...|/r.
    const double alpha0 = 27.0 / 26.0, s = 1.0;
    for (const double g_over_y : {47.5, 500.0}) {
        const double g = g_over_y * hmx_yield, y = hmx_yield;
        const double alpha1 = gimlet::test::carroll_holt_alpha_first_yield(alpha0, g, y);
        const double alpha2 = gimlet::test::carroll_holt_alpha_fully_plastic(alpha0, g, y);
        REQUIRE(alpha2 < alpha1);
        REQUIRE(alpha1 < alpha0);
        std::vector<double> alphas{alpha1, alpha2, 0.5 * (alpha1 + alpha2), 0.5 * (alpha0 + alpha1)};
        for (int i = 1; i <= 20; ++i) alphas.push_back(alpha0 + (0.5 * (alpha0 + 1.0) - alpha0) * i / 20.0);
        for (const double alpha : alphas) {
            const double a = std::cbrt(s * (alpha - 1.0)), b = std::cbrt(s * alpha);
            const double c3 = s * (alpha0 - alpha);  // 3|C|
            const auto difference = [&](double r) { return std::min(2.0 * g * c3 / (r * r * r), y); };
            // split at the elastic-plastic radius, where the integrand has a kink
            const double plastic_radius = std::clamp(std::cbrt(2.0 * g * c3 / y), a, b);
            const auto integrand = [&](double r) { return 2.0 * difference(r) / r; };
            const double numeric =
                simpson(integrand, a, plastic_radius, 2000) + simpson(integrand, plastic_radius, b, 2000);
            CAPTURE(g_over_y, alpha, alpha1, alpha2);
            CHECK(gimlet::test::carroll_holt_static_pressure(alpha, alpha0, g, y) == Approx(numeric).epsilon(1e-9));
        }
        // the phases meet: the elastic limit at alpha1, the fully plastic relation at alpha2
        CHECK(gimlet::test::carroll_holt_static_pressure(alpha1, alpha0, g, y) ==
              Approx(gimlet::test::carroll_holt_elastic_limit_pressure(y, alpha1)).epsilon(1e-10));
        CHECK(gimlet::test::carroll_holt_static_pressure(alpha2, alpha0, g, y) ==
              Approx(gimlet::test::carroll_holt_fully_plastic_pressure(y, alpha2)).epsilon(1e-10));
    }
}

TEST_CASE("Carroll-Holt: a compressible solid's error against the initial solid volume", "[support]") {
    // Fully plastic, the stress field is p(r) = 2Y ln(r/a) + 2Y/3 (p = -(sigma_r + 2 sigma_theta)/3)
    // in the current radii, whatever K. Its volume mean over the solid is alpha P (mean-stress
    // theorem), and the solid has lost the volume fraction p/K locally: an alpha from the
    // initial solid volume is low, and P(alpha) overestimates, by -ln(1 - x)/ln(alpha/(alpha - 1)),
    // x = alpha P / (K (alpha - 1)); to first order (2Y/3K) alpha/(alpha - 1).
    const double y = hmx_yield, alpha0 = 27.0 / 26.0, alpha_end = 0.5 * (alpha0 + 1.0);
    const double k = gimlet::test::carroll_holt_bulk_modulus_for(y, alpha_end, 0.03);
    CHECK(k / y == Approx(1249.3116900).epsilon(1e-9));
    for (const double alpha : {alpha0, 0.5 * (alpha0 + alpha_end), alpha_end}) {
        const double a = std::cbrt(alpha - 1.0), b = std::cbrt(alpha);  // current radii
        const auto mean_pressure = [&](double r) { return 2.0 * y * std::log(r / a) + 2.0 * y / 3.0; };
        const double solid = simpson([&](double r) { return 4.0 * pi * r * r; }, a, b, 2000);
        const double mean =
            simpson([&](double r) { return 4.0 * pi * r * r * mean_pressure(r); }, a, b, 2000) / solid;
        const double pressure = simpson([&](double r) { return 2.0 * y / r; }, a, b, 2000);
        CAPTURE(alpha);
        CHECK(mean == Approx(alpha * pressure).epsilon(1e-9));
        // the initial solid volume: each element was dV / (1 - p/K) before the load
        const double solid0 =
            simpson([&](double r) { return 4.0 * pi * r * r / (1.0 - mean_pressure(r) / k); }, a, b, 2000);
        const double alpha_initial_solid = 4.0 * pi / 3.0 * b * b * b / solid0;
        const double error = gimlet::test::carroll_holt_fully_plastic_pressure(y, alpha_initial_solid) / pressure - 1.0;
        const double estimate = gimlet::test::carroll_holt_compressibility_error(y, k, alpha);
        const double first_order = 2.0 * y / (3.0 * k) * alpha / (alpha - 1.0);
        CHECK(error > 0.0);
        // exact to first order in p/K (about 0.002 here): within 0.3 % of the error
        CHECK(error == Approx(estimate).epsilon(3e-3));
        // the first order in x underestimates by x/2, 2-6 % here
        CHECK(error > first_order);
        CHECK(error < 1.07 * first_order);
        CHECK(error < 0.0301);
    }
}

TEST_CASE("Spherical shell references refuse parameters out of range", "[support]") {
    using namespace gimlet::test;
    CHECK_THROWS_AS(lame_sphere(0.0, 1.0, -1e-6, 1e9, 1e9), std::invalid_argument);
    CHECK_THROWS_AS(lame_sphere(1.0, 1.0, -1e-6, 1e9, 1e9), std::invalid_argument);
    CHECK_THROWS_AS(lame_sphere(1.0, 2.0, -1e-6, 0.0, 1e9), std::invalid_argument);
    CHECK_THROWS_AS(lame_sphere(1.0, 2.0, -1e-6, 1e9, -1.0), std::invalid_argument);
    CHECK_THROWS_AS(alpha_from_radii(3.0, 3.0), std::invalid_argument);
    CHECK_THROWS_AS(inner_radius_incompressible(1.0, 3.0, 2.9), std::invalid_argument);
    CHECK_THROWS_AS(carroll_holt_fully_plastic_pressure(1e8, 1.0), std::invalid_argument);
    CHECK_THROWS_AS(carroll_holt_static_pressure(1.1, 27.0 / 26.0, 1e9, 1e8), std::invalid_argument);
    CHECK_THROWS_AS(carroll_holt_bulk_modulus_for(1e8, 1.02, 0.0), std::invalid_argument);
}
