// SPDX-License-Identifier: MIT
// The cavity_collapse binary's run-time choices (--contact, --temperature) are policies that
// forward each call to the library's policy the flag names (examples/cavity_collapse/
// cavity_collapse.hpp): each answer and each temperature must be that policy's, to the bit.
#include "cavity_collapse/cavity_collapse.hpp"

#include <catch2/catch.hpp>

#include <bit>
#include <cstdint>
#include <stdexcept>

namespace {

using S = cavity_collapse::S;
using cavity_collapse::chosen_law;
using cavity_collapse::chosen_temperature;
using cavity_collapse::contact_kind;

gimlet::contact::pair_view<S> pair_at_gap(double gap_in_cells) {
    gimlet::contact::pair_view<S> pair;
    pair.cell = 1e-3;
    pair.gap = gap_in_cells * pair.cell;
    pair.mass_a = pair.mass_b = 1e-3;
    pair.normal = S::vector(0.0, 1.0);
    pair.velocity_a = S::vector(0.0, 10.0);
    return pair;
}

// One HMX particle with a temperature, as the solver's store holds it.
struct point {
    using fields = gimlet::field_union_t<gimlet::core_fields<S>, gimlet::field_list<gimlet::fields::temperature>>;
    gimlet::particle_store<S, fields> store;
    point() { store.add(); }
    [[nodiscard]] auto p() { return store[0]; }
    [[nodiscard]] std::uint64_t temperature_bits() {
        return std::bit_cast<std::uint64_t>(double(p().get<gimlet::fields::temperature>()));
    }
};

// A compression step with plastic work, from the initial state.
template <class Thermal>
std::uint64_t after_step(const Thermal& thermal) {
    const gimlet::presets::hmx_constants c{};
    point pt;
    thermal.initialize(pt.p());
    pt.p().get<gimlet::fields::specific_internal_energy>() = 5.0e4;  // above e_s(0.93), about 2.7e4 J/kg
    gimlet::point_step<double> st;
    st.J_old = 0.95;
    st.J = 0.93;
    st.density0 = c.density;
    st.density = c.density / st.J;
    st.shear_energy = 150.0;
    thermal.update(st, 30.0, pt.p());
    return pt.temperature_bits();
}

}  // namespace

TEST_CASE("cavity_collapse's chosen law answers as the law --contact names", "[examples]") {
    const gimlet::contact::bardenhagen bardenhagen;
    const gimlet::contact::distance distance;
    const chosen_law as_bardenhagen(contact_kind::bardenhagen), as_distance(contact_kind::distance);
    // Within the distance switch's half cell, and two cells apart: only Bardenhagen's law engages
    // the second pair, so a law mixed up fails here.
    for (const double gap : {0.25, 2.0}) {
        const auto pair = pair_at_gap(gap);
        INFO("gap " << gap << " cells");
        CHECK(as_bardenhagen.in_contact(pair) == bardenhagen.in_contact(pair));
        CHECK(as_distance.in_contact(pair) == distance.in_contact(pair));
    }
    CHECK(as_bardenhagen.in_contact(pair_at_gap(2.0)));
    CHECK_FALSE(as_distance.in_contact(pair_at_gap(2.0)));
    CHECK(as_bardenhagen.friction() == bardenhagen.friction());
    CHECK(as_distance.friction() == distance.friction());
    CHECK_THROWS_AS(chosen_law(contact_kind::single), std::invalid_argument);
}

TEST_CASE("cavity_collapse's chosen temperature is the isentrope's or the paper's, to the bit", "[examples]") {
    const gimlet::presets::hmx_constants c{};
    const gimlet::thermal::isentrope_temperature isentrope(c.density, c.sound_speed, c.slope, c.gruneisen,
                                                           c.specific_heat, c.temperature);
    const gimlet::presets::paper_temperature paper(c.density, c.sound_speed, c.slope, c.gruneisen, c.specific_heat,
                                                     c.temperature);
    chosen_temperature chosen(c.density, c.sound_speed, c.slope, c.gruneisen, c.specific_heat, c.temperature);
    // The two forms differ after this step (the paper's adds the plastic work, the isentrope's
    // reads it from e), so a mixed-up choice fails here.
    REQUIRE(after_step(isentrope) != after_step(paper));
    CHECK_FALSE(chosen.uses_paper());
    CHECK(after_step(chosen) == after_step(isentrope));
    CHECK(chosen.reference_energy(0.93) == isentrope.reference_energy(0.93));
    chosen.use_paper(true);
    CHECK(after_step(chosen) == after_step(paper));
    // Its reference energy is the isentrope's, for the volume filter; with the paper's temperature
    // there is none.
    CHECK_THROWS_AS(chosen.reference_energy(0.93), std::logic_error);
    // The binary's scene carries the temperature --temperature named.
    for (const bool paper_flag : {false, true}) {
        cavity_collapse::settings flags;
        flags.paper_temperature = paper_flag;
        const auto scene = cavity_collapse::make_scene<cavity_collapse::run_material>(flags);
        for (const auto& body : scene.bodies()) CHECK(body.material.thermal.uses_paper() == paper_flag);
    }
    // The volume filter needs the isentrope: refused with the paper's temperature, by name.
    cavity_collapse::settings s;
    s.paper_temperature = true;
    s.volume_filter = true;
    CHECK_THROWS_WITH(cavity_collapse::validate(s), Catch::Contains("--volume-filter with --temperature paper"));
    s.paper_temperature = false;
    CHECK_NOTHROW(cavity_collapse::validate(s));
}
