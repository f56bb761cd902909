// SPDX-License-Identifier: MIT
/// \file
/// The radial factors of axisymmetric uGIMP (shape/detail/axisymmetric_gimp.hpp) against their
/// definitions integrated by quadrature, node by node, for particle sizes from 1/8 to 1/2 of a
/// cell and centres from the axis outwards (the clip at r = 0 included); and the sums a
/// consistent set of radial factors keeps.

#include "gimlet/shape/detail/axisymmetric_gimp.hpp"
#include "gimlet/shape/detail/gimp_kernel.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

namespace {

using gimlet::shape::detail::axisymmetric_gimp_radial;
using gimlet::shape::detail::radial_factors;

// The definitions integrated: over D = [max(0, r_p - half), r_p + half], split at the node's
// kinks (r_i - h, r_i, r_i + h), 3-point Gauss-Legendre on each piece, exact for the piecewise
// quadratic integrands N r, N' r and N.
radial_factors<double> by_quadrature(double r_p, double r_i, double half, double h) {
    const double lo = std::max(0.0, r_p - half), hi = r_p + half;
    std::vector<double> cuts = {lo, hi};
    for (const double c : {r_i - h, r_i, r_i + h})
        if (c > lo && c < hi) cuts.push_back(c);
    std::sort(cuts.begin(), cuts.end());
    const std::array<double, 3> x = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    double nr = 0, dnr = 0, n = 0, r = 0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double a = cuts[k], b = cuts[k + 1], mid = 0.5 * (a + b), half_len = 0.5 * (b - a);
        for (int q = 0; q < 3; ++q) {
            const double t = mid + half_len * x[q], wt = half_len * w[q];
            const double d = t - r_i;
            const double hat = std::max(0.0, 1.0 - std::abs(d) / h);
            const double slope = std::abs(d) < h ? (d > 0 ? -1.0 / h : 1.0 / h) : 0.0;
            nr += wt * hat * t;
            dnr += wt * slope * t;
            n += wt * hat;
            r += wt * t;
        }
    }
    return {nr / r, dnr / r, n / r};
}

constexpr double h = 1e-3;  // m

// Particle centres from near the axis outwards, for a half-width: around the clip (r_p < half),
// every branch and well away from the axis.
std::vector<double> centres(double half) {
    std::vector<double> r;
    for (int k = 1; k <= 400; ++k) r.push_back(k * 0.0317 * h);  // 0.0317 h to 12.7 h
    for (const double f : {0.25, 0.5, 0.999, 1.0, 1.001, 1.5}) r.push_back(f * half);
    return r;
}

}  // namespace

TEST_CASE("axisymmetric uGIMP: the radial factors are their definitions, node by node, the axis's clip included",
          "[shape][axisymmetric]") {
    double worst = 0;
    for (const double l : {1.0 / 8, 1.0 / 6, 1.0 / 4, 1.0 / 3, 1.0 / 2}) {
        const double half = l * h;
        for (const double r_p : centres(half)) {
            const int first = std::max(0, int(std::floor((r_p - half) / h)) - 1);
            for (int k = first; k <= first + 4; ++k) {
                const double r_i = k * h;
                const auto f = axisymmetric_gimp_radial(r_p, r_i, half, h);
                const auto q = by_quadrature(r_p, r_i, half, h);
                INFO("l = " << l << ", r_p = " << r_p / h << " h, node " << k);
                CHECK(f.weight == Approx(q.weight).margin(1e-12));
                CHECK(f.gradient * h == Approx(q.gradient * h).margin(1e-12));
                CHECK(f.hoop * h == Approx(q.hoop * h).margin(1e-9 * std::max(1.0, q.hoop * h)));
                worst = std::max({worst, std::abs(f.weight - q.weight), std::abs(f.gradient - q.gradient) * h});
            }
        }
    }
    std::printf("axisymmetric uGIMP radial factors against quadrature: largest difference %.1e\n", worst);
}

// Sums over the nodes a particle reaches: Σ S = 1 and Σ G = 0 (the weights part unity), Σ G r_i
// = 1 and Σ T r_i = 1 (L_rr and L_θθ exact for v_r = a r), and Σ S r_i = <r²>/<r>, the
// r-weighted mean radius, r_p + half²/(3 r_p) unclipped and 2(r_p + half)/3 clipped: not r_p.
TEST_CASE("axisymmetric uGIMP: the radial factors part unity and reproduce a radial velocity a r exactly",
          "[shape][axisymmetric]") {
    for (const double l : {1.0 / 8, 1.0 / 4, 1.0 / 2}) {
        const double half = l * h;
        for (const double r_p : centres(half)) {
            double s = 0, g = 0, gr = 0, tr = 0, sr = 0;
            const int first = std::max(0, int(std::floor((r_p - half) / h)) - 1);
            for (int k = first; k <= first + 4; ++k) {
                const double r_i = k * h;
                const auto f = axisymmetric_gimp_radial(r_p, r_i, half, h);
                s += f.weight;
                g += f.gradient * h;
                gr += f.gradient * r_i;
                tr += f.hoop * r_i;
                sr += f.weight * r_i;
            }
            INFO("l = " << l << ", r_p = " << r_p / h << " h");
            CHECK(s == Approx(1.0).margin(1e-13));
            CHECK(g == Approx(0.0).margin(1e-12));
            CHECK(gr == Approx(1.0).margin(1e-12));
            CHECK(tr == Approx(1.0).margin(1e-12));
            const double mean_r = r_p >= half ? r_p + half * half / (3 * r_p) : 2 * (r_p + half) / 3;
            CHECK(sr / h == Approx(mean_r / h).margin(1e-12));
        }
    }
}

