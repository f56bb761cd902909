# SPDX-License-Identifier: MIT
# One bounded, repeatable fuzzing run (tests/fuzz/CMakeLists.txt): HARNESS over a fresh WORK
# directory (new inputs, crash files) and the committed CORPUS, RUNS inputs from seed 1.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/new")
execute_process(
    COMMAND "${HARNESS}" -seed=1 "-runs=${RUNS}" "-max_len=${MAX_LEN}" -max_total_time=240 -timeout=20 -rss_limit_mb=2048
            -print_final_stats=1 "-artifact_prefix=${WORK}/" "${WORK}/new" "${CORPUS}"
    RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    file(GLOB found "${WORK}/crash-*" "${WORK}/timeout-*" "${WORK}/oom-*" "${WORK}/leak-*")
    message(FATAL_ERROR "fuzzing found a problem (exit ${rc}); the input: ${found}\n"
                        "reproduce with: ${HARNESS} <input file>")
endif()
