// SPDX-License-Identifier: MIT
// The observers behind the cavity-collapse measurements (surface gap, void chord and its wall
// speed, hot spot) on scenes where the answer is known by construction.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <vector>

namespace {

using S = gimlet::space<2>;
using hmx = gimlet::presets::hmx_material<>;
using solver = gimlet::solver<S, gimlet::shape::ugimp, hmx, gimlet::contact::distance>;
using gimlet::fields::position, gimlet::fields::velocity, gimlet::fields::temperature;

constexpr double h = 1e-3;  // cell

gimlet::grid_spec<S> grid() {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector(0.0, 0.0);
    gs.upper = S::vector(20e-3, 40e-3);
    gs.cell = h;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
    return gs;
}

// Two blocks 3 mm apart (faces on grid lines, so every lattice fills them exactly); the lower one with a cavity of radius 4 mm at (10, 8) mm.
solver two_blocks(int ppc_lower, int ppc_upper) {
    gimlet::scene::scene<S, hmx> sc(grid());
    const auto mat = gimlet::presets::make_hmx();
    using gimlet::scene::box, gimlet::scene::ball, gimlet::scene::difference;
    sc.add_body(difference(box<S>(S::vector(0.0, 2e-3), S::vector(20e-3, 15e-3)), ball<S>(S::vector(10e-3, 8e-3), 4e-3)),
                mat, S::vector::Zero(), ppc_lower, "lower");
    sc.add_body(box<S>(S::vector(0.0, 18e-3), S::vector(20e-3, 30e-3)), mat, S::vector::Zero(), ppc_upper, "upper");
    return solver(sc);
}

// The scene of two_blocks at 4 x 4 particles per cell (7,000 and more: the observers then run
// on the threads), as three solvers on 1, 2 and 3 threads.
std::vector<solver> on_1_2_3_threads() {
    gimlet::scene::scene<S, hmx> sc(grid());
    const auto mat = gimlet::presets::make_hmx();
    using gimlet::scene::box, gimlet::scene::ball, gimlet::scene::difference;
    sc.add_body(difference(box<S>(S::vector(0.0, 2e-3), S::vector(20e-3, 15e-3)), ball<S>(S::vector(10e-3, 8e-3), 4e-3)),
                mat, S::vector::Zero(), 4, "lower");
    sc.add_body(box<S>(S::vector(0.0, 18e-3), S::vector(20e-3, 30e-3)), mat, S::vector::Zero(), 4, "upper");
    std::vector<solver> runs;
    for (const int threads : {1, 2, 3}) {
        gimlet::solver_options<S> opt;
        opt.threads = threads;
        runs.emplace_back(sc, opt);
    }
    return runs;
}

// The index of the particle of `ps` nearest to `at` (the first of equals).
template <class Store>
std::size_t nearest(const Store& ps, const S::vector& at) {
    std::size_t k = 0;
    for (std::size_t i = 1; i < ps.size(); ++i)
        if ((ps[i].template get<position>() - at).squaredNorm() < (ps[k].template get<position>() - at).squaredNorm()) k = i;
    return k;
}

// A fixed pseudo-random sequence of doubles in [0, 1) (a 64-bit linear congruential generator,
// its top 53 bits): the same numbers on every machine.
struct sequence {
    std::uint64_t state;
    double operator()() {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return double(state >> 11) * 0x1p-53;
    }
};

}  // namespace

TEST_CASE("surface_gap: the gap between two blocks is the distance between their faces", "[diagnostics]") {
    for (int ppc : {1, 2, 4}) {
        const auto sol = two_blocks(2, ppc);
        // On the cavity's axis and away from it: the faces are flat, so the gap is 3 mm everywhere.
        for (double x : {10e-3, 3.3e-3}) {
            const auto g = gimlet::diagnostics::surface_gap(sol, 0, 1, 1, S::vector(x, 16e-3), 0.75 * h);
            REQUIRE(g.found);
            CHECK(g.lower_surface == Approx(15e-3).epsilon(1e-12));
            CHECK(g.upper_surface == Approx(18e-3).epsilon(1e-12));
            CHECK(g.gap() == Approx(3e-3).epsilon(1e-9));
        }
    }
    // A body with no particles in the strip (here: no such body) gives no gap rather than a number.
    const auto sol = two_blocks(2, 2);
    CHECK_FALSE(gimlet::diagnostics::surface_gap(sol, 0, 5, 1, S::vector(10e-3, 0.0), 0.5 * h).found);
    CHECK_THROWS_WITH(gimlet::diagnostics::surface_gap(sol, 0, 1, 2, S::vector(10e-3, 0.0), 0.5 * h),
                      Catch::Contains("line axis") && Catch::Contains("0 .. 1"));
    CHECK_THROWS_WITH(gimlet::diagnostics::surface_gap(sol, 0, 1, 1, S::vector(10e-3, 0.0), 0.0),
                      Catch::Contains("strip half-width"));
}

TEST_CASE("void_chord: a cavity's walls, length and closing speed", "[diagnostics]") {
    auto sol = two_blocks(2, 2);
    const double spacing = h / 2;
    const S::vector centre(10e-3, 8e-3);
    // The particle lattice resolves the circle to within one particle spacing.
    const auto axial = gimlet::diagnostics::void_chord(sol, 0, 1, centre, 0.5 * h, spacing);
    REQUIRE(axial.open);
    CHECK(std::abs(axial.length() - 8e-3) <= spacing);
    CHECK(std::abs(axial.centre() - 8e-3) <= 0.5 * spacing);
    const auto lateral = gimlet::diagnostics::void_chord(sol, 0, 0, centre, 0.5 * h, spacing);
    REQUIRE(lateral.open);
    CHECK(std::abs(lateral.length() - 8e-3) <= spacing);

    // Material below the cavity's centre moves up at u and above it down at u: the walls close
    // at exactly 2u; swapped, they open at 2u.
    const double u = 123.0;
    auto set_velocities = [&](double sign) {
        auto& ps = sol.particles();
        for (std::size_t i = 0; i < ps.size(); ++i) {
            auto p = ps[i];
            const bool below = p.get<position>()[1] < centre[1];
            p.get<velocity>() = S::vector(7.0, sign * (below ? u : -u));  // the x part must not matter
        }
    };
    set_velocities(1.0);
    CHECK(gimlet::diagnostics::void_chord(sol, 0, 1, centre, 0.5 * h, spacing).closing_speed() == Approx(2 * u));
    set_velocities(-1.0);
    CHECK(gimlet::diagnostics::void_chord(sol, 0, 1, centre, 0.5 * h, spacing).closing_speed() == Approx(-2 * u));

    // No void: the upper block is solid; a threshold wider than the cavity finds none either.
    const auto solid = gimlet::diagnostics::void_chord(sol, 1, 1, S::vector(10e-3, 24e-3), 0.5 * h, spacing);
    CHECK_FALSE(solid.open);
    CHECK(solid.length() == 0.0);
    CHECK_FALSE(gimlet::diagnostics::void_chord(sol, 0, 1, centre, 0.5 * h, 9e-3).open);
    // A point off the void still finds the nearest one (the cavity seen from inside the wall).
    const auto near = gimlet::diagnostics::void_chord(sol, 0, 1, S::vector(10e-3, 13e-3), 0.5 * h, spacing);
    REQUIRE(near.open);
    CHECK(near.length() == Approx(axial.length()));
}