// Far from the axis the factors tend to the planar uGIMP ones: the correction is O(l²/ρ).
TEST_CASE("axisymmetric uGIMP: far from the axis the radial factors tend to the planar ones", "[shape][axisymmetric]") {
    const double half = 0.25 * h;
    for (const double s : {-1.1, -0.7, -0.2, 0.0, 0.1, 0.6, 1.2}) {
        const double r_i = 1e4 * h, r_p = r_i + s * h;
        const auto f = axisymmetric_gimp_radial(r_p, r_i, half, h);
        const double a = std::abs(s), l = 0.25;
        const double planar = a < l ? 1 - (a * a + l * l) / (2 * l) : a <= 1 - l ? 1 - a : a < 1 + l ? (1 + l - a) * (1 + l - a) / (4 * l) : 0.0;
        CHECK(f.weight == Approx(planar).margin(1e-4));
        CHECK(f.hoop * r_p == Approx(planar).margin(1e-12));
    }
}

// The velocity gradient of the axisymmetric weak form at the stencil level (x -> r, y -> z):
// L_rr = Σ v_ir G^r_i S^z_j, L_rz = Σ v_ir S^r_i dS^z_j/dz, L_zr = Σ v_iz G^r_i S^z_j,
// L_zz = Σ v_iz S^r_i dS^z_j/dz, L_θθ = Σ v_ir T^r_i S^z_j. With nodal velocities (a r_i, b z_j)
// every particle reads L_rr = L_θθ = a, L_zz = b and L_rz = L_zr = 0 to round-off, including
// those whose domain reaches the axis; with v_r = c r z, L_rz = c Σ S^r_i r_i, the r-weighted
// mean radius (a z-gradient built on S^r with a wrong constant would miss it).
TEST_CASE("axisymmetric uGIMP: the hoop kinematics of a linear velocity field, at the axis too", "[shape][axisymmetric]") {
    namespace d = gimlet::shape::detail;
    const double a = 0.37, b = -1.3, c = 2.1;
    double worst = 0;
    for (const double l : {1.0 / 8, 1.0 / 4, 1.0 / 2}) {
        const double half = l * h;
        for (const double r_p : centres(half)) {
            const double z_p = 3.37 * h;
            int first_r = 0, first_z = 0;
            std::array<gimlet::shape::detail::radial_factors<double>, d::gimp_stencil> fr;
            d::axisymmetric_gimp_radial_stencil(r_p, half, h, first_r, fr);
            std::array<double, d::gimp_stencil> sz{}, dsz{};
            d::gimp_weights(z_p / h, l, first_z, sz.data(), dsz.data());
            double l_rr = 0, l_rz = 0, l_zr = 0, l_zz = 0, l_tt = 0, l_rz_c = 0, mean_r = 0;
            for (int i = 0; i < d::gimp_stencil; ++i) {
                const double r_i = (first_r + i) * h;
                mean_r += fr[i].weight * r_i;
                for (int j = 0; j < d::gimp_stencil; ++j) {
                    const double z_j = (first_z + j) * h, dz = dsz[j] / h;
                    const double vr = a * r_i, vz = b * z_j;
                    l_rr += vr * fr[i].gradient * sz[j];
                    l_rz += vr * fr[i].weight * dz;
                    l_zr += vz * fr[i].gradient * sz[j];
                    l_zz += vz * fr[i].weight * dz;
                    l_tt += vr * fr[i].hoop * sz[j];
                    l_rz_c += c * r_i * z_j * fr[i].weight * dz;
                }
            }
            INFO("l = " << l << ", r_p = " << r_p / h << " h");
            CHECK(l_rr == Approx(a).margin(1e-12));
            CHECK(l_tt == Approx(a).margin(1e-12));
            CHECK(l_zz == Approx(b).margin(1e-12));
            CHECK(l_rz == Approx(0.0).margin(1e-12));
            CHECK(l_zr == Approx(0.0).margin(1e-12));
            CHECK(l_rz_c == Approx(c * mean_r).epsilon(1e-12));
            worst = std::max({worst, std::abs(l_rr - a), std::abs(l_tt - a), std::abs(l_zz - b)});
        }
    }
    std::printf("axisymmetric uGIMP hoop kinematics: largest error %.1e\n", worst);
}

