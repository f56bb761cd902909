// SPDX-License-Identifier: MIT
#pragma once
// Analytic references for a hollow sphere under radial loading, the verification cases of an
// axisymmetric solver (docs/equations.md, "Spherical shells: Lame and Carroll-Holt"):
//  * lame_sphere: a thick linear elastic shell, traction-free inside, displaced radially outside;
//  * carroll_holt_*: the quasi-static collapse of an incompressible elastic-perfectly-plastic
//    shell (Carroll & Holt 1972), with its distension alpha = b^3 / (b^3 - a^3).
// Sign convention: stresses are positive in tension; a pressure P is positive in compression.
// Double precision; a parameter out of range throws std::invalid_argument naming it.

#include <cmath>
#include <stdexcept>

namespace gimlet::test {

/// A thick linear elastic hollow sphere (Lame 1852): inner radius a traction-free, outer radius
/// b displaced radially by u_b (negative inward).
///
/// Assumptions: small strain, isotropic linear elasticity (bulk modulus K, shear modulus G),
/// quasi-static, no body force, spherical symmetry. The radial displacement solving Navier's
/// equation is \f$ u = A r + B / r^2 \f$ (Lai, Rubin & Krempl, *Introduction to Continuum
/// Mechanics*, section 5.21; Bower, *Applied Mechanics of Solids*, 2009, section 4.1), so
/// \f$ \varepsilon_r = A - 2B/r^3 \f$, \f$ \varepsilon_\theta = A + B/r^3 \f$,
/// \f$ \sigma_r = 3KA - 4GB/r^3 \f$, \f$ \sigma_\theta = 3KA + 2GB/r^3 \f$. The two boundary
/// conditions \f$ \sigma_r(a) = 0 \f$ and \f$ u(b) = u_b \f$ give
/// \f$ B = 3K a^3 A / (4G) \f$ and \f$ A = 4G b^2 u_b / (4G b^3 + 3K a^3) \f$.
class lame_sphere {
public:
    lame_sphere(double a, double b, double u_b, double bulk_modulus, double shear_modulus)
        : a_(a), b_(b), u_b_(u_b), k_(bulk_modulus), g_(shear_modulus) {
        if (!(a > 0.0) || !std::isfinite(a))
            throw std::invalid_argument("lame_sphere: inner radius a must be finite and > 0");
        if (!(b > a) || !std::isfinite(b))
            throw std::invalid_argument("lame_sphere: outer radius b must be finite and > a");
        if (!std::isfinite(u_b))
            throw std::invalid_argument("lame_sphere: outer displacement u_b must be finite");
        if (!(bulk_modulus > 0.0) || !std::isfinite(bulk_modulus))
            throw std::invalid_argument("lame_sphere: bulk modulus K must be finite and > 0");
        if (!(shear_modulus > 0.0) || !std::isfinite(shear_modulus))
            throw std::invalid_argument("lame_sphere: shear modulus G must be finite and > 0");
        coefficient_a_ = 4.0 * g_ * b_ * b_ * u_b_ / (4.0 * g_ * b_ * b_ * b_ + 3.0 * k_ * a_ * a_ * a_);
        coefficient_b_ = 3.0 * k_ * a_ * a_ * a_ * coefficient_a_ / (4.0 * g_);
    }

    /// A of \f$ u = A r + B / r^2 \f$: a third of the (uniform) volumetric strain.
    double coefficient_a() const { return coefficient_a_; }
    /// B of \f$ u = A r + B / r^2 \f$ (m^3).
    double coefficient_b() const { return coefficient_b_; }

    /// Radial displacement \f$ u(r) = A r + B / r^2 \f$.
    double displacement(double r) const { return coefficient_a_ * r + coefficient_b_ / (r * r); }

    /// Radial stress \f$ \sigma_r = 3KA - 4GB/r^3 = 3KA (1 - a^3/r^3) \f$.
    double radial_stress(double r) const {
        return 3.0 * k_ * coefficient_a_ - 4.0 * g_ * coefficient_b_ / (r * r * r);
    }

    /// Hoop stress \f$ \sigma_\theta = \sigma_\phi = 3KA + 2GB/r^3 = 3KA (1 + a^3/(2 r^3)) \f$.
    double hoop_stress(double r) const {
        return 3.0 * k_ * coefficient_a_ + 2.0 * g_ * coefficient_b_ / (r * r * r);
    }

