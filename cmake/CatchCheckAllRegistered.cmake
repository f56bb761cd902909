# SPDX-License-Identifier: MIT
# Run after a test family's executable is built (tests/CMakeLists.txt): TEST_SPEC selects every
# test case that belongs to none of the family's files (`-#` and `~[#test_foo]` for each file,
# hidden cases left out). ctest registers each file's cases by that tag, so a case in the
# executable that carries none of them (one written in a header a test file includes, or in a
# file whose name Catch2 reads otherwise) would never run: the build fails instead, naming it.
#
# Inputs: TEST_EXECUTABLE, TEST_SPEC.

include("${CMAKE_CURRENT_LIST_DIR}/CatchList.cmake")
gimlet_catch_list(listing "${TEST_EXECUTABLE}" "" "" ${TEST_SPEC})
if(NOT listing STREQUAL "")
    message(FATAL_ERROR "'${TEST_EXECUTABLE}' holds test cases that no test file's tag selects, "
                        "so ctest would never run them; a test case belongs in a "
                        "tests/<family>/test_*.cpp file itself:\n${listing}")
endif()
