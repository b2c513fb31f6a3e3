# ctest entries for `mastrom simulate` (uses mastrom_cli_test of config_cli.cmake): bad input is
# rejected before any work with one line, an unwritable output fails before the run, a diverging
# run exits 3 with the time in its one line and leaves no file.
mastrom_cli_test(cli.simulate.bad_config EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: config: material\\.poisson_ratio = 0\\.7"
                 ARGS simulate configs/scheme1.toml --set material.poisson_ratio=0.7 -o sim_bad.h5)
mastrom_cli_test(cli.simulate.unknown_drive_law EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: config: drive\\.law = \"linear\".*trapezoidal, cubic"
                 ARGS simulate configs/scheme1.toml --set drive.law=linear -o sim_bad.h5)
# The default run is 8 s of simulated time (minutes): failing within the timeout proves the path is
# checked first.
mastrom_cli_test(cli.simulate.unwritable_output EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: .*no/such/dir"
                 ARGS simulate configs/scheme3.toml -o no/such/dir/out.h5)
set_tests_properties(cli.simulate.unwritable_output PROPERTIES TIMEOUT 20)
mastrom_cli_test(cli.simulate.divergence EXIT 3 ONE_LINE
                 STDERR "^mastrom: error: generalized-alpha: step to t = [0-9.e-]+ s failed"
                 ARGS simulate configs/scheme1.toml -q -o ${CMAKE_CURRENT_BINARY_DIR}/sim_div.h5
                      --set simulation.time_step=0.004 --set simulation.end_time=0.05
                      --set drive.duration=0.02 --set drive.ramp=0.005
                      --set interface.elements_axial=1 --set interface.elements_circumferential=6
                      --set material.youngs_modulus=1e6 --set simulation.adaptive=false)
add_test(NAME cli.simulate.no_file_after_divergence
         COMMAND ${CMAKE_COMMAND} -DF=${CMAKE_CURRENT_BINARY_DIR}/sim_div.h5
                 -P ${CMAKE_CURRENT_LIST_DIR}/helpers/assert_absent.cmake)
set_tests_properties(cli.simulate.no_file_after_divergence PROPERTIES DEPENDS cli.simulate.divergence)
mastrom_cli_test(cli.simulate.short_run EXIT 0 STDOUT "peak joint force .*wrote "
                 ARGS simulate configs/scheme1.toml -q -o ${CMAKE_CURRENT_BINARY_DIR}/sim_short.h5
                      --set simulation.end_time=0.02 --set drive.duration=0.015
                      --set drive.ramp=0.005 --set drive.angle_deg=2
                      --set interface.elements_axial=1 --set interface.elements_circumferential=6)
# failure_modes.cmake uses this result as a foreign file where a database or checkpoint belongs.
set_tests_properties(cli.simulate.short_run PROPERTIES FIXTURES_SETUP sim_short)
# Interface stresses: a bad yield strength is refused before any work and leaves no file; a short
# run with one reports each interface's peak and margin and writes /interfaces and the XDMF.
mastrom_cli_test(cli.simulate.bad_yield_strength EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: config: material\\.yield_strength = -1.*yield_strength > 0"
                 ARGS simulate configs/scheme1.toml --set material.yield_strength=-1
                      -o ${CMAKE_CURRENT_BINARY_DIR}/sim_bad_yield.h5)
add_test(NAME cli.simulate.no_file_after_bad_yield_strength
         COMMAND ${CMAKE_COMMAND} -DF=${CMAKE_CURRENT_BINARY_DIR}/sim_bad_yield.h5
                 -P ${CMAKE_CURRENT_LIST_DIR}/helpers/assert_absent.cmake)
set_tests_properties(cli.simulate.no_file_after_bad_yield_strength
                     PROPERTIES DEPENDS cli.simulate.bad_yield_strength)
mastrom_cli_test(cli.simulate.interface_stresses EXIT 0
                 STDOUT "interface 1: peak von Mises .* margin of safety .*min margin of safety .*wrote .*sim_stress\\.xdmf"
                 ARGS simulate configs/scheme1.toml -q -o ${CMAKE_CURRENT_BINARY_DIR}/sim_stress.h5
                      --set simulation.end_time=0.02 --set drive.duration=0.015
                      --set drive.ramp=0.005 --set drive.angle_deg=2
                      --set material.yield_strength=2.7e8 --stress-fields-at 0.005,0.01
                      --set interface.elements_axial=1 --set interface.elements_circumferential=6)
mastrom_cli_test(cli.simulate.bad_stress_field_time EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: --stress-fields-at: '9' is out of range .*\\[0, 0.02\\] s"
                 ARGS simulate configs/scheme1.toml -q -o ${CMAKE_CURRENT_BINARY_DIR}/sim_bad_field.h5
                      --set simulation.end_time=0.02 --stress-fields-at 0.01,9)