// The internal force of the axisymmetric weak form per radian at the stencil level:
// f_ir = -Σ_p V_p (σ_rr G^r S^z + σ_rz S^r dS^z/dz + σ_θθ T^r S^z), f_iz = -Σ_p V_p (σ_rz G^r S^z
// + σ_zz S^r dS^z/dz), V_p = A_p r_p. A uniform pressure over particles that tile [0, R] x [0, Z]
// (2 x 2 a cell) leaves no force at any node inside: per node, Σ_p V_p (G^r + T^r) is the
// integral of d(N_i r)/dr over the tiled region, which vanishes but at its outer edge, the axis's
// node included (N r = 0 at r = 0).
TEST_CASE("axisymmetric uGIMP: a uniform pressure leaves no force inside the material, at the axis too",
          "[shape][axisymmetric]") {
    namespace d = gimlet::shape::detail;
    const int cells_r = 8, cells_z = 6;
    const double p = 2.5e9, half = 0.25 * h;
    std::vector<double> fr((cells_r + 3) * (cells_z + 3), 0.0), fz(fr.size(), 0.0);
    auto at = [&](int k, int j) { return std::size_t(k * (cells_z + 3) + j + 1); };  // node j >= -1
    for (int pr = 0; pr < 2 * cells_r; ++pr)
        for (int pz = 0; pz < 2 * cells_z; ++pz) {
            const double r_p = (pr + 0.5) * 2 * half, z_p = (pz + 0.5) * 2 * half;
            const double volume = 2 * half * 2 * half * r_p;  // per radian
            int first_r = 0, first_z = 0;
            std::array<d::radial_factors<double>, d::gimp_stencil> f;
            d::axisymmetric_gimp_radial_stencil(r_p, half, h, first_r, f);
            std::array<double, d::gimp_stencil> sz{}, dsz{};
            d::gimp_weights(z_p / h, 0.25, first_z, sz.data(), dsz.data());
            for (int i = 0; i < d::gimp_stencil; ++i)
                for (int j = 0; j < d::gimp_stencil; ++j) {
                    if (first_r + i < 0) continue;
                    // sigma = -p I: f_ir = p V (G^r S^z + T^r S^z), f_iz = p V S^r dS^z/dz.
                    fr[at(first_r + i, first_z + j)] += p * volume * (f[i].gradient + f[i].hoop) * sz[j];
                    fz[at(first_r + i, first_z + j)] += p * volume * f[i].weight * dsz[j] / h;
                }
        }
    double inside = 0, edge = 0;
    for (int k = 0; k <= cells_r + 1; ++k)
        for (int j = -1; j <= cells_z + 1; ++j) {
            const double size = std::hypot(fr[at(k, j)], fz[at(k, j)]) / (p * h * h);
            if (k < cells_r && j > 0 && j < cells_z) inside = std::max(inside, size);
            else edge = std::max(edge, size);
        }
    std::printf("axisymmetric uGIMP, uniform pressure: largest nodal force inside %.1e, at the edges %.2f (p h^2 per radian)\n",
                inside, edge);
    CHECK(inside < 1e-12);
    CHECK(edge > 0.1);  // the edges do carry the pressure: the test can tell
}

// Linear MPM's radial factors (the point particle): the same sums, with Σ S^r r_i = r_p exactly
// (the domain is a point), and the l -> 0 limit of the uGIMP factors away from the nodes.
TEST_CASE("axisymmetric linear shape: sums, a radial velocity a r exactly, and uGIMP's limit", "[shape][axisymmetric]") {
    namespace d = gimlet::shape::detail;
    for (int k = 1; k <= 300; ++k) {
        const double r_p = (k * 0.0413 + 0.0011) * h;  // never on a node
        double s = 0, gr = 0, tr = 0, sr = 0;
        const int first = int(std::floor(r_p / h));
        for (int n = std::max(0, first - 1); n <= first + 2; ++n) {
            const double r_i = n * h;
            const auto f = d::axisymmetric_linear_radial(r_p, r_i, h);
            s += f.weight;
            gr += f.gradient * r_i;
            tr += f.hoop * r_i;
            sr += f.weight * r_i;
            const auto g = d::axisymmetric_gimp_radial(r_p, r_i, 1e-7 * h, h);
            CHECK(f.weight == Approx(g.weight).margin(1e-6));
            CHECK(f.gradient * h == Approx(g.gradient * h).margin(1e-6));
        }
        INFO("r_p = " << r_p / h << " h");
        CHECK(s == Approx(1.0).margin(1e-14));
        CHECK(gr == Approx(1.0).margin(1e-12));
        CHECK(tr == Approx(1.0).margin(1e-12));
        CHECK(sr / h == Approx(r_p / h).margin(1e-12));
    }
}
