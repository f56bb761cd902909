// SPDX-License-Identifier: MIT
/// \file
/// The axisymmetric solver against the closed-form hollow spheres of docs/equations.md,
/// "Spherical shells: Lame and Carroll-Holt" (tests/support/spherical_shell.hpp): an elastic
/// shell displaced at its outer surface (Lame) and the quasi-static collapse of an
/// elastic-perfectly-plastic one (Carroll-Holt). Each is a quarter annulus in the (r, z)
/// half-plane above a frictionless symmetry plane (slip along z at z = 0), its outer layer of
/// particles driven radially inward.

#include <gimlet/gimlet.hpp>

#include "../support/spherical_shell.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <vector>

namespace {

using A = gimlet::axisymmetric_space<double>;
using driven_fields = gimlet::field_list<gimlet::fields::driven, gimlet::fields::driven_velocity>;
using shell_elastic_solver = gimlet::solver<A, gimlet::shape::ugimp, gimlet::elastic_material,
                                            gimlet::contact::single_field, driven_fields>;
using plastic_material = gimlet::material<gimlet::strength::von_mises, gimlet::eos::linear>;
using shell_plastic_solver =
    gimlet::solver<A, gimlet::shape::ugimp, plastic_material, gimlet::contact::single_field, driven_fields>;

constexpr double pi = 3.141592653589793;

// The quarter of a spherical shell a <= |x| <= b in the (r, z) half-plane, r >= 0, z >= 0.
struct quarter_shell {
    double a, b;
    [[nodiscard]] bool contains(const A::vector& x) const {
        const double rho2 = x.squaredNorm();
        return x[0] >= 0 && x[1] >= 0 && rho2 >= a * a && rho2 <= b * b;
    }
    [[nodiscard]] A::vector lower() const { return A::vector(0.0, 0.0); }
    [[nodiscard]] A::vector upper() const { return A::vector(b, b); }
};

// The rate of a smooth ramp from 0 to 1 over [0, 1] that starts and ends at rest,
// s(t) = t - sin(2 pi t) / (2 pi): s'(t) = 1 - cos(2 pi t) (as test_axisymmetric.cpp's).
double ramp_rate(double t) { return t >= 1 ? 0.0 : 1 - std::cos(2 * pi * t); }
// s(t) itself, 1 from t = 1 on: a speed that rises smoothly from rest to its full value.
double ramp(double t) { return t >= 1 ? 1.0 : t - std::sin(2 * pi * t) / (2 * pi); }

// The shell a <= |x| <= b at 2 x 2 particles a cell on a grid from the axis and the symmetry
// plane (r = 0, z = 0) to 3 cells past b: free along r (the axis holds v_r = 0 itself), slip
// along z (v_z = 0 at z = 0: the frictionless symmetry plane).
template <class M>
gimlet::scene::scene<A, M> shell_scene(double a, double b, double h, const M& material) {
    gimlet::grid_spec<A> gs;
    gs.lower = A::vector(0.0, 0.0);
    gs.upper = A::vector(b + 3 * h, b + 3 * h);
    gs.cell = h;
    gs.bc = {gimlet::boundary::free, gimlet::boundary::slip};
    gimlet::scene::scene<A, M> sc(gs);
    sc.add_body(quarter_shell{a, b}, material, A::vector::Zero(), 2, "shell");
    return sc;
}

// Marks the particles whose centres lie within one particle spacing `delta` of the outer
// surface b as fully driven (both components); returns how many.
template <class Store>
std::size_t drive_outer_layer(Store& p, const std::vector<A::vector>& x0, double b, double delta) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (x0[i].norm() > b - delta) p.template column<gimlet::fields::driven>()[i] = 0b11, ++n;
    return n;
}

// Every driven particle moves radially inward at `speed` (m/s, > 0 inward) along its initial
// radius (the motion is radial, so the direction stays).
template <class Store>
void set_driven_speed(Store& p, const std::vector<A::vector>& x0, double speed) {
    for (std::size_t i = 0; i < p.size(); ++i)
        if (p.template column<gimlet::fields::driven>()[i])
            p.template column<gimlet::fields::driven_velocity>()[i] = -speed * x0[i] / x0[i].norm();
}

