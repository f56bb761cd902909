# SPDX-License-Identifier: MIT
# Test discovery for Catch2 v2, run after each test executable is built. It replaces the
# CatchAddTests.cmake script that catch_discover_tests() (Catch2 v2's Catch.cmake) calls, and
# takes the same -D inputs, because that script turns the listing into a CMake list: a test
# name containing ';' (or an unbalanced '[') is split into filters that match no test case,
# and such ctests "pass" without running anything. Here the listing is split on newlines
# only, and every name and filter is written as a bracket argument.
#
# Inputs used: TEST_EXECUTABLE, TEST_EXECUTOR, TEST_WORKING_DIR, TEST_SPEC, TEST_EXTRA_ARGS,
# TEST_PROPERTIES, TEST_PREFIX, TEST_SUFFIX, TEST_LIST, CTEST_FILE. (TEST_REPORTER and the
# TEST_OUTPUT_* options are not supported.)

if(NOT EXISTS "${TEST_EXECUTABLE}")
    message(FATAL_ERROR "test executable '${TEST_EXECUTABLE}' does not exist")
endif()

include("${CMAKE_CURRENT_LIST_DIR}/CatchList.cmake")
gimlet_catch_list(listing "${TEST_EXECUTABLE}" "${TEST_EXECUTOR}" "${TEST_WORKING_DIR}" ${TEST_SPEC})

# Quote `text` as a CMake bracket argument.
function(_gimlet_bracket out text)
    set(eq "=")
    while(text MATCHES "\\]${eq}\\]")
        string(APPEND eq "=")
    endwhile()
    set(${out} "[${eq}[${text}]${eq}]" PARENT_SCOPE)
endfunction()

set(extra "")
foreach(arg IN LISTS TEST_EXTRA_ARGS)
    _gimlet_bracket(q "${arg}")
    string(APPEND extra " ${q}")
endforeach()
set(props "")
foreach(arg IN LISTS TEST_PROPERTIES)
    _gimlet_bracket(q "${arg}")
    string(APPEND props " ${q}")
endforeach()
_gimlet_bracket(exe "${TEST_EXECUTABLE}")
_gimlet_bracket(workdir "${TEST_WORKING_DIR}")
set(executor "")
foreach(arg IN LISTS TEST_EXECUTOR)
    _gimlet_bracket(q "${arg}")
    string(APPEND executor "${q} ")
endforeach()

# Test cases tagged [long] (physics at full resolution, run in the release preset only; see
# docs/testing.md) also get the ctest label `long`, which the asan-ubsan test preset excludes.
gimlet_catch_list(long_listing "${TEST_EXECUTABLE}" "${TEST_EXECUTOR}" "${TEST_WORKING_DIR}" "[long]")
# Compared line by line as text (never as a CMake list: a name may contain ';').
string(REPLACE "\r" "" long_listing "\n${long_listing}\n")
# Their labels: the ones given in TEST_PROPERTIES, and `long`.
set(long_labels "long")
list(FIND TEST_PROPERTIES LABELS at)
if(NOT at EQUAL -1)
    math(EXPR at "${at} + 1")
    list(GET TEST_PROPERTIES ${at} given)
    set(long_labels "${given};long")
endif()
_gimlet_bracket(qlong "${long_labels}")

set(script "")
set(names "")
string(REPLACE "\r" "" listing "${listing}")
while(NOT listing STREQUAL "")
    string(FIND "${listing}" "\n" eol)
    if(eol EQUAL -1)
        set(line "${listing}")
        set(listing "")
    else()
        string(SUBSTRING "${listing}" 0 ${eol} line)
        math(EXPR next "${eol} + 1")
        string(SUBSTRING "${listing}" ${next} -1 listing)
    endif()
    if(line STREQUAL "")
        continue()
    endif()
    set(raw "${line}")
    # Catch quotes names that start with '#'.
    if(line MATCHES "^\"(#.*)\"$")
        set(line "${CMAKE_MATCH_1}")
    endif()

    # The filter: the exact name, with Catch's special characters escaped.
    set(filter "${line}")
    foreach(char IN ITEMS "\\" "," "[" "]")
        string(REPLACE "${char}" "\\${char}" filter "${filter}")
    endforeach()
    # The ctest name: ';' would make it a list, so it becomes ','.
    string(REPLACE ";" "," name "${TEST_PREFIX}${line}${TEST_SUFFIX}")

    _gimlet_bracket(qname "${name}")
    _gimlet_bracket(qfilter "${filter}")
    string(APPEND script "add_test(${qname} ${executor}${exe} ${qfilter}${extra})\n")
    string(APPEND script "set_tests_properties(${qname} PROPERTIES WORKING_DIRECTORY ${workdir}${props})\n")
    string(FIND "${long_listing}" "\n${raw}\n" long_at)
    if(NOT long_at EQUAL -1)
        string(APPEND script "set_tests_properties(${qname} PROPERTIES LABELS ${qlong})\n")
    endif()
    string(REPLACE ";" "\\;" lname "${name}")
    list(APPEND names "${lname}")
endwhile()

if(TEST_LIST)
    set(all "")
    foreach(n IN LISTS names)
        _gimlet_bracket(q "${n}")
        string(APPEND all " ${q}")
    endforeach()
    string(APPEND script "set(${TEST_LIST}${all})\n")
endif()

file(WRITE "${CTEST_FILE}" "${script}")