TEST_CASE("hot_spot: the hottest disc's mass-weighted mean temperature", "[diagnostics]") {
    auto sol = two_blocks(2, 2);
    auto& ps = sol.particles();
    const double radius = 0.6e-3;
    // All at 300 K except a 3 mm disc at 800 K in the upper block: the hot spot is 800 K exactly.
    const S::vector hot(6e-3, 24e-3);
    for (std::size_t i = 0; i < ps.size(); ++i) {
        auto p = ps[i];
        p.get<temperature>() = (p.get<position>() - hot).norm() < 3e-3 ? 800.0 : 300.0;
    }
    auto r = gimlet::diagnostics::hot_spot(sol, radius);
    CHECK(r.temperature == Approx(800.0).epsilon(1e-12));
    CHECK(r.max_temperature == 800.0);
    CHECK((r.centre - hot).norm() < 3e-3);

    // One particle at 1000 K among equal-mass particles at 300 K, away from any surface: the disc
    // around it holds k particles (counted here by brute force), as does each disc around an
    // interior neighbour within reach, so the hot spot is 300 + 700 / k.
    std::size_t hottest = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        auto p = ps[i];
        p.get<temperature>() = 300.0;
        if ((p.get<position>() - hot).norm() < (ps[hottest].get<position>() - hot).norm()) hottest = i;
    }
    ps[hottest].get<temperature>() = 1000.0;
    std::size_t k = 0;
    for (std::size_t i = 0; i < ps.size(); ++i)
        if ((ps[i].get<position>() - ps[hottest].get<position>()).norm() <= radius) ++k;
    REQUIRE(k >= 5);  // 2 x 2 particles per 1 mm cell: the 0.6 mm disc holds the neighbours
    r = gimlet::diagnostics::hot_spot(sol, radius);
    CHECK(r.particles == k);
    CHECK(r.temperature == Approx(300.0 + 700.0 / double(k)).epsilon(1e-12));
    CHECK(r.max_temperature == 1000.0);
    // Every disc holding the hot particle and k particles ties to the bit (the same k - 1 terms
    // m (300 - 1000) in the same order, and an exact zero); they are all tried, their bins
    // holding the hot particle, and the lowest index wins.
    std::size_t first_tie = ps.size();
    for (std::size_t i = 0; i < ps.size() && first_tie == ps.size(); ++i) {
        const S::vector c = ps[i].get<position>();
        if ((ps[hottest].get<position>() - c).squaredNorm() > radius * radius) continue;
        std::size_t count = 0;
        for (std::size_t q = 0; q < ps.size(); ++q) count += (ps[q].get<position>() - c).squaredNorm() <= radius * radius;
        if (count == k) first_tie = i;
    }
    REQUIRE(first_tie != hottest);  // a tie the rule decides
    CHECK(r.centre == ps[first_tie].get<position>());

    CHECK_THROWS_WITH(gimlet::diagnostics::hot_spot(sol, -1.0), Catch::Contains("hot-spot radius"));
}

TEST_CASE("hot_spot: skipping centres that cannot win gives the answer of trying every centre", "[diagnostics]") {
    // Temperatures from a fixed pseudo-random sequence with a few hot clusters and many ties,
    // then uniform temperatures at several disc radii (where a plain sum m T / sum m of equal
    // values rounds above them): the hottest disc equals a brute-force search over every
    // particle centre, and the disc the diagnostic names holds the particles and the mean it
    // reports. (Which of several nearly tied discs wins depends on the last bit of each sum, so
    // the centre itself is not compared with the brute force's.) No disc is hotter than the
    // hottest particle; uniform temperatures give exactly their value, at particle 0.
    auto sol = two_blocks(2, 2);
    auto& ps = sol.particles();
    sequence next{12345};
    double radius = 0.75e-3;
    auto disc = [&](const S::vector& c, std::size_t& count) {
        double mass = 0, heat = 0;
        count = 0;
        for (std::size_t q = 0; q < ps.size(); ++q)
            if ((ps[q].get<position>() - c).squaredNorm() <= radius * radius) {
                mass += double(ps[q].get<gimlet::fields::mass>());
                heat += double(ps[q].get<gimlet::fields::mass>()) * ps[q].get<temperature>();
                ++count;
            }
        return heat / mass;
    };
    const double uniform[] = {300.0, 345.06126582478936, 1000.0 / 3.0, 1e4 + 0.1};
    const double radii[] = {0.2e-3, 0.75e-3, 2e-3};
    for (int trial = 0; trial < 15; ++trial) {
        const bool random = trial < 3;
        radius = random ? 0.75e-3 : radii[(trial - 3) % 3];
        for (std::size_t i = 0; i < ps.size(); ++i) {
            const double u = next();
            ps[i].get<temperature>() = !random ? uniform[(trial - 3) / 3]
                                               : (u < 0.02 ? 300.0 + 3000.0 * next() : 300.0 + std::floor(4 * u));
        }
        const auto r = gimlet::diagnostics::hot_spot(sol, radius);
        double best = -1;
        for (std::size_t i = 0; i < ps.size(); ++i) {
            std::size_t c = 0;
            best = std::max(best, disc(ps[i].get<position>(), c));
        }
        std::size_t count = 0;
        const double at_centre = disc(r.centre, count);
        INFO("trial " << trial << ", radius " << radius);
        REQUIRE(std::isfinite(r.temperature));
        CHECK(r.temperature == Approx(best).epsilon(1e-12));
        CHECK(r.temperature <= r.max_temperature);
        if (!random) {
            CHECK(r.temperature == uniform[(trial - 3) / 3]);
            CHECK(r.centre == ps[0].get<position>());
        }
        CHECK(at_centre == Approx(r.temperature).epsilon(1e-12));
        CHECK(count == r.particles);
        // Sought above a running peak: below the hottest disc, the same disc bit for bit; at
        // it or above, nothing hotter (a peak tracked with it moves exactly as without it).
        // (300 K is below the hottest disc of the random fields, and at it in the uniform
        // field of 300 K.) Only the bins near a particle hotter than the peak are sorted.
        int below = 0;
        for (const double above : {300.0, best - 1.0, std::nextafter(r.temperature, 0.0), r.temperature, best + 1.0, 1e9}) {
            const auto a = gimlet::diagnostics::hot_spot(sol, radius, above);
            INFO("above " << above);
            CHECK(a.max_temperature == r.max_temperature);
            if (above < r.temperature) {
                ++below;
                CHECK(a.temperature == r.temperature);
                CHECK(a.centre == r.centre);
                CHECK(a.particles == r.particles);
            } else {
                CHECK_FALSE(a.temperature > above);
            }
        }
        CHECK(below >= (random || trial >= 6 ? 3 : 2));
        // NaN and +infinity are ignored (as -infinity): both give the disc the default gives.
        for (const double above : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
            const auto a = gimlet::diagnostics::hot_spot(sol, radius, above);
            INFO("above " << above);
            CHECK(a.temperature == r.temperature);
            CHECK(a.centre == r.centre);
        }
    }
    // A field cooler than the peak everywhere: no disc is sought, and none is named.
    double hottest = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        ps[i].get<temperature>() = 300.0 + 0.001 * double(i % 7);
        hottest = std::max(hottest, ps[i].get<temperature>());
    }
    const auto none = gimlet::diagnostics::hot_spot(sol, 0.75e-3, 400.0);
    CHECK(none.temperature == -std::numeric_limits<double>::infinity());
    CHECK(none.particles == 0);
    CHECK(none.max_temperature == hottest);
}