# The default output step (docs/theory.md §5.4a): chosen from the modes at the start, said on the
# first lines, kept in the file's root attributes; an explicit output.step is kept.
mastrom_cli_test(cli.simulate.default_output_step EXIT 0
                 STDOUT "^mastrom simulate: [^\n]*\n  estimated up front: [^\n]*\n  output step [0-9.e-]+ s \\(default: [0-9.]+ samples per period of mode [0-9]+ at [0-9.]+ Hz, the highest the drive excites"
                 ARGS simulate configs/scheme1.toml -q -o ${CMAKE_CURRENT_BINARY_DIR}/sim_default_step.h5
                      --set simulation.end_time=0.02 --set drive.duration=0.015
                      --set drive.ramp=0.005 --set drive.angle_deg=2 --no-stresses
                      --set interface.elements_axial=1 --set interface.elements_circumferential=6)
add_test(NAME cli.simulate.default_output_step_attributes
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/helpers/check_output_step.py
                 ${CMAKE_CURRENT_BINARY_DIR}/sim_default_step.h5)
set_tests_properties(cli.simulate.default_output_step_attributes
                     PROPERTIES DEPENDS cli.simulate.default_output_step)
mastrom_cli_test(cli.simulate.output_step_override EXIT 0
                 STDOUT "^mastrom simulate: [^\n]*\n  estimated up front: [^\n]*\n  output step 0.0005 s \\(output.step\\)\n.*outputs every 0.0005 s"
                 ARGS simulate configs/scheme1.toml -q -o ${CMAKE_CURRENT_BINARY_DIR}/sim_set_step.h5
                      --set simulation.end_time=0.02 --set drive.duration=0.015
                      --set drive.ramp=0.005 --set drive.angle_deg=2 --no-stresses
                      --set output.step=5e-4
                      --set interface.elements_axial=1 --set interface.elements_circumferential=6)
# A run that streams its outputs (written as computed) and one that holds its series (checkpoints
# force it), same arguments: fixture `sim_<tag>`, files sim_<tag>_streamed.h5 and sim_<tag>_held.h5.
function(streamed_and_held_runs tag stdout_regex)
  foreach(mode streamed held)
    set(extra)
    if(mode STREQUAL "held")
      set(extra --checkpoint-every 0.01s
                --checkpoint ${CMAKE_CURRENT_BINARY_DIR}/sim_${tag}_held.ckpt.h5)
    endif()
    mastrom_cli_test(cli.simulate.${tag}_${mode} EXIT 0 STDOUT "${stdout_regex}"
                     ARGS simulate configs/scheme1.toml -q
                          -o ${CMAKE_CURRENT_BINARY_DIR}/sim_${tag}_${mode}.h5
                          --set drive.ramp=0.005 --set drive.angle_deg=2
                          --set interface.elements_axial=1
                          --set interface.elements_circumferential=6 ${ARGN} ${extra})
    set_tests_properties(cli.simulate.${tag}_${mode} PROPERTIES FIXTURES_SETUP sim_${tag})
  endforeach()
endfunction()
# The error estimate of a streamed run (only r kept for the comparison) equals that of a run that
# holds its series: the /metrics attributes, estimates included, and every dataset bit for bit.
streamed_and_held_runs(est "estimated discretisation error: NRMSE [0-9.]+ %"
                       --estimate-error --no-stresses --set simulation.end_time=0.02
                       --set drive.duration=0.015)
mastrom_same_datasets_test(cli.simulate.estimate_error_streamed_equals_held
                           FIRST ${CMAKE_CURRENT_BINARY_DIR}/sim_est_streamed.h5
                           SECOND ${CMAKE_CURRENT_BINARY_DIR}/sim_est_held.h5
                           DATASETS /metrics /time /end /joint /drive FIXTURES sim_est)
# The interface stress histories of a streamed run (resampled onto the output instants while it
# goes, fullorder/interface_stress_stream.hpp) equal those a held run resamples at its end: every
# /interfaces dataset and the /metrics attributes bit for bit, adaptive steps across the drive's
# breakpoints.
streamed_and_held_runs(str "interface 1: peak von Mises" --set simulation.end_time=0.03
                       --set drive.duration=0.02 --set output.step=2e-4)
mastrom_same_datasets_test(cli.simulate.stresses_streamed_equal_held
                           FIRST ${CMAKE_CURRENT_BINARY_DIR}/sim_str_streamed.h5
                           SECOND ${CMAKE_CURRENT_BINARY_DIR}/sim_str_held.h5
                           DATASETS /interfaces /metrics /time /end FIXTURES sim_str)
# A first step (simulation.time_step) far longer than the ringing the drive excites is cut, with
# one line saying why: no error estimate judges the first steps after a breakpoint.
mastrom_cli_test(cli.simulate.long_first_step_is_cut EXIT 0
                 STDOUT "\n  first step after each breakpoint [0-9.e-]+ s: simulation\\.time_step = 0\\.001 s takes fewer than 10 steps per period of mode [0-9]+ at [0-9]+ Hz"
                 ARGS simulate configs/scheme1.toml -q --no-stresses
                      -o ${CMAKE_CURRENT_BINARY_DIR}/sim_long_first_step.h5
                      --set simulation.end_time=0.02 --set drive.duration=0.015
                      --set drive.ramp=0.005 --set drive.angle_deg=2 --set simulation.time_step=1e-3
                      --set interface.elements_axial=1 --set interface.elements_circumferential=6)
