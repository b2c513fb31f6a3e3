# Two-rank run of test_modes (tests run the MPI paths with 2 ranks; included by
# tests/CMakeLists.txt). The filter selects the SLEPc tests that compare with the dense reference or
# the analytic chain, plus forced non-convergence: under mpirun the SLEPc solves share one distributed
# eigenproblem, every rank checks the gathered result, and mpirun fails if any rank fails.
if(TARGET test_modes)
  set(mastrom_modes_mpi_filter
      "Backends/EveryBackend.*/slepc:Backends/IterativeBackend.IterationLimit*/slepc:SlepcAgainstDense.*")
  add_test(NAME modes.mpi2.slepc
           COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2 $<TARGET_FILE:test_modes>
                   --gtest_filter=${mastrom_modes_mpi_filter})
  # Open MPI refuses to start as root without the two variables (CI runs as root).
  set_tests_properties(modes.mpi2.slepc PROPERTIES
                       ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMP_NUM_THREADS=1"
                       PROCESSORS 2 TIMEOUT 300 LABELS "mpi")
endif()
