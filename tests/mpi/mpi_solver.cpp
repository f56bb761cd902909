// SPDX-License-Identifier: MIT
// The solver on many ranks (solver_options::processes): particle states, time steps and the
// conservation sums bitwise those of one process, for every scheme and one or two threads; a
// block that crosses every rank many times on a periodic axis keeps its particles and its mass;
// refusals name what is not distributed yet.
#include <gimlet/gimlet.hpp>
#include <gimlet/mpi/slabs.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {

using S = gimlet::space<2>;
using elastic_solver = gimlet::distributed_solver<S, gimlet::shape::ugimp, gimlet::elastic_material>;
// The same solver compiled for one process alone.
using one_process_solver = gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material>;

// Sulsky, Chen and Schreyer's two elastic disks (1994, section 5.1), on a finer cell: they
// cross slabs along both axes before, during and after the collision. `upper_first`: the upper
// disk is body 0, so the low ordinals sit on the high ranks.
gimlet::scene::scene<S, gimlet::elastic_material> two_disks(double cell, bool upper_first = false) {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Ones();
    gs.cell = cell;
    gs.bc = {gimlet::boundary::slip, gimlet::boundary::slip};
    gimlet::scene::scene<S, gimlet::elastic_material> scene(gs);
    const auto mat = gimlet::make_elastic_material(1000.0, 1000.0, 0.3);
    const auto lower = gimlet::scene::ball<S>(S::vector(0.25, 0.25), 0.2), upper = gimlet::scene::ball<S>(S::vector(0.75, 0.75), 0.2);
    if (upper_first) scene.add_body(upper, mat, S::vector(-0.1, -0.1), 2, "upper disk");
    scene.add_body(lower, mat, S::vector(0.1, 0.1), 2, "lower disk");
    if (!upper_first) scene.add_body(upper, mat, S::vector(-0.1, -0.1), 2, "upper disk");
    return scene;
}

// Every particle of `many` (this rank's) has the bits of the particle of `one` with its ordinal.
template <class Many, class One>
std::size_t differing_particles(const Many& many, const One& one) {
    std::size_t differ = 0;
    const auto& a = many.particles();
    const auto& b = one.particles();
    for (std::size_t i = 0; i < a.size(); ++i) {
        const auto j = std::size_t(many.ordinal(i));
        bool same = j < b.size();
        a.for_each_column([&](auto tag, const auto& column) {
            const auto& other = b.template column<decltype(tag)>();
            same = same && std::memcmp(&column[i], &other[j], sizeof(column[i])) == 0;
        });
        differ += same ? 0 : 1;
    }
    return differ;
}

// The bytes of appended block k of a .vtp this library writes (after its UInt64 size).
std::string block(const std::filesystem::path& path, int k) {
    std::ifstream in(path, std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    const std::string start = "<AppendedData encoding=\"raw\">\n   _";
    auto at = text.find(start);
    if (at == std::string::npos) return {};
    at += start.size();
    for (;; --k) {
        std::uint64_t n = 0;
        if (at + 8 > text.size()) return {};
        std::memcpy(&n, text.data() + at, 8);
        if (k == 0) return text.substr(at + 8, n);
        at += 8 + n;
    }
}

// A partition whose prepare hook reads this process's particles alone (it does not say it
// distributes): refused on many processes.
struct prepares_alone {
    using required_fields = gimlet::field_list<>;
    static constexpr std::size_t fields_per_body = 2;
    std::size_t seen = 0;
    template <class View>
    void prepare(const View& view) {
        seen = view.particles.size();
    }
    template <class P, class V>
    [[nodiscard]] std::size_t side(const P&, std::size_t, const V&) const {
        return 0;
    }
};

}  // namespace

