// SPDX-License-Identifier: MIT
// MPI for the MPI tests' run: started before the first test case and finished after the last,
// by a Catch2 listener (the runner is gimlet_catch_main's). ctest runs the executable under
// mpirun on 1, 2, 3 and 4 ranks; every rank runs every test case, and mpirun fails where any
// rank fails.
#define CATCH_CONFIG_EXTERNAL_INTERFACES
#include <catch2/catch.hpp>

#include <mpi.h>

namespace {

struct mpi_run : Catch::TestEventListenerBase {
    using TestEventListenerBase::TestEventListenerBase;
    void testRunStarting(const Catch::TestRunInfo&) override {
        int provided = 0;
        MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    }
    void testRunEnded(const Catch::TestRunStats&) override { MPI_Finalize(); }
};

}  // namespace

CATCH_REGISTER_LISTENER(mpi_run)
