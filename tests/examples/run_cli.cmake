# SPDX-License-Identifier: MIT
#
# Runs one example command line for tests/examples/cli.cmake (cmake -P):
#   -DEXE=<binary> -DARGS=<arguments, one string, split like a shell> -DWORKDIR=<scratch dir>
#   -DEXPECT=<text the output must contain> [-DEXIT_ZERO=ON]
# The scratch directory is emptied first and holds a regular file `a_file`, so a case can ask
# for an output directory that cannot be created (a_file/out). By default the run must exit
# non-zero; with EXIT_ZERO it must exit 0. Either way stdout + stderr must contain EXPECT
# (plain text, not a regex).

foreach(var IN ITEMS EXE WORKDIR EXPECT)
    if(NOT DEFINED ${var})
        message(FATAL_ERROR "run_cli.cmake: -D${var}=... is required")
    endif()
endforeach()

file(REMOVE_RECURSE "${WORKDIR}")
file(MAKE_DIRECTORY "${WORKDIR}")
file(WRITE "${WORKDIR}/a_file" "a regular file, not a directory\n")

separate_arguments(_args UNIX_COMMAND "${ARGS}")
execute_process(COMMAND "${EXE}" ${_args}
                WORKING_DIRECTORY "${WORKDIR}"
                RESULT_VARIABLE _rc
                OUTPUT_VARIABLE _out
                ERROR_VARIABLE _err
                TIMEOUT 120)
set(_all "${_out}${_err}")
message(STATUS "${EXE} ${ARGS}\nexit: ${_rc}\noutput:\n${_all}")

if(EXIT_ZERO)
    if(NOT _rc STREQUAL "0")
        message(FATAL_ERROR "expected exit 0, got '${_rc}'")
    endif()
elseif(_rc STREQUAL "0" OR NOT _rc MATCHES "^[0-9]+$")
    # A crash or timeout gives a non-numeric result: refused input must exit cleanly, non-zero.
    message(FATAL_ERROR "expected a clean non-zero exit, got '${_rc}'")
endif()
string(FIND "${_all}" "${EXPECT}" _at)
if(_at EQUAL -1)
    message(FATAL_ERROR "the output does not contain: ${EXPECT}")
endif()