// The smallest radius of a node that the driven particles weigh: uGIMP's support reaches
// h + l along each axis (l = delta / 2 the particle's half-width), and the driven velocity is
// set on every node a driven particle weighs (stages::driven_particles).
template <class Store>
double innermost_driven_node(const Store& p, const std::vector<A::vector>& x0, double h, double delta) {
    const double reach = h + delta / 2;
    double inner = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (!p.template column<gimlet::fields::driven>()[i]) continue;
        for (long ir = long(std::floor((x0[i][0] - reach) / h)); ir * h < x0[i][0] + reach; ++ir)
            for (long iz = long(std::floor((x0[i][1] - reach) / h)); iz * h < x0[i][1] + reach; ++iz) {
                const A::vector node(double(ir) * h, double(iz) * h);
                // A node at the support's edge (to rounding) has weight 0: not driven.
                if (ir < 0 || iz < 0 || (node - x0[i]).cwiseAbs().maxCoeff() >= reach * (1 - 1e-9)) continue;
                inner = std::min(inner, node.norm());
            }
    }
    return inner;
}

// The spherical components of a ring's stress: sigma_r = e_r . sigma . e_r with e_r = x / |x|
// in the (r, z) plane, the meridional hoop sigma_theta = e_t . sigma . e_t with e_t normal to
// e_r in that plane, and the azimuthal hoop sigma_phi, the stress_zz slot.
struct spherical_stress {
    double radial, meridional, azimuthal;
};
spherical_stress spherical(const A::matrix& s, double s_phi, const A::vector& x) {
    const A::vector e = x / x.norm(), t(-e[1], e[0]);
    return {e.dot(s * e), t.dot(s * t), s_phi};
}

}  // namespace