TEST_CASE("solver on many ranks: the two disks' particles, steps and sums are a one-process solver's bits", "[mpi][solver]") {
    const gimlet::mpi::communicator comm;
    const auto scene = two_disks(0.025);
    for (auto scheme : {gimlet::update_scheme::musl, gimlet::update_scheme::usl, gimlet::update_scheme::usf})
        for (int threads : {1, 2}) {
            gimlet::solver_options<S> one_options;
            one_options.scheme = scheme;
            one_options.threads = threads;
            one_options.sort_interval = 25;  // sorted, renumbered, on every rank alike
            if (scheme != gimlet::update_scheme::usl) one_options.consistent_mass_iterations = 1;
            auto many_options = one_options;
            many_options.processes = gimlet::mpi::make_ranks(comm);
            one_process_solver one(scene, one_options);
            elastic_solver many(scene, many_options);
            INFO("rank " << comm.rank() << " of " << comm.size() << ", scheme " << int(scheme) << ", threads " << threads);
            std::size_t steps_differ = 0;
            for (int k = 0; k < 260; ++k)  // past the collision (about 1.1 s, step 150)
                steps_differ += one.step() == many.step() ? 0 : 1;
            CHECK(steps_differ == 0);
            CHECK(comm.sum(std::uint64_t(many.particles().size())) == one.particles().size());
            CHECK(differing_particles(many, one) == 0);
            const auto a = gimlet::diagnostics::sample_conservation(one);
            const auto b = gimlet::diagnostics::sample_conservation(many);
            CHECK(std::memcmp(&a.kinetic, &b.kinetic, sizeof a.kinetic) == 0);
            CHECK(std::memcmp(&a.internal, &b.internal, sizeof a.internal) == 0);
            CHECK(std::memcmp(&a.mass, &b.mass, sizeof a.mass) == 0);
            CHECK(std::memcmp(a.momentum.data(), b.momentum.data(), sizeof(double) * 2) == 0);
        }
}

TEST_CASE("solver on many ranks: multi-field contact gives one process's bits", "[mpi][solver]") {
    const gimlet::mpi::communicator comm;
    const auto scene = two_disks(0.025);
    using bardenhagen_solver = gimlet::distributed_solver<S, gimlet::shape::ugimp, gimlet::elastic_material, gimlet::contact::bardenhagen>;
    using distance_solver = gimlet::distributed_solver<S, gimlet::shape::ugimp, gimlet::elastic_material, gimlet::contact::distance>;
    auto check = [&](auto one, auto many, const char* law) {
        INFO("rank " << comm.rank() << " of " << comm.size() << ", " << law);
        std::size_t steps_differ = 0;
        for (int k = 0; k < 260; ++k) steps_differ += one.step() == many.step() ? 0 : 1;  // through the collision
        CHECK(steps_differ == 0);
        CHECK(differing_particles(many, one) == 0);
        const double e1 = gimlet::diagnostics::kinetic_energy(one), e2 = gimlet::diagnostics::kinetic_energy(many);
        CHECK(std::memcmp(&e1, &e2, sizeof e1) == 0);
    };
    for (auto scheme : {gimlet::update_scheme::musl, gimlet::update_scheme::usf}) {
        gimlet::solver_options<S> one_options;
        one_options.scheme = scheme;
        one_options.consistent_mass_iterations = scheme == gimlet::update_scheme::musl ? 2 : 0;  // its own scatters
        one_options.cfl = 0.4;
        auto many_options = one_options;
        many_options.processes = gimlet::mpi::make_ranks(comm);
        check(bardenhagen_solver(scene, one_options), bardenhagen_solver(scene, many_options), "bardenhagen");
        check(distance_solver(scene, one_options), distance_solver(scene, many_options), "distance");
    }
}

