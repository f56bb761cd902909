// SPDX-License-Identifier: MIT
// The fields' normals at the nodes they share (docs/physics.md section 3): each field's mass
// gradient sum_p m_p G_ip over the particles whose mass goes to that field at the node,
// normalised. The solver sums it at the shared nodes only, in a pass over the particles of the
// slabs of the scatter's schedule that can reach a shared row (multi_field::exchange::
// find_shared_nodes). Here a contact policy records every shared node's normals in the first
// step, and each is compared with the sum over EVERY particle of its field, taken from the
// positions before the step with the GIMP kernel itself: a particle the slab selection missed,
// or one counted twice, would turn the normal. On two threads, above the size at which the
// passes run on them, with:
// - two bodies on a grid periodic on both axes with an odd number of slabs along y (the last
//   slab's stencils wrap onto the first, a colour of its own), side by side: they meet along
//   every row of nodes, so every slab is visited;
// - the same bodies stacked: they meet along two rows (the middle, and across the seam), so
//   only a few slabs are visited, the first and the last among them;
// - one body split into two fields by a per-particle tag (a partition), the halves meeting.
#include <gimlet/gimlet.hpp>

#include <catch2/catch.hpp>

#include "tag_partition.hpp"

#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace {

using S = gimlet::space<2>;
using vec = S::vector;
namespace f = gimlet::fields;

struct seen_node {
    vec position;
    std::vector<std::uint32_t> field;
    std::vector<vec> normal;
};
struct seen_nodes {
    std::mutex lock;
    std::vector<seen_node> nodes;
};

// Records each shared node's fields and their normals; corrects nothing, so engages nothing.
struct normal_recorder {
    static constexpr bool multi_field = true;
    using required_fields = gimlet::field_list<>;
    template <gimlet::Space Sp>
    void resolve(gimlet::contact::node_view<Sp>& node) const {
        seen_node s{node.position, {}, {}};
        for (std::size_t b = 0; b < node.count; ++b) s.field.push_back(node.field[b]), s.normal.push_back(node.normal[b]);
        const std::lock_guard<std::mutex> hold(seen->lock);
        seen->nodes.push_back(s);
    }
    std::shared_ptr<seen_nodes> seen = std::make_shared<seen_nodes>();
};
static_assert(gimlet::contact::NodeResolver<normal_recorder>);

using gimlet_multi_field_tests::by_tag;  // each body split into two fields by a tag
using gimlet_multi_field_tests::half;

constexpr double h = 1e-3;  // cell (m)

// Along one axis: x_p - x_i in cells, the nearest image on a periodic axis of length `period`
// cells (0: not periodic).
double cells_between(double xp, double xi, double period) {
    double r = (xp - xi) / h;
    if (period > 0) r -= period * std::round(r / period);
    return r;
}

// Every recorded node's normals against sum_p m_p G_ip over every particle of the field, from
// the particles as they were before the step (x, m, field of each). Returns the normals checked.
std::size_t check_normals(const std::vector<seen_node>& seen, const std::vector<vec>& x, const std::vector<double>& m,
                          const std::vector<std::uint32_t>& field, const std::vector<vec>& half_width, const vec& period) {
    std::size_t checked = 0;
    for (const seen_node& node : seen) {
        REQUIRE(node.field.size() >= 2);
        for (std::size_t b = 0; b < node.field.size(); ++b) {
            vec sum = vec::Zero();
            for (std::size_t p = 0; p < x.size(); ++p) {
                if (field[p] != node.field[b]) continue;
                double w[2], dw[2];
                for (int d = 0; d < 2; ++d) {
                    const double l = half_width[p][d] / h;
                    gimlet::shape::detail::gimp_kernel(cells_between(x[p][d], node.position[d], period[d]), l, 1 / l, w[d], dw[d]);
                }
                sum += m[p] * vec(dw[0] / h * w[1], w[0] * dw[1] / h);
            }
            REQUIRE(sum.norm() > 0);
            const vec expected = sum / sum.norm();
            INFO("node at (" << node.position[0] << ", " << node.position[1] << "), field " << node.field[b]);
            CHECK((node.normal[b] - expected).norm() < 1e-9);
            ++checked;
        }
    }
    return checked;
}

