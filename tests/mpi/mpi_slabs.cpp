// SPDX-License-Identifier: MIT
// The slabs on many ranks (gimlet/mpi/slabs.hpp): every node's sum over a slab pass, with the
// slabs split between the ranks and the bands passed on (node_fold), is bitwise the sum one
// process makes, for every shape's slab rows, periodic or not, one or two velocity fields and
// one or two threads; a rank count that leaves a rank without a slab is refused by name.
#include <gimlet/mpi/slabs.hpp>
#include <gimlet/solver/slabs.hpp>

#include <catch2/catch.hpp>

#include <Eigen/Core>

#include <bit>
#include <cstdint>
#include <random>
#include <vector>

namespace {

// A scatter of synthetic particles onto a grid of `rows` rows of `per_row` nodes: particle p
// adds w * value to the nodes of column col[p] in rows first[p] .. first[p] + Rows (wrapped on
// a periodic axis), into field block field[p], as the solver's stencils add into its arrays.
template <int SlabRows>
struct scatter_case {
    int rows = 0;
    std::size_t per_row = 0;
    bool periodic = false;
    int fields = 1;
    std::vector<int> first;
    std::vector<std::size_t> col;
    std::vector<int> field;
    std::vector<double> w, m;
    std::vector<Eigen::Vector2d> v;

    scatter_case(int rows_, std::size_t per_row_, bool periodic_, int fields_, std::size_t n, std::uint64_t seed)
        : rows(rows_), per_row(per_row_), periodic(periodic_), fields(fields_) {
        std::mt19937_64 rng(seed);
        const int last_first = periodic ? rows - 1 : rows - SlabRows - 1;
        std::uniform_int_distribution<int> row(0, last_first), fld(0, fields - 1);
        std::uniform_int_distribution<std::size_t> column(0, per_row - 1);
        std::uniform_real_distribution<double> u(-1, 1);
        for (std::size_t p = 0; p < n; ++p) {
            first.push_back(row(rng)), col.push_back(column(rng)), field.push_back(fld(rng));
            w.push_back(u(rng)), m.push_back(u(rng)), v.push_back({u(rng), 1e-9 * u(rng)});
        }
    }
    [[nodiscard]] std::size_t nodes() const { return std::size_t(rows) * per_row; }

