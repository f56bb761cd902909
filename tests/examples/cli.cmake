# SPDX-License-Identifier: MIT
#
# The examples refuse bad flags: each case runs an example binary with the given arguments
# and passes if it exits non-zero (cleanly, no crash) and its output contains the expected
# text, which names the flag and its valid range. Included by tests/CMakeLists.txt; one ctest
# per case, named examples.cli.<example>.<case> and labelled `examples;cli`. The runs happen
# in a scratch directory under the build tree (see run_cli.cmake), never in the source tree.
#
# Adding a case is one line:
#   gimlet_cli_case(<example> <case> "<arguments>" "<text the message must contain>" [EXIT_ZERO])
# `a_file` in the arguments is a regular file in the scratch directory. Cases of an example
# whose folder does not exist yet are skipped, so they can be written ahead of it.

set(_gimlet_cli_runner "${CMAKE_CURRENT_LIST_DIR}/run_cli.cmake")

function(gimlet_cli_case example name args expect)
    cmake_parse_arguments(PARSE_ARGV 4 _cli "EXIT_ZERO" "" "")
    if(NOT GIMLET_BUILD_EXAMPLES OR NOT EXISTS "${PROJECT_SOURCE_DIR}/examples/${example}/CMakeLists.txt")
        return()
    endif()
    # An example left out of this build (GIMLET_EXAMPLES) has its cases run where it is built.
    if(NOT GIMLET_EXAMPLES STREQUAL "" AND NOT example IN_LIST GIMLET_EXAMPLES)
        return()
    endif()
    set(test "examples.cli.${example}.${name}")
    # add_test would split a ';' inside an argument; $<SEMICOLON> keeps it.
    string(REPLACE ";" "$<SEMICOLON>" expect "${expect}")
    add_test(NAME "${test}"
             COMMAND "${CMAKE_COMMAND}"
                     "-DEXE=$<TARGET_FILE:${example}>"
                     "-DARGS=${args}"
                     "-DWORKDIR=${CMAKE_CURRENT_BINARY_DIR}/cli/${example}.${name}"
                     "-DEXPECT=${expect}"
                     "-DEXIT_ZERO=${_cli_EXIT_ZERO}"
                     -P "${_gimlet_cli_runner}")
    set_tests_properties("${test}" PROPERTIES LABELS "examples;cli" TIMEOUT 180)
endfunction()

