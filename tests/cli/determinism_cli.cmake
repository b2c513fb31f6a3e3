# Determinism: the same inputs give identical HDF5 datasets across runs and across 1 and
# 2 MPI ranks for `screen` and `validate`. Uses the small database of rom_cli.cmake (fixture rom_db)
# and its screen on 1 rank (fixture rom_screen1); rom_cli.cmake compares that screen with 2 ranks.
# validate runs 2 points over a 0.3 s horizon (full order + ROM, about 2 s per run). Wall-time
# datasets and attributes differ between runs by nature and are not compared.
if(NOT COMMAND mastrom_cli_test)
  return()
endif()
include(${CMAKE_CURRENT_LIST_DIR}/helpers/cli_test_functions.cmake)

set(det_dir ${CMAKE_CURRENT_BINARY_DIR})
set(det_env "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMP_NUM_THREADS=1")
# The same screen arguments as rom_cli.cmake's rom.cli.screen.h5, run once more.
set(det_screen_args --grid interface.thickness=0.001:0.002:4
    --grid drive.law=trapezoidal,cubic,cycloidal --set module.mass=0.45 -q)
set(det_validate_args --points 2 --seed 7 --set simulation.end_time=0.3 --set drive.duration=0.2
    --set drive.ramp=0.05)

mastrom_cli_test(determinism.screen.repeat EXIT 0 STDOUT "wrote "
                 ARGS screen ${det_dir}/rom_cli_db1.h5 ${det_screen_args}
                      -o ${det_dir}/det_screen_repeat.h5)
set_tests_properties(determinism.screen.repeat PROPERTIES FIXTURES_REQUIRED rom_db
                     FIXTURES_SETUP det_screen ENVIRONMENT "${det_env}")
mastrom_same_datasets_test(determinism.screen.same_h5_on_repeat
                           FIRST ${det_dir}/rom_cli_screen1.h5 SECOND ${det_dir}/det_screen_repeat.h5
                           DATASETS /screen/parameters /screen/metrics
                           FIXTURES rom_screen1 det_screen)

foreach(run 1 1b)
  mastrom_cli_test(determinism.validate.run${run} EXIT 0
                   STDOUT "2 points .*on 1 rank.*full order: adaptive steps, simulation\\.tolerance = 1e-05.*full-est +rom-est\n.*rom-est = the database's estimate.*wrote "
                   ARGS validate ${det_dir}/rom_cli_db1.h5 ${det_validate_args}
                        -o ${det_dir}/det_validate${run}.h5)
  set_tests_properties(determinism.validate.run${run} PROPERTIES FIXTURES_REQUIRED rom_db
                       FIXTURES_SETUP det_validate${run} ENVIRONMENT "${det_env}")
endforeach()
add_test(NAME determinism.validate.mpi2
         COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} 2 $<TARGET_FILE:mastrom>
                 validate ${det_dir}/rom_cli_db1.h5 ${det_validate_args}
                 -o ${det_dir}/det_validate2.h5
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(determinism.validate.mpi2 PROPERTIES FIXTURES_REQUIRED rom_db
                     FIXTURES_SETUP det_validate2 ENVIRONMENT "${det_env}" PROCESSORS 2
                     TIMEOUT 120 LABELS "mpi")
set(det_validate_datasets /validation/parameters /validation/errors
    /validation/first_frequency_error)
mastrom_same_datasets_test(determinism.validate.same_h5_on_repeat
                           FIRST ${det_dir}/det_validate1.h5 SECOND ${det_dir}/det_validate1b.h5
                           DATASETS ${det_validate_datasets}
                           FIXTURES det_validate1 det_validate1b)
mastrom_same_datasets_test(determinism.validate.same_h5_for_1_and_2_ranks
                           FIRST ${det_dir}/det_validate1.h5 SECOND ${det_dir}/det_validate2.h5
                           DATASETS ${det_validate_datasets}
                           FIXTURES det_validate1 det_validate2)
if(TEST determinism.validate.same_h5_for_1_and_2_ranks)
  set_tests_properties(determinism.validate.same_h5_for_1_and_2_ranks PROPERTIES LABELS "mpi")
endif()

# simulate on 1 and 2 threads (--threads: the shell element forces spread over threads, summed in a
# fixed order): the same datasets, value for value. Scheme 2 on the coarse 1 × 6 ring, 0.1 s.
set(det_sim_args simulate configs/scheme2.toml -q --set simulation.end_time=0.1
    --set drive.duration=0.08 --set drive.ramp=0.02 --set drive.angle_deg=20
    --set interface.elements_axial=1 --set interface.elements_circumferential=6)
foreach(threads 1 2)
  mastrom_cli_test(determinism.simulate.threads${threads} EXIT 0
                   STDOUT "constraints, [0-9]+ shell elements, mass [0-9.]+ kg, ${threads} thread.*wrote "
                   ARGS ${det_sim_args} --threads ${threads} -o ${det_dir}/det_sim_t${threads}.h5)
  set_tests_properties(determinism.simulate.threads${threads} PROPERTIES
                       FIXTURES_SETUP det_sim_t${threads})
endforeach()
mastrom_same_datasets_test(determinism.simulate.same_h5_on_1_and_2_threads
                           FIRST ${det_dir}/det_sim_t1.h5 SECOND ${det_dir}/det_sim_t2.h5
                           DATASETS /end/angular_acceleration /end/relative_angular_acceleration
                                    /joint/force /joint/torque /solver/newton_iterations
                           FIXTURES det_sim_t1 det_sim_t2)
mastrom_cli_test(cli.simulate.negative_threads EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: --threads = -1 must be >= 1"
                 ARGS ${det_sim_args} --threads -1 -o ${det_dir}/det_sim_bad.h5)
