// SPDX-License-Identifier: MIT
/// \file
/// Verification of the shape-function policies against docs/physics.md section 2: partition of
/// unity, linear and gradient reproduction in 2-D and 3-D, positivity, continuity and
/// derivatives of the 1-D factors, and the reference paper's Φ (eq-mpm-shape) with its
/// misprint corrected. Everything is in cell units (node k at x = k).

#include "gimlet/core/particle_store.hpp"
#include "gimlet/shape/all.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

namespace {

namespace sh = gimlet::shape;

using all_shapes =
    std::tuple<sh::linear, sh::ugimp, sh::cpgimp, sh::bspline_quadratic, sh::bspline_cubic>;

template <int Dim, class Real>
using vec = Eigen::Matrix<Real, Dim, 1>;
template <int Dim, class Real>
using mat = Eigen::Matrix<Real, Dim, Dim>;

/// GIMP policies read a half-width; the others ignore it (the solver passes their zero).
template <class Sh>
constexpr bool uses_half_width = Sh::required_fields::size > 0;

/// Linear MPM is only C0: its derivative jumps at nodes.
template <class Sh>
constexpr bool is_c1 = !std::is_same_v<Sh, sh::linear>;

/// Half-widths (cells) each policy is checked with.
template <class Sh>
std::vector<double> half_widths() {
    if constexpr (uses_half_width<Sh>) {
        return {0.5, 0.25, 1.0 / 6.0, 0.125};
    } else {
        return {0.0};
    }
}

/// One axis of a particle's weights, looked up by node index (zero outside the stencil), so
/// that positions whose stencils start at different nodes can be compared node by node.
template <class Sh, class Real>
struct axis_weights {
    int first = 0;
    std::array<Real, Sh::stencil> w{};
    std::array<Real, Sh::stencil> dw{};