namespace {

using hmx = gimlet::presets::hmx_material<>;

// An HMX block with a slot 1 mm wide along y, across every rank's slabs, whose sides close at
// 200 m/s: the split nodes run through every band two ranks share.
gimlet::scene::scene<S, hmx> slotted_block() {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector(-12e-3, -12e-3);
    gs.upper = S::vector(12e-3, 12e-3);
    gs.cell = 0.5e-3;
    gimlet::scene::scene<S, hmx> scene(gs);
    using box = gimlet::scene::box<S>;
    scene.add_body(gimlet::scene::difference(box(S::vector(-10e-3, -10e-3), S::vector(10e-3, 10e-3)),
                                             box(S::vector(-0.5e-3, -7e-3), S::vector(0.5e-3, 7e-3))),
                   gimlet::presets::make_hmx(), S::vector::Zero(), 2, "slotted block");
    return scene;
}

// The slot's sides set closing at 200 m/s.
template <class Solver>
void close_slot(Solver& s) {
    auto& v = s.particles().template column<gimlet::fields::velocity>();
    const auto& x = s.particles().template column<gimlet::fields::position>();
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = S::vector(x[i][0] < 0 ? 100.0 : -100.0, 0.0);
}

// docs/concepts.md's example partition, as a user writes it from there, made to distribute as
// the page says: at every node some particle hotter than a threshold reaches (the page's 400 K;
// 301 K here, which the slot's closing reaches), the particles on either side of the node along
// x in two fields.
struct split_where_hot {
    using required_fields = gimlet::field_list<>;
    static constexpr std::size_t fields_per_body = 2;
    static constexpr bool distributes = true;
    double threshold = 301;
    std::vector<char> hot;  // per node, rebuilt every step
    bool any = false;
    template <class View>
    void prepare(const View& view) {
        hot.assign(view.grid.size(), 0);
        any = false;
        const auto& T = view.particles.template column<gimlet::fields::temperature>();
        for (std::size_t i = 0; i < view.particles.size(); ++i)
            if (T[i] > threshold) {
                view.stencils[i].for_each([&](std::size_t node, auto, const auto&) { hot[node] = 1; });
                any = true;
            }
        view.across.merge_shared(1, [&](std::size_t e) { return hot[e]; },
                                 [&](std::size_t e, char theirs) { hot[e] = hot[e] || theirs; });
    }
    bool splits() const { return any; }
    template <class P, class V>
    std::size_t side(const P& p, std::size_t node, const V& at) const {
        return hot[node] && p.template get<gimlet::fields::position>()[0] > at[0] ? 1 : 0;
    }
};

// Two fields per body without hooks: each particle's side is its own half of the block (its side
// reads the particle alone), so it runs on many processes as it is.
struct halves {
    using required_fields = gimlet::field_list<>;
    static constexpr std::size_t fields_per_body = 2;
    template <class P, class V>
    std::size_t side(const P& p, std::size_t, const V&) const {
        return p.template get<gimlet::fields::position>()[0] > 0 ? 1 : 0;
    }
};

// An initialize hook alone, which does not say it distributes: refused on many processes.
struct initializes_alone {
    using required_fields = gimlet::field_list<>;
    static constexpr std::size_t fields_per_body = 1;
    template <class View>
    void initialize(View&) {}
};

}  // namespace

TEST_CASE("solver on many ranks: two fields a body without hooks, and a profile, give one process's bits", "[mpi][solver][self-contact]") {
    const gimlet::mpi::communicator comm;
    using halves_solver = gimlet::distributed_solver<S, gimlet::shape::ugimp, hmx, gimlet::contact::distance, gimlet::field_list<>, halves>;
    const auto scene = slotted_block();
    gimlet::solver_options<S> one_options;
    auto many_options = one_options;
    many_options.processes = gimlet::mpi::make_ranks(comm);
    halves_solver one(scene, one_options), many(scene, many_options);
    close_slot(one), close_slot(many);
    std::size_t steps_differ = 0;
    for (int k = 0; k < 100; ++k) steps_differ += one.step() == many.step() ? 0 : 1;
    INFO("rank " << comm.rank() << " of " << comm.size());
    CHECK(steps_differ == 0);
    CHECK(differing_particles(many, one) == 0);
    // The pressure along x across the slot's middle: many particles share a coordinate, and the
    // list is every process's, in one process's order.
    const auto pressure = [](const auto& p) { return gimlet::mean_pressure(p); };
    const auto near_axis = [](const auto& p) { return std::abs(p.template get<gimlet::fields::position>()[1]) < 1e-3; };
    const auto a = gimlet::diagnostics::profile(one, 0, pressure, near_axis);
    const auto b = gimlet::diagnostics::profile(many, 0, pressure, near_axis);
    REQUIRE(a.size() > 100);
    REQUIRE(a.size() == b.size());
    CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof a[0]) == 0);
}

