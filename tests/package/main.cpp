// SPDX-License-Identifier: MIT
// Consumer of an installed gimlet: the umbrella header must be found, compile, and work. It
// writes its own contact law the way docs/concepts.md teaches one (contact::Law), with its own
// per-particle field and counters, and checks what the framework promises: the law's counters
// and field are written, momentum is conserved and no energy is created.
#include <gimlet/gimlet.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>

namespace {

using S = gimlet::space<2, double>;

// How many steps each particle spent touching another body.
struct contact_steps {
    template <class Sp>
    using type = typename Sp::real;
    static constexpr const char* name = "contact_steps";
};

// Contact once the facing particle centres are within a cell, with Coulomb friction 0.2; it
// counts the pairs it engaged and the normal impulse it took, and marks its particles.
struct counting_contact {
    static constexpr bool multi_field = true;
    using required_fields = gimlet::field_list<contact_steps>;

    template <gimlet::Space Sp>
    [[nodiscard]] bool in_contact(const gimlet::contact::pair_view<Sp>& pair) const {
        return pair.gap <= pair.cell;
    }
    [[nodiscard]] double friction() const { return 0.2; }

    struct tally {
        std::uint64_t pairs = 0;
        double impulse = 0;  // N s (per unit thickness)
        tally& operator+=(const tally& other) {
            pairs += other.pairs;
            impulse += other.impulse;
            return *this;
        }
    };
    template <gimlet::Space Sp>
    void count(tally& t, const gimlet::contact::pair_view<Sp>& pair,
               const gimlet::contact::pair_outcome<Sp>& outcome) const {
        ++t.pairs;
        t.impulse -= double(outcome.impulse.dot(pair.normal));
    }
    void record(const tally& t) { total += t; }

    template <class P, gimlet::Space Sp>
    void after_contact(const P& p, const gimlet::contact::particle_contact<Sp>& info) const {
        if (info.engaged) p.template get<contact_steps>() += 1;
    }

    tally total;
};
static_assert(gimlet::contact::check<counting_contact>());

}  // namespace

int main() {
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector(0.04, 0.30);
    gs.cell = 0.01;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    const auto mat = gimlet::make_elastic_material(1000.0, 1e6, 0.3);
    sc.add_body(gimlet::scene::box<S>(S::vector(0.0, 0.05), S::vector(0.04, 0.15)), mat, S::vector(0.2, 1.0));
    sc.add_body(gimlet::scene::box<S>(S::vector(0.0, 0.15), S::vector(0.04, 0.25)), mat, S::vector(-0.2, -1.0));
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, counting_contact> sol(sc);
    const auto p0 = gimlet::diagnostics::linear_momentum(sol);
    const double e0 = gimlet::diagnostics::kinetic_energy(sol);
    double peak = 0;
    while (sol.time() < 0.01) {
        sol.step();
        peak = std::max(peak, (gimlet::diagnostics::kinetic_energy(sol) + gimlet::diagnostics::internal_energy(sol)) / e0);
    }
    double marked = 0;
    for (double n : sol.particles().column<contact_steps>()) marked += n > 0;
    const double dp = (gimlet::diagnostics::linear_momentum(sol) - p0).norm();
    const auto& counted = sol.contact().total;
    std::printf("user contact law: %llu pairs engaged, normal impulse %.3e N s, %g particles marked, "
                "|P - P0| = %.2e, largest (KE + IE) / KE0 = %.4f\n",
                static_cast<unsigned long long>(counted.pairs), counted.impulse, marked, dp, peak);
    const bool ok = counted.pairs > 0 && counted.impulse > 0 && marked > 0 && dp <= 1e-12 && peak <= 1.01;
    return ok ? 0 : 1;
}
