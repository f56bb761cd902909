// SPDX-License-Identifier: MIT
// Two particles in the lanes of one vector (gimlet/core/lanes.hpp): the material update of a
// pair gives each particle's own update bit for bit; a pair that would stop the run writes
// nothing and leaves the message to the one-at-a-time update; and a solver that pairs its
// particles runs to the same bits as one that does not, whatever the scheme and thread count.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#if GIMLET_HAS_LANES

namespace {

using S = gimlet::space<2>;
using elastic_fields = gimlet::field_union_t<gimlet::core_fields<S>, gimlet::elastic_material::required_fields>;
using store_type = gimlet::particle_store<S, elastic_fields>;

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }
bool same_bits(const S::matrix& a, const S::matrix& b) {
    for (int k = 0; k < 4; ++k)
        if (!same_bits(a(k), b(k))) return false;
    return true;
}

// Whether particle i of stores a and b holds the same bits in every field the update writes.
bool same_state(const store_type& a, const store_type& b, std::size_t i) {
    using namespace gimlet::fields;
    return same_bits(a.column<deformation_gradient>()[i], b.column<deformation_gradient>()[i]) &&
           same_bits(a.column<stress>()[i], b.column<stress>()[i]) && same_bits(a.column<stress_zz>()[i], b.column<stress_zz>()[i]) &&
           same_bits(a.column<specific_internal_energy>()[i], b.column<specific_internal_energy>()[i]);
}

// A strength law a user might write from docs/concepts.md ("Two particles at once"): the
// deviator advanced by 2 G dt dev(D) with the Jaumann rotation, and a stiffening with the
// compression (G J^-1, written without a branch or a library call, as lane_safe asks).
struct stiffening_elastic {
    using required_fields = gimlet::field_list<>;
    static constexpr bool lane_safe = true;
    double g;
    template <class Real, class P>
    Real update(const gimlet::point_step<Real>& st, Eigen::Matrix<Real, 3, 3>& s, const P& /*p*/) const {
        s = gimlet::strength::jaumann_rotate(st, s);
        s += st.dt * (Real(2 * g) / st.J) * gimlet::strength::deviator(st.D);
        return Real(0);
    }
    template <class Real, class P>
    Real shear_modulus(const gimlet::point_state<Real>& state, const P& /*p*/) const {
        return Real(g) / state.J;
    }
};
static_assert(gimlet::strength::Strength<stiffening_elastic>);
// The same law without the declaration: the solver updates its particles one at a time.
struct stiffening_elastic_alone : stiffening_elastic {
    static constexpr bool lane_safe = false;
};
// linear_elastic without the declaration.
struct linear_elastic_alone : gimlet::strength::linear_elastic {
    using linear_elastic::linear_elastic;
    static constexpr bool lane_safe = false;
};

using user_material = gimlet::material<stiffening_elastic, gimlet::eos::linear>;
using user_material_alone = gimlet::material<stiffening_elastic_alone, gimlet::eos::linear>;  // a type, not a solver
using elastic_alone = gimlet::material<linear_elastic_alone, gimlet::eos::linear>;
// The same elastic material without the declaration.
elastic_alone alone_of(const gimlet::elastic_material& m) {
    return {m.density, linear_elastic_alone{m.strength.shear_modulus()}, m.eos};
}

static_assert(gimlet::lanes_capable<gimlet::elastic_material, S>);
static_assert(gimlet::lanes_capable<user_material, S>);
static_assert(!gimlet::lanes_capable<user_material_alone, S>);
static_assert(!gimlet::lanes_capable<elastic_alone, S>);
static_assert(!gimlet::lanes_capable<gimlet::elastic_material, gimlet::space<3>>);
static_assert(!gimlet::lanes_capable<gimlet::elastic_material, gimlet::space<2, float>>);
// von Mises branches on the yield test (written for lanes, it gains nothing: docs/performance.md)
static_assert(!gimlet::lanes_capable<gimlet::presets::hmx_material<>, S>);