// Sought above a peak, only the bins within two of the box of the particles hotter than it are
// sorted. The hottest disc here is centred off the one particle hotter than the peak (2000 K,
// with 499.9 K material on one side of it and 300 K elsewhere, the peak 500 K): its disc reaches
// two bins from that particle's, and it must be summed whole (a disc cut to the bins within one
// is hotter: it fails with those). The warm side on each side of it in turn, at three radii, and
// on 1, 2 and 3 threads at 4 x 4 particles per cell (the first pass in blocks, which merge their
// boxes), with a workspace reused from call to call.
TEST_CASE("hot_spot: sought above a peak, the discs near the edge of the sorted bins are whole", "[diagnostics]") {
    auto runs = on_1_2_3_threads();
    std::vector<gimlet::diagnostics::hot_spot_workspace<S::vector>> work(runs.size());
    const S::vector middle(10.1e-3, 24.1e-3);  // off the particles' lattice: one particle is nearest
    for (const S::vector& side : {S::vector(1, 0), S::vector(-1, 0), S::vector(0, 1), S::vector(0, -1)}) {
        for (std::size_t k = 0; k < runs.size(); ++k) {
            auto& ps = runs[k].particles();
            const std::size_t h = nearest(ps, middle);
            const S::vector at = ps[h].get<position>();
            for (std::size_t i = 0; i < ps.size(); ++i)
                ps[i].get<temperature>() = (ps[i].get<position>() - at).dot(side) >= 0 ? 499.9 : 300.0;
            ps[h].get<temperature>() = 2000.0;
            for (const double radius : {0.75e-3, 1.2e-3, 2e-3}) {
                INFO("side " << side.transpose() << ", " << k + 1 << " threads, radius " << radius);
                const auto all = gimlet::diagnostics::hot_spot(runs[k], radius);
                const auto above = gimlet::diagnostics::hot_spot(runs[k], radius, 500.0, work[k]);
                REQUIRE(all.temperature > 500.0);
                CHECK(all.centre != at);  // off the hot particle, towards the warm side
                CHECK((all.centre - at).dot(side) > 0);
                CHECK(above.temperature == all.temperature);
                CHECK(above.centre == all.centre);
                CHECK(above.particles == all.particles);
            }
        }
    }
    // Two particles hotter than the peak, far apart and in different blocks of the first pass:
    // the hottest alone in cool material (the lower block), the other beside warm material
    // (the upper block), where the hottest disc is. The box must hold both.
    for (std::size_t k = 0; k < runs.size(); ++k) {
        auto& ps = runs[k].particles();
        const std::size_t a = nearest(ps, S::vector(3.1e-3, 5.1e-3)), b = nearest(ps, S::vector(16.1e-3, 26.1e-3));
        for (std::size_t i = 0; i < ps.size(); ++i)
            ps[i].get<temperature>() = (ps[i].get<position>() - ps[b].get<position>()).norm() < 3e-3 ? 499.9 : 300.0;
        ps[a].get<temperature>() = 2000.0;
        ps[b].get<temperature>() = 1500.0;
        INFO(k + 1 << " threads");
        const auto all = gimlet::diagnostics::hot_spot(runs[k], 0.75e-3);
        const auto above = gimlet::diagnostics::hot_spot(runs[k], 0.75e-3, 500.0, work[k]);
        REQUIRE(all.temperature > 500.0);
        CHECK((all.centre - ps[b].get<position>()).norm() < 1e-3);  // beside the cooler of the two
        CHECK(above.temperature == all.temperature);
        CHECK(above.centre == all.centre);
        CHECK(above.particles == all.particles);
        CHECK(above.max_temperature == 2000.0);
    }
}

// With no peak, the bins sorted are those within two of a particle at least about as hot as
// the hottest particle's disc. Two hot particles 1 mm apart in 300 K material: only a disc
// centred between them holds both, and that centre's bin may hold neither (the bins are 0.75 mm
// wide), so it must be tried from the hot bins' neighbours. Every placement along a row and a
// column gives the brute force's hottest disc.
TEST_CASE("hot_spot: a disc between two hot particles, in a bin of neither", "[diagnostics]") {
    auto sol = two_blocks(2, 2);
    auto& ps = sol.particles();
    const double radius = 0.75e-3;
    int off_centre = 0;
    for (const S::vector& step : {S::vector(1e-3, 0), S::vector(0, 1e-3)})
        for (int shift = 0; shift < 6; ++shift) {
            const S::vector first = S::vector(6.1e-3, 22.1e-3) + 0.5e-3 * shift * step / step.norm();
            const std::size_t a = nearest(ps, first), b = nearest(ps, S::vector(first + step));
            for (std::size_t i = 0; i < ps.size(); ++i) ps[i].get<temperature>() = 300.0;
            ps[a].get<temperature>() = 2000.0;
            ps[b].get<temperature>() = 2000.0;
            double best = -1;
            for (std::size_t i = 0; i < ps.size(); ++i) {
                double mass = 0, heat = 0;
                for (std::size_t q = 0; q < ps.size(); ++q)
                    if ((ps[q].get<position>() - ps[i].get<position>()).squaredNorm() <= radius * radius) {
                        mass += double(ps[q].get<gimlet::fields::mass>());
                        heat += double(ps[q].get<gimlet::fields::mass>()) * ps[q].get<temperature>();
                    }
                best = std::max(best, heat / mass);
            }
            const auto r = gimlet::diagnostics::hot_spot(sol, radius);
            INFO("step " << step.transpose() << ", shift " << shift);
            CHECK(r.temperature == Approx(best).epsilon(1e-12));
            off_centre += r.centre != ps[a].get<position>() && r.centre != ps[b].get<position>();
        }
    CHECK(off_centre == 12);  // the hottest disc is never centred on a hot particle
}

