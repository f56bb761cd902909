# SPDX-License-Identifier: MIT
# gimlet_catch_list(<out> <executable> <executor> <working dir> <spec...>): the names of the test
# cases a Catch2 v2 executable selects with <spec>, one a line, into <out>. Included by the
# scripts that read test listings (CatchDiscoverTests.cmake, CatchCheckAllRegistered.cmake).
#
# Catch v2 exits with the number of names it listed (modulo 256) and writes nothing to stderr.
# Anything else stops the script, never passing as an empty listing: a test case name defined
# twice in one executable makes Catch2 print an error on stderr and exit with 255 before it lists
# anything, and that must not register zero tests in silence.
function(gimlet_catch_list out executable executor workdir)
    if(workdir STREQUAL "")
        set(workdir ".")
    endif()
    execute_process(
        COMMAND ${executor} "${executable}" ${ARGN} --list-test-names-only
        OUTPUT_VARIABLE listing
        ERROR_VARIABLE errors
        RESULT_VARIABLE result
        WORKING_DIRECTORY "${workdir}")
    # Counted by their newlines (never as a CMake list: a name may contain ';').
    string(REGEX REPLACE "[^\n]" "" newlines "${listing}")
    string(LENGTH "${newlines}" count)
    math(EXPR expected "${count} % 256")
    if(NOT result STREQUAL "${expected}" OR NOT errors STREQUAL "")
        message(FATAL_ERROR "listing the test cases of '${executable}' (${ARGN}) failed: exit status "
                            "${result} for ${count} names (test case names must be unique within "
                            "one executable, a tests/<family>/ folder)\n${errors}\n${listing}")
    endif()
    set(${out} "${listing}" PARENT_SCOPE)
endfunction()
