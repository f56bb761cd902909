// SPDX-License-Identifier: MIT
// The hot spot and the surface measurements on many ranks (solver_options::processes): bitwise
// one process's, on every rank, through an impact that heats the material and moves particles
// between ranks, and on fields of temperature that tie often; discs wider than a rank's slab
// (their particles come from beyond the next rank) and narrower ones, sought with and without a
// running peak.
#include <gimlet/gimlet.hpp>
#include <gimlet/mpi/slabs.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace {

using S = gimlet::space<2>;
using hmx = gimlet::presets::hmx_material<>;
using hmx_solver = gimlet::distributed_solver<S, gimlet::shape::ugimp, hmx, gimlet::contact::distance>;
using gimlet::fields::temperature;

constexpr double cell = 1e-3;
constexpr double inf = std::numeric_limits<double>::infinity();

// Two HMX blocks 3 mm apart, the lower one with a cavity of radius 4 mm at (10, 8) mm, closing at
// 1000 m/s (the impact heats both, the cavity's walls move), at 2 x 2 particles per cell (about
// 1,800; a rank's share is a few slabs of the 40 mm along y). `upper_first`: the upper block is
// body 0, so its particles have the low ordinals.
gimlet::scene::scene<S, hmx> two_blocks(bool upper_first = false) {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector(0.0, 0.0);
    gs.upper = S::vector(20e-3, 40e-3);
    gs.cell = cell;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
    gimlet::scene::scene<S, hmx> sc(gs);
    const auto mat = gimlet::presets::make_hmx();
    using gimlet::scene::box, gimlet::scene::ball, gimlet::scene::difference;
    const auto upper = box<S>(S::vector(0.0, 18e-3), S::vector(20e-3, 30e-3));
    if (upper_first) sc.add_body(upper, mat, S::vector(0.0, -500.0), 2, "upper");
    sc.add_body(difference(box<S>(S::vector(0.0, 2e-3), S::vector(20e-3, 15e-3)), ball<S>(S::vector(10e-3, 8e-3), 4e-3)), mat,
                S::vector(0.0, 500.0), 2, "lower");
    if (!upper_first) sc.add_body(upper, mat, S::vector(0.0, -500.0), 2, "upper");
    return sc;
}

// The same bits.
template <class T>
bool same(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}
bool same(const S::vector& a, const S::vector& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 2) == 0; }

// Where two hot_spot results differ, what differs (empty: none).
std::string differences(const gimlet::diagnostics::hot_spot_result<S::vector>& one,
                        const gimlet::diagnostics::hot_spot_result<S::vector>& many) {
    std::ostringstream out;
    out.precision(17);
    if (!same(one.temperature, many.temperature)) out << " temperature " << one.temperature << " / " << many.temperature;
    if (!same(one.max_temperature, many.max_temperature))
        out << " max_temperature " << one.max_temperature << " / " << many.max_temperature;
    if (!same(one.centre, many.centre)) out << " centre " << one.centre.transpose() << " / " << many.centre.transpose();
    if (one.particles != many.particles) out << " particles " << one.particles << " / " << many.particles;
    return out.str();
}

// Every temperature set from the particle's ordinal (its index on one process): the same field
// on one process and on many.
template <class F>
void set_temperatures(hmx_solver& s, F&& of_ordinal) {
    auto& ps = s.particles();
    for (std::size_t i = 0; i < ps.size(); ++i) ps.template column<temperature>()[i] = of_ordinal(s.ordinal(i));
}

// hot_spot on one process and on many for each radius and running peak (relative to one
// process's hottest disc and hottest particle at that radius); the comparisons that differ.
// `work` is reused across the calls on many ranks.
std::vector<std::string> compare_hot_spots(const hmx_solver& one, const hmx_solver& many, const std::vector<double>& radii,
                                           gimlet::diagnostics::hot_spot_workspace<S::vector>& work, std::size_t& compared) {
    std::vector<std::string> differ;
    for (const double radius : radii) {
        const auto hottest = gimlet::diagnostics::hot_spot(one, radius);
        const double disc = hottest.temperature, particle = hottest.max_temperature;
        for (const double above : {-inf, std::nextafter(disc, 0.0), disc, 0.5 * (disc + particle), particle,
                                   std::numeric_limits<double>::quiet_NaN(), 300.0}) {
            const auto a = gimlet::diagnostics::hot_spot(one, radius, above);
            const auto b = gimlet::diagnostics::hot_spot(many, radius, above, work);
            ++compared;
            const std::string d = differences(a, b);
            if (!d.empty()) differ.push_back("radius " + std::to_string(radius) + ", above " + std::to_string(above) + ":" + d);
        }
    }
    return differ;
}