// n particles in random states: stretched, sheared and rotated F (det F from 0.5 to 1.5),
// stresses of either sign up to 1 GPa, energies, masses and volumes.
store_type random_particles(std::size_t n, std::mt19937_64& rng) {
    store_type st;
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (std::size_t k = 0; k < n; ++k) {
        auto p = st[st.add()];
        const double angle = 3.0 * u(rng), stretch = 1.0 + 0.5 * u(rng), shear = 0.3 * u(rng);
        S::matrix R;
        R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
        S::matrix U;
        U << stretch, shear, 0.0, 1.0 + 0.2 * u(rng);
        p.get<gimlet::fields::deformation_gradient>() = R * U;
        S::matrix sig;
        sig << 1e9 * u(rng), 3e8 * u(rng), 0.0, 1e9 * u(rng);
        sig(1, 0) = sig(0, 1);
        p.get<gimlet::fields::stress>() = sig;
        p.get<gimlet::fields::stress_zz>() = 1e9 * u(rng);
        p.get<gimlet::fields::specific_internal_energy>() = 1e5 * (1.0 + u(rng));
        p.get<gimlet::fields::volume0>() = 1e-8 * (1.5 + u(rng));
        p.get<gimlet::fields::mass>() = 1800.0 * p.get<gimlet::fields::volume0>() * (1.0 + 0.1 * u(rng));
    }
    return st;
}

// Velocity gradients of every kind: zero, a pure spin, a stretch, and random ones of rates from
// 1e2 to 1e7 per second (dt L up to 0.1), some entries -0.
S::matrix random_gradient(std::size_t k, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    S::matrix L = S::matrix::Zero();
    switch (k % 5) {
        case 0: L(1, 0) = -0.0; break;
        case 1: L(0, 1) = 1e6 * u(rng), L(1, 0) = -L(0, 1); break;
        case 2: L(0, 0) = 1e6 * u(rng), L(1, 1) = -0.0; break;
        default: {
            const double rate = std::pow(10.0, 2.0 + 5.0 * (0.5 + 0.5 * u(rng)));
            for (int e = 0; e < 4; ++e) L(e) = rate * u(rng);
        }
    }
    return L;
}

template <class M>
void check_pairs_against_singles(const M& mat) {
    std::mt19937_64 rng(20261127);
    const std::size_t n = 4000;
    const store_type start = random_particles(n, rng);
    std::vector<S::matrix> L(n);
    for (std::size_t k = 0; k < n; ++k) L[k] = random_gradient(k, rng);
    const double dt = 1e-8, cell = 5e-4;
    store_type pairs = start, singles = start;
    std::size_t differing = 0, rejected = 0;
    for (std::size_t i = 0; i + 1 < n; i += 2) {
        if (!gimlet::update_material_points_2(mat, pairs[i], pairs[i + 1], L[i], L[i + 1], dt, cell, 7, 1e-6)) ++rejected;
        gimlet::update_material_point(mat, singles[i], L[i], dt, cell, 7, 1e-6);
        gimlet::update_material_point(mat, singles[i + 1], L[i + 1], dt, cell, 7, 1e-6);
        differing += !same_state(pairs, singles, i) + !same_state(pairs, singles, i + 1);
    }
    CHECK(rejected == 0);
    CHECK(differing == 0);
    // The updates changed every particle's state (a test that compared unchanged states would
    // pass whatever the pair did).
    std::size_t moved = 0;
    for (std::size_t i = 0; i < n; ++i) moved += !same_state(singles, start, i);
    CHECK(moved == n);
}

}  // namespace

TEST_CASE("two particles at once: each particle's own material update, bit for bit", "[core][lanes]") {
    SECTION("linear_elastic with eos::linear") {
        check_pairs_against_singles(gimlet::make_elastic_material(1800.0, 20e9, 0.3));
    }
    SECTION("a user's lane_safe strength law") {
        check_pairs_against_singles(user_material{1800.0, stiffening_elastic{7e9}, gimlet::eos::linear{12e9}});
    }
    SECTION("lane arithmetic: each operation is the scalar one, signed zeros and NaN included") {
        const double q = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
        const double xs[] = {0.0, -0.0, 1.0, -3.5, 1e-310, 7e300, inf, -inf, q};
        for (double a : xs)
            for (double b : xs) {
                const gimlet::lanes2 x(a, b), y(b, a);
                const gimlet::lanes2 r[] = {x + y, x - y, x * y, x / y, -x};
                const double s0[] = {a + b, a - b, a * b, a / b, -a}, s1[] = {b + a, b - a, b * a, b / a, -b};
                for (int k = 0; k < 5; ++k) {
                    CHECK(same_bits(r[k][0], s0[k]));
                    CHECK(same_bits(r[k][1], s1[k]));
                }
                CHECK(gimlet::finite_lanes(x).all() == (std::isfinite(a) && std::isfinite(b)));
                CHECK((x > y).any() == (a > b || b > a));
            }
    }
}

