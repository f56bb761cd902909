// SPDX-License-Identifier: MIT
// Compile-time checks of the policy architecture: each family's concept accepts a minimal
// user-written policy and rejects a broken one; a policy that is off adds no field.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <type_traits>

namespace user {

// ---- strength: smallest conforming policy and broken variants ----
struct rigid_plastic_free {  // keeps s = 0, like strength::none, but written by a user
    using required_fields = gimlet::field_list<>;
    template <class Real, class P>
    Real update(const gimlet::point_step<Real>&, Eigen::Matrix<Real, 3, 3>& s, const P&) const {
        s.setZero();
        return Real(0);
    }
    template <class Real, class P>
    Real shear_modulus(const gimlet::point_state<Real>&, const P&) const { return Real(0); }
};
struct strength_without_modulus {
    using required_fields = gimlet::field_list<>;
    template <class Real, class P>
    Real update(const gimlet::point_step<Real>&, Eigen::Matrix<Real, 3, 3>&, const P&) const { return 0; }
};
struct strength_without_fields {
    template <class Real, class P>
    Real update(const gimlet::point_step<Real>&, Eigen::Matrix<Real, 3, 3>&, const P&) const { return 0; }
    template <class Real, class P>
    Real shear_modulus(const gimlet::point_state<Real>&, const P&) const { return 0; }
};

// ---- eos ----
struct ideal_gas_like {  // P = K (1/J - 1)
    using required_fields = gimlet::field_list<>;
    template <class Real, class P>
    Real pressure(const gimlet::point_step<Real>& st, const P&) const { return Real(1e5) * (1 / st.J - 1); }
    template <class Real, class P>
    Real bulk_modulus(const gimlet::point_state<Real>& st, const P&) const { return Real(1e5) / st.J; }
};
struct eos_without_bulk_modulus {
    using required_fields = gimlet::field_list<>;
    template <class Real, class P>
    Real pressure(const gimlet::point_step<Real>&, const P&) const { return 0; }
};

// ---- a user field and a thermal policy that declares it ----
struct heat {
    template <class S> using type = typename S::real;
    static constexpr const char* name = "heat";
};
struct heat_counter {
    static constexpr bool enabled = true;
    using required_fields = gimlet::field_list<heat>;
    template <class P> void initialize(const P& p) const { p.template get<heat>() = 0; }
    template <class Real, class P>
    void update(const gimlet::point_step<Real>&, Real dissipated, const P& p) const { p.template get<heat>() += dissipated; }
};
struct thermal_missing_field {  // uses a field it did not declare: update cannot compile
    static constexpr bool enabled = true;
    using required_fields = gimlet::field_list<>;
    template <class P> void initialize(const P&) const {}
    template <class Real, class P>
    auto update(const gimlet::point_step<Real>&, Real, const P& p) const -> decltype(void(p.template get<heat>())) {}
};

// ---- viscosity ----
struct constant_q {
    static constexpr bool enabled = true;
    using required_fields = gimlet::field_list<>;
    template <class Real, class P>
    Real pressure(const gimlet::point_step<Real>&, Real, const P&) const { return Real(1); }
    template <class Real, class P>
    Real signal_speed(Real c, Real, const P&) const { return c; }  // a constant q adds no stiffness
};
struct viscosity_enabled_without_pressure {
    static constexpr bool enabled = true;
    using required_fields = gimlet::field_list<>;
};

// ---- shape ----
struct nearest_node {
    static constexpr int stencil = 1;
    using required_fields = gimlet::field_list<>;
    template <class Real>
    static void weights(Real x, Real, int& first, Real* w, Real* dw) noexcept {
        first = static_cast<int>(std::floor(x + Real(0.5)));
        w[0] = 1;
        dw[0] = 0;
    }
    template <class P, class Real>
    static typename P::space_type::vector half_width(const P&, Real) { return P::space_type::vector::Zero(); }
};
struct shape_without_stencil {
    using required_fields = gimlet::field_list<>;
    template <class Real>
    static void weights(Real, Real, int&, Real*, Real*) noexcept {}
};

// ---- contact ----
struct my_single_field {
    static constexpr bool multi_field = false;
    using required_fields = gimlet::field_list<>;
};
struct contact_without_flag {
    using required_fields = gimlet::field_list<>;
};
// A law whose in_contact is not const: the framework calls it on a const policy.
struct law_not_const {
    static constexpr bool multi_field = true;
    using required_fields = gimlet::field_list<>;
    template <gimlet::Space S>
    bool in_contact(const gimlet::contact::pair_view<S>&) { return true; }
};
// A law and a node resolver at once: which one the solver should call is ambiguous.
struct law_and_resolver {
    static constexpr bool multi_field = true;
    using required_fields = gimlet::field_list<>;
    template <gimlet::Space S>
    bool in_contact(const gimlet::contact::pair_view<S>&) const { return true; }
    template <gimlet::Space S>
    void resolve(gimlet::contact::node_view<S>&) const {}
};
// A law with 2-D pair views only.
struct law_2d_only {
    static constexpr bool multi_field = true;
    using required_fields = gimlet::field_list<>;
    bool in_contact(const gimlet::contact::pair_view<gimlet::space<2>>&) const { return true; }
};

// ---- field tags ----
struct unnamed_field {
    template <class S> using type = double;
};

}  // namespace user