// surface_gap, void_chord and void_chords on one process and on many: the results that differ.
std::vector<std::string> compare_surfaces(const hmx_solver& one, const hmx_solver& many, std::size_t& open_chords) {
    std::vector<std::string> differ;
    namespace dg = gimlet::diagnostics;
    for (const double x : {10e-3, 3.3e-3, 17.05e-3})
        for (const double strip : {0.3e-3, 0.6e-3, 2e-3}) {
            const auto a = dg::surface_gap(one, 0, 1, 1, S::vector(x, 16e-3), strip);
            const auto b = dg::surface_gap(many, 0, 1, 1, S::vector(x, 16e-3), strip);
            if (a.found != b.found || !same(a.lower_surface, b.lower_surface) || !same(a.upper_surface, b.upper_surface))
                differ.push_back("surface_gap at x " + std::to_string(x) + ", strip " + std::to_string(strip));
        }
    auto chords_differ = [](const dg::void_chord_result& a, const dg::void_chord_result& b) {
        return a.open != b.open || !same(a.lower_wall, b.lower_wall) || !same(a.upper_wall, b.upper_wall) ||
               !same(a.lower_wall_velocity, b.lower_wall_velocity) || !same(a.upper_wall_velocity, b.upper_wall_velocity);
    };
    // Through the cavity along each axis, off its centre, and through the solid upper block.
    const std::vector<dg::chord_line<S::vector>> lines{{0, 1, S::vector(10e-3, 8e-3)},
                                                       {0, 0, S::vector(10e-3, 8e-3)},
                                                       {0, 1, S::vector(8.1e-3, 9e-3)},
                                                       {0, 0, S::vector(10e-3, 10.6e-3)},
                                                       {1, 1, S::vector(5e-3, 24e-3)}};
    for (const double strip : {0.3e-3, 0.6e-3}) {
        const auto a = dg::void_chords(one, lines, strip, 0.25 * cell);
        const auto b = dg::void_chords(many, lines, strip, 0.25 * cell);
        if (a.size() != b.size()) differ.push_back("void_chords: " + std::to_string(b.size()) + " results");
        for (std::size_t j = 0; j < a.size() && j < b.size(); ++j) {
            if (chords_differ(a[j], b[j])) differ.push_back("void_chords line " + std::to_string(j) + ", strip " + std::to_string(strip));
            open_chords += a[j].open;
        }
        const auto c = dg::void_chord(one, 0, 1, lines[0].point, strip, 0.25 * cell);
        const auto d = dg::void_chord(many, 0, 1, lines[0].point, strip, 0.25 * cell);
        if (chords_differ(c, d)) differ.push_back("void_chord, strip " + std::to_string(strip));
    }
    return differ;
}

}  // namespace

TEST_CASE("diagnostics on many ranks: hot_spot and the surfaces through an impact are one process's bits", "[mpi][diagnostics]") {
    const gimlet::mpi::communicator comm;
    const auto scene = two_blocks();
    for (const int threads : {1, 2}) {
        gimlet::solver_options<S> one_options;
        one_options.threads = threads;
        auto many_options = one_options;
        many_options.processes = gimlet::mpi::make_ranks(comm);
        hmx_solver one(scene, one_options), many(scene, many_options);
        INFO("rank " << comm.rank() << " of " << comm.size() << ", threads " << threads);
        // 0.3 mm and 0.75 mm discs, and 15 mm ones: wider than a slab of 4 ranks (10 mm) or
        // of 3 (13.3 mm), whose particles come from ranks beyond the next.
        const std::vector<double> radii{0.3e-3, 0.75e-3, 15e-3};
        gimlet::diagnostics::hot_spot_workspace<S::vector> work;
        std::vector<std::string> differ;
        std::size_t compared = 0, open_chords = 0, steps_differ = 0;
        double heated = 0;
        for (int k = 0; k <= 60; ++k) {
            if (k % 20 == 0) {
                for (auto&& d : compare_hot_spots(one, many, radii, work, compared)) differ.push_back("step " + std::to_string(k) + ", " + d);
                for (auto&& d : compare_surfaces(one, many, open_chords)) differ.push_back("step " + std::to_string(k) + ", " + d);
            }
            steps_differ += one.step() == many.step() ? 0 : 1;
        }
        heated = gimlet::diagnostics::hot_spot(one, 0.3e-3).max_temperature;
        CHECK(steps_differ == 0);
        CHECK(compared == 4 * 3 * 7);
        CHECK(open_chords > 0);
        CHECK(heated > 350.0);  // the impact heats the material (from 300 K): the discs' fields are not uniform
        for (const auto& d : differ) UNSCOPED_INFO(d);
        CHECK(differ.empty());
        // hot_material is the whole run's too.
        const std::vector<double> levels{300.0, 350.0, 500.0};
        const auto a = gimlet::diagnostics::hot_material(one, levels), b = gimlet::diagnostics::hot_material(many, levels);
        CHECK(std::memcmp(a.mass.data(), b.mass.data(), sizeof(double) * levels.size()) == 0);
        CHECK(std::memcmp(a.volume.data(), b.volume.data(), sizeof(double) * levels.size()) == 0);
    }
}