TEST_CASE("hot_spot: the same disc, centre and count on 1, 2 and 3 threads, ties to the lowest index", "[diagnostics][threads]") {
    // 4 x 4 particles per cell (7,000 and more: the centres are then tried in parallel), with
    // pseudo-random temperatures that tie often, then uniform ones, where every disc's mean is
    // exactly that temperature: particle 0's disc is named, every later centre skipped.
    std::vector<solver> runs = on_1_2_3_threads();
    REQUIRE(runs[0].particles().size() >= 4096);
    for (const int kind : {0, 1, 2}) {
        std::uint64_t state = 777;
        for (std::size_t i = 0; i < runs[0].particles().size(); ++i) {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            const double t = kind == 0 ? 300.0 + double((state >> 40) % 5) : kind == 1 ? 345.06126582478936 : 512.0;
            for (auto& run : runs) run.particles()[i].get<temperature>() = t;
        }
        const auto one = gimlet::diagnostics::hot_spot(runs[0], 0.75e-3);
        if (kind != 0) {
            CHECK(one.temperature == (kind == 1 ? 345.06126582478936 : 512.0));
            CHECK(one.centre == runs[0].particles()[0].get<position>());
        }
        for (std::size_t k = 1; k < runs.size(); ++k) {
            const auto r = gimlet::diagnostics::hot_spot(runs[k], 0.75e-3);
            INFO("temperatures " << kind << ", threads " << k + 1);
            CHECK(r.temperature == one.temperature);
            CHECK(r.centre == one.centre);
            CHECK(r.particles == one.particles);
        }
        // Sought above a running peak just under the hottest disc (the centres then skipped
        // in parallel): the same disc on every thread count.
        const double peak = std::nextafter(one.temperature, 0.0);
        for (std::size_t k = 0; k < runs.size(); ++k) {
            const auto r = gimlet::diagnostics::hot_spot(runs[k], 0.75e-3, peak);
            INFO("temperatures " << kind << ", threads " << k + 1 << ", above the peak");
            CHECK(r.temperature == one.temperature);
            CHECK(r.centre == one.centre);
            CHECK(r.particles == one.particles);
        }
    }
    // The hottest particle with NaN temperatures (the solver would have stopped; a user's
    // field need not come from it): a NaN is never taken, on every thread count, also where
    // it opens a block of the parallel pass (its first particle on 2 and 3 threads) and the
    // hottest particle lies in that block, just after it, and where particle 0's is NaN.
    const std::size_t n = runs[0].particles().size();
    const std::size_t hottest = (n + 1) / 2 + 1;  // in block 1 of 2 and of 3
    for (const bool nan_first : {false, true}) {
        for (auto& run : runs)
            for (std::size_t i = 0; i < n; ++i)
                run.particles()[i].get<temperature>() =
                    i % 97 == 3 || i == (n + 1) / 2 || i == (n + 2) / 3 || (nan_first && i == 0)
                        ? std::numeric_limits<double>::quiet_NaN()
                        : i == hottest ? 500.0 : 300.0 + double(i % 89);
        for (std::size_t k = 0; k < runs.size(); ++k) {
            INFO("NaN temperatures, threads " << k + 1 << ", NaN at particle 0: " << nan_first);
            CHECK(gimlet::diagnostics::hot_spot(runs[k], 0.75e-3).max_temperature == 500.0);
        }
    }
    // Every temperature NaN: no hottest particle (NaN) and no disc.
    for (std::size_t k = 0; k < runs.size(); ++k) {
        for (std::size_t i = 0; i < n; ++i) runs[k].particles()[i].get<temperature>() = std::numeric_limits<double>::quiet_NaN();
        const auto r = gimlet::diagnostics::hot_spot(runs[k], 0.75e-3);
        INFO("every temperature NaN, threads " << k + 1);
        CHECK(std::isnan(r.max_temperature));
        CHECK(r.temperature == -std::numeric_limits<double>::infinity());
        CHECK(r.particles == 0);
    }
}

TEST_CASE("solver::timings: every phase counted, the parts of P2G within it", "[diagnostics]") {
    // The scene above, three steps: each phase is a non-negative time, the step's phases are
    // there (P2G, G2P and the material update each took some time), and the
    // weights and the slabs, counted in P2G too, are parts of it.
    auto sol = two_blocks(2, 2);
    const double dt = 0.2 * sol.stable_time_step();
    for (int k = 0; k < 3; ++k) sol.step(dt);
    const auto& t = sol.timings();
    for (const double phase : {t.sort, t.particle_to_grid, t.grid_update, t.contact, t.grid_to_particle,
                               t.material_update, t.weights, t.slabs})
        CHECK(phase >= 0.0);
    CHECK(t.particle_to_grid > 0.0);
    CHECK(t.grid_to_particle > 0.0);
    CHECK(t.material_update > 0.0);
    CHECK(t.weights > 0.0);
    CHECK(t.slabs > 0.0);  // the bucketing runs every step
    CHECK(t.weights + t.slabs < t.particle_to_grid);  // the clearing and the scatters are the rest
}

