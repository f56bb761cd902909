// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// gimlet::processes: what a solver asks of the processes it is split between (one MPI rank each,
/// gimlet::mpi::ranks), without naming MPI: the serial library has no MPI dependency.

#include "gimlet/core/error.hpp"
#include "gimlet/core/exact_sum.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace gimlet {

/// A nodal array a slab pass writes: `blocks` blocks (velocity fields) of the grid's nodes, each
/// value copied byte for byte (numbers, fixed-size Eigen vectors), node rows along the last axis
/// outermost within a block.
struct nodal_array {
    /// The first byte of the first value.
    std::byte* data = nullptr;
    /// The bytes of one value.
    std::size_t value_bytes = 0;
    /// How many blocks of the grid's nodes the array holds.
    std::size_t blocks = 1;

    /// The array `values`, of whole blocks of `nodes` nodes (`whole` checks it: a part block would
    /// not be completed across processes).
    template <class T>
    static nodal_array of(std::vector<T>& values, std::size_t nodes, bool whole = false) {
        static_assert(std::is_trivially_destructible_v<T> && std::is_standard_layout_v<T>,
                      "nodal_array: values copied byte for byte (numbers, fixed-size Eigen vectors)");
        if (whole && (nodes == 0 || values.size() % nodes != 0))
            throw invalid_parameter("size of a nodal array a slab pass adds into", std::to_string(values.size()),
                                    "a whole number of blocks of the grid's " + std::to_string(nodes) + " nodes");
        return {reinterpret_cast<std::byte*>(values.data()), sizeof(T), nodes ? values.size() / nodes : 0};
    }
};

/// The slabs of a grid's scatter schedule (detail::slab_schedule), set up from the global rows.
struct slab_layout {
    /// The slabs and the node rows of each: slab s holds rows [first_row[s], first_row[s + 1]).
    std::vector<int> first_row;
    /// Each slab's colour (0, 1 or 2): colours scatter in increasing order.
    std::vector<int> colour;
    /// The rows per slab (the last slab may have up to twice as many less one); a particle's
    /// stencil reaches at most the first slab_rows rows of the next slab.
    int slab_rows = 1;
    /// Whether the last axis is periodic (the last slab's stencils then reach slab 0).
    bool periodic = false;
    /// The grid's nodes per row of the last axis.
    std::size_t nodes_per_row = 0;
    /// The grid's nodes in all.
    std::size_t nodes = 0;
    /// The number of slabs.
    [[nodiscard]] int slabs() const noexcept { return int(colour.size()); }
    /// The same slabs on the same grid.
    [[nodiscard]] bool operator==(const slab_layout&) const = default;
};

/// A failure on one process of a run, thrown on every process alike where they agree on failures
/// (processes::together, and the solver's stages): "rank r of n: " and the failure's message
/// (where several processes failed, the lowest-numbered particle's, else the lowest rank's).
class processes_stopped : public numerical_error {
public:
    /// The message, and whether the failure was bad input (an invalid_parameter) rather than
    /// numerical trouble.
    processes_stopped(const std::string& what, bool bad_input) : numerical_error(what), bad_input_(bad_input) {}
    /// Whether the failure was bad input (an invalid_parameter on the process that failed).
    [[nodiscard]] bool bad_input() const noexcept { return bad_input_; }

private:
    bool bad_input_;
};

namespace detail {
/// Where any process `failed`, every process throws processes_stopped with the message of the
/// failure of lowest `key` (ties: the lowest rank), "rank r of n: " before it; `min(x)` and
/// `share(text)` are the processes' collectives (processes::min, processes::share).
template <class Min, class Share>
void agree(Min&& min, Share&& share, int rank, int size, bool failed, double key, const std::string& message,
           bool bad_input) {
    const double none = std::numeric_limits<double>::infinity();
    const double lowest = min(failed ? key : none);
    if (lowest == none) return;
    const std::string mine = std::to_string(rank) + (bad_input ? " b " : " n ") + message;
    const std::string first = share(failed && key == lowest ? &mine : nullptr);
    const std::size_t space = first.find(' ');
    throw processes_stopped("rank " + first.substr(0, space) + " of " + std::to_string(size) + ": " + first.substr(space + 3),
                            first.compare(space + 1, 1, "b") == 0);
}
}  // namespace detail

/// Node rows two processes both hold: the first slab_rows rows of a slab whose slab below is the
/// other process's (nodes [first, first + count) of every block), and the other process.
struct shared_band {
    /// The first node, in each block.
    std::size_t first = 0;
    /// The number of nodes, in each block.
    std::size_t count = 0;
    /// The other process.
    int other = 0;
    /// The upper slab's index (it names the band in both processes).
    int slab = 0;
};