TEST_CASE("spherical shells: an elastic shell b/a = 3 displaced at its outer layer has Lame's stresses",
          "[solver][axisymmetric][verification]") {
    // A hollow sphere a = 3 mm, b = 9 mm (E = 1 GPa, nu = 0.3) at h = 0.25 mm, 24 cells across
    // the wall, 2 x 2 particles a cell (3622 rings, 109 of them driven). The outer layer moves
    // radially inward by u_d = -1e-3 b, ramped smoothly over 20 transit times of the wall
    // (c = sqrt((K + 4G/3)/rho)) and held for 5, with no damping.
    //
    // Where the load acts. The driven layer (centres within one particle spacing of b) sets the
    // driven velocity on every node it weighs, so the free material meets a rigidly displaced
    // band of nodes reaching about 1.5 cells inside b, not a surface at b: Lame's solution with
    // b = 9 mm is off by 3.5 % of the stresses. Lame's family with a traction-free cavity has
    // one constant (u = A (r + 3 K a^3 / (4 G r^2))), so a measured displacement fixes it: the
    // mean radial displacement u_m of the layer of rings at mid-wall, r_m = 6.06 mm, and the
    // solution is lame_sphere(a, r_m, u_m). Its loaded radius b_eff, where it reaches u_d, is
    // then a measurement, and it must lie within half a cell of the innermost node the driven
    // particles weigh (measured: b_eff = 8.607 mm = b - 1.57 h, the node at 8.620 mm; at
    // h = 0.125 mm, 8.814 and 8.811 mm). The outer stress is sigma_r(b_eff), and rings are
    // compared one cell or more from both surfaces: a + h <= |x_0| <= b_eff - h.
    //
    // What is compared: the layers of rings one particle spacing thick in initial radius, each
    // layer's mean of (ring - Lame at the ring's initial radius), against 2 % of the outer
    // sigma_r (measured: sigma_r within 1.40 %, the two hoop stresses within 0.75 % of Lame's and
    // 0.53 % of each other, u within 0.14 % of u_d; 1.27, 0.48, 0.48 and 0.06 % at h = 0.125 mm;
    // the largest sigma_r errors 1.7 cells inside b_eff and 2.7 cells from the cavity). A single
    // ring is not held to 2 %: the particles sit on the (r, z) lattice, so the cavity is a
    // staircase whose steps (long and flat near the axis and near z = 0) concentrate stress on
    // the rings beside them, and the driven band is a staircase too. In cells, that disturbance
    // does not shrink with h (measured per ring, |sigma_r - Lame| / |outer sigma_r|: up to 18 %
    // within two cells of the cavity at h = 0.25 mm, 12 % at h = 0.125 mm; every ring within 2 %
    // only from 8 cells off the cavity to 3.4 cells inside b_eff, at both h). The table prints
    // the worst ring of each layer. A layer spans every angle, so the steps average out.
    const double a = 0.003, b = 0.009, h = 0.25e-3, delta = h / 2, rho = 1000, young = 1e9, nu = 0.3;
    const auto moduli = gimlet::elastic_moduli::from_young_poisson(young, nu);
    const double bulk = moduli.bulk, shear = moduli.shear;
    const auto sc = shell_scene(a, b, h, gimlet::make_elastic_material(rho, young, nu));
    gimlet::solver_options<A> opt;
    opt.threads = 1;
    shell_elastic_solver sol(sc, opt);
    auto& p = sol.particles();
    const std::vector<A::vector> x0(p.column<gimlet::fields::position>().begin(),
                                    p.column<gimlet::fields::position>().end());
    const std::size_t driven = drive_outer_layer(p, x0, b, delta);
    REQUIRE(driven > 0);
    const double u_d = -1e-3 * b;
    const double c = std::sqrt((bulk + 4 * shear / 3) / rho), transit = (b - a) / c;
    const double ramp_time = 20 * transit, end = ramp_time + 5 * transit;
    while (sol.time() < end) {
        set_driven_speed(p, x0, -u_d * ramp_rate(sol.time() / ramp_time) / ramp_time);
        sol.step_at_most(end - sol.time());
    }
    const auto& x = p.column<gimlet::fields::position>();
    const auto& stress = p.column<gimlet::fields::stress>();
    const auto& hoop = p.column<gimlet::fields::stress_zz>();
    for (std::size_t i = 0; i < p.size(); ++i)
        if (p.column<gimlet::fields::driven>()[i]) {
            const A::vector e = x0[i] / x0[i].norm();
            REQUIRE((x[i] - x0[i]).dot(e) == Approx(u_d).epsilon(1e-3));
        }

    // The layers [a + k delta, a + (k + 1) delta) of initial radius.
    const int layers = int(std::ceil((b - a) / delta));
    auto layer_of = [&](std::size_t i) { return std::min(layers - 1, int((x0[i].norm() - a) / delta)); };
    std::vector<double> count(layers), radius(layers), disp(layers);
    for (std::size_t i = 0; i < p.size(); ++i) {
        const int k = layer_of(i);
        count[k] += 1, radius[k] += x0[i].norm(), disp[k] += (x[i] - x0[i]).dot(x0[i] / x0[i].norm());
    }
    const int mid = int(((a + b) / 2 - a) / delta);
    const double r_m = radius[mid] / count[mid], u_m = disp[mid] / count[mid];
    const gimlet::test::lame_sphere lame(a, r_m, u_m, bulk, shear);
    // b_eff: lame.displacement(r) = u_d (u is monotonic in r outside the cavity's minimum).
    double lo = r_m, hi = 2 * b;
    for (int it = 0; it < 200; ++it) {
        const double m = (lo + hi) / 2;
        (std::abs(lame.displacement(m)) < std::abs(u_d) ? lo : hi) = m;
    }
    const double b_eff = (lo + hi) / 2, r_nodes = innermost_driven_node(p, x0, h, delta);
    const double outer = std::abs(lame.radial_stress(b_eff));

    std::vector<double> e_r(layers), e_t(layers), e_p(layers), e_tp(layers), e_u(layers), worst_ring(layers);
    for (std::size_t i = 0; i < p.size(); ++i) {
        const int k = layer_of(i);
        const double r0 = x0[i].norm();
        const spherical_stress s = spherical(stress[i], hoop[i], x0[i]);
        e_r[k] += (s.radial - lame.radial_stress(r0)) / outer / count[k];
        e_t[k] += (s.meridional - lame.hoop_stress(r0)) / outer / count[k];
        e_p[k] += (s.azimuthal - lame.hoop_stress(r0)) / outer / count[k];
        e_tp[k] += (s.meridional - s.azimuthal) / outer / count[k];
        e_u[k] += ((x[i] - x0[i]).dot(x0[i] / r0) - lame.displacement(r0)) / std::abs(u_d) / count[k];
        worst_ring[k] = std::max(worst_ring[k], std::abs(s.radial - lame.radial_stress(r0)) / outer);
    }
    std::printf("Lame shell a = %g mm, b = %g mm, h = %g mm (%g cells across the wall), %zu rings (%zu driven), "
                "%zu steps\n",
                a * 1e3, b * 1e3, h * 1e3, (b - a) / h, p.size(), driven, std::size_t(sol.steps()));
    std::printf("u_d = %g um; u measured at r_m = %.4f mm: %g um; Lame's loaded radius b_eff = %.4f mm "
                "(b - %.2f h), innermost driven node %.4f mm; outer sigma_r = %.5g Pa\n",
                u_d * 1e6, r_m * 1e3, u_m * 1e6, b_eff * 1e3, (b - b_eff) / h, r_nodes * 1e3, -outer);
    std::printf("layer means - Lame, / |outer sigma_r| (u: / |u_d|); worst ring: |sigma_r - Lame| / |outer sigma_r|\n");
    std::printf("  r0 (mm) rings   u        sigma_r  sigma_th sigma_ph th - ph   worst ring  compared\n");
    double worst_r = 0, worst_t = 0, worst_p = 0, worst_tp = 0, worst_u = 0, worst_single = 0;
    for (int k = 0; k < layers; ++k) {
        if (!count[k]) continue;
        const double r = radius[k] / count[k];
        const bool compared = a + k * delta >= a + h - 1e-12 && a + (k + 1) * delta <= b_eff - h;
        if (compared) {
            worst_r = std::max(worst_r, std::abs(e_r[k]));
            worst_t = std::max(worst_t, std::abs(e_t[k]));
            worst_p = std::max(worst_p, std::abs(e_p[k]));
            worst_tp = std::max(worst_tp, std::abs(e_tp[k]));
            worst_u = std::max(worst_u, std::abs(e_u[k]));
            worst_single = std::max(worst_single, worst_ring[k]);
        }
        std::printf("  %7.4f %5d %+8.4f %+8.4f %+8.4f %+8.4f %+8.4f   %8.4f    %s\n", r * 1e3, int(count[k]), e_u[k],
                    e_r[k], e_t[k], e_p[k], e_tp[k], worst_ring[k], compared ? "yes" : "");
    }
    // The layers around mid-wall whose every ring is within 2 % of the outer sigma_r.
    int first_ok = mid, last_ok = mid;
    while (first_ok > 0 && worst_ring[first_ok - 1] <= 0.02) --first_ok;
    while (last_ok + 1 < layers && worst_ring[last_ok + 1] <= 0.02) ++last_ok;
    std::printf("compared layers: largest |error| / |outer sigma_r|: sigma_r %.4f, sigma_theta %.4f, sigma_phi %.4f, "
                "sigma_theta - sigma_phi %.4f; u %.4f of |u_d|. Single rings: worst %.4f; all within 2 %% for "
                "%.3f <= r0 < %.3f mm (%.1f cells from the cavity, %.1f from b_eff)\n",
                worst_r, worst_t, worst_p, worst_tp, worst_u, worst_single, (a + first_ok * delta) * 1e3,
                (a + (last_ok + 1) * delta) * 1e3, first_ok * delta / h, (b_eff - a - (last_ok + 1) * delta) / h);
    INFO("b_eff = " << b_eff * 1e3 << " mm, innermost driven node " << r_nodes * 1e3 << " mm; largest layer errors / |outer "
                    "sigma_r|: sigma_r " << worst_r << ", sigma_theta " << worst_t << ", sigma_phi " << worst_p
                    << ", sigma_theta - sigma_phi " << worst_tp << "; u " << worst_u << " of |u_d|");
    CHECK(std::abs(b_eff - r_nodes) < h / 2);
    CHECK(worst_r < 0.02);
    CHECK(worst_t < 0.02);
    CHECK(worst_p < 0.02);
    CHECK(worst_tp < 0.02);  // the two hoop stresses agree: spherical symmetry
    CHECK(worst_u < 0.005);  // the displacement has Lame's profile across the wall
}

