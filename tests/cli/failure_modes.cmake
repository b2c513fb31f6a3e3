# Every CLI failure mode — missing file, unreadable or corrupt HDF5 (truncated, damaged
# metadata, damaged data, random bytes, a foreign mastrom file), bad grid spec, bad override, solver
# divergence, killed MPI rank — ends with one `mastrom: error:` line, an exit code ≠ 0 and no result
# file (not even a temporary one). docs/failure_modes.md tabulates the same cases. Inputs: the small
# ROM database of rom_cli.cmake (fixture rom_db) and the short simulate result of simulate_cli.cmake
# (fixture sim_short); damaged copies are made by helpers/make_corrupt_files.cmake.
if(NOT COMMAND mastrom_cli_test)
  return()
endif()
include(${CMAKE_CURRENT_LIST_DIR}/helpers/cli_test_functions.cmake)

set(fm ${CMAKE_CURRENT_BINARY_DIR}/failure_modes)
set(fm_db ${CMAKE_CURRENT_BINARY_DIR}/rom_cli_db1.h5)
set(fm_sim ${CMAKE_CURRENT_BINARY_DIR}/sim_short.h5)
set(fm_out ${fm}/result.h5)
file(MAKE_DIRECTORY ${fm})

add_test(NAME failure_modes.make_corrupt_files
         COMMAND ${CMAKE_COMMAND} -E chdir ${fm} ${CMAKE_COMMAND} -DSOURCE=${fm_db} -DOUT=${fm}/db
                 -P ${CMAKE_CURRENT_LIST_DIR}/helpers/make_corrupt_files.cmake)
set_tests_properties(failure_modes.make_corrupt_files PROPERTIES FIXTURES_REQUIRED rom_db
                     FIXTURES_SETUP fm_corrupt)

# --- missing files ---------------------------------------------------------------------------------
mastrom_failure_test(failure_modes.missing.config EXIT 2 ONE_LINE ABSENT ${fm_out}
                     STDERR "^mastrom: error: config: cannot read no/such\\.toml: "
                     ARGS simulate no/such.toml -o ${fm_out})
foreach(cmd "rom;eval" "screen;--grid;module.mass=0.4:0.6:2" validate)
  list(GET cmd 0 tag)
  list(REMOVE_AT cmd 0)
  mastrom_failure_test(failure_modes.missing.db.${tag} EXIT 2 ONE_LINE ABSENT ${fm_out}
                       STDERR "^mastrom: error: cannot open 'no/such/db\\.h5': no such file"
                       ARGS ${tag} ${cmd} no/such/db.h5 -o ${fm_out})
endforeach()
mastrom_failure_test(failure_modes.missing.deployment EXIT 2 ONE_LINE
                     STDERR "^mastrom: error: cannot open 'no/such/full\\.h5': no such file"
                     ARGS compare no/such/full.h5 no/such/rom.h5)

# --- unreadable or corrupt HDF5 ----------------------------------------------------------------------
foreach(cmd "rom;eval" screen validate)
  string(REPLACE ";" "_" tag "${cmd}")
  set(extra)
  if(cmd STREQUAL "screen")
    set(extra --grid module.mass=0.4:0.6:2)
  endif()
  mastrom_failure_test(failure_modes.truncated.${tag} EXIT 2 ONE_LINE ABSENT ${fm_out}
                       STDERR "^mastrom: error: HDF5 H5Fopen failed for '.*db_truncated\\.h5': unable to open file \\(truncated file"
                       ARGS ${cmd} ${fm}/db_truncated.h5 ${extra} -o ${fm_out})
  mastrom_failure_test(failure_modes.random_bytes.${tag} EXIT 2 ONE_LINE ABSENT ${fm_out}
                       STDERR "^mastrom: error: cannot open '.*db_random\\.h5': not an HDF5 file"
                       ARGS ${cmd} ${fm}/db_random.h5 ${extra} -o ${fm_out})
  mastrom_failure_test(failure_modes.damaged_metadata.${tag} EXIT 2 ONE_LINE ABSENT ${fm_out}
                       STDERR "^mastrom: error: HDF5 [A-Za-z0-9_]+ failed for .*db_metadata\\.h5"
                       ARGS ${cmd} ${fm}/db_metadata.h5 ${extra} -o ${fm_out})
  mastrom_failure_test(failure_modes.damaged_data.${tag} EXIT 2 ONE_LINE ABSENT ${fm_out}
                       STDERR "^mastrom: error: (ROM database '.*db_data\\.h5' is corrupted: its content checksum|HDF5 [A-Za-z0-9_]+ failed for .*db_data\\.h5)"
                       ARGS ${cmd} ${fm}/db_data.h5 ${extra} -o ${fm_out})
  set_tests_properties(failure_modes.truncated.${tag} failure_modes.random_bytes.${tag}
                       failure_modes.damaged_metadata.${tag} failure_modes.damaged_data.${tag}
                       PROPERTIES FIXTURES_REQUIRED fm_corrupt)
