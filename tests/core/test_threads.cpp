// SPDX-License-Identifier: MIT
// Results must not depend on the number of threads: every scatter and reduction runs in a
// fixed order, so 1 and 2 threads give bitwise identical particle states.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cstring>

namespace {

using S = gimlet::space<2>;

auto run(int threads) {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Ones();
    gs.cell = 0.0125;  // 6656 particles: above the size at which loops go parallel
    gs.bc = {gimlet::boundary::slip, gimlet::boundary::slip};
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    const auto mat = gimlet::make_elastic_material(1000.0, 1000.0, 0.3);
    sc.add_body(gimlet::scene::ball<S>(S::vector(0.3, 0.3), 0.2), mat, S::vector(0.5, 0.5));
    sc.add_body(gimlet::scene::ball<S>(S::vector(0.7, 0.7), 0.2), mat, S::vector(-0.5, -0.5));
    gimlet::solver_options<S> opt;
    opt.threads = threads;
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material> sol(sc, opt);
    sol.run_until(0.2);  // well into the impact
    return sol;
}

template <class Column>
bool bitwise_equal(const Column& a, const Column& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

}  // namespace

TEST_CASE("results do not depend on the thread count", "[core][threads]") {
    const auto one = run(1);
    const auto two = run(2);
    REQUIRE(one.steps() == two.steps());
    REQUIRE(one.particles().size() > 4096);
    CHECK(bitwise_equal(one.particles().column<gimlet::fields::position>(), two.particles().column<gimlet::fields::position>()));
    CHECK(bitwise_equal(one.particles().column<gimlet::fields::velocity>(), two.particles().column<gimlet::fields::velocity>()));
    CHECK(bitwise_equal(one.particles().column<gimlet::fields::stress>(), two.particles().column<gimlet::fields::stress>()));
    CHECK(bitwise_equal(one.particles().column<gimlet::fields::deformation_gradient>(),
                        two.particles().column<gimlet::fields::deformation_gradient>()));
    CHECK(bitwise_equal(one.particles().column<gimlet::fields::specific_internal_energy>(),
                        two.particles().column<gimlet::fields::specific_internal_energy>()));
    // The run did something: the disks are in contact and stressed.
    double max_stress = 0;
    for (const auto& s : one.particles().column<gimlet::fields::stress>()) max_stress = std::max(max_stress, s.norm());
    CHECK(max_stress > 10.0);
}