TEST_CASE("solver on many ranks: a partition written from the docs gives one process's bits", "[mpi][solver][self-contact]") {
    const gimlet::mpi::communicator comm;
    using hot_solver = gimlet::distributed_solver<S, gimlet::shape::ugimp, hmx, gimlet::contact::distance, gimlet::field_list<>, split_where_hot>;
    const auto scene = slotted_block();
    gimlet::solver_options<S> one_options;
    auto many_options = one_options;
    many_options.processes = gimlet::mpi::make_ranks(comm);
    hot_solver one(scene, one_options), many(scene, many_options);
    close_slot(one), close_slot(many);
    std::size_t steps_differ = 0, split_steps = 0;
    for (int k = 0; k < 120; ++k) {
        steps_differ += one.step() == many.step() ? 0 : 1;
        split_steps += one.partition().splits() ? 1 : 0;
    }
    INFO("rank " << comm.rank() << " of " << comm.size());
    CHECK(split_steps > 20);
    CHECK(steps_differ == 0);
    CHECK(differing_particles(many, one) == 0);
}

TEST_CASE("solver on many ranks: self-contact splits the same nodes and gives one process's bits", "[mpi][solver][self-contact]") {
    const gimlet::mpi::communicator comm;
    using slot_solver = gimlet::distributed_solver<S, gimlet::shape::ugimp, hmx, gimlet::contact::distance, gimlet::field_list<>,
                                       gimlet::multi_field::self_contact>;
    const auto scene = slotted_block();
    for (auto scheme : {gimlet::update_scheme::musl, gimlet::update_scheme::usf}) {
        gimlet::solver_options<S> one_options;
        one_options.scheme = scheme;
        one_options.consistent_mass_iterations = scheme == gimlet::update_scheme::musl ? 4 : 0;
        auto many_options = one_options;
        many_options.processes = gimlet::mpi::make_ranks(comm);
        slot_solver one(scene, one_options), many(scene, many_options);
        close_slot(one), close_slot(many);
        INFO("rank " << comm.rank() << " of " << comm.size() << ", scheme " << int(scheme));
        CHECK(differing_particles(many, one) == 0);  // the surface normals set at construction
        std::size_t steps_differ = 0, splits_differ = 0, most = 0;
        for (int k = 0; k < 150; ++k) {  // the slot closes (5 us) and its faces press together
            steps_differ += one.step() == many.step() ? 0 : 1;
            splits_differ += one.partition().split_nodes() == many.partition().split_nodes() ? 0 : 1;
            most = std::max(most, one.partition().split_nodes());
        }
        CHECK(most > 40);  // the slot's length in split nodes
        CHECK(steps_differ == 0);
        CHECK(splits_differ == 0);
        CHECK(differing_particles(many, one) == 0);
        const auto a = gimlet::diagnostics::sample_conservation(one);
        const auto b = gimlet::diagnostics::sample_conservation(many);
        CHECK(std::memcmp(&a.kinetic, &b.kinetic, sizeof a.kinetic) == 0);
        CHECK(std::memcmp(a.momentum.data(), b.momentum.data(), sizeof(double) * 2) == 0);
    }
}

