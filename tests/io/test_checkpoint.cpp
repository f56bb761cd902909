// SPDX-License-Identifier: MIT
// Checkpoint and restart: a run resumed from a checkpoint matches the uninterrupted run bit for
// bit, and a damaged or mismatched checkpoint is refused whole, naming the file and the problem,
// with the target solver left as it was.
#include <gimlet/gimlet.hpp>

#include "scratch_dir.hpp"

#include <catch2/catch.hpp>

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

using Catch::Matchers::Contains;
using S = gimlet::space<2>;
using hmx = gimlet::presets::hmx_material<>;
using hmx_solver = gimlet::solver<S, gimlet::shape::ugimp, hmx, gimlet::contact::distance>;

namespace {

// Two HMX blocks 8 mm x 8 mm, 0.5 mm apart, colliding at +-300 m/s, a cavity of radius
// `cavity` (m) in the upper one; periodic in x, free in y. 0.5 mm cells, 2x2 particles per cell
// (about 1800 particles). The blocks touch after about 13 steps.
gimlet::scene::scene<S, hmx> two_blocks(double cavity = 2e-3, double density = 1900.0) {
    constexpr double w = 8e-3, gap = 0.5e-3;
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector(0.0, -2e-3);
    gs.upper = S::vector(w, 2 * w + gap + 2e-3);
    gs.cell = 0.5e-3;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
    gimlet::scene::scene<S, hmx> sc(gs);
    gimlet::presets::hmx_constants constants;
    constants.density = density;
    const auto mat = gimlet::presets::make_hmx(constants);
    sc.add_body(gimlet::scene::box<S>(S::vector(0.0, 0.0), S::vector(w, w)), mat, S::vector(0.0, 300.0), 2, "lower");
    const gimlet::scene::box<S> upper(S::vector(0.0, w + gap), S::vector(w, 2 * w + gap));
    sc.add_body(gimlet::scene::difference(upper, gimlet::scene::ball<S>(S::vector(0.5 * w, 1.5 * w + gap), cavity)),
                mat, S::vector(0.0, -300.0), 2, "upper");
    return sc;
}

// Every particle column's bytes, in field order: two solvers are in the same state if these
// are equal (together with time and steps).
template <class Solver>
std::vector<char> state_bytes(const Solver& s) {
    std::vector<char> out;
    s.particles().for_each_column([&](auto, const auto& column) {
        for (const auto& v : column) {
            const auto* p = reinterpret_cast<const char*>(&v);
            out.insert(out.end(), p, p + sizeof v);
        }
    });
    return out;
}

template <class Solver>
void steps(Solver& s, int n) {
    for (int i = 0; i < n; ++i) s.step();
}

}  // namespace

TEST_CASE("checkpoint: a resumed run matches the uninterrupted run bit for bit", "[io][checkpoint]") {
    io_test::scratch_dir dir("restart");
    constexpr int total = 40, at = 17;  // the checkpoint falls in the middle of the contact
    const auto scene = two_blocks();

    hmx_solver straight(scene);
    steps(straight, total);

    hmx_solver first(scene);
    steps(first, at);
    gimlet::io::save_checkpoint(dir / "run.ckpt", first, {{"next_output_us", 1.25}, {"snapshot", 3}});
    CHECK(!std::filesystem::exists(gimlet::io::detail::temporary_for(dir / "run.ckpt")));

    const auto info = gimlet::io::read_checkpoint_info(dir / "run.ckpt");
    CHECK(info.dimension == 2);
    CHECK(info.real_bytes == 8);
    CHECK(info.particles == first.particles().size());
    CHECK(info.steps == std::uint64_t(at));
    CHECK(info.time == double(first.time()));
    REQUIRE(info.fields.size() == hmx_solver::particle_fields::size);
    CHECK(info.fields.front() == gimlet::io::checkpoint_field{"position", 16});

    hmx_solver resumed(scene);
    const auto values = gimlet::io::load_checkpoint(dir / "run.ckpt", resumed);
    CHECK(values == gimlet::io::checkpoint_values{{"next_output_us", 1.25}, {"snapshot", 3}});
    CHECK(resumed.steps() == std::uint64_t(at));
    CHECK(resumed.time() == first.time());
    CHECK(state_bytes(resumed) == state_bytes(first));
    steps(resumed, total - at);

    INFO("particles: " << straight.particles().size());
    CHECK(resumed.steps() == straight.steps());
    CHECK(std::bit_cast<std::uint64_t>(resumed.time()) == std::bit_cast<std::uint64_t>(straight.time()));
    CHECK(state_bytes(resumed) == state_bytes(straight));
    // The blocks did collide: contact happened on both sides of the checkpoint.
    double peak = 0;
    for (std::size_t i = 0; i < straight.particles().size(); ++i)
        peak = std::max(peak, gimlet::mean_pressure(straight.particles()[i]));
    CHECK(peak > 1e9);
    // And the checkpoints of the two runs at the end are the same file.
    gimlet::io::save_checkpoint(dir / "straight.ckpt", straight);
    gimlet::io::save_checkpoint(dir / "resumed.ckpt", resumed);
    CHECK(io_test::read_bytes(dir / "straight.ckpt") == io_test::read_bytes(dir / "resumed.ckpt"));
}

