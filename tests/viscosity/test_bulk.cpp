// SPDX-License-Identifier: MIT
// viscosity::bulk against its formula (docs/equations.md, viscosity::bulk):
// q = rho h (b2^2 h e^2 + b1 c |e|) in compression (e = tr D < 0), nothing in expansion, and the
// signal speed Q + sqrt(Q^2 + c^2), Q = b1 c + b2^2 h |e|, that sets the stable step.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cmath>

namespace {

using S = gimlet::space<2>;
using store_t = gimlet::particle_store<S, gimlet::field_union_t<gimlet::core_fields<S>, gimlet::viscosity::bulk::required_fields>>;

gimlet::point_step<double> compressing(double rate) {
    gimlet::point_step<double> st;
    st.density = 1900.0;
    st.length = 1e-3;
    st.D(0, 0) = rate;  // tr D = rate
    return st;
}

}  // namespace

TEST_CASE("bulk viscosity: q and its signal speed are the Abaqus/Explicit form on the cell", "[viscosity][verification]") {
    store_t store;
    const auto p = store[store.add()];
    const gimlet::viscosity::bulk q;  // b2 = 1.2, b1 = 0.06
    const double c = 3000.0, rate = 1e4;
    // 1900 * 1e-3 * (1.44 * 1e-3 * 1e8 + 0.06 * 3000 * 1e4) = 1.9 * 1.944e6 Pa
    CHECK(q.pressure(compressing(-rate), c, p) == Approx(3.6936e6).epsilon(1e-12));
    CHECK(p.get<gimlet::fields::compression_rate>() == rate);
    // Q = 0.06 * 3000 + 1.44 * 1e-3 * 1e4 = 194.4 m/s; the damped oscillator's stable step
    // (2 / omega)(sqrt(1 + xi^2) - xi), xi = Q / c, is that of the speed c / (sqrt(1 + xi^2) - xi).
    const double Q = 194.4, xi = Q / c;
    CHECK(q.signal_speed(c, 1e-3, p) == Approx(Q + std::sqrt(Q * Q + c * c)).epsilon(1e-12));
    CHECK(q.signal_speed(c, 1e-3, p) == Approx(c / (std::sqrt(1 + xi * xi) - xi)).epsilon(1e-12));
    // Twice the cell: the quadratic term scales with h^2, the linear one with h.
    auto st = compressing(-rate);
    st.length = 2e-3;
    CHECK(q.pressure(st, c, p) == Approx(1900.0 * 2e-3 * (1.44 * 2e-3 * 1e8 + 0.06 * 3000 * 1e4)).epsilon(1e-12));
}

TEST_CASE("bulk viscosity: nothing in expansion, and no wider signal speed", "[viscosity][verification]") {
    store_t store;
    const auto p = store[store.add()];
    const gimlet::viscosity::bulk q(2.0, 0.5);
    CHECK(q.pressure(compressing(-1e4), 3000.0, p) > 0);
    CHECK(q.pressure(compressing(+1e4), 3000.0, p) == 0.0);
    CHECK(p.get<gimlet::fields::compression_rate>() == 0.0);  // the expansion cleared it
    CHECK(q.signal_speed(3000.0, 1e-3, p) == 3000.0);
    CHECK(q.pressure(compressing(0.0), 3000.0, p) == 0.0);
}

TEST_CASE("bulk viscosity: coefficients are refused by name when negative or not a number", "[viscosity][errors]") {
    using Catch::Matchers::Contains;
    CHECK_THROWS_WITH(gimlet::viscosity::bulk(-1.0, 0.06), Contains("quadratic coefficient b2"));
    CHECK_THROWS_WITH(gimlet::viscosity::bulk(1.2, -0.06), Contains("linear coefficient b1"));
    CHECK_THROWS_WITH(gimlet::viscosity::bulk(std::nan(""), 0.06), Contains("quadratic coefficient b2"));
    CHECK(!gimlet::viscosity::none::enabled);
    CHECK(gimlet::viscosity::bulk::enabled);
}

// The material update passes the wave speed as a callable (material/update.hpp): bulk asks for
// it only in compression, where q reads it, and gives the q of the number.
TEST_CASE("bulk viscosity: a wave speed given as a callable is asked for only in compression", "[viscosity]") {
    store_t store;
    const auto p = store[store.add()];
    const gimlet::viscosity::bulk q(2.4, 0.12);
    const double c = 3000.0;
    int asked = 0;
    const auto speed = [&] { return ++asked, c; };
    for (const double rate : {-1e4, -1.0, 0.0, 1.0, 1e4}) {
        asked = 0;
        const double lazy = q.pressure(compressing(rate), speed, p);
        const double lazy_rate = p.get<gimlet::fields::compression_rate>();
        CHECK(lazy == q.pressure(compressing(rate), c, p));
        CHECK(lazy_rate == p.get<gimlet::fields::compression_rate>());
        CHECK(asked == (rate < 0 ? 1 : 0));
    }
}