static_assert(gimlet::strength::Strength<user::rigid_plastic_free>);
static_assert(!gimlet::strength::Strength<user::strength_without_modulus>);
static_assert(!gimlet::strength::Strength<user::strength_without_fields>);
static_assert(gimlet::strength::Strength<gimlet::strength::linear_elastic>);
static_assert(gimlet::strength::Strength<gimlet::strength::none>);

static_assert(gimlet::eos::Eos<user::ideal_gas_like>);
static_assert(!gimlet::eos::Eos<user::eos_without_bulk_modulus>);
static_assert(gimlet::eos::Eos<gimlet::eos::linear>);

static_assert(gimlet::thermal::Thermal<user::heat_counter>);
static_assert(!gimlet::thermal::Thermal<user::thermal_missing_field>);
static_assert(gimlet::thermal::Thermal<gimlet::thermal::none>);

static_assert(gimlet::viscosity::Viscosity<user::constant_q>);
static_assert(!gimlet::viscosity::Viscosity<user::viscosity_enabled_without_pressure>);
static_assert(gimlet::viscosity::Viscosity<gimlet::viscosity::none>);

static_assert(gimlet::shape::Shape<user::nearest_node>);
static_assert(!gimlet::shape::Shape<user::shape_without_stencil>);

static_assert(gimlet::contact::Contact<user::my_single_field>);
static_assert(!gimlet::contact::Contact<user::contact_without_flag>);
static_assert(!gimlet::contact::Contact<user::law_not_const>);
static_assert(!gimlet::contact::Contact<user::law_and_resolver>);
static_assert(!gimlet::contact::Contact<user::law_2d_only>);
static_assert(gimlet::contact::Law<gimlet::contact::distance> && gimlet::contact::Law<gimlet::contact::bardenhagen>);
static_assert(gimlet::contact::check<gimlet::contact::distance>() && gimlet::contact::check<gimlet::contact::bardenhagen>() &&
              gimlet::contact::check<gimlet::contact::single_field>());

// The checkers (docs/concepts.md) accept every built-in policy and the user policies above.
static_assert(gimlet::check_field<user::heat>() && gimlet::check_field<gimlet::fields::temperature>() &&
              gimlet::check_field<gimlet::fields::velocity>());
static_assert(gimlet::shape::check<gimlet::shape::linear>() && gimlet::shape::check<gimlet::shape::ugimp>() &&
              gimlet::shape::check<gimlet::shape::cpgimp>() && gimlet::shape::check<gimlet::shape::bspline_quadratic>() &&
              gimlet::shape::check<gimlet::shape::bspline_cubic>() && gimlet::shape::check<user::nearest_node>());
static_assert(gimlet::strength::check<gimlet::strength::von_mises>() && gimlet::strength::check<gimlet::strength::linear_elastic>() &&
              gimlet::strength::check<gimlet::strength::none>());
static_assert(gimlet::eos::check<gimlet::eos::linear>() && gimlet::eos::check<gimlet::eos::mie_gruneisen<>>() &&
              gimlet::eos::check<user::ideal_gas_like>());
static_assert(gimlet::thermal::check<gimlet::thermal::none>() && gimlet::thermal::check<gimlet::thermal::isentrope_temperature>() &&
              gimlet::thermal::check<gimlet::presets::paper_temperature>() && gimlet::thermal::check<user::heat_counter>());
static_assert(gimlet::viscosity::check<gimlet::viscosity::none>() && gimlet::viscosity::check<gimlet::viscosity::bulk>() &&
              gimlet::viscosity::check<user::constant_q>());
static_assert(gimlet::multi_field::check<gimlet::multi_field::by_body>());
static_assert(gimlet::check_material<gimlet::elastic_material>() &&
              gimlet::check_material<gimlet::presets::hmx_material<>>() &&
              gimlet::check_material<gimlet::presets::hmx_material<gimlet::eos::energy_reference::internal_energy,
                                                                   gimlet::presets::paper_temperature>>());
// A program written against the presets' former folder and namespace still compiles, for one release.
static_assert(std::is_same_v<gimlet::materials::hmx_material<>, gimlet::presets::hmx_material<>>);
static_assert(gimlet::scene::check_region<gimlet::scene::box<gimlet::space<2>>, gimlet::space<2>>() &&
              gimlet::scene::check_region<gimlet::scene::ball<gimlet::space<3>>, gimlet::space<3>>() &&
              gimlet::scene::check_region<gimlet::scene::difference<gimlet::scene::box<gimlet::space<2>>,
                                                                    gimlet::scene::ball<gimlet::space<2>>>,
                                          gimlet::space<2>>());

