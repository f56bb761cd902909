// SPDX-License-Identifier: MIT
// diagnostics/schedule.hpp: a writable hook between steps (between_steps) updates a user field
// and changes particles; what it writes is checked before the next step uses it.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

using Catch::Matchers::Contains;

namespace {

using S = gimlet::space<2>;

// A user field the hook keeps: how many hook calls the particle has seen.
struct visits {
    template <class> using type = double;
    static constexpr const char* name = "visits";
};

using solver_t = gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, gimlet::contact::single_field,
                                gimlet::field_list<visits>>;

solver_t moving_block() {
    gimlet::grid_spec<S> gs;
    gs.upper = S::vector(10e-3, 10e-3);
    gs.cell = 1e-3;
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    sc.add_body(gimlet::scene::box<S>(S::vector(3e-3, 3e-3), S::vector(7e-3, 7e-3)),
                gimlet::make_elastic_material(1000.0, 1e9, 0.3), S::vector(10.0, 0.0), 2, "block");
    gimlet::solver_options<S> opt;
    opt.threads = 1;
    return solver_t(sc, opt);
}

}  // namespace

TEST_CASE("between_steps: a hook updates a user field and damps the motion", "[diagnostics]") {
    auto sol = moving_block();
    // Every 2 steps: count the visit in the user field and halve every velocity.
    gimlet::diagnostics::between_steps hook(2, [](auto& s) {
        auto& ps = s.particles();
        for (std::size_t i = 0; i < ps.size(); ++i) {
            ps[i].template get<visits>() += 1.0;
            ps[i].template get<gimlet::fields::velocity>() *= 0.5;
        }
    });
    std::uint64_t calls = 0;
    gimlet::diagnostics::every_steps count(1, [&](const auto& s) { calls = s.steps(); });
    sol.run_until(2e-6, hook, count);
    const auto steps = sol.steps();
    REQUIRE(steps >= 4);
    const double expected = double(steps / 2 + 1);  // at step 0 and every 2 steps after
    for (double v : sol.particles().column<visits>()) CHECK(v == expected);
    // The block moves rigidly: its velocity was halved at each call, and nothing else acts.
    const double vx = sol.particles().column<gimlet::fields::velocity>()[0][0];
    CHECK(vx == Approx(10.0 * std::pow(0.5, expected)).epsilon(1e-9));
    CHECK(calls == steps);
}

TEST_CASE("between_steps: a bad value a hook writes is blamed on its particle", "[diagnostics][robustness]") {
    auto sol = moving_block();
    gimlet::diagnostics::between_steps hook(3, [](auto& s) {
        if (s.steps() == 3)
            s.particles()[7].template get<gimlet::fields::velocity>()[1] = std::numeric_limits<double>::infinity();
    });
    std::string message;
    try {
        sol.run_until(2e-6, hook);
    } catch (const gimlet::numerical_error& e) {
        message = e.what();
    }
    CHECK_THAT(message, Contains("particle 7") && Contains("velocity is not finite"));
}
