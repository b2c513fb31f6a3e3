# ctest driver (cmake -P) for `mastrom modes`: run it once on one rank (and, with MPIEXEC set, once
# more on two ranks), then check the result file(s) with the compare_modes helper.
#
#   cmake -DMASTROM=<exe> -DCHECKER=<compare_modes> -DCONFIG=<toml> -DOUT_DIR=<dir>
#         [-DSTDOUT_REGEX=…] [-DMPIEXEC=<mpirun> -DMPI_FLAGS=<flags>] -P modes_run_and_check.cmake
file(REMOVE_RECURSE "${OUT_DIR}")
file(MAKE_DIRECTORY "${OUT_DIR}")

function(run_checked)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "$ ${ARGN}\nexit code: ${rc}\n--- stdout ---\n${out}--- stderr ---\n${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed with exit code ${rc}")
  endif()
  set(last_stdout "${out}" PARENT_SCOPE)
endfunction()

run_checked(${MASTROM} modes ${CONFIG} -o ${OUT_DIR}/one.h5)
if(DEFINED STDOUT_REGEX AND NOT last_stdout MATCHES "${STDOUT_REGEX}")
  message(FATAL_ERROR "stdout does not match: ${STDOUT_REGEX}")
endif()
foreach(f one.h5 one.xdmf)
  if(NOT EXISTS "${OUT_DIR}/${f}")
    message(FATAL_ERROR "${f} was not written")
  endif()
endforeach()

if(DEFINED MPIEXEC)
  separate_arguments(flags UNIX_COMMAND "${MPI_FLAGS}")
  run_checked(${MPIEXEC} ${flags} ${MASTROM} modes ${CONFIG} -o ${OUT_DIR}/two.h5)
  string(REGEX MATCHALL "mastrom modes: " headers "${last_stdout}")
  list(LENGTH headers nheaders)
  if(NOT nheaders EQUAL 1)
    message(FATAL_ERROR "expected the report of rank 0 only, got ${nheaders} headers")
  endif()
  if(NOT last_stdout MATCHES "slepc on 2 ranks")
    message(FATAL_ERROR "the SLEPc solve did not run on 2 ranks")
  endif()
  run_checked(${CHECKER} ${OUT_DIR}/one.h5 ${OUT_DIR}/two.h5 1e-8)
else()
  run_checked(${CHECKER} ${OUT_DIR}/one.h5)
endif()