// An EOS whose pressure is infinite at J = 1 exactly (lane_safe: no branch), to reach the
// update's check of a non-finite pressure.
struct singular_at_rest {
    using required_fields = gimlet::field_list<>;
    static constexpr bool lane_safe = true;
    template <class Real, class P>
    Real pressure(const gimlet::point_step<Real>& st, const P& /*p*/) const {
        return Real(1e9) / (st.J - Real(1));
    }
    template <class Real, class P>
    Real bulk_modulus(const gimlet::point_state<Real>& st, const P& /*p*/) const {
        return Real(1e9) * st.J;
    }
};
static_assert(gimlet::eos::Eos<singular_at_rest>);

TEST_CASE("two particles at once: a pair that would stop the run writes nothing", "[core][lanes]") {
    const auto mat = gimlet::make_elastic_material(1800.0, 20e9, 0.3);
    std::mt19937_64 rng(7);
    const store_type start = random_particles(2, rng);
    S::matrix calm = S::matrix::Zero(), inverting = S::matrix::Zero(), broken = S::matrix::Zero();
    calm(0, 1) = 1e3;
    inverting(0, 0) = -4e8;  // dt L_xx = -4: F_xx changes sign
    broken(1, 1) = std::numeric_limits<double>::quiet_NaN();
    const double dt = 1e-8;
    for (const auto& [bad, message] : {std::pair{inverting, std::string("inverted particle")},
                                       std::pair{broken, std::string("velocity gradient is not finite")}}) {
        for (const bool second : {false, true}) {
            store_type st = start;
            const S::matrix& La = second ? calm : bad;
            const S::matrix& Lb = second ? bad : calm;
            CHECK_FALSE(gimlet::update_material_points_2(mat, st[0], st[1], La, Lb, dt, 5e-4, 3, 0.0));
            CHECK(same_state(st, start, 0));
            CHECK(same_state(st, start, 1));
            // One at a time, the bad particle stops with its own message.
            const std::size_t b = second ? 1 : 0;
            CHECK_THROWS_WITH(gimlet::update_material_point(mat, st[b], bad, dt, 5e-4, 3, 0.0),
                              Catch::Contains("particle " + std::to_string(b) + " ") && Catch::Contains(message));
        }
    }
    SECTION("a non-finite pressure in either lane") {
        const gimlet::material<gimlet::strength::linear_elastic, singular_at_rest> singular{
            1800.0, gimlet::strength::linear_elastic{7e9}, singular_at_rest{}};
        for (const bool second : {false, true}) {
            store_type st = start;
            const std::size_t b = second ? 1 : 0;
            st.column<gimlet::fields::deformation_gradient>()[b] = S::matrix::Identity();  // J = 1 after a step at rest
            const store_type before = st;
            const S::matrix at_rest = S::matrix::Zero();
            const S::matrix& La = second ? calm : at_rest;
            const S::matrix& Lb = second ? at_rest : calm;
            CHECK_FALSE(gimlet::update_material_points_2(singular, st[0], st[1], La, Lb, dt, 5e-4, 3, 0.0));
            CHECK(same_state(st, before, 0));
            CHECK(same_state(st, before, 1));
            CHECK_THROWS_WITH(gimlet::update_material_point(singular, st[b], at_rest, dt, 5e-4, 3, 0.0),
                              Catch::Contains("particle " + std::to_string(b) + " ") && Catch::Contains("non-finite pressure"));
        }
    }
}