    /// The pressure on the outer surface that holds the displacement, \f$ P = -\sigma_r(b) \f$.
    double outer_pressure() const { return -radial_stress(b_); }

    double inner_radius() const { return a_; }
    double outer_radius() const { return b_; }

private:
    double a_, b_, u_b_, k_, g_;
    double coefficient_a_ = 0.0, coefficient_b_ = 0.0;
};

/// The distension of a hollow sphere, \f$ \alpha = b^3 / (b^3 - a^3) \f$: its volume over its
/// solid's volume (Carroll & Holt 1972). b/a = 3 gives 27/26. Requires 0 <= a < b.
inline double alpha_from_radii(double a, double b) {
    if (!(a >= 0.0) || !std::isfinite(a))
        throw std::invalid_argument("alpha_from_radii: inner radius a must be finite and >= 0");
    if (!(b > a) || !std::isfinite(b))
        throw std::invalid_argument("alpha_from_radii: outer radius b must be finite and > a");
    const double b3 = b * b * b;
    return b3 / (b3 - a * a * a);
}

/// The inner radius of an incompressible shell whose outer radius has moved from b0 to b: its
/// solid volume is kept, \f$ b^3 - a^3 = b_0^3 - a_0^3 \f$, so
/// \f$ a = (b^3 - b_0^3 + a_0^3)^{1/3} \f$. Exact for an incompressible solid at any strain;
/// a compressible one loses solid volume (docs/equations.md, "Spherical shells: Lame and
/// Carroll-Holt"). Requires 0 <= a0 < b0 and b^3 >= b0^3 - a0^3 (the void not yet closed).
inline double inner_radius_incompressible(double a0, double b0, double b) {
    if (!(a0 >= 0.0) || !std::isfinite(a0))
        throw std::invalid_argument("inner_radius_incompressible: inner radius a0 must be finite and >= 0");
    if (!(b0 > a0) || !std::isfinite(b0))
        throw std::invalid_argument("inner_radius_incompressible: outer radius b0 must be finite and > a0");
    const double a3 = b * b * b - (b0 * b0 * b0 - a0 * a0 * a0);
    if (!(a3 >= 0.0) || !std::isfinite(a3))
        throw std::invalid_argument("inner_radius_incompressible: outer radius b is below the solid's own radius");
    return std::cbrt(a3);
}

namespace detail {
// Throws std::invalid_argument(message) unless x is finite and above the bound.
inline void require_above(double x, double bound, const char* message) {
    if (!(x > bound) || !std::isfinite(x)) throw std::invalid_argument(message);
}
}  // namespace detail

/// The pressure on the outer surface of a fully plastic hollow sphere, quasi-static:
/// \f$ P = \frac{2Y}{3} \ln\frac{\alpha}{\alpha - 1} = 2Y \ln\frac{b}{a} \f$ (Carroll & Holt
/// 1972, the static relation of the plastic phase).
///
/// Assumptions: spherical symmetry, quasi-static (their dynamic relation's inertial terms,
/// of order \f$ \rho_s \dot a^2 \f$, dropped), perfect plasticity with yield stress Y (von Mises
/// or Tresca: both read \f$ |\sigma_\theta - \sigma_r| = Y \f$ here), the whole shell at yield,
/// traction-free cavity. Equilibrium \f$ d\sigma_r/dr = 2(\sigma_\theta - \sigma_r)/r = -2Y/r \f$
/// integrated from a to b. It holds in the current radii for any strain and any bulk modulus;
/// alpha is the distension of the current radii (for an incompressible solid, also its volume
/// over the initial solid volume).
inline double carroll_holt_fully_plastic_pressure(double yield_stress, double alpha) {
    detail::require_above(yield_stress, 0.0,
                          "carroll_holt_fully_plastic_pressure: yield stress Y must be finite and > 0");
    detail::require_above(alpha, 1.0,
                          "carroll_holt_fully_plastic_pressure: distension alpha must be finite and > 1");
    return 2.0 * yield_stress / 3.0 * std::log(alpha / (alpha - 1.0));
}

/// The outer pressure at which an elastic hollow sphere first yields, at its inner surface:
/// \f$ P_e = \frac{2Y}{3\alpha} = \frac{2Y}{3}\left(1 - \frac{a^3}{b^3}\right) \f$ (Carroll & Holt
/// 1972, the end of the elastic phase; Hill 1950, the thick spherical shell). From Lame's
/// solution \f$ |\sigma_\theta - \sigma_r| = \frac{3}{2} P \alpha\, a^3 / r^3 \f$, largest at
/// r = a, for any K and G (small strain). b/a = 3: \f$ P_e = 52Y/81 \approx 0.642\,Y \f$.
inline double carroll_holt_elastic_limit_pressure(double yield_stress, double alpha) {
    detail::require_above(yield_stress, 0.0,
                          "carroll_holt_elastic_limit_pressure: yield stress Y must be finite and > 0");
    detail::require_above(alpha, 1.0,
                          "carroll_holt_elastic_limit_pressure: distension alpha must be finite and > 1");
    return 2.0 * yield_stress / (3.0 * alpha);
}

/// The distension at which a shell collapsing from alpha0 first yields (incompressible,
/// small elastic strain): \f$ \alpha_1 = (2G\alpha_0 + Y) / (2G + Y) \f$ (Carroll & Holt 1972).
inline double carroll_holt_alpha_first_yield(double alpha0, double shear_modulus, double yield_stress) {
    detail::require_above(alpha0, 1.0,
                          "carroll_holt_alpha_first_yield: distension alpha0 must be finite and > 1");
    detail::require_above(shear_modulus, 0.0,
                          "carroll_holt_alpha_first_yield: shear modulus G must be finite and > 0");
    detail::require_above(yield_stress, 0.0,
                          "carroll_holt_alpha_first_yield: yield stress Y must be finite and > 0");
    return (2.0 * shear_modulus * alpha0 + yield_stress) / (2.0 * shear_modulus + yield_stress);
}

/// The distension at which the whole shell is plastic (the outer surface reaches yield):
/// \f$ \alpha_2 = 2G\alpha_0 / (2G + Y) \f$ (Carroll & Holt 1972; incompressible, small
/// elastic strain). From there on carroll_holt_fully_plastic_pressure holds.
inline double carroll_holt_alpha_fully_plastic(double alpha0, double shear_modulus, double yield_stress) {
    detail::require_above(alpha0, 1.0,
                          "carroll_holt_alpha_fully_plastic: distension alpha0 must be finite and > 1");
    detail::require_above(shear_modulus, 0.0,
                          "carroll_holt_alpha_fully_plastic: shear modulus G must be finite and > 0");
    detail::require_above(yield_stress, 0.0,
                          "carroll_holt_alpha_fully_plastic: yield stress Y must be finite and > 0");
    return 2.0 * shear_modulus * alpha0 / (2.0 * shear_modulus + yield_stress);
}

/// The quasi-static outer pressure of an incompressible elastic-perfectly-plastic shell
/// collapsed from the stress-free distension alpha0 to alpha (Carroll & Holt 1972, the three
/// static phases), with \f$ \xi = 2G(\alpha_0 - \alpha)/Y \f$ (\f$ \xi^{1/3} \f$ is the
/// elastic-plastic radius over the solid's radius \f$ (b^3 - a^3)^{1/3} \f$):
///  - elastic, \f$ \alpha_1 \le \alpha \le \alpha_0 \f$:
///    \f$ P = \frac{4G}{3} \frac{\alpha_0 - \alpha}{\alpha(\alpha - 1)} \f$;
///  - elastic-plastic, \f$ \alpha_2 \le \alpha < \alpha_1 \f$:
///    \f$ P = \frac{2Y}{3}\left[1 - \frac{\xi}{\alpha} + \ln\frac{\xi}{\alpha - 1}\right] \f$;
///  - fully plastic, \f$ \alpha < \alpha_2 \f$: \f$ P = \frac{2Y}{3}\ln\frac{\alpha}{\alpha-1} \f$.
///
/// Assumptions: as carroll_holt_fully_plastic_pressure, plus an incompressible solid, monotonic
/// collapse, and the elastic part of the strain small (the displacement \f$ u = C/r^2 \f$ with
/// \f$ 3C = a^3 - a_0^3 = (b^3 - a^3)(\alpha - \alpha_0) \f$). Requires 1 < alpha <= alpha0.
inline double carroll_holt_static_pressure(double alpha, double alpha0, double shear_modulus, double yield_stress) {
    detail::require_above(alpha, 1.0,
                          "carroll_holt_static_pressure: distension alpha must be finite and > 1");
    const double alpha1 = carroll_holt_alpha_first_yield(alpha0, shear_modulus, yield_stress);
    const double alpha2 = carroll_holt_alpha_fully_plastic(alpha0, shear_modulus, yield_stress);
    if (!(alpha <= alpha0))
        throw std::invalid_argument("carroll_holt_static_pressure: alpha must not exceed alpha0 (a collapse)");
    if (alpha >= alpha1)
        return 4.0 * shear_modulus / 3.0 * (alpha0 - alpha) / (alpha * (alpha - 1.0));
    if (alpha >= alpha2) {
        const double xi = 2.0 * shear_modulus * (alpha0 - alpha) / yield_stress;
        return 2.0 * yield_stress / 3.0 * (1.0 - xi / alpha + std::log(xi / (alpha - 1.0)));
    }
    return carroll_holt_fully_plastic_pressure(yield_stress, alpha);
}

/// The relative error of carroll_holt_fully_plastic_pressure when alpha is taken from the
/// initial solid volume (as inner_radius_incompressible does) but the solid has a finite bulk
/// modulus K. The fully plastic stress field is that of the current radii for any K; the
/// solid's volume-mean pressure is \f$ \alpha P \f$ (mean-stress theorem, cavity
/// traction-free), so the solid has lost the volume fraction \f$ \alpha P / K \f$, and with
/// \f$ f = \ln\frac{\alpha}{\alpha - 1} \f$, \f$ x = \frac{\alpha P}{K(\alpha - 1)} \f$:
/// \f$ \delta P / P = -\ln(1 - x) / f \approx \frac{2Y}{3K} \frac{\alpha}{\alpha - 1} \f$
/// (the reference overestimates; what is left out is of second order in P/K, and x need not be
/// small). alpha is the current distension; requires x < 1. docs/equations.md, "Spherical shells: Lame and Carroll-Holt".
inline double carroll_holt_compressibility_error(double yield_stress, double bulk_modulus, double alpha) {
    detail::require_above(bulk_modulus, 0.0,
                          "carroll_holt_compressibility_error: bulk modulus K must be finite and > 0");
    const double pressure = carroll_holt_fully_plastic_pressure(yield_stress, alpha);
    const double x = alpha * pressure / (bulk_modulus * (alpha - 1.0));
    if (!(x < 1.0))
        throw std::invalid_argument("carroll_holt_compressibility_error: K too small for this distension "
                                    "(the solid's lost volume exceeds the void's)");
    return -std::log1p(-x) / std::log(alpha / (alpha - 1.0));
}

/// The bulk modulus at which carroll_holt_compressibility_error equals the relative tolerance
/// at the distension alpha_min, the smallest of a check (the error grows as alpha falls):
/// \f$ K = \frac{2Y}{3} \frac{\alpha f}{(\alpha - 1)(1 - e^{-\mathrm{tol}\, f})} \f$,
/// \f$ f = \ln\frac{\alpha}{\alpha - 1} \f$. From alpha0 = 27/26 to (alpha0 + 1)/2 = 53/52
/// at 3 %: K = 1249 Y (630 Y would do at 27/26 alone).
inline double carroll_holt_bulk_modulus_for(double yield_stress, double alpha_min, double tolerance) {
    detail::require_above(yield_stress, 0.0, "carroll_holt_bulk_modulus_for: yield stress Y must be finite and > 0");
    detail::require_above(alpha_min, 1.0,
                          "carroll_holt_bulk_modulus_for: distension alpha_min must be finite and > 1");
    detail::require_above(tolerance, 0.0, "carroll_holt_bulk_modulus_for: tolerance must be finite and > 0");
    const double f = std::log(alpha_min / (alpha_min - 1.0));
    return 2.0 * yield_stress / 3.0 * alpha_min * f / ((alpha_min - 1.0) * -std::expm1(-tolerance * f));
}

}  // namespace gimlet::test