// Cells of side h from the origin to `upper`, periodic across x, `along_y` along y.
gimlet::grid_spec<S> grid(const vec& upper, gimlet::boundary along_y) {
    gimlet::grid_spec<S> gs;
    gs.lower = vec::Zero();
    gs.upper = upper;
    gs.cell = h;
    gs.bc = {gimlet::boundary::periodic, along_y};
    return gs;
}

template <class Solver>
void step_and_check(Solver& sol, const std::vector<std::uint32_t>& field, const vec& period,
                    const std::shared_ptr<seen_nodes>& seen, std::size_t at_least) {
    REQUIRE(sol.particles().size() > 4096);  // above the size at which the passes run on the threads
    const std::vector<vec> x = sol.particles().template column<f::position>();
    const std::vector<double> m = sol.particles().template column<f::mass>();
    const std::vector<vec> l = sol.particles().template column<f::domain_half_width>();
    sol.step(1e-7);
    REQUIRE(!seen->nodes.empty());
    CHECK(check_normals(seen->nodes, x, m, field, l, period) >= at_least);
}

}  // namespace

TEST_CASE("contact normals: every shared node's is the mass gradient of all its field's particles",
          "[multi_field][contact][threads]") {
    const auto mat = gimlet::make_elastic_material(1000, 1e6, 0.3);
    gimlet::solver_options<S> opt;
    opt.threads = 2;

    // 43 node rows along y: 21 slabs of 2 rows, the last of 3. The bodies touch at 21.5 mm along
    // `axis` and across the seam there.
    for (const int axis : {0, 1}) {
        DYNAMIC_SECTION("two bodies, periodic on both axes, an odd number of slabs, meeting across axis " << axis) {
            gimlet::scene::scene<S, gimlet::elastic_material> sc(grid(vec(0.043, 0.043), gimlet::boundary::periodic));
            vec mid(0.043, 0.043), start = vec::Zero(), v = vec::Zero();
            mid[axis] = start[axis] = 0.0215;
            v[axis] = 1.0;
            sc.add_body(gimlet::scene::box<S>(vec::Zero(), mid), mat, v, 2, "first");
            sc.add_body(gimlet::scene::box<S>(start, vec(0.043, 0.043)), mat, vec(-v), 2, "second");
            normal_recorder law;
            const auto seen = law.seen;
            gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, normal_recorder> sol(sc, opt, law);
            const std::vector<std::uint32_t> body = sol.particles().column<f::body>();
            // Both meeting lines, every node of each (43 along), both fields: at least 4 x 43.
            step_and_check(sol, body, vec(43, 43), seen, 4 * 43);
            bool seam = false, middle = false;
            for (const seen_node& n : seen->nodes) {
                seam = seam || n.position[axis] < 2 * h || n.position[axis] > 0.043 - 2 * h;
                middle = middle || std::abs(n.position[axis] - 0.0215) < 2 * h;
            }
            CHECK(seam);
            CHECK(middle);
        }
    }

    SECTION("one body split into two fields by a tag") {
        gimlet::scene::scene<S, gimlet::elastic_material> sc(grid(vec(0.040, 0.060), gimlet::boundary::free));
        sc.add_body(gimlet::scene::box<S>(vec(0.0, 0.010), vec(0.040, 0.050)), mat, vec::Zero(), 2, "block");
        normal_recorder law;
        const auto seen = law.seen;
        gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material, normal_recorder, gimlet::field_list<>, by_tag> sol(
            sc, opt, law);
        auto& tag = sol.particles().column<half>();
        const auto& x = sol.particles().column<f::position>();
        std::vector<std::uint32_t> field(tag.size());
        for (std::size_t i = 0; i < tag.size(); ++i) {
            tag[i] = x[i][1] < 0.0305 ? 0 : 1;  // the halves meet at y = 30.5 mm, off the grid lines
            field[i] = 2 * sol.particles().column<f::body>()[i] + tag[i];
        }
        step_and_check(sol, field, vec(40, 0), seen, 2 * 40);
    }
}
