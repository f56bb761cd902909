// SPDX-License-Identifier: MIT
// Two elastic disks collide and rebound, after Sulsky, Chen & Schreyer (1994), section 5.1.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cstdio>
#include <tuple>
#include <vector>

namespace {

using shapes = std::tuple<gimlet::shape::linear, gimlet::shape::ugimp, gimlet::shape::cpgimp,
                          gimlet::shape::bspline_quadratic, gimlet::shape::bspline_cubic>;

// After Sulsky et al.'s set-up: unit square, disks of radius 0.2 centred at (0.25, 0.25) and
// (0.75, 0.75) (theirs sit at 0.2 and 0.8 and so touch the walls; these clear them),
// E = 1000 Pa, nu = 0.3, rho = 1000 kg/m^3, v = +-(0.1, 0.1) m/s, cell 0.05, 2x2 particles per
// cell. They touch at t ~ 0.77 s and separate by t ~ 2 s; we stop at 2.4 s,
// before either reaches the walls.
template <class Shape>
std::vector<gimlet::diagnostics::conservation_sample<2>> collide(gimlet::update_scheme scheme) {
    using S = gimlet::space<2>;
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Ones();
    gs.cell = 0.05;
    gs.bc = {gimlet::boundary::slip, gimlet::boundary::slip};
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    const auto mat = gimlet::make_elastic_material(1000.0, 1000.0, 0.3);
    sc.add_body(gimlet::scene::ball<S>(S::vector(0.25, 0.25), 0.2), mat, S::vector(0.1, 0.1), 2);
    sc.add_body(gimlet::scene::ball<S>(S::vector(0.75, 0.75), 0.2), mat, S::vector(-0.1, -0.1), 2);
    gimlet::solver_options<S> opt;
    opt.scheme = scheme;
    gimlet::solver<S, Shape, gimlet::elastic_material> sol(sc, opt);
    std::vector<gimlet::diagnostics::conservation_sample<2>> samples;
    gimlet::diagnostics::every_steps obs(1, [&](const auto& s) { samples.push_back(gimlet::diagnostics::sample_conservation(s)); });
    sol.run_until(2.4, obs);
    return samples;
}

}  // namespace

namespace {

struct summary {
    double dm, dp, de, gain, min_kinetic;  // all relative
};

template <class Shape>
summary run_and_summarise(gimlet::update_scheme scheme) {
    const auto samples = collide<Shape>(scheme);
    const auto& first = samples.front();
    const double body_momentum = 0.5 * first.mass * 0.1 * std::sqrt(2.0);  // |m v| of one disk
    summary r{0, 0, 0, 0, 1};
    for (const auto& s : samples) {
        r.dm = std::max(r.dm, std::abs(s.mass - first.mass) / first.mass);
        r.dp = std::max(r.dp, (s.momentum - first.momentum).norm() / body_momentum);
        r.de = std::max(r.de, std::abs(s.total_energy() - first.total_energy()) / first.total_energy());
        r.gain = std::max(r.gain, s.total_energy() / first.total_energy() - 1);
        r.min_kinetic = std::min(r.min_kinetic, s.kinetic / first.kinetic);
    }
    std::printf("two disks, %-30s %s: |dm|/m %.1e  |dp|/|p_body| %.1e  max|dE|/E0 %.3f  max gain %.3f\n",
                Shape::name, scheme == gimlet::update_scheme::musl ? "MUSL" : scheme == gimlet::update_scheme::usl ? "USL " : "USF ",
                r.dm, r.dp, r.de, r.gain);
    // The collision really happened: most kinetic energy became strain energy mid-impact.
    CHECK(r.min_kinetic < 0.2);
    // Mass is carried by particles and never changes; momentum is exchanged only through grid
    // forces that sum to zero (the disks never reach the walls), so both hold to round-off.
    CHECK(r.dm <= 1e-14);
    CHECK(r.dp <= 1e-12);
    return r;
}

}  // namespace

// Energy: explicit MPM loses a little energy through the grid transfers at this coarse
// resolution (Sulsky et al. 1994, fig. 6: a few percent), and shows a small transient excess
// during the compression, where particle kinetic and stress-power energies are measured on
// different discretisations. Bound: within 6 % of the initial energy at all times and never
// more than 2 % above it (a growing excess would mean instability; the same bound as the
// elastic impacts of the sparse-cloud hard case). Measured: linear 1.53 %, uGIMP and cpGIMP
// 1.2 %. (With the end-of-step specific volume in the stress power, linear would read 1.29 %:
// the same motion to the bit, since this EOS does not read e, but an internal energy that
// volume under-counts by a first-order share of each step's strain.)
TEMPLATE_LIST_TEST_CASE("two elastic disks conserve mass and momentum, bound energy (MUSL)",
                        "[core][verification]", shapes) {
    const auto r = run_and_summarise<TestType>(gimlet::update_scheme::musl);
    CHECK(r.de < 0.06);
    CHECK(r.gain < 0.02);
}

// USF and USL: mass and momentum to round-off as above. USF stays within the same 6 % band
// but overshoots further during the impact (about +2.6 % here: its stress is advanced with the
// velocities of the previous configuration); USL dissipates more (Bardenhagen 2002; Buzzi et
// al. 2008) and must never gain more than the transient excess of MUSL (measured 0.5 %).
TEST_CASE("two elastic disks with USL and USF", "[core][verification]") {
    const auto usf = run_and_summarise<gimlet::shape::ugimp>(gimlet::update_scheme::usf);
    CHECK(usf.de < 0.06);
    const auto usl = run_and_summarise<gimlet::shape::ugimp>(gimlet::update_scheme::usl);
    CHECK(usl.gain < 0.02);
}
