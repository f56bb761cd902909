// SPDX-License-Identifier: MIT
// Velocity fields are not bodies (multi_field::Partition, docs/concepts.md "Velocity fields").
//
// Two elastic blocks stacked along y in a strip periodic in x, touching at y_mid (a grid line)
// and approaching each other at 1 m/s: they collide, and the distance contact separates them
// again. Every particle's state is compared to the bit:
// - split by node (each node's mass in one field, the field chosen by the node's side of a
//   plane) against one field per body: a node holding one field of a body is one velocity
//   field, whatever its index, so nothing may change;
// - ONE body whose particles carry a side tag (the partition's own per-particle field) against
//   TWO bodies of the same particles: contact between two fields of a body is contact between
//   bodies, so nothing may change there either, and the law sees the pairs as self-contact
//   (body_a == body_b, field_a != field_b).
// A partition that names the rows of nodes it splits (split_rows()) gives the same particles to
// the bit as without them, is asked side() of fewer particles, and rows of the wrong size are
// refused.
// uGIMP, 2 x 2 particles per cell, CFL 0.4 (the solver's defaults), every update scheme.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include "tag_partition.hpp"

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace {

using S = gimlet::space<2>;
using vec = S::vector;
namespace f = gimlet::fields;
namespace contact = gimlet::contact;
namespace multi_field = gimlet::multi_field;

constexpr double h = 0.01;             // cell (m)
constexpr int width = 4, length = 10;  // cells across (periodic) and along y per block
constexpr int margin = 4;              // free cells below and above
constexpr double y_mid = (margin + length) * h;

gimlet::elastic_material elastic() { return gimlet::make_elastic_material(1000, 1e6, 0.3); }

gimlet::grid_spec<S> strip_grid() {
    gimlet::grid_spec<S> gs;
    gs.lower = vec::Zero();
    gs.upper = vec(width * h, (2 * margin + 2 * length) * h);
    gs.cell = h;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
    return gs;
}

// The two blocks as two bodies, or as one body spanning both.
gimlet::scene::scene<S, gimlet::elastic_material> blocks(bool one_body) {
    gimlet::scene::scene<S, gimlet::elastic_material> sc(strip_grid());
    const double w = width * h, y0 = margin * h, y1 = y0 + 2 * length * h;
    if (one_body) {
        sc.add_body(gimlet::scene::box<S>(vec(0, y0), vec(w, y1)), elastic(), vec::Zero(), 2, "both");
    } else {
        sc.add_body(gimlet::scene::box<S>(vec(0, y0), vec(w, y_mid)), elastic(), vec::Zero(), 2, "lower");
        sc.add_body(gimlet::scene::box<S>(vec(0, y_mid), vec(w, y1)), elastic(), vec::Zero(), 2, "upper");
    }
    return sc;
}

using gimlet_multi_field_tests::half;  // a user's per-particle field (tag_partition.hpp)

// Splits each body into two fields by the side of y_mid a NODE lies on, whoever scatters there:
// no node ever holds both fields of a body.
struct by_node_side {
    using required_fields = gimlet::field_list<>;
    static constexpr std::size_t fields_per_body = 2;
    template <class P, class V>
    [[nodiscard]] std::size_t side(const P&, std::size_t, const V& node_position) const {
        return node_position[1] < y_mid ? 0 : 1;
    }
};

// by_node_side, naming the rows of nodes where it may answer 1 (split_rows(), refreshed in
// prepare): the solver asks side() only of the particles whose stencils can reach such a row.
// `extra` rows too many (a wrong size) must be refused.
template <std::size_t extra>
struct by_node_side_rows : by_node_side {
    template <class View>
    void prepare(const View& view) {
        const auto& g = view.grid;
        rows.assign(std::size_t(g.nodes(1)) + extra, 0);
        for (int r = 0; r < g.nodes(1); ++r) rows[std::size_t(r)] = g.axis_position(1, r * g.stride(1)) >= y_mid;
    }
    [[nodiscard]] const std::vector<std::uint8_t>& split_rows() const noexcept { return rows; }
    template <class P, class V>
    [[nodiscard]] std::size_t side(const P& p, std::size_t node, const V& node_position) const {
        calls->fetch_add(1, std::memory_order_relaxed);
        return by_node_side::side(p, node, node_position);
    }
    std::vector<std::uint8_t> rows;
    std::shared_ptr<std::atomic<std::uint64_t>> calls = std::make_shared<std::atomic<std::uint64_t>>(0);  // side()'s
};

using gimlet_multi_field_tests::by_tag;  // each body split by the tag (tag_partition.hpp)

// A partition that answers out of range for one particle.
struct broken {
    using required_fields = gimlet::field_list<>;
    static constexpr std::size_t fields_per_body = 2;
    template <class P, class V>
    [[nodiscard]] std::size_t side(const P& p, std::size_t, const V&) const {
        return p.template get<f::position>()[1] > y_mid + 5 * h ? 2 : 0;
    }
};

static_assert(multi_field::Partition<multi_field::by_body> && multi_field::Partition<by_node_side> &&
              multi_field::Partition<by_tag> && multi_field::Partition<by_node_side_rows<0>>);
struct no_side {
    using required_fields = gimlet::field_list<>;
    static constexpr std::size_t fields_per_body = 2;
};
static_assert(!multi_field::Partition<no_side>);

// The distance contact, counting the pairs it engages and those within one body.
struct counted_distance : contact::distance {
    counted_distance() : contact::distance(0.0) {}
    struct tally {
        std::uint64_t pairs = 0, self = 0;
        tally& operator+=(const tally& o) {
            pairs += o.pairs, self += o.self;
            return *this;
        }
    };
    template <gimlet::Space Sp>
    void count(tally& t, const contact::pair_view<Sp>& pair, const contact::pair_outcome<Sp>&) const {
        ++t.pairs;
        if (pair.body_a == pair.body_b && pair.field_a != pair.field_b) ++t.self;
    }
    void record(const tally& t) { total += t; }
    tally total;
};
static_assert(contact::Law<counted_distance> && contact::Counting<counted_distance, S>);

// The blocks approach at 1 m/s each (c_L = 36.7 m/s: the collision lasts 2 L / c_L = 5.4 ms).
template <class Solver>
void set_approach(Solver& sol) {
    auto& ps = sol.particles();
    auto& v = ps.template column<f::velocity>();
    const auto& x = ps.template column<f::position>();
    for (std::size_t i = 0; i < ps.size(); ++i) v[i] = vec(0, x[i][1] < y_mid ? 1.0 : -1.0);
    if constexpr (Solver::store_type::template has<half>) {
        auto& tag = ps.template column<half>();
        for (std::size_t i = 0; i < ps.size(); ++i) tag[i] = x[i][1] < y_mid ? 0 : 1;
    }
}

constexpr double t_end = 8e-3;  // past separation (at about 5.6 ms)

template <class A, class B>
void require_same_particles(const A& a, const B& b) {
    const auto& pa = a.particles();
    const auto& pb = b.particles();
    REQUIRE(pa.size() == pb.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < pa.size(); ++i) {
        differ += pa.template column<f::position>()[i] != pb.template column<f::position>()[i];
        differ += pa.template column<f::velocity>()[i] != pb.template column<f::velocity>()[i];
        differ += pa.template column<f::stress>()[i] != pb.template column<f::stress>()[i];
        differ += pa.template column<f::deformation_gradient>()[i] != pb.template column<f::deformation_gradient>()[i];
        differ += pa.template column<f::specific_internal_energy>()[i] != pb.template column<f::specific_internal_energy>()[i];
    }
    CHECK(differ == 0);
}

// The blocks have separated: the lower block moves down, the upper up.
template <class Solver>
void require_separated(const Solver& sol) {
    const auto& ps = sol.particles();
    const auto& x = ps.template column<f::position>();
    const auto& v = ps.template column<f::velocity>();
    const auto& m = ps.template column<f::mass>();
    double p_lower = 0, p_upper = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) (x[i][1] < y_mid ? p_lower : p_upper) += m[i] * v[i][1];
    CHECK(p_lower < 0);
    CHECK(p_upper > 0);
}