TEST_CASE("hot_spot: a workspace reused across calls, scenes and radii gives each call's own answer", "[diagnostics]") {
    // One workspace passed to calls on two scenes of different sizes (2 x 2 and 4 x 4
    // particles per cell, the larger searched on 3 threads), at three radii, without a running
    // peak, and with one just under the hottest disc, at it and above it (where the disc named
    // depends on which centres the bins' maxima skip), in an order that grows and shrinks every
    // scratch array: each answer is bit for bit that of a call with scratch of its own.
    auto small = two_blocks(2, 2);
    std::vector<solver> large = on_1_2_3_threads();
    for (auto* sol : {&small, &large[2]}) {
        std::uint64_t state = 99;
        for (std::size_t i = 0; i < sol->particles().size(); ++i) {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            sol->particles()[i].get<temperature>() = 300.0 + double((state >> 40) % 997) * 0.5;
        }
    }
    gimlet::diagnostics::hot_spot_workspace<S::vector> work;
    for (const double radius : {0.75e-3, 2e-3, 0.3e-3})
        for (auto* sol : {&large[2], &small, &large[2]}) {
            const double hottest_disc = gimlet::diagnostics::hot_spot(*sol, radius).temperature;
            for (const int peak : {0, 1, 2, 3}) {
                const double above = peak == 0   ? -std::numeric_limits<double>::infinity()
                                     : peak == 1 ? std::nextafter(hottest_disc, 0.0)
                                     : peak == 2 ? hottest_disc
                                                 : hottest_disc + 100.0;
                const auto fresh = gimlet::diagnostics::hot_spot(*sol, radius, above);
                const auto reused = gimlet::diagnostics::hot_spot(*sol, radius, above, work);
                INFO("radius " << radius << ", " << sol->particles().size() << " particles, above " << above);
                CHECK(reused.temperature == fresh.temperature);
                CHECK(reused.max_temperature == fresh.max_temperature);
                CHECK(reused.centre == fresh.centre);
                CHECK(reused.particles == fresh.particles);
            }
        }
}

TEST_CASE("hot_spot: a call on a field of NaN leaves a workspace that gives the next call its own answer", "[diagnostics][threads]") {
    // A field whose every temperature is NaN names no disc and skips the bins' passes, leaving
    // the workspace's bins from the call before; the next call on a finite field, on 3 threads,
    // must not read them.
    std::vector<solver> sols = on_1_2_3_threads();
    auto& sol = sols[2];
    std::uint64_t state = 7;
    for (std::size_t i = 0; i < sol.particles().size(); ++i) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        sol.particles()[i].get<temperature>() = 300.0 + double((state >> 40) % 991) * 0.25;
    }
    std::vector<double> finite(sol.particles().size());
    for (std::size_t i = 0; i < finite.size(); ++i) finite[i] = sol.particles()[i].get<temperature>();
    gimlet::diagnostics::hot_spot_workspace<S::vector> work;
    const auto before = gimlet::diagnostics::hot_spot(sol, 2e-3, -std::numeric_limits<double>::infinity(), work);
    for (std::size_t i = 0; i < finite.size(); ++i)
        sol.particles()[i].get<temperature>() = std::numeric_limits<double>::quiet_NaN();
    const auto none = gimlet::diagnostics::hot_spot(sol, 0.5e-3, -std::numeric_limits<double>::infinity(), work);
    CHECK(none.particles == 0);
    CHECK(std::isnan(none.max_temperature));
    for (std::size_t i = 0; i < finite.size(); ++i) sol.particles()[i].get<temperature>() = finite[i] + 1.0;
    const auto reused = gimlet::diagnostics::hot_spot(sol, 0.75e-3, -std::numeric_limits<double>::infinity(), work);
    const auto fresh = gimlet::diagnostics::hot_spot(sol, 0.75e-3);
    CHECK(reused.temperature == fresh.temperature);
    CHECK(reused.max_temperature == fresh.max_temperature);
    CHECK(reused.centre == fresh.centre);
    CHECK(reused.particles == fresh.particles);
    CHECK(before.particles > 0);
}

TEST_CASE("hot_spot: a radius too small for its bins is refused by name, from inside the threads' region", "[diagnostics][threads]") {
    // The bins are counted by one thread inside the parallel region; the error must reach the
    // caller as an exception (one that left the region would end the program).
    std::vector<solver> sols = on_1_2_3_threads();
    for (auto& sol : sols) {
        for (std::size_t i = 0; i < sol.particles().size(); ++i) sol.particles()[i].get<temperature>() = 300.0;
        CHECK_THROWS_WITH(gimlet::diagnostics::hot_spot(sol, 1e-12),
                          Catch::Matchers::Contains("hot-spot radius (m) = 1e-12 is invalid") && Catch::Matchers::Contains("valid range"));
    }
}

