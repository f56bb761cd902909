// SPDX-License-Identifier: MIT
// solver::health(): the silent guards on the way to a wave speed are counted and the first
// particle each met is named.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <string>

using Catch::Matchers::Contains;

namespace {

using S = gimlet::space<2>;
using hmx = gimlet::presets::hmx_material<>;

gimlet::solver<S, gimlet::shape::ugimp, hmx> block() {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector(8e-3, 8e-3);
    gs.cell = 1e-3;
    gimlet::scene::scene<S, hmx> sc(gs);
    sc.add_body(gimlet::scene::box<S>(S::vector(2e-3, 2e-3), S::vector(6e-3, 6e-3)), gimlet::presets::make_hmx(),
                S::vector::Zero(), 2, "block");
    gimlet::solver_options<S> opt;
    opt.threads = 1;
    return gimlet::solver<S, gimlet::shape::ugimp, hmx>(sc, opt);
}

}  // namespace

TEST_CASE("health events: a quiet run meets no guard", "[robustness][health]") {
    auto sol = block();
    for (int k = 0; k < 5; ++k) sol.step();
    CHECK(sol.health().total() == 0);
    for (const auto& f : sol.health().first) CHECK(f.empty());
}

TEST_CASE("health events: the EOS modulus cap is counted and names the particle", "[robustness][health]") {
    // Particle 5 compressed past the EOS's singularity margin (eta = 0.5 > 1/s = 0.385) from
    // outside: the time step takes its tangent modulus at the capped compression (counted), then
    // the pressure's own check stops the step with a numerical_error naming it.
    auto sol = block();
    sol.particles()[5].get<gimlet::fields::deformation_gradient>() = S::matrix::Identity() * std::sqrt(0.5);
    std::string message;
    try {
        sol.step();
    } catch (const gimlet::numerical_error& e) {
        message = e.what();
    }
    CHECK_THAT(message, Contains("particle 5") && Contains("Mie-Grueneisen limit"));
    const auto& h = sol.health();
    CHECK(h.count[0] == 1);  // eos_compression_capped, once, for the one step that was taken
    CHECK(h.count[1] == 0);
    CHECK(h.count[2] == 0);
    CHECK_THAT(h.first[0], Contains("particle 5") && Contains("step 0") && Contains("capped compression"));
    CHECK(std::string(gimlet::health_events::names[0]) == "eos_compression_capped");
}

namespace {
// A user EOS whose tangent modulus is negative (a softening law past its peak, say), with no
// shear stiffness beside it: (K + 4G/3)/rho < 0, so no wave speed exists.
struct softening {
    using required_fields = gimlet::field_list<>;
    template <class Real, class P>
    Real pressure(const gimlet::point_step<Real>&, const P&) const { return Real(0); }
    template <class Real, class P>
    Real bulk_modulus(const gimlet::point_state<Real>&, const P&) const { return Real(-1e9); }
};
using soft = gimlet::material<gimlet::strength::none, softening>;
}  // namespace

TEST_CASE("health events: a state with no wave speed is counted on every particle", "[robustness][health]") {
    gimlet::grid_spec<S> gs;
    gs.upper = S::vector(8e-3, 8e-3);
    gs.cell = 1e-3;
    gimlet::scene::scene<S, soft> sc(gs);
    sc.add_body(gimlet::scene::box<S>(S::vector(2e-3, 2e-3), S::vector(6e-3, 6e-3)), soft{1000.0, {}, {}},
                S::vector(1.0, 0.0), 2, "block");
    gimlet::solver_options<S> opt;
    opt.threads = 1;
    gimlet::solver<S, gimlet::shape::ugimp, soft> sol(sc, opt);
    const std::size_t n = sol.particles().size();
    sol.step();  // the time step from |v| alone (1 m/s): the particles do not limit it by a wave
    sol.step();
    const auto& h = sol.health();
    CHECK(h.count[2] == 2 * n);  // no_wave_speed: every particle, both steps
    CHECK(h.count[0] == 0);
    CHECK(h.count[1] == 0);      // the user EOS reports no guard of its own
    CHECK_THAT(h.first[2], Contains("particle 0") && Contains("step 0") && Contains("wave speed was taken as 0"));
}
