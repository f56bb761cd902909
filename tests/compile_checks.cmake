# SPDX-License-Identifier: MIT
#
# The checks of compilation itself, included by tests/CMakeLists.txt when
# GIMLET_BUILD_COMPILE_CHECKS is on: every public header compiled alone, the must-not-compile
# tests, the shared solvers compiled for x86-64-v4 and the package test. They run in the release
# preset (docs/testing.md).

# `--config <cfg>` for the builds ctest runs itself (failtests, package test): needed by
# multi-config generators only.
get_property(_gimlet_multi_config GLOBAL PROPERTY GENERATOR_IS_MULTI_CONFIG)
if(_gimlet_multi_config)
    set(_gimlet_config_args --config $<CONFIG>)
    set(_gimlet_build_type $<CONFIG>)
else()
    set(_gimlet_config_args "")
    set(_gimlet_build_type "${CMAKE_BUILD_TYPE}")
endif()

# ---------------------------------------------------------------------------------------------
# Header self-containment and layering: one generated translation unit per public header, which
# includes that header (twice, to check its include guard) and nothing else, compiled against an
# include tree that holds only the folders its layer may use (symbolic links into include/gimlet):
# a header that includes a folder above its layer does not compile, and the build fails (as
# mp-units builds core before systems). The layers, bottom up (docs/concepts.md, Layers):
#   core                                       the foundation: includes nothing else
#   shape strength eos thermal viscosity contact    the policy families (thermal reads eos)
#   multi_field                                the contact framework
#   material                                   a material: one policy of each constitutive family
#   scene                                      bodies of materials on a grid
#   solver                                     the composed solver and its parts
#   presets diagnostics io                     presets, measurements, files
#   materials                                  the former name of presets/, forwarding to it
#   mpi                                        the solver on many processes (needs MPI)
set(GIMLET_LAYERS
    "core:core"
    "shape:core,shape"
    "strength:core,strength"
    "eos:core,eos"
    "thermal:core,eos,thermal"
    "viscosity:core,viscosity"
    "contact:core,contact"
    "multi_field:core,contact,multi_field"
    "material:core,strength,eos,thermal,viscosity,material"
    "scene:core,strength,eos,thermal,viscosity,material,scene"
    "solver:core,shape,strength,eos,thermal,viscosity,contact,multi_field,material,scene,solver"
    "presets:core,strength,eos,thermal,viscosity,material,presets"
    "materials:core,strength,eos,thermal,viscosity,material,presets,materials"
    "diagnostics:core,diagnostics"
    "io:core,io"
    "mpi:core,shape,strength,eos,thermal,viscosity,contact,multi_field,material,scene,solver,diagnostics,io,mpi")

file(GLOB_RECURSE GIMLET_PUBLIC_HEADERS CONFIGURE_DEPENDS
     RELATIVE "${PROJECT_SOURCE_DIR}/include"
     "${PROJECT_SOURCE_DIR}/include/gimlet/*.hpp")
list(FILTER GIMLET_PUBLIC_HEADERS EXCLUDE REGEX "(^|/)detail/")
if(NOT GIMLET_USES_MPI)
    list(FILTER GIMLET_PUBLIC_HEADERS EXCLUDE REGEX "^gimlet/mpi/")  # <mpi.h> is not there
endif()
list(SORT GIMLET_PUBLIC_HEADERS)

# The include tree of each layer.
set(_gimlet_layer_names "")
foreach(entry IN LISTS GIMLET_LAYERS)
    string(REGEX REPLACE "[:,]" ";" entry "${entry}")
    list(GET entry 0 _layer)
    list(SUBLIST entry 1 -1 _allowed)
    set(_root "${CMAKE_CURRENT_BINARY_DIR}/layers/${_layer}")
    file(MAKE_DIRECTORY "${_root}/gimlet")
    foreach(folder IN LISTS _allowed)
        if(NOT EXISTS "${_root}/gimlet/${folder}")
            file(CREATE_LINK "${PROJECT_SOURCE_DIR}/include/gimlet/${folder}" "${_root}/gimlet/${folder}" SYMBOLIC)
        endif()
    endforeach()
    list(APPEND _gimlet_layer_names "${_layer}")
    set(_gimlet_layer_sources_${_layer} "")
endforeach()

