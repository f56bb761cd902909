// SPDX-License-Identifier: MIT
// viscosity::bulk against its formula (docs/equations.md, viscosity::bulk):
// q = rho h (b2^2 h e^2 + b1 c |e|) in compression (e = tr D < 0), nothing in expansion, and the
// signal speed Q + sqrt(Q^2 + c^2), Q = b1 c + b2^2 h |e|, that sets the stable step.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <type_traits>

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

namespace {

// What a policy was given.
struct given {
    double speed = -1;    // the speed, if a number
    bool number = false;  // whether it was a number
};

// A user's viscosity written with a generic wave-speed parameter and no `lazy_sound_speed`: it
// records what the material update gave it.
struct generic_q {
    static constexpr bool enabled = true;
    using required_fields = gimlet::field_list<>;
    given* record = nullptr;
    template <class Real, class C, class P>
    Real pressure(const gimlet::point_step<Real>&, const C& c, const P&) const {
        record->number = std::is_arithmetic_v<C>;
        if constexpr (std::is_arithmetic_v<C>) record->speed = double(c);
        return Real(0);
    }
    template <class Real, class P>
    Real signal_speed(Real c, Real, const P&) const { return c; }
};

// One that declares the flag but takes only a number: refused by the concept (and by
// viscosity::check, with a message).
struct lazy_number_only {
    static constexpr bool enabled = true;
    static constexpr bool lazy_sound_speed = true;
    using required_fields = gimlet::field_list<>;
    template <class Real, class P>
    Real pressure(const gimlet::point_step<Real>&, Real, const P&) const { return Real(0); }
    template <class Real, class P>
    Real signal_speed(Real c, Real, const P&) const { return c; }
};

}  // namespace

static_assert(gimlet::viscosity::lazy_sound_speed<gimlet::viscosity::bulk>);
static_assert(!gimlet::viscosity::lazy_sound_speed<generic_q>);
static_assert(gimlet::viscosity::Viscosity<generic_q>);
static_assert(!gimlet::viscosity::Viscosity<lazy_number_only>);

// Without the flag a policy is given the number, whatever its parameter's type: the wave speed
// of the particle as the update leaves it for the viscosity.
TEST_CASE("viscosity: a policy without lazy_sound_speed is given the wave speed as a number", "[viscosity]") {
    using mat_t = gimlet::material<gimlet::strength::linear_elastic, gimlet::eos::linear, gimlet::thermal::none, generic_q>;
    given record;
    const mat_t mat{1900.0, gimlet::strength::linear_elastic(4.7e9), gimlet::eos::linear(7.9e9), {},
                    generic_q{&record}};
    using store2 = gimlet::particle_store<S, gimlet::field_union_t<gimlet::core_fields<S>, mat_t::required_fields>>;
    store2 store;
    const auto p = store[store.add()];
    p.get<gimlet::fields::volume0>() = 1e-6;
    p.get<gimlet::fields::mass>() = 1900.0 * 1e-6;
    S::matrix L = S::matrix::Zero();
    L(1, 1) = 1e4;  // expanding: bulk would not ask, this policy is given it anyway
    gimlet::update_material_point(mat, p, L, 1e-8, 1e-3, 0, 0.0);
    CHECK(record.number);
    CHECK(record.speed == gimlet::longitudinal_wave_speed(p, mat));
    CHECK(record.speed > 0);
}