# impact_1d
gimlet_cli_case(impact_1d cell_zero       "--cell 0"          "--cell = 0 is invalid; valid range: (0, 1]")
gimlet_cli_case(impact_1d velocity_nan    "--velocity nan"    "--velocity = nan is invalid; valid range: (0, 1000]")
gimlet_cli_case(impact_1d velocity_text   "--velocity 3o0"    "--velocity = 3o0 is invalid; valid range: (0, 1000]")
gimlet_cli_case(impact_1d end_negative    "--end-us -5"       "--end-us = -5 is invalid; valid range: (0, 1000]")
gimlet_cli_case(impact_1d contact_unknown "--contact glue"    "--contact = glue is invalid; valid: single|distance")
gimlet_cli_case(impact_1d average_unknown "--volumetric-average yes" "--volumetric-average = yes is invalid; valid: off|on")
gimlet_cli_case(impact_1d threads_neg     "--threads -1"      "--threads = -1 is invalid; valid: a whole number in [0, 256]")
gimlet_cli_case(impact_1d threads_frac    "--threads 2.5"     "--threads = 2.5 is invalid; valid: a whole number in [0, 256]")
gimlet_cli_case(impact_1d scheme_unknown  "--scheme rk4"      "--scheme = rk4 is invalid; valid: usf|musl|usl")
gimlet_cli_case(impact_1d pic_over      "--pic-fraction 1.5" "--pic-fraction = 1.5 is invalid; valid range: [0, 1]")
gimlet_cli_case(impact_1d viscosity_neg "--viscosity-linear -0.1" "--viscosity-linear = -0.1 is invalid; valid range: [0, 10]")
gimlet_cli_case(impact_1d consistent_over "--consistent-mass 6" "--consistent-mass = 6 is invalid; valid: a whole number in [0, 5]")
gimlet_cli_case(impact_1d consistent_usl  "--consistent-mass 1 --scheme usl" "consistent_mass_iterations with the USL scheme = 1 is invalid")
gimlet_cli_case(impact_1d cfl_zero        "--cfl 0"           "--cfl = 0 is invalid; valid range: (0, 1]")
gimlet_cli_case(impact_1d cfl_usl         "--cfl 0.8 --scheme usl" "cfl (Courant number) with the USL scheme = 0.8 is invalid")
gimlet_cli_case(impact_1d filter_unknown "--volume-filter yes" "--volume-filter = yes is invalid; valid: off|on")
gimlet_cli_case(impact_1d filter_lumped "--consistent-mass 0 --volume-filter on" "volume_filter (with consistent_mass_iterations = 0) = true is invalid")
gimlet_cli_case(impact_1d unknown_flag    "--speed 300"       "unknown flag --speed")
gimlet_cli_case(impact_1d missing_value   "--cell"            "flag --cell needs a value")
gimlet_cli_case(impact_1d given_twice     "--cell 0.1 --cell 0.2" "flag --cell is given more than once")
gimlet_cli_case(impact_1d stray_argument  "300"               "unexpected argument '300'")
gimlet_cli_case(impact_1d output_file     "--output a_file"   "--output = a_file is invalid; valid: a directory that can be created and written (it exists and is not a directory)")
gimlet_cli_case(impact_1d output_under_file "--output a_file/out" "--output = a_file/out is invalid; valid: a directory that can be created and written (cannot create it")
gimlet_cli_case(impact_1d help            "--help"            "usage: impact_1d" EXIT_ZERO)

# contact_validation
gimlet_cli_case(contact_validation cell_zero      "--cell 0"         "--cell = 0 is invalid; valid range: (0, 4]")
gimlet_cli_case(contact_validation velocity_nan   "--velocity nan"   "--velocity = nan is invalid; valid range: (0, 1000]")
gimlet_cli_case(contact_validation time_negative  "--time-us -5"     "--time-us = -5 is invalid; valid range: (0, 40]")
gimlet_cli_case(contact_validation consistent_over "--consistent-mass 6" "--consistent-mass = 6 is invalid; valid: a whole number in [0, 5]")
gimlet_cli_case(contact_validation viscosity_neg  "--viscosity-quadratic -1" "--viscosity-quadratic = -1 is invalid; valid range: [0, 10]")
gimlet_cli_case(contact_validation cfl_over     "--cfl 1.5"        "--cfl = 1.5 is invalid; valid range: (0, 1]")
gimlet_cli_case(contact_validation unknown_flag   "--end-us 5"       "unknown flag --end-us")
gimlet_cli_case(contact_validation output_under_file "--output a_file/out" "--output = a_file/out is invalid; valid: a directory that can be created and written")

# sulsky_disks
gimlet_cli_case(sulsky_disks cell_zero     "--cell 0"          "--cell = 0 is invalid; valid range: (0, 0.2]")
gimlet_cli_case(sulsky_disks velocity_nan  "--velocity nan"    "--velocity = nan is invalid; valid range: (0, 10]")
gimlet_cli_case(sulsky_disks end_negative  "--end-time -5"     "--end-time = -5 is invalid; valid range: (0, 100]")
gimlet_cli_case(sulsky_disks unknown_flag  "--time-us 5"       "unknown flag --time-us")
gimlet_cli_case(sulsky_disks output_under_file "--output a_file/out" "--output = a_file/out is invalid; valid: a directory that can be created and written")