# Whether a header is gimlet/core/space.hpp or includes it, directly or not: sets ${out} to TRUE
# or FALSE. space.hpp is where gimlet includes Eigen (<Eigen/Core> and <Eigen/LU>, what the
# precompiled header below holds). Each header is scanned once (answers kept in global
# properties keyed by its path), and every scanned file re-runs the configure when it changes.
# A header met again while its own scan is under way (an include cycle) answers FALSE, and the
# scan reads #include lines whatever #if surrounds them: a wrong answer is only ever FALSE (a
# check without the precompiled header) while no header includes space.hpp conditionally.
function(_gimlet_reaches_space header out)
    get_property(_known GLOBAL PROPERTY "_gimlet_space:${header}" SET)
    if(_known)
        get_property(_answer GLOBAL PROPERTY "_gimlet_space:${header}")
        set(${out} ${_answer} PARENT_SCOPE)
        return()
    endif()
    set_property(GLOBAL PROPERTY "_gimlet_space:${header}" FALSE)  # ends a cycle, if any
    set(_answer FALSE)
    set(_file "${PROJECT_SOURCE_DIR}/include/${header}")
    if(header STREQUAL "gimlet/core/space.hpp")
        set(_answer TRUE)
    elseif(EXISTS "${_file}")
        set_property(DIRECTORY "${PROJECT_SOURCE_DIR}" APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${_file}")
        file(STRINGS "${_file}" _lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]gimlet/")
        foreach(_line IN LISTS _lines)
            string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[<\"]([^>\"]+)[>\"].*$" "\\1" _inc "${_line}")
            _gimlet_reaches_space("${_inc}" _sub)
            if(_sub)
                set(_answer TRUE)
                break()
            endif()
        endforeach()
    endif()
    set_property(GLOBAL PROPERTY "_gimlet_space:${header}" ${_answer})
    set(${out} ${_answer} PARENT_SCOPE)
endfunction()

# Parsing Eigen is most of what a header check costs (1.2 of a check's 1.7 s). The checks
# therefore share one precompiled <Eigen/Core> and <Eigen/LU> (target gimlet_header_check_pch,
# compiled as the checks are), used only by the headers that include gimlet/core/space.hpp (64
# of 71): for them it adds no declaration the header's own includes do not bring. What it
# cannot see is order: the precompiled header comes first, so a use of Eigen (or of a standard
# header Eigen includes) above the header's own includes would pass. The others, which must
# compile with no Eigen at all, skip it (docs/testing.md).
# An object library of one empty generated unit, whose only product is the precompiled header
# that other targets take with REUSE_FROM.
function(_gimlet_pch_target target)
    set(_source "${CMAKE_CURRENT_BINARY_DIR}/${target}.cpp")
    file(CONFIGURE OUTPUT "${_source}"
         CONTENT "// Generated by tests/compile_checks.cmake: builds ${target}'s precompiled header.\n")
    add_library(${target} OBJECT "${_source}")
endfunction()

_gimlet_pch_target(gimlet_header_check_pch)
target_compile_features(gimlet_header_check_pch PRIVATE cxx_std_20)
target_link_libraries(gimlet_header_check_pch PRIVATE Eigen3::Eigen gimlet_warnings)
if(GIMLET_USES_OPENMP)
    target_link_libraries(gimlet_header_check_pch PRIVATE OpenMP::OpenMP_CXX)
endif()
# The Eigen headers gimlet/core/space.hpp includes: keep the two lists in step.
target_precompile_headers(gimlet_header_check_pch PRIVATE <Eigen/Core> <Eigen/LU>)

set(GIMLET_HEADER_CHECK_SOURCES "")  # headers outside any layer (gimlet/gimlet.hpp): the whole tree
foreach(header IN LISTS GIMLET_PUBLIC_HEADERS)
    string(REGEX REPLACE "\\.hpp$" "" _name "${header}")
    string(REPLACE "/" "__" _name "${_name}")
    set(_tu "${CMAKE_CURRENT_BINARY_DIR}/header_check/${_name}.cpp")
    # file(CONFIGURE) only rewrites the file when its content changes: no needless rebuilds.
    file(CONFIGURE OUTPUT "${_tu}"
         CONTENT "// Generated by tests/compile_checks.cmake: ${header} must compile on its own, with only its layer's folders.\n#include <${header}>\n#include <${header}>\n"
         @ONLY)
    _gimlet_reaches_space("${header}" _eigen)
    if(NOT _eigen)
        set_source_files_properties("${_tu}" PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
    endif()
    string(REGEX MATCH "^gimlet/([a-z_]+)/" _in_folder "${header}")
    set(_folder "${CMAKE_MATCH_1}")
    if(_in_folder AND NOT _folder IN_LIST _gimlet_layer_names)
        message(FATAL_ERROR "tests/compile_checks.cmake: include/gimlet/${_folder}/ is in no layer of GIMLET_LAYERS")
    endif()
    if(_in_folder)
        list(APPEND _gimlet_layer_sources_${_folder} "${_tu}")
    else()
        list(APPEND GIMLET_HEADER_CHECK_SOURCES "${_tu}")
    endif()
endforeach()

if(GIMLET_HEADER_CHECK_SOURCES)
    add_library(gimlet_header_check OBJECT ${GIMLET_HEADER_CHECK_SOURCES})
    target_link_libraries(gimlet_header_check PRIVATE ${GIMLET_TARGET} gimlet_warnings)
    target_precompile_headers(gimlet_header_check REUSE_FROM gimlet_header_check_pch)
endif()
foreach(_layer IN LISTS _gimlet_layer_names)
    if(NOT _gimlet_layer_sources_${_layer})
        continue()
    endif()
    # The layer's tree only: the library's own include directory is not on the path.
    add_library(gimlet_header_check_${_layer} OBJECT ${_gimlet_layer_sources_${_layer}})
    target_include_directories(gimlet_header_check_${_layer} PRIVATE "${CMAKE_CURRENT_BINARY_DIR}/layers/${_layer}")
    target_compile_features(gimlet_header_check_${_layer} PRIVATE cxx_std_20)
    target_link_libraries(gimlet_header_check_${_layer} PRIVATE Eigen3::Eigen gimlet_warnings)
    if(GIMLET_USES_OPENMP)
        target_link_libraries(gimlet_header_check_${_layer} PRIVATE OpenMP::OpenMP_CXX)
    endif()
    if(_layer STREQUAL "mpi")
        target_link_libraries(gimlet_header_check_${_layer} PRIVATE MPI::MPI_CXX)
    endif()
    target_precompile_headers(gimlet_header_check_${_layer} REUSE_FROM gimlet_header_check_pch)
endforeach()

# ---------------------------------------------------------------------------------------------
# Must-not-compile tests (Eigen's failtest): each tests/static/fail/<name>.cpp gives two targets
# outside `all` and two ctests:
#   static.fail.<name>_ok  builds it with -DGIMLET_FAILTEST_OK and must succeed;
#   static.fail.<name>_ko  builds it as is and must fail. If the file has lines
#                          `// GIMLET_FAILTEST_EXPECT: <regex>`, the compiler output must
#                          also match one of those regexes (the intended diagnostic).
# The build is run by ctest through `cmake --build` on this build tree; RESOURCE_LOCK keeps two
# such builds from running at once in the same tree.
#
# Every failtest is built at -O0 and, with g++, with one precompiled <gimlet/gimlet.hpp> (the
# target failtest_pch, built by the first failtest that runs): what they test is whether a
# translation unit compiles, which neither the optimiser nor a second parse of the umbrella
# header decides. Both cut the serial chain of these builds at test time to about half
# (docs/testing.md). The ok variant's GIMLET_FAILTEST_OK appears in no header, so the one header
# serves both variants. Not with clang: clang 14 crashes instantiating the solver from that
# precompiled header (a segmentation fault in the frontend).
file(GLOB GIMLET_FAILTEST_SOURCES CONFIGURE_DEPENDS
     "${CMAKE_CURRENT_SOURCE_DIR}/static/fail/*.cpp")
list(SORT GIMLET_FAILTEST_SOURCES)

_gimlet_pch_target(failtest_pch)  # used with g++ only
target_link_libraries(failtest_pch PRIVATE ${GIMLET_TARGET} gimlet_warnings)
target_compile_options(failtest_pch PRIVATE $<$<CXX_COMPILER_ID:GNU,Clang>:-O0>)
target_precompile_headers(failtest_pch PRIVATE <gimlet/gimlet.hpp>)
set_target_properties(failtest_pch PROPERTIES
    EXCLUDE_FROM_ALL TRUE
    EXCLUDE_FROM_DEFAULT_BUILD TRUE)

foreach(src IN LISTS GIMLET_FAILTEST_SOURCES)
    get_filename_component(name "${src}" NAME_WE)
    file(STRINGS "${src}" _expect_lines REGEX "^[ \t]*//[ \t]*GIMLET_FAILTEST_EXPECT:")
    set(_expect "")
    foreach(line IN LISTS _expect_lines)
        string(REGEX REPLACE "^[ \t]*//[ \t]*GIMLET_FAILTEST_EXPECT:[ \t]*" "" _re "${line}")
        string(STRIP "${_re}" _re)
        if(NOT _re STREQUAL "")
            list(APPEND _expect "${_re}")
        endif()
    endforeach()

    foreach(kind IN ITEMS ok ko)
        set(target "failtest_${name}_${kind}")
        add_library(${target} OBJECT "${src}")
        target_link_libraries(${target} PRIVATE ${GIMLET_TARGET} gimlet_warnings)
        target_compile_options(${target} PRIVATE $<$<CXX_COMPILER_ID:GNU,Clang>:-O0>)
        if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
            target_precompile_headers(${target} REUSE_FROM failtest_pch)
        endif()
        if(kind STREQUAL "ok")
            target_compile_definitions(${target} PRIVATE GIMLET_FAILTEST_OK)
        endif()
        set_target_properties(${target} PROPERTIES
            EXCLUDE_FROM_ALL TRUE
            EXCLUDE_FROM_DEFAULT_BUILD TRUE)
        add_test(NAME static.fail.${name}_${kind}
                 COMMAND "${CMAKE_COMMAND}" --build "${CMAKE_BINARY_DIR}"
                         --target ${target} ${_gimlet_config_args})
        set_tests_properties(static.fail.${name}_${kind} PROPERTIES
            LABELS "static;failtest"
            RESOURCE_LOCK gimlet_build_tree
            # Started first: they run one at a time (the lock), and ctest, which on a fresh
            # clone has no timings, would leave the whole chain for the end, alone on one core.
            COST 1000)
        if(kind STREQUAL "ko")
            if(_expect)
                # Passing on the expected diagnostic (only printed when compilation fails).
                set_tests_properties(static.fail.${name}_ko PROPERTIES
                    PASS_REGULAR_EXPRESSION "${_expect}")
            else()
                set_tests_properties(static.fail.${name}_ko PROPERTIES WILL_FAIL TRUE)
            endif()
        endif()
    endforeach()
endforeach()

# ---------------------------------------------------------------------------------------------
# The shared solvers (tests/instantiations_*.cpp) compiled again for a wider instruction set,
# x86-64-v4 (AVX-512 and FMA), at -O3 and with the project's warnings, as objects that nothing
# links or runs. g++'s flow warnings (-Wmaybe-uninitialized) follow the code it generates, so a
# header that is clean in the portable build can warn in a user's -march=native one, and stop
# it under -Werror (g++ 12 with AVX-512 warns on a loop whose bound it cannot see:
# docs/testing.md, "A native build"). With g++ only (clang has no such warnings), on x86-64
# where it takes the flag. What it covers: every member of the shared solvers (2-D, double,
# uGIMP; elastic and HMX; every contact law; both partitions), not 3-D, float, the other
# shapes, or the tests' own solvers.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$")
    include(CheckCXXCompilerFlag)
    check_cxx_compiler_flag(-march=x86-64-v4 GIMLET_HAS_MARCH_X86_64_V4)
    if(GIMLET_HAS_MARCH_X86_64_V4)
        add_library(gimlet_wide_isa_check OBJECT instantiations_elastic.cpp instantiations_hmx.cpp)
        target_link_libraries(gimlet_wide_isa_check PRIVATE ${GIMLET_TARGET} gimlet_warnings)
        # -O3 whatever the build type: the warnings need the optimiser's flow analysis.
        target_compile_options(gimlet_wide_isa_check PRIVATE -march=x86-64-v4 -O3)
    endif()
endif()

# ---------------------------------------------------------------------------------------------
# Package test: install this build tree into a scratch prefix, then configure, build and run
# tests/package (a consumer that only knows find_package(gimlet)) against it.
set(GIMLET_PACKAGE_PREFIX "${CMAKE_BINARY_DIR}/package-install")
set(GIMLET_PACKAGE_BUILD "${CMAKE_BINARY_DIR}/package-build")

# The consumer is built with the same compiler and flags as this tree (sanitizers included).
set(_gimlet_consumer_options
    "-DCMAKE_PREFIX_PATH=${GIMLET_PACKAGE_PREFIX}"
    "-DGIMLET_EXPECTED_PREFIX=${GIMLET_PACKAGE_PREFIX}"
    "-DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER}"
    "-DCMAKE_CXX_FLAGS=${CMAKE_CXX_FLAGS}"
    "-DCMAKE_EXE_LINKER_FLAGS=${CMAKE_EXE_LINKER_FLAGS}"
    "-DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF")
set(_gimlet_consumer_config "")
if(_gimlet_build_type)
    list(APPEND _gimlet_consumer_options "-DCMAKE_BUILD_TYPE=${_gimlet_build_type}")
    set(_gimlet_consumer_config --build-config ${_gimlet_build_type})
    if(NOT _gimlet_multi_config)
        string(TOUPPER "${CMAKE_BUILD_TYPE}" _cfg)
        # At -O1, as the tests are (tests/CMakeLists.txt): the package tests check that the
        # installed copy is found, compiles and works, not how fast; at -O3 they would be the
        # release preset's two longest tests (docs/testing.md).
        string(REGEX REPLACE "-O[23s]" "-O1" _consumer_flags "${CMAKE_CXX_FLAGS_${_cfg}}")
        list(APPEND _gimlet_consumer_options
             "-DCMAKE_CXX_FLAGS_${_cfg}=${_consumer_flags}")
    endif()
endif()

add_test(NAME package.install
         COMMAND "${CMAKE_COMMAND}"
                 "-DGIMLET_BUILD_DIR=${CMAKE_BINARY_DIR}"
                 "-DGIMLET_PREFIX=${GIMLET_PACKAGE_PREFIX}"
                 "-DGIMLET_CONFIG=${_gimlet_build_type}"
                 -P "${CMAKE_CURRENT_SOURCE_DIR}/package/install.cmake")
set_tests_properties(package.install PROPERTIES
    LABELS package
    FIXTURES_SETUP gimlet_installed
    COST 1000)  # first: the consumer builds (about 25 s) wait on it

# A project built against the installed copy with ctest --build-and-test, then run.
function(gimlet_package_test name source binary)
    add_test(NAME "${name}"
             COMMAND "${CMAKE_CTEST_COMMAND}"
                     --build-and-test "${source}" "${binary}"
                     --build-generator "${CMAKE_GENERATOR}"
                     --build-makeprogram "${CMAKE_MAKE_PROGRAM}"
                     ${_gimlet_consumer_config}
                     --build-options ${_gimlet_consumer_options}
                     --test-command ${ARGN})
    set_tests_properties("${name}" PROPERTIES
        LABELS package
        FIXTURES_REQUIRED gimlet_installed
        COST 1000)  # the longest tests of the release preset: started early, not last
endfunction()

gimlet_package_test(package.consume "${CMAKE_CURRENT_SOURCE_DIR}/package" "${GIMLET_PACKAGE_BUILD}"
                    gimlet_package_consumer)
# The same consumer linked to gimlet::gimlet alone (no OpenMP component): serial, and it must work.
set_tests_properties(package.consume PROPERTIES FIXTURES_SETUP gimlet_consumer_built)
add_test(NAME package.consume_serial COMMAND "${GIMLET_PACKAGE_BUILD}/gimlet_package_consumer_serial")
set_tests_properties(package.consume_serial PROPERTIES LABELS package FIXTURES_REQUIRED gimlet_consumer_built)
# The consumer of the mpi component (find_package(gimlet COMPONENTS mpi)), where MPI was found:
# started alone, it runs on one process.
if(GIMLET_USES_MPI)
    add_test(NAME package.consume_mpi COMMAND "${GIMLET_PACKAGE_BUILD}/gimlet_package_consumer_mpi")
    set_tests_properties(package.consume_mpi PROPERTIES LABELS "package;mpi" FIXTURES_REQUIRED gimlet_consumer_built
                         ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_btl_vader_single_copy_mechanism=none")
endif()

# The custom_material tutorial stands alone: built on its own against the installed package, as a
# user who copies its folder out of the tree would (docs/concepts.md points to it).
gimlet_package_test(package.tutorial "${PROJECT_SOURCE_DIR}/examples/custom_material"
                    "${CMAKE_BINARY_DIR}/package-tutorial"
                    custom_material --output "${CMAKE_BINARY_DIR}/package-tutorial/out")
