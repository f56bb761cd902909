// SPDX-License-Identifier: MIT
// The reference paper's contact validation at a coarse cell: single-field and Bardenhagen
// contact put a spurious pressure spike at the interface; the distance-switched contact does not.
#include "contact_validation/contact_validation.hpp"

#include <catch2/catch.hpp>

#include <cstdio>

TEST_CASE("contact validation: the distance switch removes the interface pressure spike", "[examples][contact][verification]") {
    contact_validation::settings s;
    s.cell = 2e-3;  // coarse: 20 x 52 cells per block
    const auto single = contact_validation::run<gimlet::contact::single_field>(s, "single");
    const auto barden = contact_validation::run<gimlet::contact::bardenhagen>(s, "bardenhagen");
    const auto dist = contact_validation::run<gimlet::contact::distance>(s, "distance");

    // The plateau's own noise: the largest cell-averaged pressure in the shocked region away from
    // the interface (beyond 4 cells, inside the plateau window), relative to the plateau.
    auto noise_ceiling = [&](const contact_validation::result& r) {
        double top = 0;
        for (const auto& [y, p] : r.cells)
            if (std::abs(y) >= 4 * s.cell && std::abs(y) <= 14 * s.cell) top = std::max(top, p);
        return top / r.plateau;
    };
    for (const auto* r : {&single, &barden, &dist})
        std::printf("contact validation (2 mm cells, 14 us): %-12s interface peak / plateau %.3f "
                    "(particles %.3f), plateau %.3e Pa, plateau noise ceiling %.3f\n",
                    r->policy.c_str(), r->peak_over_plateau, r->particle_peak_over_plateau, r->plateau,
                    noise_ceiling(*r));

    // The plateau is the shocked state (Rankine-Hugoniot: about 2.0 GPa at 300 m/s) for all three.
    for (const auto* r : {&single, &barden, &dist}) CHECK(r->plateau == Approx(2.0e9).epsilon(0.1));
    // Single field and Bardenhagen: a spike far above anything in the plateau.
    CHECK(single.peak_over_plateau > 2.0);
    CHECK(barden.peak_over_plateau > 2.0);
    // Distance-switched: the interface is no higher than the plateau's own noise, and well under
    // half the spikes of the other two. (The bound of 1.05 is below that noise at this cell,
    // where the plateau rings by about +-20 %: measured 1.14 here; the next test holds it where
    // the ringing is smaller than 5 %.)
    CHECK(dist.peak_over_plateau <= noise_ceiling(dist));
    CHECK(dist.peak_over_plateau < 0.5 * single.peak_over_plateau);
    CHECK(dist.peak_over_plateau < 0.5 * barden.peak_over_plateau);
}

// The bound, interface peak over plateau at most 1.05 for the distance switch, needs a
// cell at which the shocked plateau itself is flat to better than 5 %: the FLIP ringing behind
// the shock (docs/reproduction.md, Known differences) puts cell-averaged values of 1.2-1.5 times
// the plateau into the plateau at 2 and 1 mm (the distance policy reads 1.14 and 1.07 there).
// 0.5 mm, the example's default (80 x 100 cells per block), is the coarsest power-of-two cell
// where it is; the full validation run, distance policy only (about 5 s on one core in Release,
// 100 s under ASan/UBSan).
// `long` (release only): its coarse twin under asan-ubsan is the 2 mm test above, which runs
// the same scene and the same distance policy (docs/testing.md).
TEST_CASE("contact validation: the distance switch's interface peak is within 5 % of the plateau at 0.5 mm",
          "[examples][contact][verification][long]") {
    contact_validation::settings s;
    s.cell = 0.5e-3;
    const auto dist = contact_validation::run<gimlet::contact::distance>(s, "distance");
    std::printf("contact validation (0.5 mm cells, 14 us): distance     interface peak / plateau %.3f (particles "
                "%.3f), plateau %.3e Pa\n",
                dist.peak_over_plateau, dist.particle_peak_over_plateau, dist.plateau);
    // Rankine-Hugoniot plateau for HMX at 300 m/s is about 2.0 GPa (as above, 10 %).
    CHECK(dist.plateau == Approx(2.0e9).epsilon(0.1));
    CHECK(dist.peak_over_plateau <= 1.05);
}