TEST_CASE("surface_gap, void_chord and hot_material: the same walls, speeds and sums on 1, 2 and 3 threads", "[diagnostics][threads]") {
    // The scene of the test above (7,000 and more particles: the strips are gathered on the
    // threads), each particle given a pseudo-random velocity, the same in every run: the walls'
    // speeds are means over particle layers in the strip's sorted order, so a strip gathered in
    // another order would show in their last bits.
    std::vector<solver> runs = on_1_2_3_threads();
    REQUIRE(runs[0].particles().size() >= 4096);
    std::uint64_t state = 99;
    for (std::size_t i = 0; i < runs[0].particles().size(); ++i) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        const double u = double(state >> 11) * 0x1p-53;
        for (auto& run : runs) {
            auto p = run.particles()[i];
            p.get<velocity>() = S::vector(100.0 * u - 50.0, 37.0 * u * u - 20.0);
            // For hot_material below: unequal masses, temperatures and volumes.
            p.get<gimlet::fields::mass>() *= 0.5 + u;
            p.get<temperature>() = 300.0 + 1000.0 * u;
            p.get<gimlet::fields::deformation_gradient>()(0, 0) = 0.9 + 0.2 * u * u;
        }
    }
    const std::vector<double> levels{400.0, 700.0, 1250.0};
    const auto hot = gimlet::diagnostics::hot_material(runs[0], levels);
    REQUIRE(hot.mass[0] > hot.mass[1]);
    const double strip = 0.6 * h;
    const auto gap = gimlet::diagnostics::surface_gap(runs[0], 0, 1, 1, S::vector(10e-3, 16e-3), strip);
    const auto axial = gimlet::diagnostics::void_chord(runs[0], 0, 1, S::vector(10e-3, 8e-3), strip, 0.25 * h);
    const auto lateral = gimlet::diagnostics::void_chord(runs[0], 0, 0, S::vector(10e-3, 8e-3), strip, 0.25 * h);
    REQUIRE(gap.found);
    REQUIRE(axial.open);
    REQUIRE(lateral.open);
    for (std::size_t k = 1; k < runs.size(); ++k) {
        INFO("threads " << k + 1);
        // The strips themselves, point for point (the sort keeps tied coordinates in the order
        // gathered, so the gathered order must be the serial one).
        for (const std::uint32_t body : {0u, 1u})
            for (const int axis : {0, 1}) {
                const auto mine = gimlet::diagnostics::detail::strip(runs[k], body, axis, S::vector(10e-3, 8e-3), strip);
                const auto one = gimlet::diagnostics::detail::strip(runs[0], body, axis, S::vector(10e-3, 8e-3), strip);
                REQUIRE(mine.size() == one.size());
                bool same = true;
                for (std::size_t q = 0; q < one.size(); ++q)
                    same = same && mine[q].coordinate == one[q].coordinate && mine[q].velocity == one[q].velocity &&
                           mine[q].half_spacing == one[q].half_spacing;
                CHECK(same);
            }
        const auto g = gimlet::diagnostics::surface_gap(runs[k], 0, 1, 1, S::vector(10e-3, 16e-3), strip);
        const auto above = gimlet::diagnostics::hot_material(runs[k], levels);
        CHECK(above.mass == hot.mass);
        CHECK(above.volume == hot.volume);
        CHECK(g.found);
        CHECK(g.lower_surface == gap.lower_surface);
        CHECK(g.upper_surface == gap.upper_surface);
        for (const auto& [mine, one] : {std::pair{gimlet::diagnostics::void_chord(runs[k], 0, 1, S::vector(10e-3, 8e-3), strip, 0.25 * h), axial},
                                        std::pair{gimlet::diagnostics::void_chord(runs[k], 0, 0, S::vector(10e-3, 8e-3), strip, 0.25 * h), lateral}}) {
            CHECK(mine.open == one.open);
            CHECK(mine.lower_wall == one.lower_wall);
            CHECK(mine.upper_wall == one.upper_wall);
            CHECK(mine.lower_wall_velocity == one.lower_wall_velocity);
            CHECK(mine.upper_wall_velocity == one.upper_wall_velocity);
        }
    }
    // void_chords, the lines' strips gathered in one pass: each line's chord is void_chord's
    // alone on one thread, bit for bit, on every thread count (an open cavity's two chords and
    // a closed line through the other body, so a strip mixed up between lines would show).
    const std::vector<gimlet::diagnostics::chord_line<S::vector>> lines{
        {0, 1, S::vector(10e-3, 8e-3)}, {1, 1, S::vector(10e-3, 24e-3)}, {0, 0, S::vector(10e-3, 8e-3)}};
    for (std::size_t k = 0; k < runs.size(); ++k) {
        INFO("threads " << k + 1);
        const auto all = gimlet::diagnostics::void_chords(runs[k], lines, strip, 0.25 * h);
        REQUIRE(all.size() == lines.size());
        for (std::size_t j = 0; j < lines.size(); ++j) {
            INFO("line " << j);
            const auto one = gimlet::diagnostics::void_chord(runs[0], lines[j].body, lines[j].axis, lines[j].point, strip, 0.25 * h);
            CHECK(all[j].open == one.open);
            CHECK(all[j].lower_wall == one.lower_wall);
            CHECK(all[j].upper_wall == one.upper_wall);
            CHECK(all[j].lower_wall_velocity == one.lower_wall_velocity);
            CHECK(all[j].upper_wall_velocity == one.upper_wall_velocity);
        }
        CHECK(all[0].open);
        CHECK_FALSE(all[1].open);
    }
    CHECK(gimlet::diagnostics::void_chords(runs[0], {}, strip, 0.25 * h).empty());
    CHECK_THROWS_WITH(gimlet::diagnostics::void_chords(runs[0], {}, 0.0, 0.25 * h), Catch::Contains("strip half-width"));
}

// What diagnostics::hot_spot reads of a solver, and nothing else: particles with positions,
// masses and temperatures, and a thread count. It tries the observer in 3-D and with unequal
// masses (whose sums round differently in any other order) without compiling a solver.
// (particles_of: a store of the given fields and a thread count, all an observer reads.)
template <int Dim, class Real, class... Fields>
struct particles_of {
    using S = gimlet::space<Dim, Real>;
    using vector = typename S::vector;
    using store_type = gimlet::particle_store<S, gimlet::field_list<Fields...>>;
    static constexpr int dim = Dim;
    store_type store;
    gimlet::solver_options<S> opt;
    [[nodiscard]] const store_type& particles() const { return store; }
    [[nodiscard]] const gimlet::solver_options<S>& options() const { return opt; }
};
template <int Dim>
using particles_only = particles_of<Dim, double, gimlet::fields::position, gimlet::fields::mass, gimlet::fields::temperature>;

