# SPDX-License-Identifier: MIT
# Run by the ctests docs.<page>.<n> (tests/docs/CMakeLists.txt): runs one program of the user
# guide and, where the page shows its output, compares what it printed with what is shown.
#   cmake -DPROGRAM=<binary> -DEXPECTED=<file or empty> -DSOURCE=<page:line> -P run_block.cmake
execute_process(COMMAND "${PROGRAM}" OUTPUT_VARIABLE printed ERROR_VARIABLE errors RESULT_VARIABLE status)
if(NOT status EQUAL 0)
    message("--- printed:\n${printed}--- on stderr:\n${errors}---")
    message(FATAL_ERROR "${SOURCE}: the guide's program exited with status ${status}")
endif()
if(NOT EXPECTED STREQUAL "")
    file(READ "${EXPECTED}" shown)
    if(NOT printed STREQUAL shown)
        message("--- the page shows:\n${shown}--- the program printed:\n${printed}---")
        message(FATAL_ERROR "${SOURCE}: the program's output is not what the page shows under it "
                            "(update the ```text block that follows it)")
    endif()
endif()