TEST_CASE("solver on many ranks: more particles than a seeding batch, of two densities, give one process's bits",
          "[mpi][solver]") {
    // Each rank keeps its own particles batch by batch (the lower block is more than one batch)
    // with one process's ordinals, and cuts node masses at the whole run's heaviest particle: the
    // lower ranks hold only the light block, whose heaviest particle is a third of it.
    const gimlet::mpi::communicator comm;
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Ones();
    gs.cell = 1.0 / 200;
    gs.bc = {gimlet::boundary::slip, gimlet::boundary::slip};
    gimlet::scene::scene<S, gimlet::elastic_material> scene(gs);
    // The light block's sides move off the lattice, so nodes beyond them gain masses that cross
    // both cut-offs (a particle's weight there grows as the square of its move).
    scene.add_body(gimlet::scene::box<S>(S::vector(0.05, 0), S::vector(0.95, 0.5)), gimlet::make_elastic_material(1000.0, 1e5, 0.3),
                   S::vector(0.1, 0.05), 2, "light");
    scene.add_body(gimlet::scene::box<S>(S::vector(0, 0.6), S::vector(1, 1)), gimlet::make_elastic_material(3000.0, 1e5, 0.3),
                   S::vector(-0.03, -0.1), 2, "heavy");
    gimlet::solver_options<S> one_options, many_options;
    one_options.mass_cutoff = many_options.mass_cutoff = 1e-3;
    many_options.processes = gimlet::mpi::make_ranks(comm);
    elastic_solver one(scene, one_options), many(scene, many_options);
    REQUIRE(one.particles().size() == 136000);
    REQUIRE(std::size_t(comm.sum(std::uint64_t(many.particles().size()))) == one.particles().size());
    std::size_t out_of_order = 0;
    for (std::size_t i = 1; i < many.particles().size(); ++i) out_of_order += many.ordinal(i) > many.ordinal(i - 1) ? 0 : 1;
    CHECK(out_of_order == 0);
    CHECK(differing_particles(many, one) == 0);
    std::size_t steps_differ = 0;
    for (int k = 0; k < 30; ++k) steps_differ += one.step() == many.step() ? 0 : 1;
    INFO("rank " << comm.rank() << " of " << comm.size());
    CHECK(steps_differ == 0);
    CHECK(differing_particles(many, one) == 0);
}

TEST_CASE("solver on many ranks: a block crossing every rank on a periodic axis keeps its particles", "[mpi][solver]") {
    const gimlet::mpi::communicator comm;
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector(0.2, 0.4);
    gs.cell = 0.02;
    gs.bc = {gimlet::boundary::slip, gimlet::boundary::periodic};
    gimlet::scene::scene<S, gimlet::elastic_material> scene(gs);
    const auto mat = gimlet::make_elastic_material(1000.0, 1e5, 0.3);
    scene.add_body(gimlet::scene::box<S>(S::vector(0.04, 0.1), S::vector(0.16, 0.18)), mat, S::vector(0, 40.0), 2, "block");
    gimlet::solver_options<S> options;
    options.processes = gimlet::mpi::make_ranks(comm);
    elastic_solver many(scene, options), one(scene, gimlet::solver_options<S>{});
    const std::uint64_t count = one.particles().size();
    const double mass = gimlet::diagnostics::total_mass(one);
    // 40 m/s for 0.02 s: twice round the 0.4 m periodic axis, through every rank.
    std::size_t lost = 0, mass_changed = 0, differ = 0;
    while (many.time() < 0.02) {
        one.step(), many.step();
        lost += comm.sum(std::uint64_t(many.particles().size())) == count ? 0 : 1;
        mass_changed += gimlet::diagnostics::total_mass(many) == mass ? 0 : 1;
    }
    differ = differing_particles(many, one);
    INFO("rank " << comm.rank() << " of " << comm.size() << ", steps " << many.steps());
    CHECK(many.steps() > 100);
    CHECK(lost == 0);
    CHECK(mass_changed == 0);
    CHECK(differ == 0);
    // Every ordinal once.
    std::vector<std::uint8_t> seen(count, 0);
    for (std::size_t i = 0; i < many.particles().size(); ++i) seen[many.ordinal(i)] += 1;
    std::vector<std::uint8_t> all(count, 0);
    MPI_Allreduce(seen.data(), all.data(), int(count), MPI_UINT8_T, MPI_SUM, comm.get());
    CHECK(std::count(all.begin(), all.end(), std::uint8_t(1)) == std::ptrdiff_t(count));
}