    [[nodiscard]] bool in_stencil(int k) const { return k >= first && k < first + Sh::stencil; }
    [[nodiscard]] Real weight(int k) const { return in_stencil(k) ? w[k - first] : Real(0); }
    [[nodiscard]] Real slope(int k) const { return in_stencil(k) ? dw[k - first] : Real(0); }
};

template <class Sh, class Real>
axis_weights<Sh, Real> evaluate(Real x, Real l) {
    axis_weights<Sh, Real> a;
    Sh::weights(x, l, a.first, a.w.data(), a.dw.data());
    return a;
}

/// Each policy's 1-D weight written branch by branch as docs/physics.md section 2 states it, an
/// oracle independent of the policies' closed forms. `r = x_p - x_i` in cells.
template <class Sh>
double reference_weight(double r, double l) {
    const double a = std::abs(r);
    if constexpr (std::is_same_v<Sh, sh::linear>) {
        return a < 1 ? 1 - a : 0;
    } else if constexpr (uses_half_width<Sh>) {
        if (a < l) return 1 - (a * a + l * l) / (2 * l);
        if (a < 1 - l) return 1 - a;
        if (a < 1 + l) return (1 + l - a) * (1 + l - a) / (4 * l);
        return 0;
    } else if constexpr (std::is_same_v<Sh, sh::bspline_quadratic>) {
        if (a < 0.5) return 0.75 - a * a;
        if (a < 1.5) return (1.5 - a) * (1.5 - a) / 2;
        return 0;
    } else {
        if (a < 1) return 2.0 / 3.0 - a * a + a * a * a / 2;
        if (a < 2) return (2 - a) * (2 - a) * (2 - a) / 6;
        return 0;
    }
}

/// How densely to sample one axis.
enum class sampling {
    boundaries,  ///< the branch and stencil boundaries only (3-D, where points multiply fast)
    generic,     ///< the boundaries plus a few points between them
    near,        ///< as generic, plus 1e-12 either side of every point
};

/// Coordinates along one axis (in cells) for half-width l, in three cells, one of them at
/// negative x. The boundaries are where some policy changes branch or stencil: the node and
/// cell edge (offset 0), the half-cell (1/2) and the GIMP boundaries ±l and ±(1 - l) (mod 1;
/// ±(1 + l) falls on the same points).
std::vector<double> axis_samples(double l, sampling how) {
    std::vector<double> offsets = {0.0, 0.5};
    if (l > 0) {
        offsets.push_back(l);
        offsets.push_back(1 - l);
    }
    if (how != sampling::boundaries) offsets.insert(offsets.end(), {0.1, 0.37, 0.77, 0.93});
    std::vector<double> xs;
    for (const double base : {-3.0, 0.0, 4.0}) {
        for (const double o : offsets) {
            xs.push_back(base + o);
            if (how == sampling::near) {
                xs.push_back(base + o - 1e-12);
                xs.push_back(base + o + 1e-12);
            }
        }
    }
    return xs;
}

/// Every point of the grid `axis` x ... x `axis` (Dim times).
template <int Dim, class Real>
std::vector<vec<Dim, Real>> grid_of(const std::vector<double>& axis) {
    std::size_t total = 1;
    for (int d = 0; d < Dim; ++d) total *= axis.size();
    std::vector<vec<Dim, Real>> points(total);
    for (std::size_t n = 0; n < total; ++n) {
        std::size_t rest = n;
        for (int d = 0; d < Dim; ++d) {
            points[n][d] = static_cast<Real>(axis[rest % axis.size()]);
            rest /= axis.size();
        }
    }
    return points;
}

/// Sums over a particle's N-D stencil.
template <int Dim, class Real>
struct moments {
    Real sum_w = 0;                                       ///< Σ S_ip
    vec<Dim, Real> sum_grad = vec<Dim, Real>::Zero();     ///< Σ ∇S_ip
    vec<Dim, Real> sum_wx = vec<Dim, Real>::Zero();       ///< Σ S_ip x_i
    mat<Dim, Real> sum_grad_x = mat<Dim, Real>::Zero();   ///< Σ ∇S_ip ⊗ x_i
    Real min_w = std::numeric_limits<Real>::infinity();   ///< min S_ip
};

/// The tensor-product weights of docs/physics.md section 2, S = Π_d w_d and
/// ∂S/∂x_d = dw_d Π_{e≠d} w_e, summed over the stencil of a particle at `x` with half-width `l`.
template <class Sh, int Dim, class Real>
moments<Dim, Real> stencil_moments(const vec<Dim, Real>& x, const vec<Dim, Real>& l) {
    std::array<axis_weights<Sh, Real>, Dim> axes;
    for (int d = 0; d < Dim; ++d) axes[d] = evaluate<Sh>(x[d], l[d]);
    int nodes = 1;
    for (int d = 0; d < Dim; ++d) nodes *= Sh::stencil;

    moments<Dim, Real> m;
    for (int n = 0; n < nodes; ++n) {
        Real w = 1;
        vec<Dim, Real> grad = vec<Dim, Real>::Ones();
        vec<Dim, Real> xi;
        int rest = n;
        for (int d = 0; d < Dim; ++d) {
            const int a = rest % Sh::stencil;
            rest /= Sh::stencil;
            xi[d] = static_cast<Real>(axes[d].first + a);
            w *= axes[d].w[a];
            for (int e = 0; e < Dim; ++e) grad[e] *= (e == d ? axes[d].dw[a] : axes[d].w[a]);
        }
        m.sum_w += w;
        m.sum_grad += grad;
        m.sum_wx += w * xi;
        m.sum_grad_x += grad * xi.transpose();
        m.min_w = std::min(m.min_w, w);
    }
    return m;
}

/// The largest error seen and where, so a failure names the position instead of drowning in
/// thousands of passing assertions.
struct worst_case {
    double error = 0;
    std::string where = "(none)";

