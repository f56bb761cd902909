// SPDX-License-Identifier: MIT
// Sorting particles by cell (solver_options::sort_interval): it permutes particles with all
// their fields, changes results only by the order of floating-point sums, and a run resumed
// from saved particles sorts at the same steps and reproduces the uninterrupted run bitwise.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <vector>

namespace {

using S = gimlet::space<2>;

/// Each particle's original index, to follow it through sorts.
struct tag {
    template <class Sp> using type = double;
    static constexpr const char* name = "tag";
};

template <class Contact = gimlet::contact::single_field>
using solver = gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, Contact, gimlet::field_list<tag>>;

gimlet::scene::scene<S, gimlet::elastic_material> disks() {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Ones();
    gs.cell = 0.025;
    gs.bc = {gimlet::boundary::slip, gimlet::boundary::periodic};
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    const auto mat = gimlet::make_elastic_material(1000.0, 1000.0, 0.3);
    sc.add_body(gimlet::scene::ball<S>(S::vector(0.3, 0.3), 0.2), mat, S::vector(0.5, 0.4));
    sc.add_body(gimlet::scene::ball<S>(S::vector(0.7, 0.7), 0.2), mat, S::vector(-0.5, -0.6));
    return sc;
}

template <class Sol>
void number(Sol& sol) {
    auto& t = sol.particles().template column<tag>();
    for (std::size_t i = 0; i < t.size(); ++i) t[i] = double(i);
}

template <class Column>
bool bitwise_equal(const Column& a, const Column& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

}  // namespace

TEST_CASE("sorting moves every field with its particle and orders particles by node", "[core][sort]") {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Ones();
    gs.cell = 0.1;
    gs.bc = {gimlet::boundary::free, gimlet::boundary::free};
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    sc.add_body(gimlet::scene::box<S>(S::vector(0.2, 0.2), S::vector(0.8, 0.6)),
                gimlet::make_elastic_material(1000.0, 1000.0, 0.3), S::vector::Zero());
    gimlet::solver_options<S> opt;
    opt.sort_interval = 1;
    solver<> sol(sc, opt);
    number(sol);
    const auto before = sol.particles().column<gimlet::fields::position>();
    sol.step(1e-4);  // at rest and unstressed: nobody moves
    const auto& t = sol.particles().column<tag>();
    const auto& x = sol.particles().column<gimlet::fields::position>();
    std::vector<double> ids(t.begin(), t.end());
    std::sort(ids.begin(), ids.end());
    std::vector<double> expected(ids.size());
    std::iota(expected.begin(), expected.end(), 0.0);
    CHECK(ids == expected);  // a permutation
    bool moved = false, carried = true, ordered = true;
    // uGIMP's stencil starts one node before the nearest node: the sort key is the nearest node,
    // row-major with x fastest.
    auto key = [&](std::size_t i) {
        return std::lround(x[i][1] / gs.cell) * 1000 + std::lround(x[i][0] / gs.cell);
    };
    for (std::size_t i = 0; i < t.size(); ++i) {
        const auto from = static_cast<std::size_t>(t[i]);
        moved = moved || from != i;
        carried = carried && x[i] == before[from];
        if (i > 0) ordered = ordered && (key(i - 1) < key(i) || (key(i - 1) == key(i) && t[i - 1] < t[i]));
    }
    CHECK(moved);    // the fill order is not the node order, so the sort did something
    CHECK(carried);  // each particle kept its own position
    CHECK(ordered);  // by node, and stable within a node
}

TEST_CASE("sorting changes results only by round-off", "[core][sort]") {
    gimlet::solver_options<S> sorted_opt;
    sorted_opt.sort_interval = 3;
    solver<> plain(disks()), sorted(disks(), sorted_opt);
    number(plain);
    number(sorted);
    plain.run_until(0.2);
    sorted.run_until(0.2);
    REQUIRE(plain.steps() == sorted.steps());
    const auto& tp = plain.particles().column<tag>();
    const auto& ts = sorted.particles().column<tag>();
    std::vector<std::size_t> where(tp.size());
    for (std::size_t i = 0; i < ts.size(); ++i) where[static_cast<std::size_t>(ts[i])] = i;
    double worst = 0;
    for (std::size_t i = 0; i < tp.size(); ++i) {
        const S::vector d = plain.particles().column<gimlet::fields::position>()[static_cast<std::size_t>(tp[i])] -
                            sorted.particles().column<gimlet::fields::position>()[where[static_cast<std::size_t>(tp[i])]];
        worst = std::max(worst, d.norm());
    }
    CHECK(worst < 1e-10);  // m, in a 1 m domain after an impact
    bool permuted = false;
    for (std::size_t i = 0; i < ts.size(); ++i) permuted = permuted || ts[i] != double(i);
    CHECK(permuted);
}

TEST_CASE("a resumed run sorts at the same steps and reproduces the uninterrupted run bitwise", "[core][sort]") {
    using sol_t = solver<gimlet::contact::bardenhagen>;
    gimlet::solver_options<S> opt;
    opt.sort_interval = 5;
    constexpr double dt = 2e-4;
    sol_t whole(disks(), opt);
    for (int n = 0; n < 23; ++n) whole.step(dt);

    sol_t first(disks(), opt);
    for (int n = 0; n < 11; ++n) first.step(dt);
    // What a checkpoint holds: every particle field, the time and the step count.
    sol_t resumed(disks(), opt);
    resumed.particles().for_each_column([&](auto t, auto& column) {
        column = first.particles().template column<decltype(t)>();
    });
    resumed.resume_at(first.time(), first.steps());
    for (int n = 0; n < 12; ++n) resumed.step(dt);

    REQUIRE(resumed.steps() == whole.steps());
    bool same = true;
    whole.particles().for_each_column([&](auto t, const auto& column) {
        same = same && bitwise_equal(column, resumed.particles().template column<decltype(t)>());
    });
    CHECK(same);
}

TEST_CASE("sort_interval is validated", "[core][sort]") {
    gimlet::solver_options<S> opt;
    opt.sort_interval = -1;
    CHECK_THROWS_AS(solver<>(disks(), opt), gimlet::invalid_parameter);
}