TEMPLATE_TEST_CASE_SIG("hot_spot in 2-D and 3-D, unequal masses: the brute-force disc, the same bits on 1, 2 and 3 threads",
                       "[diagnostics][threads]", ((int Dim), Dim), 2, 3) {
    // 6,000 particles scattered in a box of 12 mm (the bins, the sort and the centres then run
    // on the threads), masses and temperatures from a fixed pseudo-random sequence, a few hot
    // clusters. The disc the observer names equals a search over every centre, and 1, 2 and 3
    // threads give the same mean to the bit: the sums run in the same order (by bin, then by
    // index) whatever the blocks.
    particles_only<Dim> run;
    auto& st = run.store;
    sequence next{2024};
    for (int k = 0; k < 6000; ++k) {
        auto p = st[st.add()];
        auto& x = p.template get<gimlet::fields::position>();
        for (int d = 0; d < Dim; ++d) x[d] = 12e-3 * next() - 2e-3;
        p.template get<gimlet::fields::mass>() = 1e-6 * (0.5 + next());
        const double u = next();
        p.template get<gimlet::fields::temperature>() = u < 0.03 ? 400.0 + 2000.0 * next() : 300.0 + 50.0 * u;
    }
    const double radius = Dim == 2 ? 0.4e-3 : 1.5e-3;
    const auto& xs = st.template column<gimlet::fields::position>();
    const auto& ms = st.template column<gimlet::fields::mass>();
    const auto& ts = st.template column<gimlet::fields::temperature>();
    auto disc = [&](const auto& c, std::size_t& count) {
        double mass = 0, heat = 0;
        count = 0;
        for (std::size_t q = 0; q < st.size(); ++q)
            if ((xs[q] - c).squaredNorm() <= radius * radius) mass += ms[q], heat += ms[q] * ts[q], ++count;
        return heat / mass;
    };
    double best = -1;
    for (std::size_t i = 0; i < st.size(); ++i) {
        std::size_t c = 0;
        best = std::max(best, disc(xs[i], c));
    }
    run.opt.threads = 1;
    const auto one = gimlet::diagnostics::hot_spot(run, radius);
    std::size_t count = 0;
    CHECK(one.temperature == Approx(best).epsilon(1e-12));
    CHECK(disc(one.centre, count) == Approx(one.temperature).epsilon(1e-12));
    CHECK(count == one.particles);
    CHECK(one.max_temperature == *std::max_element(ts.begin(), ts.end()));
    // The named disc's mean summed in the documented order, to the bit: bins of side `radius`
    // from the particles' lowest corner, the bins around the centre's with the first axis
    // fastest, each bin's particles by index, relative to the hottest particle of those bins.
    {
        typename particles_only<Dim>::vector lo = xs[0];
        for (const auto& x : xs) lo = lo.cwiseMin(x);
        auto bin_of = [&](const auto& x, int d) { return long(double(x[d] - lo[d]) / radius); };
        std::array<long, 3> centre_bin{}, at{};
        for (int d = 0; d < Dim; ++d) centre_bin[std::size_t(d)] = bin_of(one.centre, d);
        auto each_around = [&](auto&& f) {  // f(q) for the particles of the bins around, in order
            for (at[2] = Dim == 3 ? centre_bin[2] - 1 : 0; at[2] <= (Dim == 3 ? centre_bin[2] + 1 : 0); ++at[2])
                for (at[1] = centre_bin[1] - 1; at[1] <= centre_bin[1] + 1; ++at[1])
                    for (at[0] = centre_bin[0] - 1; at[0] <= centre_bin[0] + 1; ++at[0])
                        for (std::size_t q = 0; q < st.size(); ++q) {
                            bool in_bin = true;
                            for (int d = 0; d < Dim; ++d) in_bin = in_bin && bin_of(xs[q], d) == at[std::size_t(d)];
                            if (in_bin) f(q);
                        }
        };
        double ref = -std::numeric_limits<double>::infinity();
        each_around([&](std::size_t q) { ref = std::max(ref, double(ts[q])); });
        if (!std::isfinite(ref)) ref = 0;
        double mass = 0, excess = 0;
        each_around([&](std::size_t q) {
            if (double((xs[q] - one.centre).squaredNorm()) > radius * radius) return;
            mass += double(ms[q]);
            excess += double(ms[q]) * (double(ts[q]) - ref);
        });
        CHECK(ref + excess / mass == one.temperature);
        CHECK(one.temperature <= ref);
    }
    for (const int threads : {2, 3}) {
        run.opt.threads = threads;
        for (const double above : {-std::numeric_limits<double>::infinity(), std::nextafter(one.temperature, 0.0)}) {
            const auto r = gimlet::diagnostics::hot_spot(run, radius, above);
            INFO("threads " << threads << ", above " << above);
            CHECK(r.temperature == one.temperature);
            CHECK(r.centre == one.centre);
            CHECK(r.particles == one.particles);
            CHECK(r.max_temperature == one.max_temperature);
        }
    }
    // No particles: no disc and no hottest particle, as where every temperature is NaN.
    particles_only<Dim> none;
    const auto empty = gimlet::diagnostics::hot_spot(none, radius);
    CHECK(empty.temperature == -std::numeric_limits<double>::infinity());
    CHECK(std::isnan(empty.max_temperature));
    CHECK(empty.particles == 0);
}

// What diagnostics::detail::strips reads of a solver: positions, velocities, bodies, initial
// volumes and a thread count.
template <int Dim, class Real>
using strip_particles =
    particles_of<Dim, Real, gimlet::fields::position, gimlet::fields::velocity, gimlet::fields::body, gimlet::fields::volume0>;

TEMPLATE_TEST_CASE_SIG("strips: the points of the plain membership test, with particles on the strips' edges, in 2-D and 3-D",
                       "[diagnostics][threads]", ((int Dim, class Real), Dim, Real), (2, double), (3, double), (2, float),
                       (3, float)) {
    // strips passes over a particle outside a box around each body's strips before the exact
    // test (surfaces.hpp). Each strip must hold what testing every particle against every line
    // gives, in the same order. The lines:
    //   - body 0: three along the first axis, 0.3 mm wide;
    //   - body 2: three along the last axis, 0.3 mm wide;
    //   - body 3: two along the first axis, through points near zero on either side of it and
    //     as narrow as 2^-18 m (3.8 µm), where x - p rounds in float;
    //   - body 4: one along each axis (a box open in every dimension).
    // Body 1 has no line. Of 8,000 particles, a third lie anywhere, a third within a line's
    // strip and a third on its edges: on the value p +- w in the solver's precision, or one or
    // two representable steps to either side, where the exact test decides. Their coordinates
    // along the lines fall on a 0.1 mm grid, so that many points tie in each strip and a strip
    // gathered in another order would sort differently.
    using particles = strip_particles<Dim, Real>;
    using vector = typename particles::vector;
    particles run;
    auto& st = run.store;
    sequence next{77};
    std::vector<gimlet::diagnostics::detail::strip_line<vector>> lines;
    for (std::uint32_t body : {0u, 2u})
        for (int k = 0; k < 3; ++k) {
            vector point;
            for (int d = 0; d < Dim; ++d) point[d] = Real(1e-3 * (2.0 + 3.0 * k + 0.7 * d + 0.1 * body));
            lines.push_back({body, body == 0 ? 0 : Dim - 1, point, 0.3e-3});
        }
    for (const double near_zero : {-2.51743313e-6, 1.7e-6}) {
        vector point;
        for (int d = 0; d < Dim; ++d) point[d] = Real(near_zero * (1.0 + 0.3 * d));
        lines.push_back({3, 0, point, std::ldexp(1.0, -18)});
    }
    for (int axis = 0; axis < Dim; ++axis) {
        vector point;
        for (int d = 0; d < Dim; ++d) point[d] = Real(5e-3 + 1e-3 * axis);
        lines.push_back({4, axis, point, 0.2e-3});
    }
    const std::uint32_t bodies[] = {0, 1, 2, 3, 4};
    for (int q = 0; q < 8000; ++q) {
        auto p = st[st.add()];
        p.template get<gimlet::fields::volume0>() = Real(std::pow(0.25e-3 * (0.5 + next()), Dim));
        auto& v = p.template get<gimlet::fields::velocity>();
        for (int d = 0; d < Dim; ++d) v[d] = Real(100.0 * next() - 50.0);
        auto& x = p.template get<gimlet::fields::position>();
        for (int d = 0; d < Dim; ++d) x[d] = Real(0.1e-3 * std::floor(120.0 * next()));
        std::uint32_t body = bodies[std::size_t(next() * 5.0)];
        if (q % 3 != 0) {  // near a line, in its body
            const auto& line = lines[std::size_t(next() * double(lines.size()))];
            body = line.body;
            for (int d = 0; d < Dim; ++d) {
                if (d == line.axis) continue;
                const Real w = Real(line.half_width);
                if (q % 3 == 2) {
                    x[d] = line.point[d] + Real(double(w) * (2.0 * next() - 1.0));
                    continue;
                }
                Real edge = next() < 0.5 ? Real(line.point[d] - w) : Real(line.point[d] + w);
                const double step = next();
                const Real away = step < 0.5 ? -1 : 1;
                if (step < 0.2 || step > 0.8) edge = std::nextafter(edge, edge + away);
                if (step < 0.1 || step > 0.9) edge = std::nextafter(edge, edge + away);
                if (step > 0.4 && step < 0.6) edge = std::nextafter(edge, edge - away);
                x[d] = edge;
            }
        }
        p.template get<gimlet::fields::body>() = body;
    }
    const auto& xs = st.template column<gimlet::fields::position>();
    const auto& vs = st.template column<gimlet::fields::velocity>();
    const auto& bs = st.template column<gimlet::fields::body>();
    const auto& v0 = st.template column<gimlet::fields::volume0>();
    for (const int threads : {1, 2, 3}) {
        run.opt.threads = threads;
        const auto found = gimlet::diagnostics::detail::strips(run, lines);
        REQUIRE(found.size() == lines.size());
        for (std::size_t j = 0; j < lines.size(); ++j) {
            INFO("threads " << threads << ", line " << j);
            const auto& line = lines[j];
            std::vector<gimlet::diagnostics::detail::strip_point> plain;
            for (std::size_t q = 0; q < st.size(); ++q) {
                if (bs[q] != line.body) continue;
                bool inside = true;
                for (int d = 0; d < Dim; ++d)
                    if (d != line.axis && std::abs(double(xs[q][d] - line.point[d])) > line.half_width) inside = false;
                if (inside)
                    plain.push_back({double(xs[q][line.axis]), 0.5 * std::pow(double(v0[q]), 1.0 / Dim), double(vs[q][line.axis])});
            }
            std::sort(plain.begin(), plain.end());  // as strips sorts the points it gathered in this order
            CHECK(plain.size() >= 10);  // every strip holds points: the comparison means something
            REQUIRE(found[j].size() == plain.size());
            bool same = true;
            for (std::size_t k = 0; k < plain.size(); ++k)
                same = same && found[j][k].coordinate == plain[k].coordinate && found[j][k].velocity == plain[k].velocity &&
                       found[j][k].half_spacing == plain[k].half_spacing;
            CHECK(same);
        }
    }
    // A line through a point that is not finite: the exact test takes every particle of its
    // body (no comparison with NaN holds), and so must the box.
    vector nan_point;
    for (int d = 0; d < Dim; ++d) nan_point[d] = std::numeric_limits<Real>::quiet_NaN();
    std::size_t of_body_0 = 0;
    for (std::size_t q = 0; q < st.size(); ++q) of_body_0 += bs[q] == 0;
    CHECK(gimlet::diagnostics::detail::strips(run, {{0, 0, nan_point, 0.3e-3}})[0].size() == of_body_0);
}

