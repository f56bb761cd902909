// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// gimlet::mpi::environment and gimlet::mpi::communicator: MPI started and stopped, and the
/// collective operations a distributed run needs, none of which adds floating-point numbers in
/// an order that depends on the ranks (the optional `mpi` component: gimlet::mpi).

#include "gimlet/core/error.hpp"
#include "gimlet/core/exact_sum.hpp"
#include "gimlet/core/processes.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <string>
#include <vector>

/// The optional MPI component (target gimlet::mpi): slabs of the grid on many processes, with
/// results bitwise independent of how many.
namespace gimlet::mpi {

/// MPI for the life of the object: MPI_Init_thread (OpenMP threads call no MPI: funneled) and
/// MPI_Finalize. A program makes one, first thing in main; where MPI is already running (a test
/// harness started it) the object leaves it running.
class environment {
public:
    /// Start MPI with main's arguments.
    environment(int& argc, char**& argv) {
        int started = 0;
        MPI_Initialized(&started);
        if (started) return;
        int provided = 0;
        MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
        owner_ = true;
        if (provided < MPI_THREAD_FUNNELED) {
            MPI_Finalize();
            owner_ = false;
            throw invalid_parameter("MPI thread support", std::to_string(provided),
                                    "MPI_THREAD_FUNNELED or more (the main thread calls MPI while OpenMP threads run)");
        }
    }
    environment(const environment&) = delete;
    environment& operator=(const environment&) = delete;
    ~environment() {
        if (owner_) MPI_Finalize();
    }

private:
    bool owner_ = false;
};

/// The processes of a run (an MPI communicator, not owned) and its collectives. Sums of
/// floating-point numbers go through exact sums (gimlet::exact_sum), whose digits are added as
/// integers, so a result does not depend on the number of processes; minima and maxima are
/// exact in any order.
class communicator {
public:
    /// The processes of `comm` (MPI_COMM_WORLD by default).
    explicit communicator(MPI_Comm comm = MPI_COMM_WORLD) : comm_(comm) {
        MPI_Comm_rank(comm_, &rank_);
        MPI_Comm_size(comm_, &size_);
    }

    /// This process's rank, 0 .. size() - 1.
    [[nodiscard]] int rank() const noexcept { return rank_; }
    /// The number of processes.
    [[nodiscard]] int size() const noexcept { return size_; }
    /// The MPI communicator.
    [[nodiscard]] MPI_Comm get() const noexcept { return comm_; }

    /// Wait for every process.
    void barrier() const { MPI_Barrier(comm_); }
    /// The least of every process's x.
    [[nodiscard]] double min(double x) const { return reduce(x, MPI_MIN); }
    /// The greatest of every process's x.
    [[nodiscard]] double max(double x) const { return reduce(x, MPI_MAX); }
    /// The sum of every process's n (integers: any order is exact).
    [[nodiscard]] std::uint64_t sum(std::uint64_t n) const {
        std::uint64_t out = 0;
        MPI_Allreduce(&n, &out, 1, MPI_UINT64_T, MPI_SUM, comm_);
        return out;
    }
    /// The sum of the n of the processes below this one (0 on rank 0).
    [[nodiscard]] std::uint64_t exclusive_sum(std::uint64_t n) const {
        std::uint64_t out = 0;
        MPI_Exscan(&n, &out, 1, MPI_UINT64_T, MPI_SUM, comm_);
        return rank_ == 0 ? 0 : out;
    }
    /// The exact sum of every process's partial sum: the digits added as integers, the
    /// non-finite states OR-ed.
    [[nodiscard]] exact_sum sum(const exact_sum& part) const {
        const exact_sum::digit_array mine = part.digits();
        exact_sum::digit_array total{};
        MPI_Allreduce(mine.data(), total.data(), exact_sum::digit_count, MPI_INT64_T, MPI_SUM, comm_);
        MPI_Allreduce(&mine[exact_sum::digit_count], &total[exact_sum::digit_count], 1, MPI_INT64_T, MPI_BOR, comm_);
        return exact_sum::from_digits(total);
    }

    /// The text of the lowest rank that passes one (`mine` not null), on every rank; empty where
    /// none does.
    [[nodiscard]] std::string share(const std::string* mine) const {
        int first = mine ? rank_ : size_;
        int lowest = size_;
        MPI_Allreduce(&first, &lowest, 1, MPI_INT, MPI_MIN, comm_);
        if (lowest == size_) return {};
        std::string text = rank_ == lowest ? *mine : std::string();
        int length = int(text.size());
        MPI_Bcast(&length, 1, MPI_INT, lowest, comm_);
        text.resize(std::size_t(length));
        MPI_Bcast(text.data(), length, MPI_CHAR, lowest, comm_);
        return text;
    }