    // The nodal mass and momentum arrays after scattering the particles `mine` (indices into the
    // case's particles, in increasing order) with the schedule's order, on `threads` threads,
    // exchanging through `exchange`.
    template <class X>
    void scatter(const std::vector<std::size_t>& mine, int threads, std::vector<double>& mass,
                 std::vector<Eigen::Vector2d>& momentum, X&& exchange) const {
        gimlet::detail::slab_schedule<SlabRows> slabs;
        slabs.set_up(rows, periodic);
        slabs.resize(mine.size());
        for (std::size_t k = 0; k < mine.size(); ++k) slabs.assign(k, first[mine[k]]);
        slabs.bucket();
        mass.assign(nodes() * std::size_t(fields), 0.0);
        momentum.assign(nodes() * std::size_t(fields), Eigen::Vector2d::Zero());
        slabs.for_each(threads > 1, threads, [&](std::size_t k) {
            const std::size_t p = mine[k];
            for (int r = 0; r <= SlabRows; ++r) {
                const std::size_t e = std::size_t(field[p]) * nodes() + std::size_t((first[p] + r) % rows) * per_row + col[p];
                mass[e] += w[p] * m[p];
                momentum[e] += w[p] * m[p] * v[p];
            }
        }, exchange);
    }
};

bool same(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

template <int SlabRows>
void check_fold(int rows, bool periodic, int fields, int threads) {
    const gimlet::mpi::communicator comm;
    const scatter_case<SlabRows> c(rows, 5, periodic, fields, 4000, std::uint64_t(rows * 10 + fields));
    gimlet::detail::slab_schedule<SlabRows> global;
    global.set_up(rows, periodic);
    if (global.slabs() < comm.size()) return;  // refused: the next test case
    // One process's sums, on every rank.
    std::vector<std::size_t> all(c.first.size());
    for (std::size_t p = 0; p < all.size(); ++p) all[p] = p;
    std::vector<double> mass_1;
    std::vector<Eigen::Vector2d> momentum_1;
    c.scatter(all, 1, mass_1, momentum_1, gimlet::detail::no_exchange{});
    // This rank's particles (those of its slabs), scattered with the bands passed on.
    gimlet::mpi::ranks processes(comm);
    processes.set_up(global.layout(c.per_row, c.nodes()));
    const gimlet::mpi::slab_ranks ranks(global.slabs(), comm.size());
    std::vector<std::size_t> mine;
    for (std::size_t p = 0; p < all.size(); ++p)
        if (processes.owner(std::min(c.first[p] / SlabRows, global.slabs() - 1)) == comm.rank()) mine.push_back(p);
    std::vector<double> mass;
    std::vector<Eigen::Vector2d> momentum;
    {
        // The exchange takes the arrays' addresses: size them first.
        mass.assign(c.nodes() * std::size_t(fields), 0.0);
        momentum.assign(c.nodes() * std::size_t(fields), Eigen::Vector2d::Zero());
    }
    gimlet::detail::fold_exchange<2> exchange{&processes, {gimlet::nodal_array::of(mass, c.nodes()), gimlet::nodal_array::of(momentum, c.nodes())}};
    c.scatter(mine, threads, mass, momentum, exchange);
    // Every node of this rank's slabs and of the band above its last slab.
    const int first_slab = ranks.first(comm.rank()), end_slab = ranks.first(comm.rank() + 1);
    const int first_row = global.first_row(first_slab);
    int end_row = global.end_row(end_slab - 1) + SlabRows;
    if (!periodic) end_row = std::min(end_row, rows);
    std::size_t compared = 0, differ = 0;
    for (int f = 0; f < fields; ++f)
        for (int r = first_row; r < end_row; ++r)
            for (std::size_t k = 0; k < c.per_row; ++k) {
                const std::size_t e = std::size_t(f) * c.nodes() + std::size_t(r % rows) * c.per_row + k;
                ++compared;
                if (!same(mass[e], mass_1[e]) || !same(momentum[e][0], momentum_1[e][0]) ||
                    !same(momentum[e][1], momentum_1[e][1]))
                    ++differ;
            }
    INFO("rank " << comm.rank() << " of " << comm.size() << ", rows " << rows << ", periodic " << periodic
                 << ", slab rows " << SlabRows << ", fields " << fields << ", threads " << threads);
    CHECK(compared > 0);
    CHECK(differ == 0);
}

}  // namespace

TEST_CASE("node_fold: every node's sum on many ranks is bitwise one process's sum", "[mpi][slabs]") {
    for (int threads : {1, 2})
        for (int fields : {1, 2}) {
            for (bool periodic : {false, true}) {
                check_fold<1>(23, periodic, fields, threads);  // linear: slabs of one row
                check_fold<2>(40, periodic, fields, threads);  // uGIMP: even slab count
                check_fold<2>(31, periodic, fields, threads);  // odd slab count (a third colour where periodic)
                check_fold<3>(17, periodic, fields, threads);  // cubic B-spline
            }
            check_fold<2>(9, true, fields, threads);  // four slabs: on four ranks, one each
            check_fold<2>(7, true, fields, threads);  // three slabs, the last wrapping
        }
}

TEST_CASE("slab_ranks: contiguous slabs for every rank, refused where a rank would have none", "[mpi][slabs]") {
    for (int slabs : {1, 2, 3, 7, 20})
        for (int ranks = 1; ranks <= slabs; ++ranks) {
            const gimlet::mpi::slab_ranks r(slabs, ranks);
            CHECK(r.first(0) == 0);
            CHECK(r.first(ranks) == slabs);
            for (int k = 0; k < ranks; ++k) CHECK(r.first(k + 1) > r.first(k));
            for (int s = 0; s < slabs; ++s) CHECK((r.first(r.owner(s)) <= s && s < r.first(r.owner(s) + 1)));
        }
    CHECK_THROWS_WITH(gimlet::mpi::slab_ranks(3, 4), Catch::Contains("MPI ranks") && Catch::Contains("1 .. 3"));
}