TEST_CASE("hot_spot: a disc before the hottest particle that ties with its disc is not skipped", "[diagnostics]") {
    // Unit masses. Particles 0-2 at 400 K, close together: their discs hold only them, and
    // their bins' hottest particle is 400 K. Far away, particle 3 at 1000 K with six at 300 K
    // within 0.01 mm of it: every disc there holds all seven, (1000 + 6 x 300) / 7 = 400 K
    // exactly, and its bins' hottest particle is 1000 K. All ten discs tie at 400 K, the floor
    // is particle 3's disc, and particles 0-2, whose bins are as hot as the floor and which
    // come before particle 3, must be tried: the lowest index, particle 0, wins.
    particles_only<2> run;
    auto& st = run.store;
    auto add = [&](double x, double y, double t) {
        auto p = st[st.add()];
        p.get<position>() = particles_only<2>::vector(x, y);
        p.get<gimlet::fields::mass>() = 1.0;
        p.get<temperature>() = t;
    };
    add(0.0, 0.0, 400.0);
    add(0.1e-3, 0.0, 400.0);
    add(0.0, 0.1e-3, 400.0);
    add(50e-3, 0.0, 1000.0);
    for (int k = 0; k < 6; ++k) add(50e-3 + 0.01e-3 * std::cos(k * 1.0471975511965976), 0.01e-3 * std::sin(k * 1.0471975511965976), 300.0);
    for (const double above : {-std::numeric_limits<double>::infinity(), 399.0}) {
        const auto r = gimlet::diagnostics::hot_spot(run, 1e-3, above);
        INFO("above " << above);
        CHECK(r.temperature == 400.0);
        CHECK(r.centre == st[0].get<position>());
        CHECK(r.particles == 3);
        CHECK(r.max_temperature == 1000.0);
    }
}

TEST_CASE("hot_material: the mass and current area hotter than each temperature", "[diagnostics]") {
    auto sol = two_blocks(2, 2);
    auto& ps = sol.particles();
    // A 3 mm disc at 800 K in the upper block, a ring around it at 500 K, the rest at 300 K.
    const S::vector hot(6e-3, 24e-3);
    double mass_800 = 0, mass_500 = 0, area_800 = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        auto p = ps[i];
        const double r = (p.get<position>() - hot).norm();
        p.get<temperature>() = r < 3e-3 ? 800.0 : (r < 4e-3 ? 500.0 : 300.0);
        if (r < 4e-3) mass_500 += p.get<gimlet::fields::mass>();
        if (r < 3e-3) {
            mass_800 += p.get<gimlet::fields::mass>();
            area_800 += p.get<gimlet::fields::volume0>();
        }
    }
    const auto m = gimlet::diagnostics::hot_material(sol, {299.0, 400.0, 700.0, 800.0});
    CHECK(m.mass[0] == Approx(gimlet::diagnostics::total_mass(sol)).epsilon(1e-12));
    CHECK(m.mass[1] == Approx(mass_500).epsilon(1e-12));
    CHECK(m.mass[2] == Approx(mass_800).epsilon(1e-12));
    CHECK(m.mass[3] == 0.0);  // strictly hotter
    CHECK(m.volume[2] == Approx(area_800).epsilon(1e-12));  // F = I: the current area is V0
    // About pi (3 mm)^2 of material, to the particle spacing.
    CHECK(m.volume[2] == Approx(3.14159265 * 9e-6).epsilon(0.05));
}

TEST_CASE("progress: reports step, time and time left, and when the run is done", "[diagnostics]") {
    auto sol = two_blocks(1, 1);
    std::ostringstream out;
    gimlet::diagnostics::progress bar(out, 1e-6, 1e-9);  // report at (almost) every step
    sol.run_until(1e-6, bar);
    const std::string text = out.str();
    CHECK(text.find("left") != std::string::npos);
    CHECK(text.find("of 1.000 us") != std::string::npos);
    CHECK(text.find("t = 1.000 us: done") != std::string::npos);
    CHECK_THROWS_WITH(gimlet::diagnostics::progress(out, 0.0), Catch::Contains("progress end time"));
}
