# SPDX-License-Identifier: MIT
# Run by the ctest `package.install`: install the build tree GIMLET_BUILD_DIR into a fresh
# prefix GIMLET_PREFIX (removed first, so no file of an older install can hide a missing one).
#   cmake -DGIMLET_BUILD_DIR=... -DGIMLET_PREFIX=... [-DGIMLET_CONFIG=...] -P install.cmake
foreach(var IN ITEMS GIMLET_BUILD_DIR GIMLET_PREFIX)
    if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
        message(FATAL_ERROR "install.cmake: ${var} is not set")
    endif()
endforeach()

file(REMOVE_RECURSE "${GIMLET_PREFIX}")

set(config_args "")
if(DEFINED GIMLET_CONFIG AND NOT GIMLET_CONFIG STREQUAL "")
    set(config_args --config "${GIMLET_CONFIG}")
endif()

execute_process(
    COMMAND "${CMAKE_COMMAND}" --install "${GIMLET_BUILD_DIR}" --prefix "${GIMLET_PREFIX}"
            ${config_args}
    RESULT_VARIABLE result)
if(NOT result EQUAL 0)
    message(FATAL_ERROR "cmake --install failed (${result})")
endif()
if(NOT EXISTS "${GIMLET_PREFIX}/include/gimlet")
    message(FATAL_ERROR "no headers were installed under ${GIMLET_PREFIX}/include/gimlet")
endif()
