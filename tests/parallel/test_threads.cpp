// SPDX-License-Identifier: MIT
// Results must not depend on the number of threads: every scatter and reduction runs in a
// fixed order, so 1 and 2 threads give bitwise identical particle states. The scatter runs in
// parallel over slabs of the grid (solver.hpp, for_each_particle_by_slab), so the scenes below
// cover each scheme, single- and multi-field grids, walls and periodic axes, and sorting.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cstring>

namespace {

using S = gimlet::space<2>;

template <class Column>
bool bitwise_equal(const Column& a, const Column& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

template <class Solver>
void check_same(const Solver& one, const Solver& two) {
    REQUIRE(one.steps() == two.steps());
    REQUIRE(one.particles().size() > 4096);  // above the size at which loops go parallel
    CHECK(bitwise_equal(one.particles().template column<gimlet::fields::position>(),
                        two.particles().template column<gimlet::fields::position>()));
    CHECK(bitwise_equal(one.particles().template column<gimlet::fields::velocity>(),
                        two.particles().template column<gimlet::fields::velocity>()));
    CHECK(bitwise_equal(one.particles().template column<gimlet::fields::stress>(),
                        two.particles().template column<gimlet::fields::stress>()));
    CHECK(bitwise_equal(one.particles().template column<gimlet::fields::deformation_gradient>(),
                        two.particles().template column<gimlet::fields::deformation_gradient>()));
    CHECK(bitwise_equal(one.particles().template column<gimlet::fields::specific_internal_energy>(),
                        two.particles().template column<gimlet::fields::specific_internal_energy>()));
    // The run did something: the bodies are in contact and stressed.
    double max_stress = 0;
    for (const auto& s : one.particles().template column<gimlet::fields::stress>()) max_stress = std::max(max_stress, s.norm());
    CHECK(max_stress > 10.0);
}

// With light > 0, a small third disk of that fraction of the others' density sits where they
// meet: its particles are light (solver_options::light_particle_ratio) once they share nodes.
// consistent_mass: solver_options::consistent_mass_iterations.
template <class Contact = gimlet::contact::single_field>
auto disks(int threads, gimlet::update_scheme scheme, int sort_interval = 0, double room = 0, double light = 0,
           int consistent_mass = 0) {
    gimlet::grid_spec<S> gs;
    gs.lower = -room * S::vector::Ones();
    gs.upper = (1 + room) * S::vector::Ones();
    gs.cell = 0.0125;  // 6656 particles
    gs.bc = {gimlet::boundary::slip, gimlet::boundary::slip};
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    const auto mat = gimlet::make_elastic_material(1000.0, 1000.0, 0.3);
    sc.add_body(gimlet::scene::ball<S>(S::vector(0.3, 0.3), 0.2), mat, S::vector(0.5, 0.5));
    sc.add_body(gimlet::scene::ball<S>(S::vector(0.7, 0.7), 0.2), mat, S::vector(-0.5, -0.5));
    if (light > 0)
        sc.add_body(gimlet::scene::ball<S>(S::vector(0.5, 0.5), 0.05), gimlet::make_elastic_material(1000.0 * light, 1000.0 * light, 0.3),
                    S::vector(0.0, 0.0));
    gimlet::solver_options<S> opt;
    opt.threads = threads;
    opt.scheme = scheme;
    opt.sort_interval = sort_interval;
    opt.consistent_mass_iterations = consistent_mass;
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, Contact> sol(sc, opt);
    sol.run_until(0.2);  // well into the impact
    return sol;
}

// Two HMX blocks pressed together along y, periodic on both axes (they also meet across the
// seam), with an odd number of slabs along the periodic last axis: the slab whose stencils wrap
// onto the first gets a colour of its own.
// volume_filter: solver_options::volume_filter with two consistent-mass iterations.
auto blocks(int threads, gimlet::update_scheme scheme, double pic_fraction = 0, bool volume_filter = false) {
    using material = gimlet::presets::hmx_material<>;
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector(0.043, 0.043);  // 43 node rows along y: 21 slabs of 2 rows, the last of 3
    gs.cell = 1e-3;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::periodic};
    gimlet::scene::scene<S, material> sc(gs);
    const auto hmx = gimlet::presets::make_hmx();
    // Touching at y = 21.5 mm and across the seam, so contact acts from the first step.
    sc.add_body(gimlet::scene::box<S>(S::vector(0.0, 0.0), S::vector(0.043, 0.0215)), hmx, S::vector(0.0, 300.0), 2,
                "lower");
    sc.add_body(gimlet::scene::box<S>(S::vector(0.0, 0.0215), S::vector(0.043, 0.043)), hmx, S::vector(0.0, -300.0), 2,
                "upper");
    gimlet::solver_options<S> opt;
    opt.threads = threads;
    opt.scheme = scheme;
    opt.pic_fraction = pic_fraction;
    opt.volume_filter = volume_filter;
    opt.consistent_mass_iterations = volume_filter ? 2 : 0;
    gimlet::solver<S, gimlet::shape::ugimp, material, gimlet::contact::distance> sol(sc, opt);
    for (int n = 0; n < 60; ++n) sol.step(1e-8);
    return sol;
}

}  // namespace

TEST_CASE("results do not depend on the thread count", "[core][threads]") {
    check_same(disks(1, gimlet::update_scheme::musl), disks(2, gimlet::update_scheme::musl));
}