const char* scheme_name(gimlet::update_scheme s) {
    return s == gimlet::update_scheme::musl ? "MUSL" : s == gimlet::update_scheme::usl ? "USL" : "USF";
}

}  // namespace

TEST_CASE("a partition by node side changes nothing where no node holds two fields of a body",
          "[multi_field][verification]") {
    const auto scheme = GENERATE(gimlet::update_scheme::musl, gimlet::update_scheme::usl, gimlet::update_scheme::usf);
    // The damping transfer and volumetric averaging read the fields too.
    const bool extras = GENERATE(false, true);
    INFO(scheme_name(scheme) << (extras ? " with the PIC blend and volumetric averaging" : ""));
    gimlet::solver_options<S> opt;
    opt.scheme = scheme;
    if (extras) opt.pic_fraction = 0.5, opt.volumetric_average = true;
    const auto sc = blocks(false);
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, contact::distance> by_body(sc, opt);
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, contact::distance, gimlet::field_list<>, by_node_side>
        split(sc, opt);
    set_approach(by_body);
    set_approach(split);
    by_body.run_until(t_end);
    split.run_until(t_end);
    CHECK(split.steps() == by_body.steps());
    require_same_particles(by_body, split);
    require_separated(split);
}

TEST_CASE("two fields of one body meet as two bodies do: self-contact through a partition",
          "[multi_field][verification]") {
    const auto scheme = GENERATE(gimlet::update_scheme::musl, gimlet::update_scheme::usl, gimlet::update_scheme::usf);
    INFO(scheme_name(scheme));
    gimlet::solver_options<S> opt;
    opt.scheme = scheme;
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, counted_distance> two(blocks(false), opt);
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, counted_distance, gimlet::field_list<>, by_tag>
        one(blocks(true), opt);
    REQUIRE(one.materials().size() == 1);
    set_approach(two);
    set_approach(one);
    two.run_until(t_end);
    one.run_until(t_end);
    std::printf("self-contact, %s: %llu pairs engaged between two bodies, %llu within one (%llu self)\n",
                scheme_name(scheme), static_cast<unsigned long long>(two.contact().total.pairs),
                static_cast<unsigned long long>(one.contact().total.pairs),
                static_cast<unsigned long long>(one.contact().total.self));
    CHECK(one.steps() == two.steps());
    require_same_particles(two, one);
    require_separated(one);
    CHECK(two.contact().total.pairs > 0);
    CHECK(two.contact().total.self == 0);
    CHECK(one.contact().total.pairs == two.contact().total.pairs);
    CHECK(one.contact().total.self == one.contact().total.pairs);
}

