// SPDX-License-Identifier: MIT
// core/particle_store.hpp: one column per field tag, keyed by the tag; a new particle's fields
// start at the tag's initial value; a particle handle reads and writes its own row.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <set>
#include <string>

namespace {

using S = gimlet::space<2>;

struct damage {
    template <class Sp>
    using type = typename Sp::real;
    static constexpr const char* name = "damage";
};
struct porosity {  // starts at 0.1, not zero
    template <class Sp>
    using type = typename Sp::real;
    static constexpr const char* name = "porosity";
    template <class Sp>
    static type<Sp> initial() {
        return 0.1;
    }
};
using fields = gimlet::field_union_t<gimlet::core_fields<S>, gimlet::field_list<damage, porosity>>;
using store_t = gimlet::particle_store<S, fields>;

}  // namespace

TEST_CASE("particle store: columns by tag, initial values, rows through handles", "[core]") {
    store_t store;
    CHECK(store.empty());
    static_assert(store_t::has<damage> && store_t::has<gimlet::fields::position>);
    static_assert(!store_t::has<gimlet::fields::temperature>);
    for (int i = 0; i < 5; ++i) CHECK(store.add() == std::size_t(i));
    REQUIRE(store.size() == 5);
    for (std::size_t i = 0; i < store.size(); ++i) {
        CHECK(store[i].get<damage>() == 0.0);
        CHECK(store[i].get<porosity>() == 0.1);
        CHECK(store[i].get<gimlet::fields::deformation_gradient>() == S::matrix::Identity());  // F starts at I
        CHECK(store[i].index() == i);
    }
    // A handle writes its own row of the column, and nothing else.
    store[3].get<damage>() = 0.5;
    store[3].get<gimlet::fields::velocity>() = S::vector(1, 2);
    const auto& d = store.column<damage>();
    CHECK(d[3] == 0.5);
    CHECK(d[2] == 0.0);
    CHECK(d[4] == 0.0);
    CHECK(store.column<gimlet::fields::velocity>()[3] == S::vector(1, 2));
    CHECK(store.column<gimlet::fields::velocity>()[0] == S::vector::Zero());
    // Every field has one column, visited once, under its tag's name, each as long as the store.
    std::set<std::string> names;
    std::size_t columns = 0;
    store.for_each_column([&](auto tag, auto& column) {
        names.insert(decltype(tag)::name);
        ++columns;
        CHECK(column.size() == store.size());
    });
    CHECK(columns == names.size());
    CHECK(names.count("damage") == 1);
    CHECK(names.count("porosity") == 1);
    CHECK(names.count("position") == 1);
}