TEST_CASE("solver on many ranks: a bad particle on one rank stops every rank, named by its ordinal", "[mpi][solver]") {
    const gimlet::mpi::communicator comm;
    gimlet::solver_options<S> options;
    options.processes = gimlet::mpi::make_ranks(comm);
    elastic_solver many(two_disks(0.05), options);
    for (int k = 0; k < 5; ++k) many.step();
    // Particle 150 (of the lower disk) is on one rank only; its velocity turns NaN there.
    int here = 0;
    for (std::size_t i = 0; i < many.particles().size(); ++i)
        if (many.ordinal(i) == 150) {
            many.particles().template column<gimlet::fields::velocity>()[i][0] = std::numeric_limits<double>::quiet_NaN();
            here = 1;
        }
    CHECK(comm.sum(std::uint64_t(here)) == 1);
    CHECK_THROWS_WITH(many.step(), Catch::Contains("particle 150 (body 0)") && Catch::Contains("velocity"));
}

TEST_CASE("solver on many ranks: where several particles fail, the lowest ordinal is named, as on one process", "[mpi][solver]") {
    const gimlet::mpi::communicator comm;
    // The upper disk first: its particles have the low ordinals and sit on the high ranks.
    const auto scene = two_disks(0.05, true);
    gimlet::solver_options<S> options;
    options.processes = gimlet::mpi::make_ranks(comm);
    elastic_solver one(scene), many(scene, options);
    const std::uint64_t high = one.particles().size() - 5;
    for (auto* s : {&one, &many})
        for (std::size_t i = 0; i < s->particles().size(); ++i)
            if (s->ordinal(i) == 5 || s->ordinal(i) == high)
                s->particles().template column<gimlet::fields::velocity>()[i][1] = std::numeric_limits<double>::infinity();
    std::string expected;
    try {
        one.step(1e-3);
    } catch (const gimlet::numerical_error& e) {
        expected = e.what();
    }
    REQUIRE_THAT(expected, Catch::Contains("particle 5 (body 0)"));
    // step(dt): the checks run inside the step's own agreement too; the particle is named once.
    CHECK_THROWS_WITH(many.step(1e-3), Catch::Contains(expected) && Catch::StartsWith("rank "));
    CHECK_THROWS_AS(many.step(1e-3), gimlet::processes_stopped);
}