    template <class Point>
    void update(double e, const Point& x, const Point& l) {
        if (std::isnan(error)) return;
        if (std::isnan(e) || e > error) {
            std::ostringstream os;
            os.precision(17);
            os << "x = (" << x.transpose() << "), l = (" << l.transpose() << ")";
            error = e;
            where = os.str();
        }
    }
    void update(double e, double x, double l) {
        update(e, vec<1, double>::Constant(x), vec<1, double>::Constant(l));
    }
};

/// Worst deviations from Σ S = 1, Σ ∇S = 0, Σ S x_i = x_p, Σ ∇S ⊗ x_i = I and S >= 0; the two
/// reproduction errors are relative to 1 + |x_p| (they carry the node coordinates).
struct reproduction_errors {
    worst_case unity, gradient_sum, linear, gradient_linear, negative;
};

/// The largest absolute entry of a vector or matrix, in double.
template <class Derived>
double max_abs(const Eigen::MatrixBase<Derived>& a) {
    return static_cast<double>(a.cwiseAbs().maxCoeff());
}

template <class Sh, int Dim, class Real>
reproduction_errors measure_reproduction(const std::vector<vec<Dim, Real>>& points,
                                         const vec<Dim, Real>& l) {
    reproduction_errors r;
    for (const auto& x : points) {
        const auto m = stencil_moments<Sh, Dim, Real>(x, l);
        const double scale = 1 + max_abs(x);
        r.unity.update(std::abs(static_cast<double>(m.sum_w) - 1), x, l);
        r.gradient_sum.update(max_abs(m.sum_grad), x, l);
        r.linear.update(max_abs(m.sum_wx - x) / scale, x, l);
        r.gradient_linear.update(max_abs(m.sum_grad_x - mat<Dim, Real>::Identity()) / scale, x, l);
        r.negative.update(std::max(0.0, -static_cast<double>(m.min_w)), x, l);
    }
    return r;
}

#define GIMLET_CHECK_WORST(w, tol) \
    do {                           \
        INFO((w).where);           \
        CHECK((w).error <= (tol)); \
    } while (false)

/// Each reproduction error within `tol`, and no negative weight at all.
void check_errors(const reproduction_errors& r, double tol) {
    GIMLET_CHECK_WORST(r.unity, tol);
    GIMLET_CHECK_WORST(r.gradient_sum, tol);
    GIMLET_CHECK_WORST(r.linear, tol);
    GIMLET_CHECK_WORST(r.gradient_linear, tol);
    GIMLET_CHECK_WORST(r.negative, 0.0);
}

/// All five reproduction checks for every half-width of `Sh`, on the grid of `axis_samples`.
template <class Sh, int Dim, class Real>
void check_all_reproduction(sampling how, double tol) {
    for (const double l : half_widths<Sh>()) {
        const auto points = grid_of<Dim, Real>(axis_samples(l, how));
        const vec<Dim, Real> half_width = vec<Dim, Real>::Constant(static_cast<Real>(l));
        const auto r = measure_reproduction<Sh, Dim, Real>(points, half_width);
        INFO("l = " << l);
        check_errors(r, tol);
    }
}

/// A particle store with the core fields of a Dim-D scene plus the fields `Sh` reads.
template <class Sh, int Dim>
using store_for = gimlet::particle_store<
    gimlet::space<Dim, double>,
    gimlet::field_union_t<gimlet::core_fields<gimlet::space<Dim, double>>,
                          typename Sh::required_fields>>;

/// A store holding one particle of initial half-width `l0` (m) and deformation gradient `f`.
template <class Sh, int Dim>
store_for<Sh, Dim> one_particle(const vec<Dim, double>& l0, const mat<Dim, double>& f) {
    store_for<Sh, Dim> store;
    store.add();
    store[0].template get<gimlet::fields::domain_half_width>() = l0;
    store[0].template get<gimlet::fields::deformation_gradient>() = f;
    return store;
}

/// Nodes worth looking at around x: a cell more than any stencil reaches on each side.
std::vector<int> nodes_near(double x) {
    const int k = static_cast<int>(std::floor(x));
    std::vector<int> ks;
    for (int i = k - 3; i <= k + 4; ++i) ks.push_back(i);
    return ks;
}

/// Call `visit(x, k)` for every sample x along one axis and every node k around it.
template <class Visit>
void for_each_sample_node(double l, sampling how, Visit&& visit) {
    for (const double x : axis_samples(l, how)) {
        for (const int k : nodes_near(x)) visit(x, k);
    }
}

}  // namespace

