# SPDX-License-Identifier: MIT
# Warning flags for gimlet's own tests, examples and benchmarks.
#
# `gimlet_warnings` is a private INTERFACE target: link it to a target you build, never to the
# `gimlet` library itself, so that users of the installed package get no flags from us.
# It is not installed and not exported; an example built against an installed gimlet checks
# `if(TARGET gimlet_warnings)` before linking it.
#
# Dependencies found as imported targets (Eigen3::Eigen, Catch2::Catch2) are included as
# system headers, so their warnings are not ours to fix; gimlet's own headers are checked.

if(TARGET gimlet_warnings)
    return()
endif()

add_library(gimlet_warnings INTERFACE)
target_compile_options(gimlet_warnings INTERFACE
    $<$<CXX_COMPILER_ID:GNU,Clang,AppleClang>:-Wall -Wextra -Wpedantic>
    $<$<CXX_COMPILER_ID:MSVC>:/W4 /permissive->)
if(GIMLET_WERROR)
    target_compile_options(gimlet_warnings INTERFACE
        $<$<CXX_COMPILER_ID:GNU,Clang,AppleClang>:-Werror>
        $<$<CXX_COMPILER_ID:MSVC>:/WX>)
endif()
