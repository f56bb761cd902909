# SPDX-License-Identifier: MIT
# The `docs` target's last step: fail if Doxygen's warning log holds a warning that
# docs/doxygen-suppressions.txt does not list.
#
#   cmake -DLOG=<doxygen-warnings.log> -DSUPPRESSIONS=<docs/doxygen-suppressions.txt> \
#         -P cmake/doxygen_check.cmake
#
# A warning is a line `<file>:<line>: warning: ...` (or `error:`) with the indented lines that
# continue it (a list of undocumented parameters, say); any other line of the log counts as one
# too. Each suppression is a CMake regular expression, matched against the whole warning; a
# warning that none matches is printed and fails the target. A suppression that matches no
# warning is reported (it is stale and can go) but does not fail.

cmake_minimum_required(VERSION 3.25)

foreach(var LOG SUPPRESSIONS)
    if(NOT DEFINED ${var})
        message(FATAL_ERROR "doxygen_check.cmake: -D${var}=... is required")
    endif()
endforeach()
if(NOT EXISTS "${LOG}")
    message(FATAL_ERROR "doxygen_check.cmake: no warning log ${LOG} (did Doxygen run?)")
endif()

# Read a file as a CMake list of lines, with any ';' in them kept.
function(read_lines file out)
    file(READ "${file}" text)
    string(REPLACE ";" "\\;" text "${text}")
    string(REPLACE "\n" ";" text "${text}")
    set(${out} "${text}" PARENT_SCOPE)
endfunction()

# The suppressions: `<regex> # <reason>`, one a line; blank lines and lines starting with '#'
# are comments. The regex ends at the first " # "; a suppression without a reason is refused.
# Patterns and warnings are kept in numbered variables, not lists, so a ';' in them is text.
set(n_patterns 0)
read_lines("${SUPPRESSIONS}" lines)
foreach(line IN LISTS lines)
    string(STRIP "${line}" line)
    if(line STREQUAL "" OR line MATCHES "^#")
        continue()
    endif()
    string(FIND "${line}" " # " at)
    if(at LESS 1)
        message(FATAL_ERROR "doxygen_check.cmake: ${SUPPRESSIONS}: no reason (` # why`) in: ${line}")
    endif()
    string(SUBSTRING "${line}" 0 ${at} pattern)
    math(EXPR from "${at} + 3")
    string(SUBSTRING "${line}" ${from} -1 reason)
    string(STRIP "${pattern}" pattern_${n_patterns})
    string(STRIP "${reason}" reason)
    if(reason STREQUAL "")
        message(FATAL_ERROR "doxygen_check.cmake: ${SUPPRESSIONS}: empty reason in: ${line}")
    endif()
    set(used_${n_patterns} FALSE)
    math(EXPR n_patterns "${n_patterns} + 1")
endforeach()

# The warnings, each with its continuation lines.
set(n_warnings 0)
read_lines("${LOG}" lines)
foreach(line IN LISTS lines)
    if(line STREQUAL "")
        continue()
    endif()
    if(line MATCHES "^[ \t]" AND n_warnings GREATER 0)
        math(EXPR last "${n_warnings} - 1")
        string(APPEND warning_${last} "\n${line}")
    else()
        set(warning_${n_warnings} "${line}")
        math(EXPR n_warnings "${n_warnings} + 1")
    endif()
endforeach()

set(left 0)
set(suppressed 0)
if(n_warnings GREATER 0)
    math(EXPR last_warning "${n_warnings} - 1")
    foreach(w RANGE ${last_warning})
        set(matched FALSE)
        if(n_patterns GREATER 0)
            math(EXPR last_pattern "${n_patterns} - 1")
            foreach(i RANGE ${last_pattern})
                if("${warning_${w}}" MATCHES "${pattern_${i}}")
                    set(matched TRUE)
                    set(used_${i} TRUE)
                    break()
                endif()
            endforeach()
        endif()
        if(matched)
            math(EXPR suppressed "${suppressed} + 1")
        else()
            math(EXPR left "${left} + 1")
            message("${warning_${w}}")
        endif()
    endforeach()
endif()

if(n_patterns GREATER 0)
    math(EXPR last_pattern "${n_patterns} - 1")
    foreach(i RANGE ${last_pattern})
        if(NOT used_${i})
            message(STATUS "doxygen_check.cmake: suppression matched no warning (stale?): ${pattern_${i}}")
        endif()
    endforeach()
endif()

if(left GREATER 0)
    message(FATAL_ERROR "Doxygen: ${left} warning(s) above not listed in ${SUPPRESSIONS} "
                        "(${suppressed} suppressed; full log: ${LOG})")
endif()
message(STATUS "Doxygen: no warnings left (${suppressed} suppressed by ${SUPPRESSIONS})")
