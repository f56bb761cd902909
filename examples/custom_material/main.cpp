// SPDX-License-Identifier: MIT
// Tutorial: write your own material policy in your own code and plug it into gimlet.
//
// We define a Maxwell viscoelastic deviatoric law, with its own per-particle field that records
// the energy it dissipates, combine it with gimlet's linear EOS, and run the two-disk collision
// of the flagship example with it and with gimlet's elastic law side by side. Nothing is
// registered anywhere: the solver is specialised for our type at compile time.
//
//   custom_material [--relaxation-time 0.5] [--output results/custom_material]
//
// It needs gimlet and nothing else: copy this folder anywhere, then
//   cmake -S . -B build -DCMAKE_PREFIX_PATH=<gimlet's install prefix> && cmake --build build
#include <gimlet/gimlet.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>

namespace my {

// 1. A field of our own: a tag type naming its value type per space, and a name for output.
struct dissipated_energy {
    template <class S> using type = typename S::real;  // J/kg
    static constexpr const char* name = "dissipated_energy";
};

// 2. The strength policy. The gimlet::strength::Strength concept asks for:
//    - required_fields: the per-particle fields it needs (the solver stores exactly these plus
//      the core fields and those of the other policies);
//    - update(step, s, p): advance the 3x3 deviatoric stress s over step.dt, return the energy
//      dissipated per unit mass;
//    - shear_modulus(state, p): for the time step's wave speed.
// Maxwell model: ds/dt = 2 G D' - s / tau (+ Jaumann rotation), dissipating s:s/(2 G tau) per
// unit volume and time (e.g. Christensen, Theory of Viscoelasticity, 1982, ch. 1).
class maxwell {
public:
    using required_fields = gimlet::field_list<dissipated_energy>;

    maxwell(double shear_modulus, double relaxation_time) : g_(shear_modulus), tau_(relaxation_time) {
        gimlet::require_positive("Maxwell shear modulus G (Pa)", shear_modulus);
        gimlet::require_positive("Maxwell relaxation time tau (s)", relaxation_time);
    }

    template <class Real, class P>
    Real update(const gimlet::point_step<Real>& st, Eigen::Matrix<Real, 3, 3>& s, const P& p) const {
        s = gimlet::strength::jaumann_rotate(st, s);
        s += st.dt * Real(2 * g_) * gimlet::strength::deviator(st.D);
        // Exact relaxation over the step, so any dt is stable.
        const Real keep = std::exp(-st.dt / Real(tau_));
        // Energy released by the relaxation: the elastic energy s:s/(4 G) per unit volume lost.
        const Real w = (Real(1) - keep * keep) * s.cwiseProduct(s).sum() / (Real(4 * g_) * st.density);
        s *= keep;
        p.template get<dissipated_energy>() += w;
        return w;
    }

    template <class Real, class P>
    Real shear_modulus(const gimlet::point_state<Real>&, const P&) const { return Real(g_); }

private:
    double g_, tau_;
};

static_assert(gimlet::strength::Strength<maxwell>, "maxwell must model the Strength concept");

}  // namespace my

// 3. A material that uses it: our strength, gimlet's EOS, no thermal model, no viscosity.
using maxwell_material = gimlet::material<my::maxwell, gimlet::eos::linear>;
using S = gimlet::space<2>;

template <class Material>
auto disks(const Material& mat) {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Ones();
    gs.cell = 0.05;
    gs.bc = {gimlet::boundary::slip, gimlet::boundary::slip};
    gimlet::scene::scene<S, Material> scene(gs);
    scene.add_body(gimlet::scene::ball<S>(S::vector(0.25, 0.25), 0.2), mat, S::vector(0.1, 0.1));
    scene.add_body(gimlet::scene::ball<S>(S::vector(0.75, 0.75), 0.2), mat, S::vector(-0.1, -0.1));
    return scene;
}

int main(int argc, char** argv) try {
    // The two flags, read by hand so that the tutorial stands alone.
    double tau = 0.5;
    std::filesystem::path out = "results/custom_material";
    for (int i = 1; i < argc; i += 2) {
        const std::string flag = argv[i];
        if (flag != "--relaxation-time" && flag != "--output") throw std::invalid_argument("unknown flag " + flag);
        if (i + 1 >= argc) throw std::invalid_argument("flag " + flag + " needs a value");
        const std::string value = argv[i + 1];
        if (flag == "--output") {
            out = value;
            continue;
        }
        char* end = nullptr;
        tau = std::strtod(value.c_str(), &end);
        if (value.empty() || *end != '\0') tau = NAN;  // not a number: refused below
        gimlet::require(std::isfinite(tau) && tau > 0 && tau <= 1e6, "--relaxation-time (s)", tau, "(0, 1e6]");
    }
    std::filesystem::create_directories(out);

    const auto k = gimlet::elastic_moduli::from_young_poisson(1000.0, 0.3);
    // 4. The solver, specialised for our material; it stores our field because we asked for it.
    gimlet::solver<S, gimlet::shape::ugimp, maxwell_material> visco(
        disks(maxwell_material{1000.0, my::maxwell{k.shear, tau}, gimlet::eos::linear{k.bulk}}));
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material> elastic(
        disks(gimlet::make_elastic_material(1000.0, 1000.0, 0.3)));
    static_assert(decltype(visco)::store_type::has<my::dissipated_energy>);
    static_assert(!decltype(elastic)::store_type::has<my::dissipated_energy>);

    std::ofstream csv(out / "energy.csv");
    gimlet::io::exact_numbers(csv);  // every number reads back exactly
    csv << "time_s,kinetic_elastic_J,kinetic_maxwell_J,dissipated_maxwell_J\n";
    auto dissipated = [](const auto& s) {
        double w = 0;
        const auto& m = s.particles().template column<gimlet::fields::mass>();
        const auto& d = s.particles().template column<my::dissipated_energy>();
        for (std::size_t i = 0; i < m.size(); ++i) w += m[i] * d[i];
        return w;
    };
    const double end = 2.4, every = 0.05;
    for (double t = every; t <= end + 1e-9; t += every) {
        visco.run_until(t);
        elastic.run_until(t);
        csv << t << ',' << gimlet::diagnostics::kinetic_energy(elastic) << ','
            << gimlet::diagnostics::kinetic_energy(visco) << ',' << dissipated(visco) << '\n';
    }
    const double k_el = gimlet::diagnostics::kinetic_energy(elastic), k_mx = gimlet::diagnostics::kinetic_energy(visco);
    std::printf("after the collision (t = %.1f s), of the initial 2.6 J of kinetic energy:\n", end);
    std::printf("  elastic disks keep   %.3f J\n", k_el);
    std::printf("  Maxwell disks keep   %.3f J and dissipated %.3f J (tau = %g s)\n", k_mx, dissipated(visco), tau);
    std::printf("  time series: %s\n", (out / "energy.csv").string().c_str());
    return 0;
} catch (const std::exception& e) {
    std::cerr << "custom_material: " << e.what() << '\n';
    return 1;
}