TEMPLATE_LIST_TEST_CASE("2-D: partition of unity, linear and gradient reproduction",
                        "[shape][verification]", all_shapes) {
    check_all_reproduction<TestType, 2, double>(sampling::near, 1e-14);
}

TEMPLATE_LIST_TEST_CASE("3-D: partition of unity, linear and gradient reproduction",
                        "[shape][verification]", all_shapes) {
    check_all_reproduction<TestType, 3, double>(sampling::boundaries, 1e-14);
}

TEMPLATE_LIST_TEST_CASE("float: partition of unity and reproduction in 2-D and 3-D",
                        "[shape][verification]", all_shapes) {
    check_all_reproduction<TestType, 2, float>(sampling::generic, 1e-6);
    check_all_reproduction<TestType, 3, float>(sampling::boundaries, 1e-6);
}

TEMPLATE_LIST_TEST_CASE("1-D weights follow docs/physics.md section 2 branch by branch",
                        "[shape][verification]", all_shapes) {
    // Also checks the stencil placement: a node outside [first, first + stencil) must be one
    // the formula gives zero, for every position including nodes and half-cells. Where the
    // formula gives zero the policy must give exactly zero weight and slope (linear MPM's
    // one-sided slope at the edge of its support excepted).
    for (const double l : half_widths<TestType>()) {
        worst_case err, not_zero;
        for_each_sample_node(l, sampling::near, [&](double x, int k) {
            const auto a = evaluate<TestType>(x, l);
            const double expected = reference_weight<TestType>(x - k, l);
            err.update(std::abs(a.weight(k) - expected), x, l);
            if (expected == 0 && (is_c1<TestType> || std::abs(x - k) > 1)) {
                not_zero.update(std::abs(a.weight(k)) + std::abs(a.slope(k)), x, l);
            }
        });
        GIMLET_CHECK_WORST(err, 1e-15);
        GIMLET_CHECK_WORST(not_zero, 0.0);
    }
}

TEMPLATE_LIST_TEST_CASE("weights are non-negative and continuous across branch boundaries",
                        "[shape][verification]", all_shapes) {
    constexpr double eps = 1e-12;
    for (const double l : half_widths<TestType>()) {
        worst_case jump_w, jump_dw, negative;
        for_each_sample_node(l, sampling::generic, [&](double b, int k) {
            const auto below = evaluate<TestType>(b - eps, l);
            const auto above = evaluate<TestType>(b + eps, l);
            jump_w.update(std::abs(above.weight(k) - below.weight(k)), b, l);
            if constexpr (is_c1<TestType>) {
                jump_dw.update(std::abs(above.slope(k) - below.slope(k)), b, l);
            }
            negative.update(std::max({0.0, -below.weight(k), -above.weight(k)}), b, l);
        });
        INFO("l = " << l);
        // Slopes are at most 1 per cell and curvatures at most 1/l, so 2e-12 either way.
        GIMLET_CHECK_WORST(jump_w, 1e-10);
        GIMLET_CHECK_WORST(jump_dw, 1e-9);
        GIMLET_CHECK_WORST(negative, 0.0);
    }
}

TEMPLATE_LIST_TEST_CASE("derivative matches a central difference of the weight",
                        "[shape][verification]", all_shapes) {
    // Where the curvature jumps (C1 branch points) the central difference is off by
    // delta * jump / 4 <= 1e-7 * 8 / 4; round-off adds about 1e-9.
    constexpr double delta = 1e-7;
    for (const double l : half_widths<TestType>()) {
        worst_case err;
        for_each_sample_node(l, sampling::near, [&](double x, int k) {
            if (!is_c1<TestType> && std::abs(x - std::round(x)) < 2 * delta) return;
            const double fd = (evaluate<TestType>(x + delta, l).weight(k) -
                               evaluate<TestType>(x - delta, l).weight(k)) /
                              (2 * delta);
            err.update(std::abs(fd - evaluate<TestType>(x, l).slope(k)), x, l);
        });
        INFO("l = " << l);
        GIMLET_CHECK_WORST(err, 1e-6);
    }
}