TEST_CASE("diagnostics on many ranks: hot_spot on fields that tie, and with no disc to name, is one process's", "[mpi][diagnostics]") {
    const gimlet::mpi::communicator comm;
    const auto scene = two_blocks();
    gimlet::solver_options<S> many_options;
    many_options.processes = gimlet::mpi::make_ranks(comm);
    hmx_solver one(scene), many(scene, many_options);
    for (int k = 0; k < 10; ++k) one.step(), many.step();  // particles off the lattice, moved between ranks
    INFO("rank " << comm.rank() << " of " << comm.size());
    const std::vector<double> radii{0.3e-3, 0.75e-3, 2e-3, 15e-3};
    gimlet::diagnostics::hot_spot_workspace<S::vector> work;
    std::size_t compared = 0;
    auto check_field = [&](const char* field) {
        INFO(field);
        const auto differ = compare_hot_spots(one, many, radii, work, compared);
        for (const auto& d : differ) UNSCOPED_INFO(d);
        CHECK(differ.empty());
    };
    // Pseudo-random temperatures of five values (discs tie often: the lowest ordinal must win),
    // with a few hot clusters.
    auto pseudo_random = [](std::uint64_t ordinal, std::uint64_t seed) {
        std::uint64_t state = (ordinal + 1) * 0x9E3779B97F4A7C15ULL ^ seed;
        for (int k = 0; k < 3; ++k) state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return double(state >> 11) * 0x1p-53;
    };
    for (auto* s : {&one, &many})
        set_temperatures(*s, [&](std::uint64_t o) {
            const double u = pseudo_random(o, 1);
            return u < 0.01 ? 500.0 + 2000.0 * pseudo_random(o, 2) : 300.0 + std::floor(5 * u);
        });
    check_field("five values and hot clusters");
    // Uniform: every disc's mean is that temperature, the first particle's disc is named.
    for (auto* s : {&one, &many}) set_temperatures(*s, [](std::uint64_t) { return 345.06126582478936; });
    check_field("uniform");
    const auto uniform = gimlet::diagnostics::hot_spot(many, 0.75e-3);
    CHECK(uniform.temperature == 345.06126582478936);
    CHECK(same(uniform.centre, one.particles().template column<gimlet::fields::position>()[0]));
    // The hottest particle on one rank only, and two equal hottest particles far apart (ties to
    // the lowest ordinal), in cool material.
    const std::uint64_t n = one.particles().size();
    for (auto* s : {&one, &many}) set_temperatures(*s, [&](std::uint64_t o) { return o == n / 3 ? 2000.0 : 300.0 + double(o % 3); });
    check_field("one hottest particle");
    for (auto* s : {&one, &many})
        set_temperatures(*s, [&](std::uint64_t o) { return o == n / 5 || o == n - 7 ? 2000.0 : 300.0 + double(o % 3); });
    check_field("two hottest particles");
    // No disc hotter than the running peak, W = 900 K: a patch at exactly W in the lower block
    // (its discs' means are W exactly), and isolated particles hotter than W in 300 K material,
    // whose discs are cooler than W: particle 0 (1000 K, the lowest ordinal, in the lower block),
    // the hottest particle (2000 K) and another (1500 K) in the upper block, far from the lower
    // ranks. One process tries the patch's centres (their bins' hottest particle is W, the floor,
    // and they come before the hottest particle) and names its first disc: a rank must compare
    // with the hottest particle of the whole run, not its own (particle 0), and try the centres
    // in the box of every rank's particles hotter than W, not its own.
    {
        const auto& x = one.particles().template column<gimlet::fields::position>();
        std::uint64_t hottest = 0, other = 0;
        std::vector<std::uint8_t> patch(n, 0);
        for (std::uint64_t o = 0; o < n; ++o) {
            if ((x[o] - S::vector(5e-3, 28e-3)).norm() < (x[hottest] - S::vector(5e-3, 28e-3)).norm()) hottest = o;
            if ((x[o] - S::vector(19e-3, 29e-3)).norm() < (x[other] - S::vector(19e-3, 29e-3)).norm()) other = o;
            patch[o] = (x[o] - S::vector(16e-3, 5e-3)).norm() < 1.5e-3;
        }
        for (auto* s : {&one, &many})
            set_temperatures(*s, [&](std::uint64_t o) {
                return o == 0 ? 1000.0 : o == hottest ? 2000.0 : o == other ? 1500.0 : patch[o] ? 900.0 : 300.0;
            });
        for (const double above : {900.0, -inf}) {
            const auto a = gimlet::diagnostics::hot_spot(one, 0.75e-3, above), b = gimlet::diagnostics::hot_spot(many, 0.75e-3, above);
            INFO("a patch at the peak, above " << above << ":" << differences(a, b));
            CHECK(a.temperature == 900.0);  // the patch's first disc, as designed
            CHECK(differences(a, b).empty());
        }
    }
    // Every temperature NaN: no hottest particle and no disc, on every rank.
    for (auto* s : {&one, &many}) set_temperatures(*s, [](std::uint64_t) { return std::numeric_limits<double>::quiet_NaN(); });
    const auto nan = gimlet::diagnostics::hot_spot(many, 0.75e-3);
    CHECK(std::isnan(nan.max_temperature));
    CHECK(nan.temperature == -inf);
    CHECK(nan.particles == 0);
    CHECK(compared == 4 * radii.size() * 7);
    // A radius too small for the bins is refused on every rank, as on one process.
    for (auto* s : {&one, &many}) set_temperatures(*s, [](std::uint64_t) { return 300.0; });
    CHECK_THROWS_WITH(gimlet::diagnostics::hot_spot(many, 1e-12), Catch::Contains("hot-spot radius (m) = 1e-12 is invalid"));
}