namespace {

// One quasi-static collapse of an elastic-perfectly-plastic hollow sphere and what it measured.
struct collapse_sample {
    std::size_t step;
    double alpha, way, a, outer, pressure, fully_plastic, yielded;
};
struct collapse_result {
    std::vector<collapse_sample> samples;
    double onset_alpha = 0;           // the distension at which every ring inside the shell is at yield
    double worst_plastic = 0;         // max |P / P_fp - 1| from the onset on
    double worst_above = -1;          // max (P / P_fp - 1) over the whole collapse
    std::size_t rings = 0, driven = 0, steps = 0;
};

// A shell a0 = 3 mm, b0 = 9 mm (b/a = 3, alpha0 = 27/26, porosity 1/27) of von Mises material
// (perfectly plastic, Y = 1 MPa, G = 1000 Y) with a linear EOS (K = 1250 Y), rho = 1000 kg/m^3,
// collapsed from alpha0 until alpha <= alpha0 - way (alpha0 - (alpha0 + 1) / 2): `way` of the way to
// (alpha0 + 1) / 2.
//
// The body reaches 2 mm past b0, to 11 mm, and its outer layer is driven; the shell
// a0 <= |x_0| <= b0 measured here is the free material inside, its outer surface the material
// sphere that started at b0 = 9 mm. Why 2 mm: the driven layer moves the nodes it weighs, a band
// about 1.5 cells deep (the Lame test), with one radial speed, where the plastic flow slows as
// 1/r^2 across it; so the band compresses (its rings reach a pressure of about 10 Y by the end)
// and disturbs the flow around it. Measured with the body 1 mm past b0, P at b0 drifts to
// +2.4 % of the relation by the end at h = 0.25 mm and +4.4 % at h = 0.125 mm (where the band is
// closer in cells but not in mm: the disturbance has a size in mm); 2 mm past b0, within
// +-0.9 % at h = 0.25 mm and +0.4 to +0.9 % at h = 0.125 mm, converged.
//  * The outer pressure is P = -sigma_r averaged over the rings whose initial radius lies within
//    one particle spacing of b0 (two layers, about 220 rings at h = 0.25 mm; sigma_r is linear
//    in r across them, 2Y/r, so their mean is sigma_r at b0).
//  * The current outer radius b is b0 plus the same rings' mean radial displacement.
//  * The current solid volume V_s (per radian) is the particles' own: (b0^3 - a0^3) / 3 times the
//    ratio of the current to the initial volume (J V_0) summed over the rings inside b0 (the
//    lattice's initial volume is 1.0007 of the exact one at h = 0.25 mm: only its ratio is used).
//    So alpha = b^3 / (3 V_s) = b^3 / (b^3 - a^3) is the distension of the current radii, which
//    Carroll-Holt's fully plastic relation holds in for any bulk modulus, and the solid's elastic
//    loss of volume (alpha P / K = 0.22 % at the end; docs/equations.md, "Spherical shells: Lame
//    and Carroll-Holt", 3 % of P with alpha from the initial solid volume at K = 1250 Y) is
//    measured, not an error. The current a is (b^3 - 3 V_s)^(1/3).
//  * The drive: the layer's inward speed rises as ramp() over 20 transit times of the wall
//    (c = sqrt((K + 4G/3)/rho) = 1607 m/s; 5.0 us across a0..b) to `speed` and stays there. No
//    damping.
collapse_result carroll_holt_collapse(double h, double speed, double way, std::size_t sample_every) {
    const double a0 = 0.003, b0 = 0.009, b = 0.011, delta = h / 2, rho = 1000;
    const double yield = 1e6, shear = 1000 * yield, bulk = 1250 * yield;
    const auto sc = shell_scene(a0, b, h,
                                plastic_material{rho, gimlet::strength::von_mises(shear, yield), gimlet::eos::linear(bulk)});
    gimlet::solver_options<A> opt;
    opt.threads = 1;
    shell_plastic_solver sol(sc, opt);
    auto& p = sol.particles();
    const std::vector<A::vector> x0(p.column<gimlet::fields::position>().begin(),
                                    p.column<gimlet::fields::position>().end());
    collapse_result out;
    out.rings = p.size();
    out.driven = drive_outer_layer(p, x0, b, delta);
    double initial_inside = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (x0[i].norm() < b0) initial_inside += p.column<gimlet::fields::volume0>()[i];
    const double exact_inside = (b0 * b0 * b0 - a0 * a0 * a0) / 3;
    const double alpha0 = gimlet::test::alpha_from_radii(a0, b0), alpha_end = alpha0 - way * (alpha0 - 1) / 2;
    const double c = std::sqrt((bulk + 4 * shear / 3) / rho), ramp_time = 20 * (b - a0) / c;
    const auto& x = p.column<gimlet::fields::position>();
    const auto& stress = p.column<gimlet::fields::stress>();
    const auto& hoop = p.column<gimlet::fields::stress_zz>();
    auto measure = [&] {
        double volume = 0, n_outer = 0, sigma_r = 0, u = 0, n_inside = 0, n_yielded = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const double r0 = x0[i].norm();
            const spherical_stress s = spherical(stress[i], hoop[i], x0[i]);
            if (r0 < b0) {
                volume += gimlet::current_volume(p[i]);
                // The ring's von Mises stress sqrt(3 J2) over the 3-D deviator, as the strength
                // computes it (at yield in spherical symmetry, |sigma_theta - sigma_r| = Y).
                const double mean = (stress[i].trace() + hoop[i]) / 3;
                const A::matrix dev = stress[i] - mean * A::matrix::Identity();
                const double dzz = hoop[i] - mean;
                const double eq = std::sqrt(1.5 * (dev.cwiseProduct(dev).sum() + dzz * dzz));
                n_inside += 1;
                if (eq >= (1 - 1e-6) * yield) n_yielded += 1;
            }
            if (std::abs(r0 - b0) < delta) {
                n_outer += 1;
                sigma_r += s.radial;
                u += (x[i] - x0[i]).dot(x0[i] / r0);
            }
        }
        collapse_sample smp{};
        smp.step = std::size_t(sol.steps());
        smp.outer = b0 + u / n_outer;
        const double solid = exact_inside * volume / initial_inside;
        const double b3 = smp.outer * smp.outer * smp.outer;
        smp.alpha = b3 / (3 * solid);
        smp.a = std::cbrt(b3 - 3 * solid);
        smp.way = (alpha0 - smp.alpha) / (alpha0 - alpha_end);
        smp.pressure = -sigma_r / n_outer;
        smp.fully_plastic = gimlet::test::carroll_holt_fully_plastic_pressure(yield, smp.alpha);
        smp.yielded = n_yielded / n_inside;
        return smp;
    };
    collapse_sample s = measure();
    while (s.alpha > alpha_end) {
        set_driven_speed(p, x0, speed * ramp(sol.time() / ramp_time));
        sol.step();
        if (sol.steps() % sample_every) continue;
        s = measure();
        out.samples.push_back(s);
        const double rel = s.pressure / s.fully_plastic - 1;
        out.worst_above = std::max(out.worst_above, rel);
        if (out.onset_alpha == 0 && s.yielded == 1.0) out.onset_alpha = s.alpha;
        if (out.onset_alpha != 0) out.worst_plastic = std::max(out.worst_plastic, std::abs(rel));
    }
    out.steps = std::size_t(sol.steps());
    // The table: every 2.5 % of the way.
    std::printf("Carroll-Holt collapse, h = %g mm (%g cells across the wall a0..b0), %zu rings (%zu driven), drive %g m/s, "
                "%zu steps; alpha0 = %.6f, first yield (incompressible) at %.6f, fully plastic (incompressible) at %.6f\n",
                h * 1e3, (b0 - a0) / h, out.rings, out.driven, speed, out.steps, alpha0,
                gimlet::test::carroll_holt_alpha_first_yield(alpha0, shear, yield),
                gimlet::test::carroll_holt_alpha_fully_plastic(alpha0, shear, yield));
    std::printf("  step   alpha     way     a (mm)   b (mm)   P/Y     P_fp/Y  P/P_fp-1  yielded\n");
    double next = 0;
    for (const auto& m : out.samples) {
        if (m.way < next && &m != &out.samples.back()) continue;
        next = std::floor(m.way / 0.025 + 1) * 0.025;
        std::printf("  %6zu %.6f %6.3f  %.4f   %.5f  %.4f  %.4f  %+.4f   %.4f\n", m.step, m.alpha, m.way, m.a * 1e3,
                    m.outer * 1e3, m.pressure / yield, m.fully_plastic / yield, m.pressure / m.fully_plastic - 1,
                    m.yielded);
    }
    std::printf("every ring of the shell at yield from alpha = %.6f (%.3f of the way); from there |P/P_fp - 1| <= %.4f; "
                "P/P_fp - 1 <= %+.4f over the whole collapse\n",
                out.onset_alpha, (alpha0 - out.onset_alpha) / (alpha0 - alpha_end), out.worst_plastic, out.worst_above);
    return out;
}

}  // namespace