    /// f() on every process; if it throws on any, every process throws gimlet::processes_stopped
    /// with the lowest failing rank's message (agree()). A processes_stopped from f, agreed on
    /// every process already, passes through. Call it where every process reaches the same
    /// call, so that a failure on one rank stops them all instead of leaving the others waiting
    /// in their next exchange.
    template <class F>
    void together(F&& f) const {
        std::string message;
        bool failed = false, bad_input = false;
        try {
            f();
        } catch (const processes_stopped&) {
            throw;
        } catch (const invalid_parameter& e) {
            failed = true, bad_input = true, message = e.what();
        } catch (const std::exception& e) {
            failed = true, message = e.what();
        } catch (...) {
            failed = true, message = "an exception that is not a std::exception";
        }
        agree(failed, std::numeric_limits<double>::max(), message, bad_input);
    }

    /// detail::agree on these processes. Collective.
    void agree(bool failed, double key, const std::string& message, bool bad_input) const {
        detail::agree([&](double x) { return min(x); }, [&](const std::string* text) { return share(text); }, rank_,
                      size_, failed, key, message, bad_input);
    }

    /// Every process's bytes to every process (`out[r]` to rank r); returns what each rank sent
    /// here, indexed by rank.
    [[nodiscard]] std::vector<std::vector<std::byte>> all_to_all(const std::vector<std::vector<std::byte>>& out) const {
        const auto n = std::size_t(size_);
        std::vector<std::uint64_t> send_count(n), receive_count(n);
        for (std::size_t r = 0; r < n; ++r) send_count[r] = out[r].size();
        // A message past MPI's int count stops every process before any is posted.
        std::uint64_t largest = 0;
        for (auto c : send_count) largest = std::max(largest, c);
        agree(largest >= message_limit, 0, "bytes for one process in one exchange = " + std::to_string(largest) +
                                              " is invalid; valid range: < 2^31 (MPI counts are int): use more processes",
              false);
        MPI_Alltoall(send_count.data(), 1, MPI_UINT64_T, receive_count.data(), 1, MPI_UINT64_T, comm_);
        std::vector<std::vector<std::byte>> in(n);
        std::vector<MPI_Request> requests;
        requests.reserve(2 * n);
        constexpr int tag = 7;
        for (std::size_t r = 0; r < n; ++r) {
            in[r].resize(receive_count[r]);
            if (r == std::size_t(rank_)) {
                in[r] = out[r];
                continue;
            }
            if (receive_count[r] > 0) {
                requests.emplace_back();
                irecv(in[r].data(), in[r].size(), int(r), tag, requests.back());
            }
            if (!out[r].empty()) {
                requests.emplace_back();
                isend(out[r].data(), out[r].size(), int(r), tag, requests.back());
            }
        }
        MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
        return in;
    }

    /// A non-blocking send of `bytes` bytes (below 2^31: MPI counts are int) to rank `to`. The
    /// buffer stays untouched until the request is waited for.
    void isend(const void* data, std::size_t bytes, int to, int tag, MPI_Request& request) const {
        require(bytes < message_limit, "bytes in one message", double(bytes), "< 2^31");
        MPI_Isend(data, int(bytes), MPI_BYTE, to, tag, comm_, &request);
    }
    /// A non-blocking receive of exactly `bytes` bytes from rank `from`.
    void irecv(void* data, std::size_t bytes, int from, int tag, MPI_Request& request) const {
        require(bytes < message_limit, "bytes in one message", double(bytes), "< 2^31");
        MPI_Irecv(data, int(bytes), MPI_BYTE, from, tag, comm_, &request);
    }
    /// A blocking receive of exactly `bytes` bytes from rank `from`.
    void recv(void* data, std::size_t bytes, int from, int tag) const {
        require(bytes < message_limit, "bytes in one message", double(bytes), "< 2^31");
        MPI_Recv(data, int(bytes), MPI_BYTE, from, tag, comm_, MPI_STATUS_IGNORE);
    }

private:
    static constexpr std::uint64_t message_limit = std::uint64_t(1) << 31;  // MPI counts are int

    [[nodiscard]] double reduce(double x, MPI_Op op) const {
        double out = 0;
        MPI_Allreduce(&x, &out, 1, MPI_DOUBLE, op, comm_);
        return out;
    }

    MPI_Comm comm_;
    int rank_ = 0, size_ = 1;
};

}  // namespace gimlet::mpi