TEST_CASE("diagnostics on many ranks: the strips hold one process's points in one process's order", "[mpi][diagnostics]") {
    // Before any step the particles sit on the lattice: a strip wider than the spacing holds
    // rows of points of equal coordinate along the line, whose order after the sort is the
    // order they were gathered in, and the walls' speeds (means over a layer in that order)
    // show it in their last bits. Velocities are set per particle so that the means depend on
    // it. Then the upper block first and both blocks made one body (no step is taken): the
    // upper block's particles, on the upper ranks, have the low ordinals, so equal coordinates
    // along a horizontal line through both blocks come from several ranks out of rank order.
    const gimlet::mpi::communicator comm;
    INFO("rank " << comm.rank() << " of " << comm.size());
    for (const bool upper_first : {false, true}) {
        INFO("upper block first, one body: " << upper_first);
        const auto scene = two_blocks(upper_first);
        gimlet::solver_options<S> many_options;
        many_options.processes = gimlet::mpi::make_ranks(comm);
        hmx_solver one(scene), many(scene, many_options);
        for (auto* s : {&one, &many}) {
            auto& ps = s->particles();
            for (std::size_t i = 0; i < ps.size(); ++i) {
                const double u = double((s->ordinal(i) * 2654435761ULL) % 1000) / 1000.0;
                ps.template column<gimlet::fields::velocity>()[i] = S::vector(37.0 * u - 11.0, 100.0 * u * u - 31.0);
                if (upper_first) ps.template column<gimlet::fields::body>()[i] = 0;
            }
        }
        const std::vector<gimlet::diagnostics::detail::strip_line<S::vector>> lines{{0, 1, S::vector(10e-3, 8e-3), 0.6e-3},
                                                                                    {upper_first ? 0u : 1u, 1, S::vector(5e-3, 24e-3), 1.1e-3},
                                                                                    {0, 0, S::vector(10e-3, 8e-3), 0.6e-3},
                                                                                    {0, 0, S::vector(10e-3, 16.5e-3), 14e-3}};
        const auto a = gimlet::diagnostics::detail::strips(one, lines), b = gimlet::diagnostics::detail::strips(many, lines);
        REQUIRE(a.size() == b.size());
        std::size_t points = 0, ties = 0, differ = 0;
        for (std::size_t j = 0; j < a.size(); ++j) {
            REQUIRE(a[j].size() == b[j].size());
            points += a[j].size();
            for (std::size_t k = 0; k < a[j].size(); ++k) {
                differ += same(a[j][k].coordinate, b[j][k].coordinate) && same(a[j][k].velocity, b[j][k].velocity) &&
                                  same(a[j][k].half_spacing, b[j][k].half_spacing)
                              ? 0
                              : 1;
                ties += k > 0 && a[j][k].coordinate == a[j][k - 1].coordinate;
            }
        }
        INFO("points " << points << ", ties " << ties);
        CHECK(points > 500);
        CHECK(ties > 500);  // the order of equal coordinates is what is checked
        CHECK(differ == 0);
        if (!upper_first) {
            std::size_t open = 0;
            CHECK(compare_surfaces(one, many, open).empty());
            CHECK(open > 0);
        }
    }
}
