// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The grid's slabs on many processes: which rank owns which slabs (gimlet::mpi::slab_ranks),
/// and the exchange that completes every node's sum in the one-process order
/// (gimlet::mpi::node_fold).

#include "gimlet/core/error.hpp"
#include "gimlet/mpi/communicator.hpp"
#include "gimlet/core/processes.hpp"

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace gimlet::mpi {

/// Contiguous ranges of the slabs of one global schedule (detail::slab_schedule, built from the
/// global rows and periodicity), one per rank, as even in count as the division allows: rank r
/// owns slabs [first(r), first(r + 1)). A slab's colour belongs to its global index, so the
/// order in which each node sums its particles is the same for any number of ranks.
class slab_ranks {
public:
    /// `slabs` slabs on `ranks` ranks. Throws gimlet::invalid_parameter where a rank would own
    /// no whole slab (ranks > slabs).
    slab_ranks(int slabs, int ranks) : slabs_(slabs), ranks_(ranks) {
        require(ranks >= 1 && ranks <= slabs, "MPI ranks", double(ranks),
                "1 .. " + std::to_string(slabs) + ": the grid's slabs of node rows along the last axis, at least one a rank");
    }

    /// The first slab of rank r (first(ranks) = slabs).
    [[nodiscard]] int first(int r) const noexcept {
        return int(std::int64_t(slabs_) * r / ranks_);
    }
    /// The rank that owns slab s.
    [[nodiscard]] int owner(int s) const noexcept {
        // The largest r with first(r) <= s.
        int r = int((std::int64_t(s) * ranks_ + ranks_ - 1) / slabs_);
        while (r > 0 && first(r) > s) --r;
        while (r + 1 < ranks_ && first(r + 1) <= s) ++r;
        return r;
    }
    /// The number of slabs.
    [[nodiscard]] int slabs() const noexcept { return slabs_; }
    /// The number of ranks.
    [[nodiscard]] int ranks() const noexcept { return ranks_; }

private:
    int slabs_, ranks_;
};

/// The exchange that makes every node's sum over a slab pass on many processes bitwise the sum
/// one process makes. One process adds a node's contributions colour by colour: a node of the
/// first rows of slab u (the rows the stencils of slab u - 1 reach) takes them from slabs u - 1
/// and u, the one of lower colour first, each in particle order (detail::slab_schedule). Where
/// the two slabs are on different ranks, the rank of the first colour scatters its slab and
/// passes its running sums of those rows (the band) to the other, which goes on from them, adds
/// its own and passes the completed sums back. No partial sums are added to each other, so
/// every node's sum is the one-process left fold, and node values outside the bands never
/// travel. (The alternative, copies of the neighbours' particles scattered by each rank, would
/// send whole particles before every scatter: a band of SlabRows node rows is smaller than the
/// particles that reach it.)
///
/// Every rank holds the whole grid's arrays and touches its own slabs' rows and the band above
/// its last slab. Before a pass the bands must hold the same values on both ranks (zero, or
/// the last pass's completed sums: every pass ends with them so).
class node_fold {
    // A band of node rows two ranks both add to: the first SlabRows rows of the upper slab.
    struct band {
        int tag = 0, other = 0;  // the upper slab's index x 2 (+1 for the completed sums); the other rank
        int mine = 0, theirs = 0;  // the colours of this rank's slab and the other's
        std::size_t first = 0, count = 0;  // nodes [first, first + count) of each block
    };

public:
    /// The slabs (set up from the global rows) on the processes of `comm`.
    node_fold(const communicator& comm, const slab_layout& layout)
        : comm_(comm), ranks_(layout.slabs(), comm.size()), nodes_(layout.nodes) {
        const int L = layout.slabs(), me = comm.rank();
        for (int u = 0; u < L; ++u) {
            if (u == 0 && !(layout.periodic && L > 1)) continue;  // slab 0 has no slab below
            const int s = (u + L - 1) % L;
            const int lower = ranks_.owner(s), upper = ranks_.owner(u);
            if (lower == upper || (lower != me && upper != me)) continue;
            band b;
            b.tag = 2 * u;
            b.other = lower == me ? upper : lower;
            b.mine = layout.colour[std::size_t(lower == me ? s : u)];
            b.theirs = layout.colour[std::size_t(lower == me ? u : s)];
            const int first = layout.first_row[std::size_t(u)];
            const int end = std::min(first + layout.slab_rows, layout.first_row[std::size_t(u) + 1]);
            b.first = std::size_t(first) * layout.nodes_per_row;
            b.count = std::size_t(end - first) * layout.nodes_per_row;
            bands_.push_back(b);
            shared_.push_back({b.first, b.count, b.other, u});
        }
        const int tag_limit = 3 * L + 2;
        int* upper_bound = nullptr;
        int found = 0;
        MPI_Comm_get_attr(comm.get(), MPI_TAG_UB, &upper_bound, &found);
        require(!found || *upper_bound >= tag_limit, "slabs along the last axis", double(L),
                "at most " + std::to_string(found ? *upper_bound / 3 - 1 : 0) + " (this MPI's largest message tag / 3)");
    }

    /// The bands this rank shares with others, in slab order.
    [[nodiscard]] std::span<const shared_band> bands() const noexcept { return shared_; }

    /// `mine[b]` to the other rank of bands()[b]; returns what it passed for the same band.
    [[nodiscard]] std::vector<std::vector<std::byte>> swap(const std::vector<std::vector<std::byte>>& mine) {
        // Tags above the fold's (2 x slabs + 2): the band's upper slab names it on both ranks.
        const int base = 2 * ranks_.slabs() + 2;
        std::vector<std::uint64_t> sizes(bands_.size()), theirs(bands_.size());
        std::vector<MPI_Request> requests;
        for (std::size_t b = 0; b < bands_.size(); ++b) {
            sizes[b] = mine[b].size();
            comm_.isend(&sizes[b], sizeof(std::uint64_t), bands_[b].other, base + shared_[b].slab, requests.emplace_back());
            comm_.irecv(&theirs[b], sizeof(std::uint64_t), bands_[b].other, base + shared_[b].slab, requests.emplace_back());
        }
        MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
        requests.clear();
        std::vector<std::vector<std::byte>> in(bands_.size());
        for (std::size_t b = 0; b < bands_.size(); ++b) {
            in[b].resize(theirs[b]);
            if (!mine[b].empty())
                comm_.isend(mine[b].data(), mine[b].size(), bands_[b].other, base + shared_[b].slab, requests.emplace_back());
            if (!in[b].empty())
                comm_.irecv(in[b].data(), in[b].size(), bands_[b].other, base + shared_[b].slab, requests.emplace_back());
        }
        MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
        return in;
    }

    /// The ranks that own the slabs.
    [[nodiscard]] const slab_ranks& ranks() const noexcept { return ranks_; }

    /// After colour c's slabs of a pass over `arrays` have scattered on every rank: the running
    /// sums of the bands whose next contributor is the other rank go to it, and those this rank
    /// adds to next come in.
    void after_colour(int c, std::span<const nodal_array> arrays) {
        for (const auto& b : bands_)
            if (b.mine == c && b.theirs > c) send(b, b.tag, arrays);
        for (const auto& b : bands_)
            if (b.theirs == c && b.mine > c) receive(b, b.tag, arrays);
    }
    /// After the last colour: the completed sums go back to the rank that added first.
    void finish(std::span<const nodal_array> arrays) {
        for (const auto& b : bands_)
            if (b.mine > b.theirs) send(b, b.tag + 1, arrays);
        for (const auto& b : bands_)
            if (b.theirs > b.mine) receive(b, b.tag + 1, arrays);
        MPI_Waitall(int(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
        requests_.clear();
        outgoing_.clear();
    }

private:
    [[nodiscard]] static std::size_t band_bytes(const band& b, std::span<const nodal_array> arrays) {
        std::size_t bytes = 0;
        for (const auto& a : arrays) bytes += a.blocks * b.count * a.value_bytes;
        return bytes;
    }
    void send(const band& b, int tag, std::span<const nodal_array> arrays) {
        auto& buffer = outgoing_.emplace_back(band_bytes(b, arrays));
        std::byte* at = buffer.data();
        for (const auto& a : arrays)
            for (std::size_t k = 0; k < a.blocks; ++k) {
                const std::size_t bytes = b.count * a.value_bytes;
                std::memcpy(at, a.data + (k * nodes_ + b.first) * a.value_bytes, bytes);
                at += bytes;
            }
        comm_.isend(buffer.data(), buffer.size(), b.other, tag, requests_.emplace_back());
    }
    void receive(const band& b, int tag, std::span<const nodal_array> arrays) {
        incoming_.resize(band_bytes(b, arrays));
        comm_.recv(incoming_.data(), incoming_.size(), b.other, tag);
        const std::byte* at = incoming_.data();
        for (const auto& a : arrays)
            for (std::size_t k = 0; k < a.blocks; ++k) {
                const std::size_t bytes = b.count * a.value_bytes;
                std::memcpy(a.data + (k * nodes_ + b.first) * a.value_bytes, at, bytes);
                at += bytes;
            }
    }

    communicator comm_;
    slab_ranks ranks_;
    std::size_t nodes_;
    std::vector<band> bands_;
    std::vector<shared_band> shared_;  // bands_ as processes::bands gives them
    std::vector<std::vector<std::byte>> outgoing_;  // kept until their sends complete
    std::vector<std::byte> incoming_;
    std::vector<MPI_Request> requests_;
};

/// A solver on the ranks of an MPI communicator (solver_options::processes of a
/// gimlet::distributed_solver = the shared pointer make_ranks gives): the gimlet::processes a
/// solver calls, on MPI.
class ranks final : public processes {
public:
    /// The ranks of `comm`, on a duplicate of it: the library's messages never meet the
    /// program's own.
    explicit ranks(const communicator& comm = communicator{}) : comm_(duplicate(comm)) {}
    ranks(const ranks&) = delete;
    ranks& operator=(const ranks&) = delete;
    ~ranks() override {
        int finalized = 0;
        MPI_Finalized(&finalized);
        MPI_Comm handle = comm_.get();
        if (!finalized) MPI_Comm_free(&handle);
    }

    [[nodiscard]] int rank() const override { return comm_.rank(); }
    [[nodiscard]] int size() const override { return comm_.size(); }
    // A solver's slabs. Solvers built from copies of one options object share this object: that
    // is safe for the same slabs (the exchanges keep nothing between passes), refused for others.
    void set_up(const slab_layout& layout) override {
        if (fold_ && !(layout_ == layout))
            throw invalid_parameter("solver_options::processes", "shared with a solver of other slabs",
                                    "one gimlet::mpi::make_ranks() for each solver of its own grid");
        if (fold_) return;
        fold_.emplace(comm_, layout);
        layout_ = layout;
    }
    [[nodiscard]] int owner(int slab) const override { return fold_->ranks().owner(slab); }
    void after_colour(int colour, std::span<const nodal_array> arrays) override { fold_->after_colour(colour, arrays); }
    void finish(std::span<const nodal_array> arrays) override { fold_->finish(arrays); }
    [[nodiscard]] std::span<const shared_band> bands() const override { return fold_->bands(); }
    [[nodiscard]] std::vector<std::vector<std::byte>> swap(const std::vector<std::vector<std::byte>>& mine) override {
        return fold_->swap(mine);
    }
    [[nodiscard]] std::vector<std::vector<std::byte>> all_to_all(const std::vector<std::vector<std::byte>>& out) override {
        return comm_.all_to_all(out);
    }
    [[nodiscard]] double min(double x) override { return comm_.min(x); }
    [[nodiscard]] double max(double x) override { return comm_.max(x); }
    [[nodiscard]] std::uint64_t sum(std::uint64_t n) override { return comm_.sum(n); }
    [[nodiscard]] std::uint64_t exclusive_sum(std::uint64_t n) override { return comm_.exclusive_sum(n); }
    [[nodiscard]] exact_sum sum(const exact_sum& part) override { return comm_.sum(part); }
    [[nodiscard]] std::string share(const std::string* mine) override { return comm_.share(mine); }
    void together(const std::function<void()>& f) override { comm_.together(f); }

    /// The communicator.
    [[nodiscard]] const communicator& comm() const noexcept { return comm_; }

private:
    static communicator duplicate(const communicator& comm) {
        MPI_Comm copy = MPI_COMM_NULL;
        MPI_Comm_dup(comm.get(), &copy);
        return communicator(copy);
    }

    communicator comm_;
    std::optional<node_fold> fold_;
    slab_layout layout_;
};

/// The processes of `comm` for solver_options::processes, of a gimlet::distributed_solver (a
/// plain gimlet::solver refuses them).
[[nodiscard]] inline std::shared_ptr<processes> make_ranks(const communicator& comm = communicator{}) {
    return std::make_shared<ranks>(comm);
}

}  // namespace gimlet::mpi