TEST_CASE("the paper's Phi (eq-mpm-shape) with its misprint corrected", "[shape][verification]") {
    // docs/physics.md section 2: the paper prints the inner branch as (7 - 16 r^2)/16; it is /8.
    CHECK(sh::paper_phi(0.0) == Approx(7.0 / 8.0).margin(1e-15));
    CHECK(sh::paper_phi(0.25) == Approx(0.75).margin(1e-15));
    CHECK(sh::paper_phi(0.75) == Approx(0.25).margin(1e-15));
    CHECK(sh::paper_phi(1.25) == Approx(0.0).margin(1e-15));
    CHECK(sh::paper_phi(2.0) == 0.0);

    // The misprinted /16 jumps from 3/8 to 3/4 at r = 1/4; the corrected Φ is continuous at
    // every branch boundary, approached from both sides.
    for (const double b : {0.25, 0.75, 1.25}) {
        INFO("r = " << b);
        CHECK(sh::paper_phi(b - 1e-12) == Approx(sh::paper_phi(b + 1e-12)).margin(1e-10));
        CHECK(sh::paper_phi(b - 1e-12) == Approx(sh::paper_phi(b)).margin(1e-10));
    }

    // Φ is uGIMP at l = 1/4 (2x2 particles per cell): the paper's branches and the policy's
    // closed form agree at every node, inside and outside the stencil, and Φ sums to one.
    worst_case err, unity;
    for (const double x : axis_samples(0.25, sampling::near)) {
        const auto a = evaluate<sh::ugimp>(x, 0.25);
        double sum = 0;
        for (const int k : nodes_near(x)) {
            err.update(std::abs(a.weight(k) - sh::paper_phi(x - k)), x, 0.25);
            sum += sh::paper_phi(x - k);
        }
        unity.update(std::abs(sum - 1), x, 0.25);
    }
    GIMLET_CHECK_WORST(err, 1e-15);
    GIMLET_CHECK_WORST(unity, 1e-15);
}

TEST_CASE("cpGIMP half-width follows the stretch of F, capped at half a cell",
          "[shape][verification]") {
    const double h = 2e-3;  // m
    const auto half_width = [h](const Eigen::Matrix2d& f) -> Eigen::Vector2d {
        const auto store = one_particle<sh::cpgimp, 2>(Eigen::Vector2d::Constant(h / 4), f);
        return sh::cpgimp::half_width(store[0], h);
    };

    SECTION("F = diag(2, 0.5) with l0 = h/4 gives (1/2, 1/8) cells") {
        const Eigen::Vector2d l = half_width(Eigen::Vector2d(2.0, 0.5).asDiagonal());
        CHECK(l[0] == Approx(0.5).margin(1e-15));
        CHECK(l[1] == Approx(0.125).margin(1e-15));

        // The stretched, unequal half-widths still give a partition of unity.
        const auto r = measure_reproduction<sh::cpgimp, 2, double>(
            grid_of<2, double>(axis_samples(0.125, sampling::near)), l);
        check_errors(r, 1e-14);
    }
    SECTION("a stretch beyond half a cell is capped so the 3-node stencil stays valid") {
        const Eigen::Vector2d l = half_width(Eigen::Vector2d(3.0, 1.0).asDiagonal());
        CHECK(l[0] == Approx(0.5).margin(1e-15));
        CHECK(l[1] == Approx(0.25).margin(1e-15));
    }
    SECTION("only the diagonal stretch counts, whatever its sign") {
        const Eigen::Vector2d l = half_width((Eigen::Matrix2d() << 1.0, 0.7, 0.3, -0.5).finished());
        CHECK(l[0] == Approx(0.25).margin(1e-15));
        CHECK(l[1] == Approx(0.125).margin(1e-15));
    }
}

