# SPDX-License-Identifier: MIT
# Run after a test family's executable is built (tests/CMakeLists.txt): TEST_SPEC selects every
# test case that belongs to none of the family's files (`-#` and `~[#test_foo]` for each file,
# hidden cases left out). ctest registers each file's cases by that tag, so a case in the
# executable that carries none of them (one written in a header a test file includes, or in a
# file whose name Catch2 reads otherwise) would never run: the build fails instead, naming it.
#
# Inputs: TEST_EXECUTABLE, TEST_SPEC.

execute_process(
    COMMAND "${TEST_EXECUTABLE}" ${TEST_SPEC} --list-test-names-only
    OUTPUT_VARIABLE listing
    ERROR_VARIABLE errors
    RESULT_VARIABLE result)
if(NOT errors STREQUAL "" OR NOT result MATCHES "^[0-9]+$" OR (listing STREQUAL "" AND NOT result STREQUAL "0"))
    # Catch2 refuses to list anything when two test cases share a name (exit status 255).
    message(FATAL_ERROR "listing the test cases of '${TEST_EXECUTABLE}' failed (exit status ${result}); "
                        "test case names must be unique within a family:\n${errors}${listing}")
elseif(NOT listing STREQUAL "")
    message(FATAL_ERROR "'${TEST_EXECUTABLE}' holds test cases that no test file's tag selects, "
                        "so ctest would never run them; a test case belongs in a "
                        "tests/<family>/test_*.cpp file itself:\n${listing}")
endif()