endforeach()
mastrom_failure_test(failure_modes.truncated.restart EXIT 2 ONE_LINE ABSENT ${fm_out}
                     STDERR "^mastrom: error: HDF5 H5Fopen failed for '.*db_truncated\\.h5'"
                     ARGS simulate configs/scheme1.toml --restart ${fm}/db_truncated.h5
                          -o ${fm_out})
mastrom_failure_test(failure_modes.random_bytes.config EXIT 2 ONE_LINE ABSENT ${fm_out}
                     STDERR "^mastrom: error: config: .*db_random\\.h5:[0-9]+:[0-9]+: TOML syntax error"
                     ARGS simulate ${fm}/db_random.h5 -o ${fm_out})
set_tests_properties(failure_modes.truncated.restart failure_modes.random_bytes.config PROPERTIES
                     FIXTURES_REQUIRED fm_corrupt)
# Foreign mastrom files: a deployment result where a database or checkpoint belongs, and back.
mastrom_failure_test(failure_modes.foreign.screen EXIT 2 ONE_LINE ABSENT ${fm_out}
                     STDERR "^mastrom: error: ROM database '.*sim_short\\.h5' is not a mastrom ROM database \\(no root attribute 'format'; it is a 'full-order' file\\)"
                     ARGS screen ${fm_sim} --grid module.mass=0.4:0.6:2 -o ${fm_out})
mastrom_failure_test(failure_modes.foreign.restart EXIT 2 ONE_LINE ABSENT ${fm_out}
                     STDERR "^mastrom: error: '.*sim_short\\.h5' is not a mastrom checkpoint \\(no root attribute 'format'\\)"
                     ARGS simulate configs/scheme1.toml --restart ${fm_sim} -o ${fm_out})
set_tests_properties(failure_modes.foreign.screen failure_modes.foreign.restart PROPERTIES
                     FIXTURES_REQUIRED sim_short)
mastrom_failure_test(failure_modes.foreign.compare EXIT 2 ONE_LINE
                     STDERR "^mastrom: error: '.*rom_cli_db1\\.h5' is not a mastrom deployment file: missing /time"
                     ARGS compare ${fm_db} ${fm_db})
mastrom_failure_test(failure_modes.foreign.restart_db EXIT 2 ONE_LINE ABSENT ${fm_out}
                     STDERR "^mastrom: error: '.*rom_cli_db1\\.h5' is not a mastrom checkpoint \\(format 'mastrom-rom-database', expected 'mastrom-checkpoint'\\)"
                     ARGS simulate configs/scheme1.toml --restart ${fm_db} -o ${fm_out})
set_tests_properties(failure_modes.foreign.compare failure_modes.foreign.restart_db PROPERTIES
                     FIXTURES_REQUIRED rom_db)

# --- bad grid spec (screen) --------------------------------------------------------------------------
set(fm_grid_cases
    "malformed|module.mass|--grid 'module\\.mass' is malformed: expected KEY=LO:HI:N or KEY=V1,V2"
    "not_numbers|module.mass=a:b:c|--grid 'module\\.mass=a:b:c' is malformed: expected KEY=LO:HI:N with finite numbers"
    "reversed|module.mass=0.6:0.4:3|--grid 'module\\.mass=0\\.6:0\\.4:3': LO = 0\\.6 must be less than HI = 0\\.4"
    "zero_points|module.mass=0.4:0.6:0|--grid 'module\\.mass=0\\.4:0\\.6:0': N must be an integer"
    "bad_law|drive.law=linear,cubic|--grid 'drive\\.law=linear,cubic': config: drive\\.law = \"linear\" is not a known drive law"
    "not_a_parameter|material.density=2000:3000:3|--grid material\\.density: not a parameter of this database")
foreach(case ${fm_grid_cases})
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 tag)
  list(GET parts 1 grid)
  list(GET parts 2 regex)
  mastrom_failure_test(failure_modes.grid.${tag} EXIT 2 ONE_LINE ABSENT ${fm}/screen.csv
                       STDERR "^mastrom: error: ${regex}"
                       ARGS screen ${fm_db} --grid ${grid} -o ${fm}/screen.csv)
  set_tests_properties(failure_modes.grid.${tag} PROPERTIES FIXTURES_REQUIRED rom_db)
endforeach()
# --step: a positive number, and not together with --set output.step.
mastrom_failure_test(failure_modes.screen_step.negative EXIT 2 ONE_LINE ABSENT ${fm}/screen.csv
                     STDERR "^mastrom: error: --step -0\\.001 s; allowed: > 0"
                     ARGS screen ${fm_db} --grid module.mass=0.4:0.6:2 --step -0.001
                          -o ${fm}/screen.csv)