static_assert(gimlet::Field<user::heat>);
static_assert(!gimlet::Field<user::unnamed_field>);

// ---- pay only for what the scene calls for ----
using S2 = gimlet::space<2>;
using S3 = gimlet::space<3>;
using elastic_solver = gimlet::solver<S2, gimlet::shape::ugimp, gimlet::elastic_material>;
using heated_material = gimlet::material<gimlet::strength::linear_elastic, gimlet::eos::linear, user::heat_counter>;
using heated_solver = gimlet::solver<S2, gimlet::shape::ugimp, heated_material>;

// thermal::none adds no field: no temperature column, no user heat column.
static_assert(!elastic_solver::store_type::has<gimlet::fields::temperature>);
static_assert(!elastic_solver::store_type::has<user::heat>);
static_assert(heated_solver::store_type::has<user::heat>);
// Shape functions add only what they read: linear MPM needs no particle size.
static_assert(!gimlet::solver<S2, gimlet::shape::linear, gimlet::elastic_material>::store_type::has<gimlet::fields::domain_half_width>);
static_assert(elastic_solver::store_type::has<gimlet::fields::domain_half_width>);
// Plane strain carries sigma_zz; 3-D does not need it.
static_assert(elastic_solver::store_type::has<gimlet::fields::stress_zz>);
static_assert(!gimlet::solver<S3, gimlet::shape::ugimp, gimlet::elastic_material>::store_type::has<gimlet::fields::stress_zz>);
// No duplicate columns: the union is exact.
static_assert(elastic_solver::particle_fields::size == gimlet::core_fields<S2>::size + 1);
static_assert(heated_solver::particle_fields::size == gimlet::core_fields<S2>::size + 2);
// The union keeps first occurrence order and drops duplicates.
static_assert(std::is_same_v<gimlet::field_union_t<gimlet::field_list<gimlet::fields::mass, gimlet::fields::body>,
                                                   gimlet::field_list<gimlet::fields::body, user::heat>>,
                             gimlet::field_list<gimlet::fields::mass, gimlet::fields::body, user::heat>>);

TEST_CASE("a user policy with its own field runs in the solver", "[static][core]") {
    gimlet::grid_spec<S2> gs;
    gs.upper = S2::vector(1.0, 0.6);
    gs.cell = 0.1;
    gimlet::scene::scene<S2, heated_material> sc(gs);
    const auto k = gimlet::elastic_moduli::from_young_poisson(1e6, 0.3);
    sc.add_body(gimlet::scene::box<S2>(S2::vector(0.2, 0.2), S2::vector(0.6, 0.4)),
                heated_material{1000.0, gimlet::strength::linear_elastic{k.shear}, gimlet::eos::linear{k.bulk}},
                S2::vector(1.0, 0.0));
    heated_solver sol(sc);
    for (int i = 0; i < 10; ++i) sol.step();
    // Elastic: nothing dissipated, so the user's heat column stays zero (and exists).
    for (double h : sol.particles().column<user::heat>()) CHECK(h == 0.0);
    CHECK(sol.particles().column<user::heat>().size() == sol.particles().size());
}

TEST_CASE("a single-field scene allocates one grid field, a multi-field scene one per body", "[static][contact]") {
    gimlet::grid_spec<S2> gs;
    gs.upper = S2::vector(1.0, 0.6);
    gs.cell = 0.1;
    gimlet::scene::scene<S2, gimlet::elastic_material> sc(gs);
    const auto mat = gimlet::make_elastic_material(1000.0, 1e6, 0.3);
    sc.add_body(gimlet::scene::box<S2>(S2::vector(0.1, 0.1), S2::vector(0.4, 0.3)), mat, S2::vector::Zero());
    sc.add_body(gimlet::scene::box<S2>(S2::vector(0.5, 0.1), S2::vector(0.9, 0.3)), mat, S2::vector::Zero());
    sc.add_body(gimlet::scene::box<S2>(S2::vector(0.1, 0.4), S2::vector(0.9, 0.5)), mat, S2::vector::Zero());
    const elastic_solver single(sc);
    const gimlet::solver<S2, gimlet::shape::ugimp, gimlet::elastic_material, gimlet::contact::bardenhagen> multi(sc);
    CHECK(single.background_grid().field_count() == 1);
    CHECK(single.background_grid().mass.size() == single.background_grid().size());
    CHECK(multi.background_grid().field_count() == 3);
    CHECK(multi.background_grid().mass.size() == 3 * multi.background_grid().size());
}
