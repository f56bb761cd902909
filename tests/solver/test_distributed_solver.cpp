// SPDX-License-Identifier: MIT
// gimlet::distributed_solver on one process (no solver_options::processes) gives a plain
// solver's bits: its many-process branches are taken only where processes are given. Built and
// run without MPI, so that a build without it compiles the distributed solver too.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cstring>

namespace {

using S = gimlet::space<2>;

}  // namespace

TEST_CASE("distributed solver without processes: a plain solver's bits, step by step", "[solver][distributed]") {
    // Sulsky, Chen and Schreyer's two elastic disks (1994, section 5.1), through their collision.
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Ones();
    gs.cell = 0.05;
    gimlet::scene::scene<S, gimlet::elastic_material> scene(gs);
    const auto mat = gimlet::make_elastic_material(1000.0, 1000.0, 0.3);
    scene.add_body(gimlet::scene::ball<S>(S::vector(0.25, 0.25), 0.2), mat, S::vector(0.1, 0.1), 2, "lower disk");
    scene.add_body(gimlet::scene::ball<S>(S::vector(0.75, 0.75), 0.2), mat, S::vector(-0.1, -0.1), 2, "upper disk");
    gimlet::solver_options<S> options;
    options.scheme = gimlet::update_scheme::musl;
    options.consistent_mass_iterations = 1;
    options.sort_interval = 25;
    options.threads = 2;
    using contact = gimlet::contact::distance;
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, contact> plain(scene, options);
    gimlet::distributed_solver<S, gimlet::shape::ugimp, gimlet::elastic_material, contact> distributed(scene, options);
    STATIC_REQUIRE(!decltype(plain)::distributed);
    STATIC_REQUIRE(decltype(distributed)::distributed);
    REQUIRE(distributed.processes() == nullptr);
    std::size_t steps_differ = 0;
    for (int k = 0; k < 150; ++k) {
        const double a = plain.step(), b = distributed.step();
        steps_differ += std::memcmp(&a, &b, sizeof a) == 0 ? 0 : 1;
    }
    CHECK(steps_differ == 0);
    REQUIRE(distributed.particles().size() == plain.particles().size());
    std::size_t columns_differ = 0;
    distributed.particles().for_each_column([&](auto tag, const auto& column) {
        const auto& other = plain.particles().template column<decltype(tag)>();
        columns_differ += std::memcmp(&column[0], &other[0], sizeof(column[0]) * column.size()) == 0 ? 0 : 1;
    });
    CHECK(columns_differ == 0);
    for (std::size_t i = 0; i < distributed.particles().size(); i += 97) CHECK(distributed.ordinal(i) == i);
}