/// The processes a solver is split between (solver_options::processes of a
/// gimlet::distributed_solver; a plain gimlet::solver refuses them): each owns whole slabs
/// of the grid along its last axis and the particles whose stencils start in them. The solver
/// calls every member on every process alike (they are collective); a program's own code that
/// calls one (diagnostics do) must too. gimlet::mpi::ranks is the MPI implementation.
class processes {
public:
    virtual ~processes() = default;

    /// This process's number, 0 .. size() - 1.
    [[nodiscard]] virtual int rank() const = 0;
    /// The number of processes.
    [[nodiscard]] virtual int size() const = 0;

    /// The solver's slabs, once, before anything else. Throws gimlet::invalid_parameter where a
    /// process would own no slab.
    virtual void set_up(const slab_layout& layout) = 0;
    /// The process that owns slab s.
    [[nodiscard]] virtual int owner(int slab) const = 0;

    /// A slab pass over `arrays`, after colour c's slabs have scattered on every process (c = 0,
    /// 1, 2): the running sums of the nodes two processes both add to pass to the process that
    /// adds next.
    virtual void after_colour(int colour, std::span<const nodal_array> arrays) = 0;
    /// A slab pass over `arrays`, after its last colour: the completed sums go back, so that
    /// the nodes two processes both add to hold every contribution in the one-process order.
    virtual void finish(std::span<const nodal_array> arrays) = 0;

    /// The bands this process shares with others (after set_up), in slab order.
    [[nodiscard]] virtual std::span<const shared_band> bands() const = 0;
    /// `mine[b]` to the other process of bands()[b]; returns what that process passed for the
    /// same band. For values both processes combine in an order-free way (a maximum).
    [[nodiscard]] virtual std::vector<std::vector<std::byte>> swap(const std::vector<std::vector<std::byte>>& mine) = 0;

    /// Bytes to every process (`out[r]` to process r); returns what each sent here, by process.
    [[nodiscard]] virtual std::vector<std::vector<std::byte>> all_to_all(const std::vector<std::vector<std::byte>>& out) = 0;
    /// The least of every process's x (exact in any order).
    [[nodiscard]] virtual double min(double x) = 0;
    /// The greatest of every process's x (exact in any order).
    [[nodiscard]] virtual double max(double x) = 0;
    /// The sum of every process's n.
    [[nodiscard]] virtual std::uint64_t sum(std::uint64_t n) = 0;
    /// The sum of the n of the processes below this one (0 on the first).
    [[nodiscard]] virtual std::uint64_t exclusive_sum(std::uint64_t n) = 0;
    /// The exact sum of every process's partial sum.
    [[nodiscard]] virtual exact_sum sum(const exact_sum& part) = 0;
    /// The text of the lowest process that passes one (`mine` not null), on every process; empty
    /// where none does.
    [[nodiscard]] virtual std::string share(const std::string* mine) = 0;
    /// f() on every process; if it throws on any, every process throws processes_stopped with the
    /// lowest failing process's message, so that none waits for a process that stopped. A
    /// processes_stopped from f (an agreement inside it) passes through unchanged.
    virtual void together(const std::function<void()>& f) = 0;
};

namespace detail {
/// A solver's processes (solver_options::processes; its processes()), or null: one process (a
/// plain gimlet::solver's are always null), or an object without processes().
template <class Solver>
[[nodiscard]] gimlet::processes* processes_of(const Solver& s) {
    if constexpr (requires { s.processes(); }) return s.processes();
    else return (void)s, nullptr;
}

/// Every process's `mine` on every process, in increasing `ordinal` (a record's leading
/// std::uint64_t: its particle's ordinal), records of one ordinal in the order their process
/// gave them: the sequence one process's particle loop makes. `Record` is copied byte for byte.
/// Collective.
template <class Record>
[[nodiscard]] std::vector<Record> in_ordinal_order(gimlet::processes& procs, const std::vector<Record>& mine) {
    static_assert(std::is_trivially_copyable_v<Record>, "in_ordinal_order: records copied byte for byte");
    std::vector<std::byte> bytes(mine.size() * sizeof(Record));
    if (!mine.empty()) std::memcpy(bytes.data(), mine.data(), bytes.size());
    const auto in = procs.all_to_all(std::vector<std::vector<std::byte>>(std::size_t(procs.size()), bytes));
    std::vector<Record> every;
    for (const auto& from : in)
        for (std::size_t at = 0; at + sizeof(Record) <= from.size(); at += sizeof(Record)) {
            Record r;
            std::memcpy(&r, from.data() + at, sizeof r);
            every.push_back(r);
        }
    std::stable_sort(every.begin(), every.end(), [](const Record& a, const Record& b) { return a.ordinal < b.ordinal; });
    return every;
}
}  // namespace detail

}  // namespace gimlet