// The node loops (clearing the nodal arrays, nodal velocities, the momentum update) go parallel
// only on grids of 16,384 entries and more: the same disks with 2 units of empty grid on every
// side (400 x 400 cells with their ghost nodes, two fields: over 300,000 entries).
TEST_CASE("results do not depend on the thread count: a grid large enough for parallel node loops", "[core][threads]") {
    using gimlet::contact::bardenhagen;
    check_same(disks<bardenhagen>(1, gimlet::update_scheme::musl, 0, 2.0),
               disks<bardenhagen>(2, gimlet::update_scheme::musl, 0, 2.0));
}

// The consistent mass's gather and slab-ordered scatter, and its node loops on a grid large
// enough for them to go parallel (solver_options::consistent_mass_iterations).
TEST_CASE("results do not depend on the thread count: consistent-mass accelerations", "[core][threads]") {
    using gimlet::contact::bardenhagen;
    check_same(disks<bardenhagen>(1, gimlet::update_scheme::musl, 0, 2.0, 0, 2),
               disks<bardenhagen>(2, gimlet::update_scheme::musl, 0, 2.0, 0, 2));
}

TEST_CASE("results do not depend on the thread count: USL, USF", "[core][threads]") {
    check_same(disks(1, gimlet::update_scheme::usl), disks(2, gimlet::update_scheme::usl));
    check_same(disks(1, gimlet::update_scheme::usf), disks(2, gimlet::update_scheme::usf));
}

TEST_CASE("results do not depend on the thread count: multi-field contact", "[core][threads]") {
    using gimlet::contact::bardenhagen;
    check_same(disks<bardenhagen>(1, gimlet::update_scheme::musl), disks<bardenhagen>(2, gimlet::update_scheme::musl));
}

TEST_CASE("results do not depend on the thread count: particles far lighter than their neighbours", "[core][threads]") {
    const auto one = disks(1, gimlet::update_scheme::musl, 0, 0, 1e-6);
    const auto two = disks(2, gimlet::update_scheme::musl, 0, 0, 1e-6);
    CHECK(one.light_particles() > 0);
    check_same(one, two);
}

TEST_CASE("results do not depend on the thread count: sorting by cell", "[core][threads]") {
    check_same(disks(1, gimlet::update_scheme::musl, 7), disks(2, gimlet::update_scheme::musl, 7));
}

TEST_CASE("results do not depend on the thread count: HMX, distance contact, periodic axes", "[core][threads]") {
    check_same(blocks(1, gimlet::update_scheme::musl), blocks(2, gimlet::update_scheme::musl));
    check_same(blocks(1, gimlet::update_scheme::usf), blocks(2, gimlet::update_scheme::usf));
}

TEST_CASE("results do not depend on the thread count: the PIC blend and its heat", "[core][threads]") {
    check_same(blocks(1, gimlet::update_scheme::musl, 0.5), blocks(2, gimlet::update_scheme::musl, 0.5));
}

// The volume filter's gathers and slab-ordered scatters, and the heat it returns through the nodes
// (solver_options::volume_filter), per velocity field.
TEST_CASE("results do not depend on the thread count: the volume filter", "[core][threads]") {
    check_same(blocks(1, gimlet::update_scheme::musl, 0, true), blocks(2, gimlet::update_scheme::musl, 0, true));
    check_same(blocks(1, gimlet::update_scheme::usf, 0, true), blocks(2, gimlet::update_scheme::usf, 0, true));
}

TEST_CASE("results do not depend on the thread count: self-contact in a slotted block and sorting", "[core][threads]") {
    // One HMX body with a slot 1 mm wide and 33 mm long across a 43 mm periodic block; the
    // material above the slot moves down at 300 m/s, below it up, so the slot's faces meet after
    // 1.7 us and self-contact (multi_field::self_contact, whose per-step passes scatter by slab)
    // splits the nodes between them. Sorted every 7 steps: the partition's field moves with its
    // particles.
    using material = gimlet::presets::hmx_material<>;
    auto run = [](int threads) {
        gimlet::grid_spec<S> gs;
        gs.lower = S::vector(0.0, -0.02);
        gs.upper = S::vector(0.043, 0.02);
        gs.cell = 1e-3;
        gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
        gimlet::scene::scene<S, material> sc(gs);
        using box = gimlet::scene::box<S>;
        sc.add_body(gimlet::scene::difference(box(S::vector(0.0, -0.015), S::vector(0.043, 0.015)),
                                              box(S::vector(0.005, -0.0005), S::vector(0.038, 0.0005))),
                    gimlet::presets::make_hmx(), S::vector::Zero(), 2, "slotted block");
        gimlet::solver_options<S> opt;
        opt.threads = threads;
        opt.sort_interval = 7;
        gimlet::solver<S, gimlet::shape::ugimp, material, gimlet::contact::distance, gimlet::field_list<>,
                       gimlet::multi_field::self_contact>
            sol(sc, opt);
        auto& ps = sol.particles();
        auto& v = ps.template column<gimlet::fields::velocity>();
        const auto& x = ps.template column<gimlet::fields::position>();
        for (std::size_t i = 0; i < ps.size(); ++i) v[i] = S::vector(0.0, x[i][1] < 0 ? 300.0 : -300.0);
        std::size_t split = 0;
        for (int n = 0; n < 120; ++n) {
            sol.step(2e-8);
            split = std::max(split, sol.partition().split_nodes());
        }
        CHECK(split > 0);
        return sol;
    };
    check_same(run(1), run(2));
}
