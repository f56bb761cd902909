// SPDX-License-Identifier: MIT
// Rigid-body motions must not stress an elastic body.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <tuple>

namespace {

using shapes = std::tuple<gimlet::shape::linear, gimlet::shape::ugimp, gimlet::shape::cpgimp,
                          gimlet::shape::bspline_quadratic, gimlet::shape::bspline_cubic>;

template <class S>
typename S::vector vec(double x, double y, double z = 0) {
    typename S::vector v;
    v[0] = x;
    v[1] = y;
    if constexpr (S::dim == 3) v[2] = z;
    return v;
}

// A block translating through a periodic grid, crossing several cells, stays unstressed: the
// nodal velocity of a uniform field is the field itself, and sum_i G_ip = 0 gives L = 0.
template <class Shape, int Dim>
void check_translation() {
    using S = gimlet::space<Dim>;
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Constant(0.8);
    gs.cell = 0.1;
    gs.bc.fill(gimlet::boundary::periodic);  // a translation that wraps round the periodic box
    gimlet::scene::scene<S, gimlet::elastic_material> sc(gs);
    const auto mat = gimlet::make_elastic_material(1000.0, 1e6, 0.3);
    const auto v0 = vec<S>(3.0, -2.0, 1.0);
    sc.add_body(gimlet::scene::box<S>(vec<S>(0.2, 0.2, 0.2), vec<S>(0.55, 0.45, 0.5)), mat, v0, 2);
    gimlet::solver<S, Shape, gimlet::elastic_material> sol(sc);
    const auto x0 = sol.particles().template column<gimlet::fields::position>();
    sol.run_until(0.25);  // 0.75 m along x: about 7 cells, wrapping through the periodic seam
    const auto& p = sol.particles();
    double max_stress = 0, max_dv = 0, max_energy = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        max_stress = std::max(max_stress, p.template column<gimlet::fields::stress>()[i].norm());
        max_dv = std::max(max_dv, (p.template column<gimlet::fields::velocity>()[i] - v0).norm());
        max_energy = std::max(max_energy, std::abs(p.template column<gimlet::fields::specific_internal_energy>()[i]));
    }
    INFO("steps " << sol.steps() << ", max |sigma| " << max_stress << " Pa");
    // Round-off only (a node under the mass cut-off keeps its particles' mean velocity, so a
    // rigid translation stays one there too): far below an equivalent strain of 1e-9
    // (|sigma| < 2 G 1e-9).
    const double g = mat.strength.shear_modulus();
    CHECK(max_stress < 2 * g * 1e-9);
    CHECK(max_dv < 1e-8 * v0.norm());
    CHECK(max_energy < 1e-12);
    // Every particle moved by v0 t (modulo the period).
    const auto& x = p.template column<gimlet::fields::position>();
    for (std::size_t i = 0; i < p.size(); ++i) {
        typename S::vector d = x[i] - x0[i] - v0 * sol.time();
        for (int k = 0; k < Dim; ++k) d[k] -= 0.8 * std::round(d[k] / 0.8);
        REQUIRE(d.norm() < 1e-10);
    }
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("rigid translation produces no stress (2-D)", "[core][verification]", shapes) {
    check_translation<TestType, 2>();
}

TEMPLATE_LIST_TEST_CASE("rigid translation produces no stress (3-D)", "[core][verification]", shapes) {
    check_translation<TestType, 3>();
}

// A rigid spin: the nodal velocities of an exact rigid field v = w x (x - c), interpolated by
// each shape function, give a skew velocity gradient (linear reproduction of gradients), so the
// solver's kinematic and constitutive update leaves an unstressed particle unstressed with
// det F = 1, and rotates a pre-stressed one without changing its stress invariants.
TEMPLATE_LIST_TEST_CASE("rigid rotation produces no stress", "[core][verification]", shapes) {
    using S = gimlet::space<2>;
    using Shape = TestType;
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Ones();
    gs.cell = 0.1;
    gs.bc = {gimlet::boundary::free, gimlet::boundary::free};
    const gimlet::grid<S> g(gs, Shape::stencil);
    const S::vector centre(0.5, 0.5);
    const double omega = 2.0;  // rad/s
    std::vector<S::vector> v(g.size());
    for (std::size_t n = 0; n < g.size(); ++n) {
        const S::vector r = g.position(g.unflatten(n)) - centre;
        v[n] = omega * S::vector(-r[1], r[0]);
    }

    using fields = gimlet::field_union_t<gimlet::core_fields<S>, typename Shape::required_fields>;
    gimlet::particle_store<S, fields> store;
    const auto mat = gimlet::make_elastic_material(1000.0, 1e6, 0.3);
    // Two particles at awkward positions: one unstressed, one pre-stressed.
    for (const S::vector& x : {S::vector(0.437, 0.5123), S::vector(0.55, 0.45)}) {
        auto p = store[store.add()];
        p.template get<gimlet::fields::position>() = x;
        p.template get<gimlet::fields::volume0>() = 0.0025;
        p.template get<gimlet::fields::mass>() = 2.5;
        if constexpr (decltype(store)::template has<gimlet::fields::domain_half_width>)
            p.template get<gimlet::fields::domain_half_width>() = S::vector::Constant(0.025);
    }
    S::matrix pre;
    pre << 3e4, 1e4, 1e4, -2e4;
    store.template column<gimlet::fields::stress>()[1] = pre;
    store.template column<gimlet::fields::stress_zz>()[1] = -1e4;
    const double j2_before = [&] {
        const auto s = gimlet::stress3(store[1]);
        const auto d = gimlet::strength::deviator<double>(s);
        return 0.5 * d.cwiseProduct(d).sum();
    }();

    // A quarter turn in 400 steps; the particles stay put (only the kinematics is under test).
    const double dt = (std::numbers::pi / 2) / omega / 400;
    for (int step = 0; step < 400; ++step) {
        for (std::size_t i = 0; i < store.size(); ++i) {
            gimlet::detail::stencil<S, Shape::stencil> st;
            auto p = store[i];
            st.template compute_with<Shape>(g, p.template get<gimlet::fields::position>(), Shape::half_width(p, gs.cell));
            S::matrix L = S::matrix::Zero();
            st.for_each([&](std::size_t node, double, const S::vector& grad) { L += v[node] * grad.transpose(); });
            REQUIRE((L + L.transpose()).norm() < 1e-12 * omega);
            gimlet::update_material_point(mat, p, L, dt, gs.cell, std::size_t(step), step * dt);
        }
    }
    const auto& p0 = store[0];
    // Round-off only: an equivalent strain below 1e-12.
    CHECK(p0.template get<gimlet::fields::stress>().norm() < 2 * mat.strength.shear_modulus() * 1e-12);
    CHECK(std::abs(p0.template get<gimlet::fields::deformation_gradient>().determinant() - 1.0) < 1e-12);
    // F is the quarter-turn rotation.
    S::matrix r90;
    r90 << 0, -1, 1, 0;
    CHECK((p0.template get<gimlet::fields::deformation_gradient>() - r90).norm() < 1e-4);
    // The pre-stressed particle: pressure and J2 unchanged, stress rotated by a quarter turn.
    const auto s1 = gimlet::stress3(store[1]);
    const auto d1 = gimlet::strength::deviator<double>(s1);
    CHECK(std::abs(0.5 * d1.cwiseProduct(d1).sum() - j2_before) < 1e-10 * j2_before);
    const S::matrix rotated = r90 * pre * r90.transpose();
    CHECK((store.template column<gimlet::fields::stress>()[1] - rotated).norm() < 1e-3 * pre.norm());
}
