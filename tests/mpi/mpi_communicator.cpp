// SPDX-License-Identifier: MIT
// The collectives (gimlet/mpi/communicator.hpp): a sum of doubles over the ranks is the exact
// sum of all the terms rounded once, the same bits for any rank count; a failure on one rank
// stops every rank with its message.
#include <gimlet/mpi/communicator.hpp>

#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

TEST_CASE("communicator::sum of exact sums: the same bits on any rank count", "[mpi][communicator]") {
    const gimlet::mpi::communicator comm;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> mant(-1, 1);
    std::uniform_int_distribution<int> exp(-80, 80);
    std::vector<double> terms(10007);
    for (auto& x : terms) x = std::ldexp(mant(rng), exp(rng));
    gimlet::exact_sum all, mine;
    for (std::size_t i = 0; i < terms.size(); ++i) {
        all += terms[i];
        if (int(i % std::size_t(comm.size())) == comm.rank()) mine += terms[i];
    }
    const double total = comm.sum(mine).value();
    CHECK(std::bit_cast<std::uint64_t>(total) == std::bit_cast<std::uint64_t>(all.value()));
    CHECK(comm.sum(std::uint64_t(comm.rank() + 1)) == std::uint64_t(comm.size() * (comm.size() + 1) / 2));
    CHECK(comm.exclusive_sum(1) == std::uint64_t(comm.rank()));
    CHECK(comm.min(double(comm.rank())) == 0.0);
    CHECK(comm.max(double(comm.rank())) == double(comm.size() - 1));
}

TEST_CASE("communicator::together: a failure on one rank stops every rank with its message, alike", "[mpi][communicator]") {
    const gimlet::mpi::communicator comm;
    const int failing = comm.size() - 1;
    const auto run = [&] {
        comm.together([&] {
            if (comm.rank() == failing) throw std::runtime_error("particle 12 left the grid");
        });
    };
    // The same type and message on every rank, the failing one included.
    CHECK_THROWS_AS(run(), gimlet::processes_stopped);
    CHECK_THROWS_WITH(run(), "rank " + std::to_string(failing) + " of " + std::to_string(comm.size()) +
                                 ": particle 12 left the grid");
    CHECK_NOTHROW(comm.together([] {}));
}
