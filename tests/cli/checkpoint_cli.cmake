# ctest entries for `mastrom simulate --checkpoint-every / --restart` (crash safety): a run
# killed with SIGKILL after a checkpoint, restarted from it, ends with datasets equal value for value
# to the uninterrupted run's (helpers/kill_and_restart.sh); a restart with another configuration or
# from a file that is no checkpoint is refused with one line. Scheme 1 on the coarse 1 × 6 ring,
# 15 000 steps of 1 ms: about 1 s per run with the pipelined 2-thread stepping, long enough that
# the kill (0.1 s after the first checkpoint) lands mid-run. (1500 steps took 1 s in 2026-11-22's
# build and 0.1 s after the pipelining: the kill then came after the end.)
include(${CMAKE_CURRENT_LIST_DIR}/helpers/cli_test_functions.cmake)

set(ckpt_dir ${CMAKE_CURRENT_BINARY_DIR}/checkpoint_cli)
# Fixed 1 ms steps (adaptive steps below; in-process: tests/fullorder/test_checkpoint.cpp).
set(ckpt_run_args configs/scheme1.toml -q --set simulation.adaptive=false --set simulation.time_step=1e-3
    --set simulation.end_time=15 --set drive.duration=1.0 --set drive.ramp=0.05
    --set drive.angle_deg=10 --set interface.elements_axial=1
    --set interface.elements_circumferential=6)

# Adaptive steps on the same mast and drive, outputs every 1 ms: about 3.5 s per run.
set(ckpt_adaptive_args configs/scheme1.toml -q --set simulation.end_time=15 --set drive.duration=1.0
    --set drive.ramp=0.05 --set drive.angle_deg=10 --set interface.elements_axial=1
    --set interface.elements_circumferential=6 --set output.step=1e-3)

find_program(MASTROM_BASH bash)
if(MASTROM_BASH AND MASTROM_H5DIFF)
  add_test(NAME cli.checkpoint.kill_and_restart_bit_identical
           COMMAND ${MASTROM_BASH} ${CMAKE_CURRENT_LIST_DIR}/helpers/kill_and_restart.sh
                   $<TARGET_FILE:mastrom> ${MASTROM_H5DIFF} ${ckpt_dir} -- ${ckpt_run_args}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.checkpoint.kill_and_restart_bit_identical PROPERTIES
                       FIXTURES_SETUP checkpoint_file TIMEOUT 120
                       ENVIRONMENT "OMP_NUM_THREADS=1")
  # The same with adaptive steps (the default): the outputs streamed as the steps go, each
  # checkpoint carrying the continuous response's window instead of the step points.
  add_test(NAME cli.checkpoint.adaptive_kill_and_restart_bit_identical
           COMMAND ${MASTROM_BASH} ${CMAKE_CURRENT_LIST_DIR}/helpers/kill_and_restart.sh
                   $<TARGET_FILE:mastrom> ${MASTROM_H5DIFF} ${ckpt_dir}_adaptive -- ${ckpt_adaptive_args}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.checkpoint.adaptive_kill_and_restart_bit_identical PROPERTIES
                       TIMEOUT 180 ENVIRONMENT "OMP_NUM_THREADS=1")

  # The checkpoint left by the killed run is refused for another configuration, naming the key.
  mastrom_failure_test(cli.checkpoint.other_config EXIT 2 ONE_LINE ABSENT ${ckpt_dir}/other.h5
                       STDERR "^mastrom: error: --restart '.*ck\\.h5' was written with a different configuration: drive\\.angle_deg = 10\\.0 in the checkpoint, 11\\.0 now"
                       ARGS simulate ${ckpt_run_args} --set drive.angle_deg=11 --restart ${ckpt_dir}/ck.h5
                            -o ${ckpt_dir}/other.h5)
  set_tests_properties(cli.checkpoint.other_config PROPERTIES FIXTURES_REQUIRED checkpoint_file)
endif()

# A result file is not a checkpoint; the flags are checked before any work.
mastrom_failure_test(cli.checkpoint.not_a_checkpoint EXIT 2 ONE_LINE
                     ABSENT ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5
                     STDERR "^mastrom: error: 'configs/scheme1\\.toml' is not|^mastrom: error: cannot open 'configs/scheme1\\.toml': not an HDF5 file"
                     ARGS simulate ${ckpt_run_args} --restart configs/scheme1.toml
                          -o ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5)
mastrom_failure_test(cli.checkpoint.missing EXIT 2 ONE_LINE
                     ABSENT ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5
                     STDERR "^mastrom: error: cannot open 'no/such/ck\\.h5': no such file"
                     ARGS simulate ${ckpt_run_args} --restart no/such/ck.h5
                          -o ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5)
mastrom_failure_test(cli.checkpoint.file_without_interval EXIT 2 ONE_LINE
                     ABSENT ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5
                     STDERR "^mastrom: error: --checkpoint 'c\\.h5' needs --checkpoint-every N"
                     ARGS simulate ${ckpt_run_args} --checkpoint c.h5
                          -o ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5)
mastrom_failure_test(cli.checkpoint.same_as_result EXIT 2 ONE_LINE
                     ABSENT ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5
                     STDERR "^mastrom: error: --checkpoint '.*ckpt_bad\\.h5' is the result file"
                     ARGS simulate ${ckpt_run_args} --checkpoint-every 10
                          --checkpoint ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5
                          -o ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5)
mastrom_failure_test(cli.checkpoint.negative_interval EXIT 2 ONE_LINE
                     ABSENT ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5
                     STDERR "^mastrom: error: --checkpoint-every = -5 must be >= 1"
                     ARGS simulate ${ckpt_run_args} --checkpoint-every -5
                          -o ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5)
# The interval in simulated seconds (the kill-and-restart run uses "0.04s"): a malformed value and
# one shorter than a time step are refused before any work.
mastrom_failure_test(cli.checkpoint.interval_not_a_number EXIT 2 ONE_LINE
                     ABSENT ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5
                     STDERR "^mastrom: error: --checkpoint-every = '0\\.5 min' is not a number; allowed: N time steps"
                     ARGS simulate ${ckpt_run_args} --checkpoint-every "0.5 min"
                          -o ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5)
mastrom_failure_test(cli.checkpoint.interval_below_one_step EXIT 2 ONE_LINE
                     ABSENT ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5
                     STDERR "^mastrom: error: --checkpoint-every = 0\\.0001s must be >= one time step \\(0\\.001 s\\)"
                     ARGS simulate ${ckpt_run_args} --checkpoint-every 0.0001s
                          -o ${CMAKE_CURRENT_BINARY_DIR}/ckpt_bad.h5)
