// SPDX-License-Identifier: MIT
// solver_options::volume_filter: each particle's J replaced by the L2 projection of the
// particles' J onto the grid (the consistent-mass iteration), its energy moved along the
// reference isentrope and the energy that move releases returned as heat (docs/equations.md,
// "Particle-scale state filters", (D)). What it must do: leave a state the grid represents
// alone, remove a row pattern the grid cannot see, keep the internal energy, and never cool a
// particle below its thermal energy.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace {

using S = gimlet::space<2>;
using material = gimlet::materials::hmx_material<>;
using solver = gimlet::solver<S, gimlet::shape::ugimp, material>;

constexpr double excess = 100.0;  // J/kg of thermal energy above the reference isentrope

// An HMX block filling a doubly periodic 8 x 8 mm grid (1 mm cells, 2 x 2 particles a cell), at
// rest, every particle at J = j_of(y) with e = e_s(J) + excess.
template <class JOfY>
solver block(bool filter, JOfY j_of) {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector(8e-3, 8e-3);
    gs.cell = 1e-3;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::periodic};
    gimlet::scene::scene<S, material> sc(gs);
    const auto hmx = gimlet::materials::make_hmx();
    sc.add_body(gimlet::scene::box<S>(gs.lower, gs.upper), hmx, S::vector::Zero(), 2, "block");
    gimlet::solver_options<S> opt;
    opt.threads = 1;
    opt.consistent_mass_iterations = 4;
    opt.cfl = 0.4;
    opt.volume_filter = filter;
    solver sol(sc, opt);
    auto& ps = sol.particles();
    auto& F = ps.template column<gimlet::fields::deformation_gradient>();
    auto& e = ps.template column<gimlet::fields::specific_internal_energy>();
    const auto& x = ps.template column<gimlet::fields::position>();
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const double j = j_of(x[i][1]);
        F[i] = std::sqrt(j) * S::matrix::Identity();
        e[i] = hmx.thermal.reference_energy(j) + excess;
    }
    return sol;
}

double internal_energy(const solver& sol) {
    const auto& ps = sol.particles();
    double sum = 0;
    for (std::size_t i = 0; i < ps.size(); ++i)
        sum += ps.template column<gimlet::fields::mass>()[i] * ps.template column<gimlet::fields::specific_internal_energy>()[i];
    return sum;
}

}  // namespace

// A uniform compression is what the grid represents exactly: the projection's fixed point.
TEST_CASE("volume filter: a uniform state is left as it is", "[core][volume_filter]") {
    auto uniform = [](double) { return 0.95; };
    auto with = block(true, uniform);
    auto without = block(false, uniform);
    with.step(1e-9);
    without.step(1e-9);
    const auto& a = with.particles();
    const auto& b = without.particles();
    double dj = 0, de = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        dj = std::max(dj, std::abs(a.template column<gimlet::fields::deformation_gradient>()[i].determinant() -
                                   b.template column<gimlet::fields::deformation_gradient>()[i].determinant()));
        de = std::max(de, std::abs(a.template column<gimlet::fields::specific_internal_energy>()[i] -
                                   b.template column<gimlet::fields::specific_internal_energy>()[i]));
    }
    CHECK(dj < 1e-12);
    CHECK(de < 1e-6);  // J/kg, of about 1.5e5
}

// Particle rows alternating J = 0.94 and 0.96 (two rows a cell): a pattern whose stresses the
// nodal forces cannot see, as a shock leaves behind it. One filtered step takes every particle to
// the mean, keeps the internal energy, and returns the isentrope's energy as heat.
TEST_CASE("volume filter: a row pattern the grid cannot see goes, the energy stays", "[core][volume_filter]") {
    auto rows = [](double y) { return std::fmod(std::floor(y / 0.5e-3), 2.0) == 0 ? 0.94 : 0.96; };
    auto sol = block(true, rows);
    const auto hmx = gimlet::materials::make_hmx();
    const double e0 = internal_energy(sol);
    sol.step(1e-12);  // the filter's change; the step's own work is negligible over 1e-12 s
    const auto& ps = sol.particles();
    double jmin = 1, jmax = 0, least_excess = 1e30, mean_excess = 0, mass = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const double j = ps.template column<gimlet::fields::deformation_gradient>()[i].determinant();
        const double m = ps.template column<gimlet::fields::mass>()[i];
        const double x = ps.template column<gimlet::fields::specific_internal_energy>()[i] - hmx.thermal.reference_energy(j);
        jmin = std::min(jmin, j), jmax = std::max(jmax, j);
        least_excess = std::min(least_excess, x);
        mean_excess += m * x, mass += m;
    }
    mean_excess /= mass;
    CHECK(jmax - jmin < 1e-3 * 0.02);       // the pattern's 0.02 gone
    CHECK(std::abs(0.5 * (jmin + jmax) - 0.95) < 1e-6);
    CHECK(std::abs(internal_energy(sol) / e0 - 1) < 1e-9);
    CHECK(least_excess >= excess - 1e-6);   // no particle cooled
    // The pattern's energy (the isentrope is convex: e_s(0.94) + e_s(0.96) > 2 e_s(0.95)) is now heat.
    const double released = 0.5 * (hmx.thermal.reference_energy(0.94) + hmx.thermal.reference_energy(0.96)) -
                            hmx.thermal.reference_energy(0.95);
    CHECK(released > 0);
    CHECK(mean_excess - excess == Approx(released).epsilon(1e-3));
}