mastrom_failure_test(failure_modes.screen_step.twice EXIT 2 ONE_LINE ABSENT ${fm}/screen.csv
                     STDERR "^mastrom: error: --step 0\\.001 and --set output\\.step=1e-4 both set the ROM step; give one"
                     ARGS screen ${fm_db} --grid module.mass=0.4:0.6:2 --step 0.001
                          --set output.step=1e-4 -o ${fm}/screen.csv)
set_tests_properties(failure_modes.screen_step.negative failure_modes.screen_step.twice PROPERTIES
                     FIXTURES_REQUIRED rom_db)
# Under mpirun: still one mastrom line (rank 0's), whatever mpirun adds.
mastrom_failure_test(failure_modes.grid.reversed.mpi2 EXIT nonzero ONE_ERROR_LINE MPI
                     ABSENT ${fm}/screen.csv
                     STDERR "mastrom: error: --grid 'module\\.mass=0\\.6:0\\.4:3': LO = 0\\.6 must be less than HI = 0\\.4"
                     ARGS screen ${fm_db} --grid module.mass=0.6:0.4:3 -o ${fm}/screen.csv)
set_tests_properties(failure_modes.grid.reversed.mpi2 PROPERTIES FIXTURES_REQUIRED rom_db)

# --- bad overrides, every config-driven command --------------------------------------------------
set(fm_override_cases
    "malformed|interface.thickness|config: --set \"interface\\.thickness\" is malformed: expected section\\.key=value"
    "wrong_type|interface.thickness=abc|config: interface\\.thickness = \"abc\" has the wrong type: expected a number"
    "unknown|nosuch.key=1|config: unknown section \\[nosuch\\]"
    "out_of_range|interface.thickness=-1|config: interface\\.thickness = -1 is out of range: must satisfy 0 < thickness")
foreach(case ${fm_override_cases})
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 tag)
  list(GET parts 1 override)
  list(GET parts 2 regex)
  foreach(cmd simulate modes "rom;eval" screen validate)
    string(REPLACE ";" "_" ctag "${cmd}")
    if(cmd STREQUAL "simulate" OR cmd STREQUAL "modes")
      set(input configs/scheme1.toml)
    else()
      set(input ${fm_db})
    endif()
    set(extra)
    if(cmd STREQUAL "screen")
      set(extra --grid module.mass=0.4:0.6:2)
    endif()
    set(name failure_modes.override.${tag}.${ctag})
    mastrom_failure_test(${name} EXIT 2 ONE_LINE ABSENT ${fm_out}
                         STDERR "^mastrom: error: ${regex}"
                         ARGS ${cmd} ${input} ${extra} --set ${override} -o ${fm_out})
    if(NOT input STREQUAL "configs/scheme1.toml")
      set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED rom_db)
    endif()
  endforeach()
endforeach()

# --- solver divergence: a 4 ms step on a 10⁶ Pa shell (as simulate_cli.cmake's divergence test) ---
# Fixed steps: adaptive steps would shorten the step until it converges.
set(fm_diverge --set simulation.time_step=0.004 --set simulation.end_time=0.05
    --set drive.duration=0.02 --set drive.ramp=0.005 --set simulation.adaptive=false)
mastrom_failure_test(failure_modes.divergence.validate EXIT 3 ONE_LINE ABSENT ${fm_out}
                     STDERR "^mastrom: error: generalized-alpha: step to t = [0-9.e-]+ s failed"
                     ARGS validate ${fm_db} --points 1 ${fm_diverge} -o ${fm_out})
mastrom_failure_test(failure_modes.divergence.validate.mpi2 EXIT nonzero ONE_ERROR_LINE MPI
                     ABSENT ${fm_out}
                     STDERR "mastrom: error: generalized-alpha: step to t = [0-9.e-]+ s failed"
                     ARGS validate ${fm_db} --points 2 ${fm_diverge} -o ${fm_out})
set_tests_properties(failure_modes.divergence.validate failure_modes.divergence.validate.mpi2
                     PROPERTIES FIXTURES_REQUIRED rom_db)

# --- killed MPI rank: rank 1 of a 2-rank validate gets SIGKILL one second in ----------------------
find_program(MASTROM_BASH bash)
if(MASTROM_BASH)
  # The run must outlast the helper's 1 s wait before the kill: on an idle machine a 3 s horizon
  # finished in 0.6 s and the kill found no process. 300 s takes minutes; the kill ends it.
  add_test(NAME failure_modes.killed_rank.validate
           COMMAND ${MASTROM_BASH} ${CMAKE_CURRENT_LIST_DIR}/helpers/kill_rank.sh
                   ${MPIEXEC_EXECUTABLE} ${fm}/killed.h5 -- $<TARGET_FILE:mastrom> validate
                   ${fm_db} --points 2 --set simulation.end_time=300 --set drive.duration=200
                   -o ${fm}/killed.h5
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(failure_modes.killed_rank.validate PROPERTIES FIXTURES_REQUIRED rom_db
                       ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMP_NUM_THREADS=1"
                       PROCESSORS 2 TIMEOUT 60 LABELS "mpi")
endif()
