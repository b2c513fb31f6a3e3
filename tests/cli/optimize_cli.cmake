# ctest entries for `mastrom optimize` on the small database of rom_cli.cmake (Scheme 1, 1 x 6
# mesh, thickness x module mass on a 3 x 3 grid): one confirmed run (ROM optimum, full-order
# check), one with a frequency constraint, and the refusals of bad input, each one line, exit 2,
# no record file.
if(NOT COMMAND mastrom_cli_test OR NOT COMMAND mastrom_failure_test)
  return()
endif()

set(opt_dir ${CMAKE_CURRENT_BINARY_DIR})
set(opt_env "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMP_NUM_THREADS=1")
set(opt_bad ${opt_dir}/optimize_cli_bad.h5)

mastrom_cli_test(optimize.cli.confirmed EXIT 0
                 STDOUT "round 1: .*mass \\(min\\) .*peak_rel_end_angular_acceleration .*<= 50 .*confirmed: .*wrote "
                 ARGS optimize ${opt_dir}/rom_cli_db1.h5 --minimize mass
                      --subject-to "peak_rel_end_angular_acceleration <= 50" --rounds 2 -q
                      -o ${opt_dir}/optimize_cli.h5)
set_tests_properties(optimize.cli.confirmed PROPERTIES FIXTURES_REQUIRED rom_db
                     ENVIRONMENT "${opt_env}")

# A frequency constraint confirmed by the full order's modal solve at the deployed angle; the
# constraint printed as written (≤).
mastrom_cli_test(optimize.cli.frequency_confirmed EXIT 0
                 STDOUT "frequency_1 +Hz +>= 1500 +[0-9.]+ .* yes\n.*peak_rel_end_angular_acceleration +rad/s\\^2 +≤ 50 .*modal solves .*confirmed: "
                 ARGS optimize ${opt_dir}/rom_cli_db1.h5 --minimize mass
                      --subject-to "frequency_1 >= 1500"
                      --subject-to "peak_rel_end_angular_acceleration ≤ 50" --rounds 2 -q
                      -o ${opt_dir}/optimize_cli_frequency.csv)
set_tests_properties(optimize.cli.frequency_confirmed PROPERTIES FIXTURES_REQUIRED rom_db
                     ENVIRONMENT "${opt_env}")

mastrom_failure_test(optimize.cli.unknown_metric EXIT 2 ONE_LINE ABSENT ${opt_bad}
                     STDERR "--minimize 'no_such_metric'"
                     ARGS optimize ${opt_dir}/rom_cli_db1.h5 --minimize no_such_metric -q -o ${opt_bad})
mastrom_failure_test(optimize.cli.malformed_constraint EXIT 2 ONE_LINE ABSENT ${opt_bad}
                     STDERR "--subject-to .peak_joint_force =< 3.: .=<. is no operator; write <= \\(or ≤\\)"
                     ARGS optimize ${opt_dir}/rom_cli_db1.h5 --minimize mass
                          --subject-to "peak_joint_force =< 3" -q -o ${opt_bad})
mastrom_failure_test(optimize.cli.infeasible EXIT 2 ONE_LINE ABSENT ${opt_bad}
                     STDERR "is met by no design in the box"
                     ARGS optimize ${opt_dir}/rom_cli_db1.h5 --minimize mass
                          --subject-to "peak_rel_end_angular_acceleration <= 1e-9" -q -o ${opt_bad})
mastrom_failure_test(optimize.cli.stress_without_modes EXIT 2 ONE_LINE ABSENT ${opt_bad}
                     STDERR "--minimize 'max_peak_von_mises'.*no stress modes"
                     ARGS optimize ${opt_dir}/rom_cli_db_plain.h5 --minimize max_peak_von_mises -q
                          -o ${opt_bad})
set_tests_properties(optimize.cli.unknown_metric optimize.cli.malformed_constraint
                     optimize.cli.infeasible PROPERTIES FIXTURES_REQUIRED rom_db)
set_tests_properties(optimize.cli.stress_without_modes PROPERTIES FIXTURES_REQUIRED rom_db_plain)