namespace {

// Two blocks of different materials colliding (an odd number of particles, so that a pair
// straddles the bodies: it has to take each particle's own material).
// large: 7,267 particles (3,363 and 3,904), above the solver's threshold for running its particle
// loops on the threads (4096); otherwise 465 (225 and 240), below it.
template <class M>
gimlet::scene::scene<S, M> colliding_blocks(const M& mat, const M& softer, bool large = false) {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector(0.0, 0.0);
    gs.upper = S::vector(1.0, 0.6);
    gs.cell = large ? 0.0125 : 0.05;
    gs.bc = {gimlet::boundary::slip, gimlet::boundary::periodic};
    gimlet::scene::scene<S, M> sc(gs);
    const S::vector left_upper = large ? S::vector(0.49, 0.47) : S::vector(0.495, 0.475);
    sc.add_body(gimlet::scene::box<S>(S::vector(0.13, 0.1), left_upper), mat, S::vector(60.0, 5.0), 2, "left");
    sc.add_body(gimlet::scene::box<S>(S::vector(0.5, 0.12), S::vector(0.9, 0.5)), softer, S::vector(-40.0, 0.0), 2, "right");
    return sc;
}

template <class Paired, class Alone>
void check_solver_pairs(const Paired& m_paired, const Paired& soft_paired, const Alone& m_alone, const Alone& soft_alone) {
    using solver_paired = gimlet::solver<S, gimlet::shape::ugimp, Paired>;
    using solver_alone = gimlet::solver<S, gimlet::shape::ugimp, Alone>;
    static_assert(gimlet::lanes_capable<Paired, S> && !gimlet::lanes_capable<Alone, S>);
    // Every scheme, with and without volumetric averaging, on one thread; then the large scene
    // on 2 and 3 threads, where the material passes hand out their groups on the threads.
    struct run_case {
        gimlet::update_scheme scheme;
        bool averaged, large;
        int threads;
    };
    std::vector<run_case> cases;
    for (const auto scheme : {gimlet::update_scheme::musl, gimlet::update_scheme::usf, gimlet::update_scheme::usl})
        for (const bool averaged : {false, true}) cases.push_back({scheme, averaged, false, 1});
    for (const auto scheme : {gimlet::update_scheme::musl, gimlet::update_scheme::usf})
        for (const int threads : {2, 3}) cases.push_back({scheme, true, true, threads});
    for (const auto& [scheme, averaged, large, threads] : cases) {
        gimlet::solver_options<S> o;
        o.scheme = scheme;
        o.volumetric_average = averaged;
        o.threads = threads;
        o.cfl = 0.4;
        solver_paired a(colliding_blocks(m_paired, soft_paired, large), o);
        solver_alone b(colliding_blocks(m_alone, soft_alone, large), o);
        // An odd first body, so that a pair straddles the bodies, and an odd last particle.
        const auto& body = a.particles().template column<gimlet::fields::body>();
        const auto first_body = std::size_t(std::count(body.begin(), body.end(), 0));
        REQUIRE(body.size() == (large ? 7267u : 465u));
        REQUIRE(first_body % 2 == 1);
        for (int k = 0; k < (large ? 20 : 40); ++k) b.step(a.step());
        using namespace gimlet::fields;
        const auto& pa = a.particles();
        const auto& pb = b.particles();
        std::size_t differing = 0;
        for (std::size_t i = 0; i < pa.size(); ++i) {
            differing += !same_bits(pa.template column<deformation_gradient>()[i], pb.template column<deformation_gradient>()[i]) ||
                         !same_bits(pa.template column<stress>()[i], pb.template column<stress>()[i]) ||
                         !same_bits(pa.template column<stress_zz>()[i], pb.template column<stress_zz>()[i]) ||
                         !same_bits(pa.template column<specific_internal_energy>()[i], pb.template column<specific_internal_energy>()[i]) ||
                         !same_bits(pa.template column<position>()[i](0), pb.template column<position>()[i](0)) ||
                         !same_bits(pa.template column<velocity>()[i](1), pb.template column<velocity>()[i](1));
        }
        INFO("scheme " << int(scheme) << ", averaged " << averaged << ", " << body.size() << " particles, threads " << threads);
        CHECK(differing == 0);
        // The blocks have met: the update saw stresses (a run that stayed unstressed would
        // compare zeros).
        double largest = 0;
        for (std::size_t i = 0; i < pa.size(); ++i) largest = std::max(largest, pa.template column<stress>()[i].norm());
        CHECK(largest > 1e6);
    }
}

}  // namespace

TEST_CASE("two particles at once: a solver that pairs its particles runs to the same bits", "[core][lanes]") {
    // linear_elastic against itself without lane_safe (the solver types are what the test costs
    // to compile: a user's law goes through the same solver code, and its pairs are checked
    // against its singles above).
    const auto mat = gimlet::make_elastic_material(1800.0, 20e9, 0.3), soft = gimlet::make_elastic_material(1500.0, 8e9, 0.35);
    check_solver_pairs(mat, soft, alone_of(mat), alone_of(soft));
}

TEST_CASE("two particles at once: an inverted particle is named as one at a time names it", "[core][lanes]") {
    // The first particle to invert, found by a solver that pairs and one that does not.
    const auto mat = gimlet::make_elastic_material(1000.0, 1e6, 0.3);
    const elastic_alone alone = alone_of(mat);
    auto message = [](auto&& sol) {
        try {
            sol.step(0.01);  // far beyond the CFL limit
        } catch (const gimlet::numerical_error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    for (const auto scheme : {gimlet::update_scheme::musl, gimlet::update_scheme::usf}) {  // finish_step, update_material_points
        gimlet::solver_options<S> o;
        o.scheme = scheme;
        const std::string paired =
            message(gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material>(colliding_blocks(mat, mat), o));
        const std::string one = message(gimlet::solver<S, gimlet::shape::ugimp, elastic_alone>(colliding_blocks(alone, alone), o));
        INFO("scheme " << int(scheme));
        CHECK_THAT(paired, Catch::Contains("inverted particle"));
        CHECK(paired == one);
    }
}

#endif
