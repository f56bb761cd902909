// SPDX-License-Identifier: MIT
#pragma once
// The processes an example runs on (examples' helper, not part of the library): under mpirun
// where it is built with MPI (gimlet::mpi; GIMLET_EXAMPLE_MPI), else one; and the examples'
// solver type (example::solver), a distributed_solver where so built. The first process
// writes, prints and draws.

#include <gimlet/core/processes.hpp>
#include <gimlet/solver/solver.hpp>

#include <cstdint>
#include <memory>
#include <utility>

#if GIMLET_EXAMPLE_MPI
#include <gimlet/mpi/slabs.hpp>
#endif

namespace example {

// Whether the example is built to run on many processes (with MPI).
#if GIMLET_EXAMPLE_MPI
inline constexpr bool distributed = true;
#else
inline constexpr bool distributed = false;
#endif

// The example's solver: one that runs on many processes (gimlet::distributed_solver) where it is
// built with MPI, else one compiled for one process alone.
template <class S, class Sh, class M, class C = gimlet::contact::single_field, class X = gimlet::field_list<>,
          class P = gimlet::multi_field::by_body>
using solver = gimlet::solver<S, Sh, M, C, X, P, distributed>;

class run_processes {
public:
    // MPI started (where built with it) for the program's life.
    run_processes([[maybe_unused]] int& argc, [[maybe_unused]] char**& argv)
#if GIMLET_EXAMPLE_MPI
        : environment_(argc, argv)
#endif
    {
    }

    // Whether this process writes, prints and draws (the first).
    [[nodiscard]] bool writer() const { return rank() == 0; }
    [[nodiscard]] int rank() const {
#if GIMLET_EXAMPLE_MPI
        return comm_.rank();
#else
        return 0;
#endif
    }
    [[nodiscard]] int size() const {
#if GIMLET_EXAMPLE_MPI
        return comm_.size();
#else
        return 1;
#endif
    }
    // f() on every process; where it throws on any, every process throws (the writer's message).
    template <class F>
    void together(F&& f) const {
#if GIMLET_EXAMPLE_MPI
        comm_.together(std::forward<F>(f));
#else
        std::forward<F>(f)();
#endif
    }
    // A solver's processes (solver_options::processes; one object a solver), or null on one.
    [[nodiscard]] std::shared_ptr<gimlet::processes> for_solver() const {
#if GIMLET_EXAMPLE_MPI
        if (comm_.size() > 1) return gimlet::mpi::make_ranks(comm_);
#endif
        return nullptr;
    }
    // The sum of every process's n.
    [[nodiscard]] std::uint64_t sum(std::uint64_t n) const {
#if GIMLET_EXAMPLE_MPI
        return comm_.sum(n);
#else
        return n;
#endif
    }

private:
#if GIMLET_EXAMPLE_MPI
    gimlet::mpi::environment environment_;
    gimlet::mpi::communicator comm_;
#endif
};

}  // namespace example