TEST_CASE("a partition that chooses a field out of range stops the run, naming the particle",
          "[multi_field][errors]") {
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, contact::distance, gimlet::field_list<>, broken>
        sol(blocks(false));
    try {
        sol.step();
        FAIL("no error");
    } catch (const gimlet::numerical_error& e) {
        const std::string what = e.what();
        INFO(what);
        CHECK(what.find("particle") != std::string::npos);
        CHECK(what.find("outside [0, 2)") != std::string::npos);
        CHECK(what.find("step 0") != std::string::npos);
    }
}

TEST_CASE("a partition that names its split rows is asked only near them, with the same results",
          "[multi_field][verification]") {
    // The rows flag the upper block's nodes, which the lower block's particles mostly cannot
    // reach: those particles take side 0 without being asked, as by_node_side would answer.
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, contact::distance, gimlet::field_list<>, by_node_side>
        asked(blocks(false));
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, contact::distance, gimlet::field_list<>,
                   by_node_side_rows<0>>
        skipped(blocks(false));
    set_approach(asked);
    set_approach(skipped);
    asked.run_until(t_end);
    skipped.run_until(t_end);
    CHECK(skipped.steps() == asked.steps());
    require_same_particles(asked, skipped);
    require_separated(skipped);
    // Asked of fewer particles than every particle at every node of every step, and of some.
    const std::uint64_t every = skipped.steps() * skipped.particles().size() * 9;
    const std::uint64_t calls = skipped.partition().calls->load();
    INFO(calls << " of " << every);
    CHECK(calls > 0);
    CHECK(calls < every * 3 / 4);
}

TEST_CASE("split rows of the wrong size are refused, naming them", "[multi_field][errors]") {
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, contact::distance, gimlet::field_list<>,
                   by_node_side_rows<1>>
        sol(blocks(false));
    try {
        sol.step();
        FAIL("no error");
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        INFO(what);
        CHECK(what.find("split_rows()") != std::string::npos);
        CHECK(what.find("one flag per row of nodes") != std::string::npos);
    }
}
