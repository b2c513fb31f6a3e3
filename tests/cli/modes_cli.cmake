# ctest entries for `mastrom modes` (included by tests/CMakeLists.txt after config_cli.cmake, whose
# mastrom_cli_test() it uses): help, the printed table and the written HDF5 + XDMF pair, rejected
# backends, and the 2-rank run whose frequencies must equal the 1-rank ones.
if(NOT COMMAND mastrom_cli_test)
  include(${CMAKE_CURRENT_LIST_DIR}/config_cli.cmake)
endif()

add_executable(compare_modes ${CMAKE_CURRENT_LIST_DIR}/helpers/compare_modes.cpp)
target_link_libraries(compare_modes PRIVATE mastrom_modes)
mastrom_warnings(compare_modes)

set(mastrom_modes_check ${CMAKE_CURRENT_LIST_DIR}/helpers/modes_run_and_check.cmake)
set(mastrom_modes_out ${CMAKE_CURRENT_BINARY_DIR}/modes_cli)
set(mastrom_mpi_env "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMP_NUM_THREADS=1")

mastrom_cli_test(cli.modes.help EXIT 0 STDOUT "--backend" ARGS modes --help)
mastrom_cli_test(cli.modes.listed EXIT 0 STDOUT "modes" ARGS --help)

# Scheme 3 (the default mast) on one rank: table, the 323 Hz first bending pair, files written
# and valid (compare_modes checks the HDF5 layout and the XDMF references).
add_test(NAME cli.modes.table_and_files
         COMMAND ${CMAKE_COMMAND} -DMASTROM=$<TARGET_FILE:mastrom>
                 -DCHECKER=$<TARGET_FILE:compare_modes> -DCONFIG=configs/scheme3.toml
                 -DOUT_DIR=${mastrom_modes_out}/scheme3
                 "-DSTDOUT_REGEX=frequency \\[Hz\\].*\n +1 +323\\.[0-9]+ .*bending-y\n +2 +323\\.[0-9]+ .*bending-z.*wrote"
                 -P ${mastrom_modes_check}
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(cli.modes.table_and_files PROPERTIES ENVIRONMENT "${mastrom_mpi_env}")

# Rejected backends: exit code 2 and one line naming the value and the allowed names.
mastrom_cli_test(cli.modes.bad_backend EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: --backend = 'lapack' is not a backend \\(allowed: slepc, arpack, dense\\)"
                 ARGS modes configs/scheme1.toml --backend lapack -o ${mastrom_modes_out}/never.h5)
mastrom_cli_test(cli.modes.bad_config_backend EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: config: .*backend"
                 ARGS modes configs/scheme1.toml --set modes.backend=lapack)
mastrom_cli_test(cli.modes.dense_backend EXIT 0 STDOUT "eigen-solver dense on 1 rank: converged"
                 ARGS modes configs/scheme1.toml --backend dense -q
                      -o ${mastrom_modes_out}/scheme1_dense.h5)

# Two ranks against one: the same frequencies (to 1e-8 relative), rank 0 alone reports.
if(MPIEXEC_EXECUTABLE)
  add_test(NAME cli.modes.mpi2_matches_one_rank
           COMMAND ${CMAKE_COMMAND} -DMASTROM=$<TARGET_FILE:mastrom>
                   -DCHECKER=$<TARGET_FILE:compare_modes> -DCONFIG=configs/scheme2.toml
                   -DOUT_DIR=${mastrom_modes_out}/mpi2 -DMPIEXEC=${MPIEXEC_EXECUTABLE}
                   "-DMPI_FLAGS=${MPIEXEC_NUMPROC_FLAG} 2" -P ${mastrom_modes_check}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.modes.mpi2_matches_one_rank PROPERTIES
                       ENVIRONMENT "${mastrom_mpi_env}" PROCESSORS 2 TIMEOUT 300 LABELS "mpi")
  # The modal-analysis library tests with SLEPc on a mast, as one distributed eigenproblem.
  if(TARGET test_modes)
    add_test(NAME modes.mpi2.mast
             COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2 $<TARGET_FILE:test_modes>
                     --gtest_filter=MastBackends.*)
    set_tests_properties(modes.mpi2.mast PROPERTIES ENVIRONMENT "${mastrom_mpi_env}"
                         PROCESSORS 2 TIMEOUT 300 LABELS "mpi")
  endif()
endif()
