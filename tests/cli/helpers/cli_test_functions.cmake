# Test functions shared by tests/cli/checkpoint_cli.cmake and failure_modes.cmake (included by them;
# not globbed by tests/CMakeLists.txt, which includes tests/cli/*.cmake only).
include_guard(GLOBAL)

# mastrom_failure_test(name EXIT code|nonzero STDERR regex [ONE_LINE | ONE_ERROR_LINE]
#                      [ABSENT file] [MPI] [ARGS …])
# Runs `mastrom ARGS` (under `mpirun -n 2` with MPI) from the source directory through
# helpers/run_cli.cmake: checks the exit code, the error line and, with ABSENT, that no result file
# (not even a temporary one) is left behind.
function(mastrom_failure_test name)
  cmake_parse_arguments(T "ONE_LINE;ONE_ERROR_LINE;MPI" "EXIT;STDERR;ABSENT" "ARGS" ${ARGN})
  set(defs -DEXPECT_EXIT=${T_EXIT} "-DSTDERR_REGEX=${T_STDERR}")
  if(T_ONE_LINE)
    list(APPEND defs -DONE_LINE_STDERR=ON)
  endif()
  if(T_ONE_ERROR_LINE)
    list(APPEND defs -DONE_ERROR_LINE=ON)
  endif()
  if(DEFINED T_ABSENT)
    list(APPEND defs "-DABSENT=${T_ABSENT}")
  endif()
  set(launcher)
  if(T_MPI)
    set(launcher ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2)
  endif()
  add_test(NAME ${name}
           COMMAND ${CMAKE_COMMAND} ${defs} -P ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/run_cli.cmake --
                   ${launcher} $<TARGET_FILE:mastrom> ${T_ARGS}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(${name} PROPERTIES ENVIRONMENT
                       "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMP_NUM_THREADS=1")
  if(T_MPI)
    set_tests_properties(${name} PROPERTIES PROCESSORS 2 LABELS "mpi")
  endif()
endfunction()

# mastrom_same_datasets_test(name FIRST a.h5 SECOND b.h5 DATASETS /x /y … [FIXTURES f…])
# The listed datasets of two HDF5 files are equal element by element (h5diff without a tolerance:
# exact equality of every value). Attributes are not compared (wall times differ between runs).
function(mastrom_same_datasets_test name)
  cmake_parse_arguments(T "" "FIRST;SECOND" "DATASETS;FIXTURES" ${ARGN})
  if(NOT MASTROM_H5DIFF)
    return()
  endif()
  string(REPLACE ";" "," datasets "${T_DATASETS}")
  add_test(NAME ${name}
           COMMAND ${CMAKE_COMMAND} -DH5DIFF=${MASTROM_H5DIFF} -DFIRST=${T_FIRST}
                   -DSECOND=${T_SECOND} -DDATASETS=${datasets}
                   -P ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/same_datasets.cmake)
  if(T_FIXTURES)
    set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED "${T_FIXTURES}")
  endif()
endfunction()

find_program(MASTROM_H5DIFF h5diff)