TEST_CASE("solver on many ranks: a checkpoint written on two ranks resumes on all, bit for bit", "[mpi][solver][checkpoint]") {
    const gimlet::mpi::communicator comm;
    const auto scene = two_disks(0.025);
    using contact_solver = gimlet::distributed_solver<S, gimlet::shape::ugimp, gimlet::elastic_material, gimlet::contact::distance>;
    const auto path = std::filesystem::temp_directory_path() / ("gimlet_mpi_checkpoint_" + std::to_string(comm.size()) + ".ckpt");
    // Written on the first two ranks (one where there is one).
    MPI_Comm pair = MPI_COMM_NULL;
    MPI_Comm_split(comm.get(), comm.rank() < 2 ? 0 : MPI_UNDEFINED, comm.rank(), &pair);
    if (pair != MPI_COMM_NULL) {
        gimlet::solver_options<S> options;
        options.processes = gimlet::mpi::make_ranks(gimlet::mpi::communicator(pair));
        contact_solver first(scene, options);
        for (int k = 0; k < 120; ++k) first.step();
        gimlet::io::save_checkpoint(path, first, {{"answer", 42.0}});
    }
    comm.barrier();
    // Resumed on every rank; one process goes the whole way.
    gimlet::solver_options<S> options;
    options.processes = gimlet::mpi::make_ranks(comm);
    contact_solver resumed(scene, options), one(scene);
    const auto values = gimlet::io::load_checkpoint(path, resumed);
    CHECK(values.at("answer") == 42.0);
    CHECK(resumed.steps() == 120);
    for (int k = 0; k < 120; ++k) one.step();
    for (int k = 0; k < 80; ++k) {
        one.step();
        resumed.step();
    }
    INFO("rank " << comm.rank() << " of " << comm.size());
    CHECK(differing_particles(resumed, one) == 0);
    // A VTK snapshot on many ranks is the file one process writes.
    const auto vtp_one = std::filesystem::temp_directory_path() / ("gimlet_mpi_one_" + std::to_string(comm.size()) + ".vtp");
    const auto vtp_many = std::filesystem::temp_directory_path() / ("gimlet_mpi_many_" + std::to_string(comm.size()) + ".vtp");
    gimlet::io::vtp_writer_for<contact_solver> writer;
    writer.add_field<gimlet::fields::velocity>();
    writer.add_field<gimlet::fields::mass>();
    if (comm.rank() == 0) writer.write(vtp_one, one);
    writer.write(vtp_many, resumed);
    if (comm.rank() == 0) {
        std::ifstream a(vtp_one, std::ios::binary), b(vtp_many, std::ios::binary);
        const std::string sa{std::istreambuf_iterator<char>(a), {}}, sb{std::istreambuf_iterator<char>(b), {}};
        CHECK(!sa.empty());
        CHECK(sa == sb);
    }
    // Pieces, one a rank, nothing gathered: put in ordinal order by their ordinals (the array
    // after the two added), they hold one process's particles (here the velocities, the first
    // array), and the .pvtp names them all.
    const auto pvtp = std::filesystem::temp_directory_path() / ("gimlet_mpi_pieces_" + std::to_string(comm.size()) + ".pvtp");
    writer.write_pieces(pvtp, resumed);
    comm.barrier();
    // (Checked on the first rank without REQUIRE: the others go on to the collectives below.)
    const auto pieces_hold_one_process = [&] {
        const std::string whole = block(vtp_one, 0);
        const std::size_t size = 3 * sizeof(double);
        CHECK(whole.size() == one.particles().size() * size);
        std::string ordered(whole.size(), '\0');
        std::vector<int> seen(one.particles().size(), 0);
        for (int r = 0; r < comm.size(); ++r) {
            const std::string v = block(writer.piece_path(pvtp, r), 0), o = block(writer.piece_path(pvtp, r), 2);
            CHECK(o.size() / 8 * size == v.size());
            for (std::size_t k = 0; k < o.size() / 8 && (k + 1) * size <= v.size(); ++k) {
                std::int64_t ordinal = -1;
                std::memcpy(&ordinal, o.data() + 8 * k, 8);
                if (ordinal < 0 || std::size_t(ordinal) >= seen.size()) return false;
                ++seen[std::size_t(ordinal)];
                ordered.replace(std::size_t(ordinal) * size, size, v, k * size, size);
            }
        }
        CHECK(std::count(seen.begin(), seen.end(), 1) == std::ptrdiff_t(seen.size()));  // each once
        return !whole.empty() && ordered == whole;
    };
    if (comm.rank() == 0) {
        CHECK(pieces_hold_one_process());
        std::ifstream in(pvtp, std::ios::binary);
        const std::string summary{std::istreambuf_iterator<char>(in), {}};
        CHECK(summary.find("<VTKFile type=\"PPolyData\"") != std::string::npos);
        for (int r = 0; r <= comm.size(); ++r)
            CHECK((summary.find("<Piece Source=\"" + writer.piece_path(pvtp, r).filename().string() + "\"/>") !=
                   std::string::npos) == (r < comm.size()));
    }
    // A series on many ranks: one .pvd, each snapshot a .pvtp of pieces. Made on every rank
    // without the solver's processes (each rank writing the same .pvd, under a temporary name of
    // its own) it is refused at its first snapshot on every rank; in a directory that cannot be
    // written every rank stops.
    const auto pvd = std::filesystem::temp_directory_path() / ("gimlet_mpi_series_" + std::to_string(comm.size()) + ".pvd");
    gimlet::io::pvd_writer series(pvd, options.processes);
    const auto snapshot = series.write(writer, resumed);
    CHECK(snapshot.extension() == ".pvtp");
    CHECK(std::filesystem::exists(snapshot));
    CHECK(std::filesystem::exists(writer.piece_path(snapshot, comm.size() - 1)));
    const std::filesystem::path alone_pvd = pvd.string() + ".alone.pvd";
    for (int k = 0; k < 20; ++k) {
        gimlet::io::pvd_writer alone(alone_pvd);
        alone.add(double(k), vtp_one);
        CHECK(alone.entries().size() == 1);
        if (k == 19)
            CHECK_THROWS_WITH(alone.write(writer, resumed),
                              Catch::Matchers::Contains("none, where the solver has processes") &&
                                  Catch::Matchers::Contains("the solver's (solver_options::processes)"));
    }
    CHECK_THROWS_AS(gimlet::io::pvd_writer(std::filesystem::temp_directory_path() / "gimlet no such directory" / "s.pvd",
                                           options.processes),
                    gimlet::processes_stopped);
    comm.barrier();
    if (comm.rank() == 0) std::filesystem::remove(alone_pvd);
    if (pair != MPI_COMM_NULL) MPI_Comm_free(&pair);
    if (comm.rank() == 0) {
        for (const auto& f : {path, vtp_one, vtp_many, pvtp, pvd, snapshot}) std::filesystem::remove(f);
        for (int r = 0; r < comm.size(); ++r)
            std::filesystem::remove(writer.piece_path(pvtp, r)), std::filesystem::remove(writer.piece_path(snapshot, r));
    }
}