TEST_CASE("spherical shells: a perfectly plastic shell b/a = 3 collapses to (alpha0 + 1)/2 at Carroll-Holt's "
          "pressure",
          "[solver][axisymmetric][verification][long]") {
    // alpha from 27/26 to 53/52: a from 3 mm to 2.38 mm (b from 9 to 8.938 mm), at h = 0.25 mm
    // (24 cells across the wall at the start, 9.5 across the cavity's radius at the end), 5635
    // rings, 11,150 steps, 17.7 s in release (tests at -O1, one thread): [long]. The drive,
    // 0.075 m/s, moves the cavity's wall at up to 1.6 m/s: the inertial terms, of order
    // rho adot^2, are 0.1 % of P. The turn to full plasticity sets the shell ringing, undamped,
    // at a period of about 45 us (some 10 transit times), by an amount that grows with the
    // drive: P oscillates about the relation by +-1.5 % at this drive, +-2 % at 0.1 m/s (14 s);
    // with the body 1 mm past b0, +-4 % at 0.15 m/s and +-12 % at 0.3 m/s. No damping is used.
    //
    // What is checked: from the first sample at which every ring of the shell is at yield
    // (measured: alpha = 1.03728, 6.2 % of the way; the incompressible three-phase relation
    // puts it at alpha2 = 1.03794, 2.7 %, and the solid's compressibility moves it by order
    // alpha P / K, docs/equations.md) to (alpha0 + 1)/2, P is within 3 % of (2Y/3) ln(alpha /
    // (alpha - 1)) (measured: within 1.75 %, the largest just after the onset; at h = 0.125 mm
    // within 1 %). Before the onset the shell is elastic, then part plastic, and P rises from 0
    // to the relation within a change of alpha of 1e-3, where the fully plastic relation does
    // not apply and the incompressible three-phase one is off by the compressibility's shift
    // (P measured 3 % under it at alpha2). Over the whole collapse P does not exceed the fully
    // plastic pressure by more than 3 % (statically no phase exceeds it).
    const collapse_result r = carroll_holt_collapse(0.25e-3, 0.075, 1.0, 50);
    const double alpha0 = 27.0 / 26;
    INFO("every ring at yield from alpha = " << r.onset_alpha << "; from there the largest |P/P_fp - 1| = "
                                             << r.worst_plastic << "; over the collapse P/P_fp - 1 <= " << r.worst_above);
    REQUIRE(r.onset_alpha > 0);
    CHECK((alpha0 - r.onset_alpha) / (alpha0 - (alpha0 + 1) / 2) < 0.1);
    CHECK(r.worst_plastic < 0.03);
    CHECK(r.worst_above < 0.03);
}

TEST_CASE("spherical shells: a perfectly plastic shell at 0.5 mm collapses a quarter of the way at Carroll-Holt's "
          "pressure",
          "[solver][axisymmetric][verification]") {
    // The coarse twin of the test above, for the asan-ubsan preset (0.95 s in release, 5.4 s
    // under asan-ubsan): the same material, drive, body and measurements at h = 0.5 mm (12 cells
    // across the wall), a quarter of the way to (alpha0 + 1)/2. What holds at this size: every
    // ring at yield from 6.4 % of the way, then P above the relation by 2.6 to 5.2 % (the
    // coarse cell's error: under 1.75 % at 0.25 mm), so within 6 %.
    const collapse_result r = carroll_holt_collapse(0.5e-3, 0.075, 0.25, 25);
    INFO("every ring at yield from alpha = " << r.onset_alpha << "; from there the largest |P/P_fp - 1| = "
                                             << r.worst_plastic << "; over the collapse P/P_fp - 1 <= " << r.worst_above);
    REQUIRE(r.onset_alpha > 0);
    CHECK(r.worst_plastic < 0.06);
    CHECK(r.worst_above < 0.06);
}
