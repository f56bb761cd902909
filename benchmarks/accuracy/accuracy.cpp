// SPDX-License-Identifier: MIT
// Accuracy against wall time, one thread, for each shape function, update scheme, precision,
// resolution and particles per cell:
//   mms        the manufactured solution of tests/solver/test_convergence.cpp (Wallstedt &
//              Guilkey 2008), a sine displacement of amplitude A = 0.01 L in a periodic strip,
//              at a Courant number of 0.2; error = max_p |x_p - x_exact| / A at the peak.
//   impact_1d  examples/impact_1d (HMX slabs at +-300 m/s, uGIMP, double): relative error of
//              the plateau stress sigma_yy and of the shock speed against Rankine-Hugoniot, with
//              the library's defaults ("ugimp") and the HMX examples' ("ugimp-k4").
// Prints CSV rows: case, shape, scheme, precision, resolution, ppc, particles, steps, error,
// error2 (impact_1d: shock-speed error), seconds.
// Flags: --case mms|impact|all (all), --quick 1 (fewer resolutions, for the smoke test).
#include "common/bench.hpp"
#include "common/hmx_defaults.hpp"
#include "impact_1d/impact_1d.hpp"

#include <cstdio>
#include <exception>
#include <numbers>

namespace {

constexpr double pi = std::numbers::pi;

/// Each particle's reference position X_p (the manufactured solution is Lagrangian).
struct reference_position {
    template <class Sp> using type = typename Sp::vector;
    static constexpr const char* name = "reference_position";
};

const char* scheme_name(gimlet::update_scheme s) {
    return s == gimlet::update_scheme::musl ? "musl" : s == gimlet::update_scheme::usl ? "usl" : "usf";
}

/// u_x = A sin(kX) sin(wt), w = c k / 2, with the body force that makes it exact for gimlet's
/// elastic material (the derivation is in tests/solver/test_convergence.cpp).
template <class Shape, class Real>
void mms(gimlet::update_scheme scheme, int cells, int ppc, double amplitude_fraction, double courant) {
    using S = gimlet::space<2, Real>;
    using fields = gimlet::field_list<gimlet::fields::external_acceleration, reference_position>;
    using solver = gimlet::solver<S, Shape, gimlet::elastic_material, gimlet::contact::single_field, fields>;
    const double length = 1.0, amplitude = amplitude_fraction * length, rho0 = 1.0, h = length / cells;
    gimlet::grid_spec<S> gs;
    gs.upper = typename S::vector(Real(length), Real(Shape::stencil * h));
    gs.cell = Real(h);
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::periodic};
    const auto mat = gimlet::make_elastic_material(rho0, 1.0, 0.3);
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    sc.add_body(gimlet::scene::box<S>(gs.lower, gs.upper), mat, S::vector::Zero(), ppc, "strip");
    gimlet::solver_options<S> opt;
    opt.threads = 1;
    opt.scheme = scheme;
    const auto t0 = std::chrono::steady_clock::now();
    solver sol(sc, opt);
    const double bulk = mat.eos.bulk_modulus(), shear = mat.strength.shear_modulus();
    const double c = std::sqrt((bulk + 4 * shear / 3) / rho0), k = 2 * pi / length, omega = c * k / 2;
    auto& parts = sol.particles();
    auto& ref = parts.template column<reference_position>();
    auto& x = parts.template column<gimlet::fields::position>();
    auto& b = parts.template column<gimlet::fields::external_acceleration>();
    for (std::size_t p = 0; p < parts.size(); ++p) {
        ref[p] = x[p];
        parts.template column<gimlet::fields::velocity>()[p] =
            typename S::vector(Real(amplitude * omega * std::sin(k * double(ref[p][0]))), Real(0));
    }
    const double end = pi / (2 * omega);
    const int steps = static_cast<int>(std::ceil(end / (courant * h / c)));
    const double dt = end / steps;
    for (int n = 0; n < steps; ++n) {
        const double st = std::sin(omega * n * dt);
        for (std::size_t p = 0; p < parts.size(); ++p) {
            const double kx = k * double(ref[p][0]);
            const double jac = 1 + amplitude * k * std::cos(kx) * st;
            const double djac = -amplitude * k * k * std::sin(kx) * st;
            const double accel = -amplitude * omega * omega * std::sin(kx) * st;
            b[p] = typename S::vector(Real(accel - (bulk + 4 * shear / (3 * jac)) * djac / rho0), Real(0));
        }
        sol.step(Real(dt));
    }
    const double seconds = bench::seconds_since(t0);
    double worst = 0;
    for (std::size_t p = 0; p < parts.size(); ++p) {
        double d = double(x[p][0]) - (double(ref[p][0]) + amplitude * std::sin(k * double(ref[p][0])));
        d -= length * std::round(d / length);  // periodic images
        worst = std::max(worst, std::abs(d));
    }
    std::printf("mms,%s,%s,%s,%d,%d,%zu,%d,%.4e,,%.4f\n", Shape::name, scheme_name(scheme),
                sizeof(Real) == 4 ? "float" : "double", cells, ppc, parts.size(), steps, worst / amplitude, seconds);
    std::fflush(stdout);
}