TEST_CASE("uGIMP half-width ignores F; point-particle policies have none",
          "[shape][verification]") {
    const double h = 0.5;
    // A const store: policies also read through const handles.
    const auto store = one_particle<sh::ugimp, 3>(Eigen::Vector3d(0.125, 0.25, 0.0625),
                                                  Eigen::Vector3d(2, 3, 4).asDiagonal());
    const Eigen::Vector3d l = sh::ugimp::half_width(store[0], h);
    CHECK(l[0] == Approx(0.25).margin(1e-15));
    CHECK(l[1] == Approx(0.5).margin(1e-15));
    CHECK(l[2] == Approx(0.125).margin(1e-15));
    CHECK(sh::linear::half_width(store[0], h).isZero());
    CHECK(sh::bspline_quadratic::half_width(store[0], h).isZero());
    CHECK(sh::bspline_cubic::half_width(store[0], h).isZero());
}

TEST_CASE("uGIMP with a zero half-width degrades to linear MPM, not NaN", "[shape][verification]") {
    for (const double x : {-2.3, 0.1, 0.5, 3.77}) {
        const auto g = evaluate<sh::ugimp>(x, 0.0);
        const auto m = evaluate<sh::linear>(x, 0.0);
        INFO("x = " << x);
        for (const int k : nodes_near(x)) {
            CHECK(g.weight(k) == Approx(m.weight(k)).margin(1e-15));
            CHECK(g.slope(k) == Approx(m.slope(k)).margin(1e-15));
        }
    }
}

#undef GIMLET_CHECK_WORST  // the family's files compile as one unit (docs/testing.md)

// The two-axes form of the GIMP weights (weights_2d; why, at shape::detail::gimp_weights_2d)
// must give what weights() gives axis by axis, bit for bit: the solver takes either, and the
// outputs are byte-identical whichever it takes. Random positions and half-widths, and the
// exact cases where a branch of the kernel turns: quarter points, l = 1/4, zeros of both signs,
// half-widths beyond 1/2 and at 0 (clamped).
#if defined(__GNUC__)
TEMPLATE_TEST_CASE("GIMP weights of both axes at once are weights() axis by axis, bit for bit", "[shape][verification]",
                   gimlet::shape::ugimp, gimlet::shape::cpgimp) {
    std::uint64_t state = 0x9e3779b97f4a7c15ULL;
    auto next = [&] {  // splitmix64: the same numbers on every platform
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;  // [0, 1)
    };
    std::size_t differ = 0, cases = 0;
    for (int k = 0; k < 200000; ++k) {
        std::array<double, 2> x{100 * next() - 50, 100 * next() - 50}, l{0.6 * next(), 0.6 * next()};
        if (k % 5 == 0) x[0] = 0.25 * std::floor(4 * x[0]), l[0] = 0.25;  // |r| = l, 1 - l, 1 + l exactly
        if (k % 7 == 0) x[1] = 0.25 * std::floor(4 * x[1]), l[1] = 0.25;
        if (k % 11 == 0) x[1] = (k % 22 == 0) ? -0.0 : 0.0;
        if (k % 13 == 0) l[0] = 0.0;
        std::array<int, 2> first{};
        std::array<std::array<double, TestType::stencil>, 2> w{}, dw{};
        TestType::weights_2d(x, l, first, w, dw);
        for (int d = 0; d < 2; ++d) {
            int f = 0;
            std::array<double, TestType::stencil> ws{}, dws{};
            static_assert(std::is_same_v<typename TestType::weights_2d_shape, TestType>);
            TestType::weights(x[d], l[d], f, ws.data(), dws.data());
            ++cases;
            if (f != first[d] || std::memcmp(ws.data(), w[d].data(), sizeof ws) != 0 ||
                std::memcmp(dws.data(), dw[d].data(), sizeof dws) != 0)
                ++differ;
        }
    }
    CHECK(cases == 400000);
    CHECK(differ == 0);
}
#endif