namespace {

// Loading `file` into `target` must throw checkpoint_error naming the file and `problem`, and
// leave the target's particles, time and steps untouched.
template <class Solver>
void expect_refused(const std::filesystem::path& file, Solver& target, const std::string& problem) {
    const auto before = state_bytes(target);
    const auto time = target.time();
    const auto taken = target.steps();
    CHECK_THROWS_AS(gimlet::io::load_checkpoint(file, target), gimlet::io::checkpoint_error);
    CHECK_THROWS_AS(gimlet::io::load_checkpoint(file, target), gimlet::invalid_parameter);
    CHECK_THROWS_WITH(gimlet::io::load_checkpoint(file, target), Contains(file.string()) && Contains(problem));
    CHECK(state_bytes(target) == before);
    CHECK(target.time() == time);
    CHECK(target.steps() == taken);
}

}  // namespace

TEST_CASE("checkpoint: damaged or mismatched files are refused whole, naming the problem", "[io][checkpoint][errors]") {
    io_test::scratch_dir dir("refused");
    const auto scene = two_blocks();
    hmx_solver saved(scene);
    steps(saved, 5);
    const auto good = dir / "good.ckpt";
    gimlet::io::save_checkpoint(good, saved, {{"k", 1.0}});
    const auto bytes = io_test::read_bytes(good);
    REQUIRE(bytes.size() > 100000);

    hmx_solver target(scene);  // in a state different from the file's
    steps(target, 2);
    const auto bad = dir / "bad.ckpt";

    SECTION("missing") { expect_refused(dir / "absent.ckpt", target, "cannot be opened"); }
    SECTION("truncated at any length") {
        for (const std::size_t keep : {std::size_t(0), std::size_t(5), std::size_t(8), std::size_t(40),
                                       std::size_t(71), std::size_t(72), std::size_t(300), bytes.size() / 2,
                                       bytes.size() - 8, bytes.size() - 1}) {
            INFO("kept " << keep << " of " << bytes.size() << " bytes");
            io_test::write_bytes(bad, {bytes.begin(), bytes.begin() + std::ptrdiff_t(keep)});
            expect_refused(bad, target, "truncated");
        }
    }
    SECTION("trailing bytes") {
        auto longer = bytes;
        longer.push_back('x');
        io_test::write_bytes(bad, longer);
        expect_refused(bad, target, "1 unexpected bytes after its end");
    }
    SECTION("a flipped byte in the columns, the header or the checksum") {
        for (const std::size_t at : {bytes.size() - 100, bytes.size() / 2, std::size_t(44), bytes.size() - 3}) {
            INFO("byte " << at);
            auto flipped = bytes;
            flipped[at] = char(flipped[at] ^ 0x10);
            io_test::write_bytes(bad, flipped);
            expect_refused(bad, target, "checksum mismatch: the file is corrupt");
        }
    }
    SECTION("wrong magic") {
        auto other = bytes;
        other[0] = 'X';
        io_test::write_bytes(bad, other);
        expect_refused(bad, target, "not a gimlet checkpoint (wrong magic");
        io_test::write_bytes(bad, {'h', 'e', 'l', 'l', 'o'});
        expect_refused(bad, target, "wrong magic");
    }
    SECTION("another format version or byte order") {
        auto other = bytes;
        other[8] = 2;
        io_test::write_bytes(bad, other);
        expect_refused(bad, target, "format version 2; this gimlet reads version 1");
        other = bytes;
        std::swap(other[12], other[15]);
        io_test::write_bytes(bad, other);
        expect_refused(bad, target, "other byte order");
    }
    SECTION("another particle count (a different scene)") {
        hmx_solver smaller(two_blocks(3e-3));
        REQUIRE(smaller.particles().size() != saved.particles().size());
        expect_refused(good, smaller,
                       "particle count differs: the file holds " + std::to_string(saved.particles().size()) +
                           " particles, the solver " + std::to_string(smaller.particles().size()));
    }
    SECTION("another scene with the same particle count") {
        // A denser material: every position and the particle count stay, every mass changes.
        hmx_solver other(two_blocks(2e-3, 1910.0));
        REQUIRE(other.particles().size() == saved.particles().size());
        expect_refused(good, other, "its particles are not the solver's scene: bodies, masses or reference volumes "
                                    "differ");
        const auto before = state_bytes(other);
        CHECK_THROWS(gimlet::io::load_checkpoint(good, other));
        CHECK(state_bytes(other) == before);
    }
    SECTION("the same scene, particles sorted by cell: accepted") {
        gimlet::solver_options<S> opt;
        opt.sort_interval = 1;
        hmx_solver sorted(scene, opt);
        steps(sorted, 3);
        const auto sorted_file = dir / "sorted.ckpt";
        gimlet::io::save_checkpoint(sorted_file, sorted, {});
        hmx_solver fresh(scene, opt);
        CHECK_NOTHROW(gimlet::io::load_checkpoint(sorted_file, fresh));
    }
    SECTION("another field layout (a solver of another type)") {
        // Linear MPM keeps no particle domain size.
        gimlet::solver<S, gimlet::shape::linear, hmx, gimlet::contact::distance> linear(scene);
        expect_refused(good, linear, "particle field layout differs");
        expect_refused(good, linear, "fields only in the file: domain_half_width");
        // An elastic material keeps no plastic strain, plastic work or temperature.
        gimlet::scene::scene<S, gimlet::elastic_material> esc(scene.grid());
        for (const auto& b : scene.bodies())
            esc.add_body(gimlet::scene::box<S>(b.lower, b.upper), gimlet::make_elastic_material(1900.0, 1e10, 0.25),
                         b.velocity);
        gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material> elastic(esc);
        expect_refused(good, elastic, "fields only in the file: plastic_strain, plastic_work, temperature");
    }
    SECTION("another dimension") {
        using S3 = gimlet::space<3>;
        gimlet::grid_spec<S3> gs;
        gs.upper = S3::vector::Ones();
        gs.cell = 0.25;
        gimlet::scene::scene<S3, gimlet::elastic_material> sc(gs);
        sc.add_body(gimlet::scene::box<S3>(S3::vector::Zero(), S3::vector::Constant(0.5)),
                    gimlet::make_elastic_material(1000.0, 1e6, 0.3), S3::vector::Zero(), 1);
        gimlet::solver<S3, gimlet::shape::ugimp, gimlet::elastic_material> three_d(sc);
        expect_refused(good, three_d, "dimension differs: the file is 2-D, the solver 3-D");
    }
    // The good file still loads after all this.
    gimlet::io::load_checkpoint(good, target);
    CHECK(state_bytes(target) == state_bytes(saved));
}

TEST_CASE("checkpoint: an unwritable path is refused, an existing checkpoint survives", "[io][checkpoint][errors]") {
    io_test::scratch_dir dir("unwritable");
    hmx_solver sol(two_blocks());
    const auto missing = dir / "no such directory" / "run.ckpt";
    CHECK_THROWS_WITH(gimlet::io::save_checkpoint(missing, sol),
                      Contains("checkpoint file") && Contains(missing.string()) && Contains("writable file"));
    // A failed save leaves the previous checkpoint as it was: the rename never happened.
    const auto file = dir / "run.ckpt";
    gimlet::io::save_checkpoint(file, sol);
    const auto before = io_test::read_bytes(file);
    std::filesystem::create_directory(gimlet::io::detail::temporary_for(file));  // blocks the temporary file
    steps(sol, 1);
    CHECK_THROWS_WITH(gimlet::io::save_checkpoint(file, sol), Contains("run.ckpt") && Contains("writable file"));
    CHECK(io_test::read_bytes(file) == before);
}
