# ctest entries for `mastrom uq` (included after rom_cli.cmake, whose small Scheme 1 database
# rom_cli_db1.h5 — thickness × module mass, 3 × 3, stress modes — they use): a short deployment,
# two uncertain inputs, one limit; the full order at the tails; 1 and 2 ranks give the same
# samples and metrics; bad input is one line and exit code 2, with no file left behind.
if(NOT COMMAND mastrom_cli_test)
  return()
endif()

set(uq_args uq ${rom_dir}/rom_cli_db1.h5 configs/scheme1.toml
    --set interface.elements_axial=1 --set interface.elements_circumferential=6
    --set simulation.time_step=1e-3 --set drive.duration=0.3 --set drive.ramp=0.05
    --set drive.angle_deg=10 --set simulation.end_time=0.4
    --set uncertainty.interface.thickness.distribution=truncated_normal
    --set uncertainty.interface.thickness.mean=0.0015 --set uncertainty.interface.thickness.std=1e-4
    --set uncertainty.interface.thickness.lower=0.0012 --set uncertainty.interface.thickness.upper=0.0018
    --set uncertainty.module.mass.distribution=uniform --set uncertainty.module.mass.lower=0.45
    --set uncertainty.module.mass.upper=0.55 --samples 64 -q)
mastrom_cli_test(uq.cli.run EXIT 0
                 STDOUT "256 ROM evaluations \\(64 base samples, sobol, seed 1\\) of 2 inputs x 12 metrics.*peak_rel_end_angular_acceleration +mean .*P\\(peak_rel_end_angular_acceleration > 0\\.2\\) = .*conservative \\(ROM error estimate against the limit\\).*Sobol indices.*interface\\.thickness +S .*full order at the tails .*q01 .*q99 .*critical .*wrote .*uq_cli1\\.h5.*wrote .*uq_cli1\\.csv"
                 ARGS ${uq_args} --limit "peak_rel_end_angular_acceleration > 0.2"
                      -o ${rom_dir}/uq_cli1.h5 --csv ${rom_dir}/uq_cli1.csv)
set_tests_properties(uq.cli.run PROPERTIES FIXTURES_REQUIRED rom_db FIXTURES_SETUP uq1
                     ENVIRONMENT "${rom_env}" TIMEOUT 300)
# Two ranks share the full-order runs at the tails as well (rank 0 runs two, rank 1 one): the
# same rows and values as one rank's, bit for bit.
add_test(NAME uq.cli.mpi2
         COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2 $<TARGET_FILE:mastrom> ${uq_args}
                 --limit "peak_rel_end_angular_acceleration > 0.2" -o ${rom_dir}/uq_cli2.h5
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(uq.cli.mpi2 PROPERTIES FIXTURES_REQUIRED rom_db FIXTURES_SETUP uq2
                     ENVIRONMENT "${rom_env}" PROCESSORS 2 TIMEOUT 120 LABELS "mpi")
find_program(MASTROM_H5DIFF h5diff)
if(MASTROM_H5DIFF)
  foreach(dataset /uq/inputs /uq/metrics /uq/summary/mean /uq/sobol/total /uq/tails/row
          /uq/tails/full_value /uq/tails/full_error_estimate)
    string(REPLACE "/" "_" name ${dataset})
    add_test(NAME uq.cli.same_h5${name}_for_1_and_2_ranks
             COMMAND ${MASTROM_H5DIFF} ${rom_dir}/uq_cli1.h5 ${rom_dir}/uq_cli2.h5 ${dataset})
    set_tests_properties(uq.cli.same_h5${name}_for_1_and_2_ranks PROPERTIES
                         FIXTURES_REQUIRED "uq1;uq2" LABELS "mpi")
  endforeach()
endif()
mastrom_cli_test(uq.cli.bad_limit EXIT 2 ONE_LINE
                 STDERR "uq: --limit \"peak_force > 1\": peak_force is not a metric of this study"
                 ARGS ${uq_args} --limit "peak_force > 1" -o ${rom_dir}/uq_cli_bad.h5)
mastrom_cli_test(uq.cli.bad_distribution EXIT 2 ONE_LINE
                 STDERR "uncertainty\\.module\\.mass\\.upper = 0\\.4 is out of range: must satisfy upper > lower = 0\\.45"
                 ARGS ${uq_args} --set uncertainty.module.mass.upper=0.4 -o ${rom_dir}/uq_cli_bad.h5)
mastrom_cli_test(uq.cli.bad_samples EXIT 2 ONE_LINE STDERR "--samples"
                 ARGS ${uq_args} --samples 1 -o ${rom_dir}/uq_cli_bad.h5)
set_tests_properties(uq.cli.bad_limit uq.cli.bad_distribution uq.cli.bad_samples PROPERTIES
                     FIXTURES_REQUIRED rom_db FIXTURES_SETUP uq_bad)
add_test(NAME uq.cli.bad_input_leaves_no_file
         COMMAND ${CMAKE_COMMAND} -DF=${rom_dir}/uq_cli_bad.h5
                 -P ${CMAKE_CURRENT_LIST_DIR}/helpers/assert_absent.cmake)
set_tests_properties(uq.cli.bad_input_leaves_no_file PROPERTIES FIXTURES_REQUIRED uq_bad)