# custom_material
gimlet_cli_case(custom_material relaxation_zero "--relaxation-time 0"   "--relaxation-time (s) = 0 is invalid; valid range: (0, 1e6]")
gimlet_cli_case(custom_material relaxation_inf  "--relaxation-time inf" "--relaxation-time (s) = inf is invalid; valid range: (0, 1e6]")
gimlet_cli_case(custom_material relaxation_text "--relaxation-time 0.5s" "--relaxation-time (s) = nan is invalid; valid range: (0, 1e6]")
gimlet_cli_case(custom_material unknown_flag    "--cell 0.1"            "unknown flag --cell")
gimlet_cli_case(custom_material missing_value   "--output"              "flag --output needs a value")

# cavity_collapse
gimlet_cli_case(cavity_collapse radius_too_big "--radius 30"       "--radius = 30 is invalid; valid range: [0, 18]")
gimlet_cli_case(cavity_collapse cell_zero      "--cell 0"          "--cell = 0 is invalid; valid range: (0, 4]")
gimlet_cli_case(cavity_collapse velocity_nan   "--velocity nan"    "--velocity = nan is invalid; valid range: (0, 2000]")
gimlet_cli_case(cavity_collapse end_negative   "--end-us -5"       "--end-us = -5 is invalid; valid range: (0, 1000]")
gimlet_cli_case(cavity_collapse contact_unknown "--contact none"   "--contact = none is invalid; valid: single|bardenhagen|distance")
gimlet_cli_case(cavity_collapse average_unknown "--volumetric-average 1" "--volumetric-average = 1 is invalid; valid: off|on")
gimlet_cli_case(cavity_collapse temperature_unknown "--temperature hot" "--temperature = hot is invalid; valid: isentrope|paper")
gimlet_cli_case(cavity_collapse self_contact_unknown "--self-contact maybe" "--self-contact = maybe is invalid; valid: on|off")
gimlet_cli_case(cavity_collapse self_contact_single "--contact single --self-contact on" "--self-contact with --contact single = on is invalid")
gimlet_cli_case(cavity_collapse pic_negative "--pic-fraction -0.5" "--pic-fraction = -0.5 is invalid; valid range: [0, 1]")
gimlet_cli_case(cavity_collapse consistent_negative "--consistent-mass -1" "--consistent-mass = -1 is invalid; valid: a whole number in [0, 5]")
gimlet_cli_case(cavity_collapse filter_paper "--consistent-mass 1 --volume-filter on --temperature paper" "--volume-filter with --temperature paper = on is invalid; valid range: off")
gimlet_cli_case(cavity_collapse viscosity_nan  "--viscosity-quadratic nan" "--viscosity-quadratic = nan is invalid; valid range: [0, 10]")
gimlet_cli_case(cavity_collapse cfl_text       "--cfl 0.4x"       "--cfl = 0.4x is invalid; valid range: (0, 1]")
# The consistent mass (4 iterations by default) raises the highest grid frequency: the solver refuses
# a Courant number above 1/sqrt(5), by name.
gimlet_cli_case(cavity_collapse cfl_consistent "--cfl 0.45"       "cfl (Courant number, with consistent_mass_iterations = 4) = 0.45 is invalid")
gimlet_cli_case(cavity_collapse unknown_flag   "--time-us 5"       "unknown flag --time-us")
gimlet_cli_case(cavity_collapse geometry_unknown "--geometry sphere" "--geometry = sphere is invalid; valid: plane|axisymmetric|3d")
gimlet_cli_case(cavity_collapse side_plane     "--side free"       "--side with --geometry plane = free is invalid")
gimlet_cli_case(cavity_collapse geometry_single "--geometry 3d --contact single" "--contact with --geometry 3d = single is invalid")
gimlet_cli_case(cavity_collapse axisymmetric_filter "--geometry axisymmetric --consistent-mass 1 --volume-filter on" "--volume-filter with --geometry axisymmetric = on is invalid")
gimlet_cli_case(cavity_collapse output_under_file "--output a_file/out" "--output = a_file/out is invalid; valid: a directory that can be created and written")
