// SPDX-License-Identifier: MIT
// The MPI tests' main(): MPI around Catch2's runner. ctest runs the executable under mpirun on
// 1, 2, 3 and 4 ranks; every rank runs every test case, and mpirun fails where any rank fails.
#define CATCH_CONFIG_RUNNER
#include <gimlet/mpi/communicator.hpp>

#include <catch2/catch.hpp>

int main(int argc, char** argv) {
    gimlet::mpi::environment mpi(argc, argv);
    return Catch::Session().run(argc, argv);
}