TEST_CASE("solver on many ranks: what is not distributed yet is refused by name", "[mpi][solver]") {
    const gimlet::mpi::communicator comm;
    const auto scene = two_disks(0.05);
    gimlet::solver_options<S> options;
    options.processes = gimlet::mpi::make_ranks(comm);
    // A solver compiled for one process, given processes: pointed to distributed_solver.
    CHECK_THROWS_WITH(one_process_solver(scene, options), Catch::Contains("solver_options::processes") &&
                                                            Catch::Contains("gimlet::distributed_solver"));
    options.volumetric_average = true;
    CHECK_THROWS_WITH(elastic_solver(scene, options), Catch::Contains("volumetric_average") && Catch::Contains("many processes"));
    options.volumetric_average = false;
    options.consistent_mass_iterations = 1;
    options.volume_filter = true;
    CHECK_THROWS_WITH(elastic_solver(scene, options), Catch::Contains("volume_filter"));
    options.volume_filter = false;
    options.consistent_mass_iterations = 0;
    using own_partition_solver = gimlet::distributed_solver<S, gimlet::shape::ugimp, gimlet::elastic_material, gimlet::contact::bardenhagen,
                                                gimlet::field_list<>, prepares_alone>;
    CHECK_THROWS_WITH(own_partition_solver(scene, options), Catch::Contains("distributes"));
    using initializing_solver = gimlet::distributed_solver<S, gimlet::shape::ugimp, gimlet::elastic_material, gimlet::contact::bardenhagen,
                                               gimlet::field_list<>, initializes_alone>;
    CHECK_THROWS_WITH(initializing_solver(scene, options), Catch::Contains("distributes"));
    // A rank count above the slabs: one cell, with the cubic B-spline's ghost nodes beyond each
    // side, is 10 node rows in 3 slabs of 3.
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector(1.0, 0.05);
    gs.cell = 0.05;
    gimlet::scene::scene<S, gimlet::elastic_material> flat(gs);
    flat.add_body(gimlet::scene::box<S>(S::vector(0.2, 0.0), S::vector(0.8, 0.05)),
                  gimlet::make_elastic_material(1000.0, 1000.0, 0.3), S::vector::Zero(), 2, "strip");
    // One processes object for two solvers of other grids; particles added on one rank.
    {
        elastic_solver first(scene, options);
        CHECK_THROWS_WITH(elastic_solver(two_disks(0.025), options), Catch::Contains("make_ranks() for each solver"));
        first.step();
        if (comm.rank() == 0) first.particles().add();
        CHECK_THROWS_WITH(first.step(), Catch::Contains("not added or removed"));
    }
    using cubic_solver = gimlet::distributed_solver<S, gimlet::shape::bspline_cubic, gimlet::elastic_material>;
    options.processes = gimlet::mpi::make_ranks(comm);
    if (comm.size() > 3) CHECK_THROWS_WITH(cubic_solver(flat, options), Catch::Contains("MPI ranks") && Catch::Contains("1 .. 3"));
    else CHECK_NOTHROW(cubic_solver(flat, options));
}