template <class Real>
void mms_all(const std::vector<int>& resolutions, const std::vector<int>& ppcs, double a, double cfl) {
    using enum gimlet::update_scheme;
    for (const auto scheme : {musl, usl, usf})
        for (const int cells : resolutions)
            for (const int ppc : ppcs) {
                mms<gimlet::shape::linear, Real>(scheme, cells, ppc, a, cfl);
                mms<gimlet::shape::ugimp, Real>(scheme, cells, ppc, a, cfl);
                mms<gimlet::shape::cpgimp, Real>(scheme, cells, ppc, a, cfl);
                mms<gimlet::shape::bspline_quadratic, Real>(scheme, cells, ppc, a, cfl);
                mms<gimlet::shape::bspline_cubic, Real>(scheme, cells, ppc, a, cfl);
            }
}

// `config` names the mass matrix and the viscosity in the shape column: "ugimp" is the library's
// defaults (the lumped mass, Abaqus's (0.06, 1.2)); "ugimp-k4" the HMX examples' (four
// consistent-mass iterations, (0.12, 2.4); not with USL, which refuses the consistent mass).
void impact(const std::vector<double>& cells_mm, const char* config, int consistent_mass, double b1, double b2) {
    using enum gimlet::update_scheme;
    const auto mat = gimlet::presets::make_hmx({}, gimlet::viscosity::bulk(b2, b1));
    for (const auto scheme : {musl, usl, usf}) {
        if (consistent_mass > 0 && scheme == usl) continue;
        for (const double cell : cells_mm) {
            impact_1d::settings s;
            s.cell = cell * 1e-3;
            s.scheme = scheme;
            s.consistent_mass = consistent_mass;
            s.threads = 1;
            const auto t0 = std::chrono::steady_clock::now();
            double err = NAN, err2 = NAN;
            std::size_t particles = 0;
            try {
                const auto r = impact_1d::run(s, mat);
                err = std::abs(r.plateau_sigma_yy / r.rh.sigma_yy - 1);
                err2 = std::abs(r.shock_speed / r.rh.shock_speed - 1);
                particles = std::size_t(2 * 4 * 2 * (s.length / s.cell) * 2);  // 2 slabs, 4 cells wide, 2x2 per cell
            } catch (const std::exception& e) {
                std::fprintf(stderr, "impact_1d %s %s at %g mm failed: %s\n", config, scheme_name(scheme), cell, e.what());
            }
            std::printf("impact_1d,%s,%s,double,%g,2,%zu,,%.4e,%.4e,%.4f\n", config, scheme_name(scheme), cell, particles,
                        err, err2, bench::seconds_since(t0));
            std::fflush(stdout);
        }
    }
}

}  // namespace

int main(int argc, char** argv) try {
    bench::flags f(argc, argv);
    const std::string which = f.text("case", "all");
    const bool quick = f.number("quick", 0) != 0;
    const double amplitude = f.number("amplitude", 0.01);
    const double cfl = f.number("courant", 0.2);
    f.finish();
    std::printf("case,shape,scheme,precision,resolution,ppc,particles,steps,error,error2,seconds\n");
    if (which == "mms" || which == "all") {
        const std::vector<int> res = quick ? std::vector<int>{16} : std::vector<int>{16, 32, 64, 128};
        const std::vector<int> ppc = quick ? std::vector<int>{2} : std::vector<int>{1, 2, 3};
        mms_all<double>(res, ppc, amplitude, cfl);
        mms_all<float>(res, ppc, amplitude, cfl);
    }
    if (which == "impact" || which == "all") {
        const std::vector<double> cells = quick ? std::vector<double>{0.4} : std::vector<double>{0.4, 0.2, 0.1, 0.05};
        impact(cells, "ugimp", 0, 0.06, 1.2);
        impact(cells, "ugimp-k4", example::hmx_defaults::consistent_mass, example::hmx_defaults::viscosity_linear,
               example::hmx_defaults::viscosity_quadratic);
    }
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "bench_accuracy: %s\n", e.what());
    return 1;
}
