# Plain messages for numeric options and for an interrupted run (cli/cli_common.hpp numberInRange,
# cli/interrupt.hpp). CLI11's own range check printed "Value 0 not in range 0.000000 to 1.79…e308"
# for `--points 0`; these say what is allowed in words.
foreach(spec
    "points_zero|validate,no.h5,--points,0|--points: 0 is out of range; allowed: a whole number >= 1"
    "points_text|validate,no.h5,--points,abc|--points: abc is not a number; allowed: a whole number >= 1"
    "points_fraction|validate,no.h5,--points,2.5|--points: 2\\.5 is out of range; allowed: a whole number >= 1"
    "seed_negative|validate,no.h5,--seed,-3|--seed: -3 is out of range; allowed: a whole number from 0 to"
    "tolerance_negative|validate,no.h5,--tolerance,-0.1|--tolerance: -0\\.1 is out of range; allowed: a number >= 0"
    "compare_tolerance_nan|compare,a.h5,b.h5,--tolerance,nan|--tolerance: nan is not a number; allowed: a number >= 0"
    "build_modes_zero|rom,build,configs/scheme1.toml,--param,interface.thickness=0.001:0.002:2,--modes,0,-o,x.h5|--modes: 0 is out of range; allowed: a whole number >= 1"
    "study_modes_zero|study,shell_thickness,--modes,0|--modes: 0 is out of range; allowed: a whole number >= 1")
  string(REPLACE "|" ";" parts "${spec}")
  list(GET parts 0 name)
  list(GET parts 1 args)
  list(GET parts 2 message)
  string(REPLACE "," ";" args "${args}")
  mastrom_cli_test(cli.messages.${name} EXIT 2 ONE_LINE STDERR "^mastrom: error: ${message}"
                   ARGS ${args})
endforeach()

find_program(MASTROM_BASH bash)
find_program(MASTROM_H5DUMP h5dump)
if(MASTROM_BASH AND MASTROM_H5DUMP)
  # Both signals leave the samples computed in a valid file marked incomplete.
  foreach(signal INT TERM)
    string(TOLOWER ${signal} tag)
    add_test(NAME cli.messages.interrupted_simulate_${tag}
             COMMAND ${MASTROM_BASH} ${CMAKE_CURRENT_LIST_DIR}/helpers/interrupt_simulate.sh
                     $<TARGET_FILE:mastrom> ${MASTROM_H5DUMP} ${signal}
                     ${CMAKE_CURRENT_BINARY_DIR}/interrupt_simulate_${tag} -- configs/scheme3.toml
             WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
    set_tests_properties(cli.messages.interrupted_simulate_${tag} PROPERTIES TIMEOUT 60)
  endforeach()
  # SIGTERM on the other ways a run is written: fixed steps (the stress histories streamed on the
  # recorded states), fixed steps with checkpoints (streamed, flushed at every checkpoint) and an
  # adaptive run with checkpoints (the series held in memory): each leaves a valid file marked
  # incomplete whose stress histories reach its last output instant.
  foreach(case fixed_steps fixed_checkpointed checkpointed)
    if(case STREQUAL "fixed_steps")
      set(extra --set simulation.adaptive=false --set simulation.time_step=2e-5)
    elseif(case STREQUAL "fixed_checkpointed")
      set(extra --set simulation.adaptive=false --set simulation.time_step=2e-5
          --checkpoint-every 0.002s)
    else()
      set(extra --checkpoint-every 0.002s)
    endif()
    add_test(NAME cli.messages.interrupted_simulate_term_${case}
             COMMAND ${MASTROM_BASH} ${CMAKE_CURRENT_LIST_DIR}/helpers/interrupt_simulate.sh
                     $<TARGET_FILE:mastrom> ${MASTROM_H5DUMP} TERM
                     ${CMAKE_CURRENT_BINARY_DIR}/interrupt_simulate_term_${case} --
                     configs/scheme3.toml ${extra}
             WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
    set_tests_properties(cli.messages.interrupted_simulate_term_${case} PROPERTIES TIMEOUT 60)
  endforeach()
  # `rom eval -o` sees the signal between the blocks of its file: a valid file marked incomplete.
  foreach(signal INT TERM)
    string(TOLOWER ${signal} tag)
    add_test(NAME cli.messages.interrupted_rom_eval_${tag}
             COMMAND ${MASTROM_BASH} ${CMAKE_CURRENT_LIST_DIR}/helpers/interrupt_rom_eval.sh
                     $<TARGET_FILE:mastrom> ${MASTROM_H5DUMP} ${signal}
                     ${CMAKE_CURRENT_BINARY_DIR}/interrupt_rom_eval_${tag}
             WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
    set_tests_properties(cli.messages.interrupted_rom_eval_${tag} PROPERTIES TIMEOUT 60
                         ENVIRONMENT "OMP_NUM_THREADS=1")
  endforeach()
endif()
