# SPDX-License-Identifier: MIT
# An example on one process and under mpirun on RANKS processes writes the same file, byte for
# byte. -DEXE=<binary> -DMPIEXEC=<mpirun> -DRANKS=<n> -DFILE=<file name> -DOUT=<scratch dir>
# -DARGS=<the example's arguments, ';'-separated>
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${EXE}" ${ARGS} --output "${OUT}/one" RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE log)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "one process: exit ${rc}\n${log}")
endif()
execute_process(COMMAND "${MPIEXEC}" -np ${RANKS} --oversubscribe "${EXE}" ${ARGS} --output "${OUT}/many"
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE log)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${RANKS} processes: exit ${rc}\n${log}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${OUT}/one/${FILE}" "${OUT}/many/${FILE}" RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
    message(FATAL_ERROR "${FILE} differs between one process and ${RANKS}")
endif()
