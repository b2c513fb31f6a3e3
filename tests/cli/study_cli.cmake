# ctest entries for `mastrom study` (uses mastrom_cli_test of config_cli.cmake). A tiny case (Scheme
# 1 of configs/studies/schemes.toml, 1 × 6 mesh, 2° in 15 ms, dense modal solve) runs with both
# models and must write both deployment files and the table; bad names, keys, cases, models and
# paths fail before any run with one line; a diverging case exits 3 and leaves no table.
if(NOT COMMAND mastrom_cli_test)
  return()
endif()
set(study_dir ${CMAKE_CURRENT_BINARY_DIR}/study_cli)
set(study_env "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMP_NUM_THREADS=1")
set(study_tiny --case scheme1 --set simulation.end_time=0.02 --set drive.duration=0.015
    --set drive.ramp=0.005 --set drive.angle_deg=2 --set interface.elements_axial=1
    --set interface.elements_circumferential=6 --set modes.backend=dense --set modes.count=6 -q)

mastrom_cli_test(cli.study.help EXIT 0 STDOUT "--set.*--model.*--case" ARGS study --help)
mastrom_cli_test(cli.study.list EXIT 0 STDOUT "drive_laws\ninner_diameter\nmaterials\nschemes\nshell_thickness\n"
                 ARGS study --list)
mastrom_cli_test(cli.study.tiny EXIT 0
                 STDOUT "schemes/scheme1 +full .*schemes/scheme1 +rom .*schemes/scheme1 +diff .*wrote .*study\\.csv"
                 ARGS study schemes ${study_tiny} -o ${study_dir})
set_tests_properties(cli.study.tiny PROPERTIES FIXTURES_SETUP study_tiny ENVIRONMENT "${study_env}")
add_test(NAME cli.study.tiny_outputs
         COMMAND ${CMAKE_COMMAND} -DDIR=${study_dir} -DSTUDY=schemes -DCASE=scheme1
                 -P ${CMAKE_CURRENT_LIST_DIR}/helpers/check_study_outputs.cmake)
set_tests_properties(cli.study.tiny_outputs PROPERTIES FIXTURES_REQUIRED study_tiny)

# Plain run configurations form one study named "configs", one case per file.
mastrom_cli_test(cli.study.plain_configs EXIT 0 STDOUT "configs/scheme1 +rom .*wrote "
                 ARGS study configs/scheme1.toml --model rom ${study_tiny}
                      -o ${CMAKE_CURRENT_BINARY_DIR}/study_cli_plain)
set_tests_properties(cli.study.plain_configs PROPERTIES ENVIRONMENT "${study_env}")

# Failure paths: exit 2 and one line naming what is wrong, before any run.
mastrom_cli_test(cli.study.unknown_name EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: study: 'no_such_study' is neither a file nor a known study \\(available: drive_laws, inner_diameter, materials, schemes, shell_thickness\\)"
                 ARGS study no_such_study -o ${study_dir}_bad)
mastrom_cli_test(cli.study.bad_key EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: study '.*shell_thickness\\.toml', case 'h0\\.5mm': .*interface\\.thickness = -1"
                 ARGS study shell_thickness --set interface.thickness=-1 -o ${study_dir}_bad)
mastrom_cli_test(cli.study.bad_case EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: --case = 'scheme9' is not a case .*schemes/scheme1"
                 ARGS study schemes --case scheme9 -o ${study_dir}_bad)
mastrom_cli_test(cli.study.bad_model EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: --model = 'fast' is not a model \\(allowed: both, full, rom\\)"
                 ARGS study schemes --model fast -o ${study_dir}_bad)
mastrom_cli_test(cli.study.unwritable_output EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: -o: cannot create directory '/dev/null/x/schemes'"
                 ARGS study schemes -o /dev/null/x)
set_tests_properties(cli.study.unwritable_output PROPERTIES TIMEOUT 20)
# A case that diverges (soft shells, 4 ms steps) exits 3; the table is not written.
mastrom_cli_test(cli.study.divergence EXIT 3 ONE_LINE
                 STDERR "^mastrom: error: generalized-alpha: step to t = [0-9.e-]+ s failed"
                 ARGS study schemes --case scheme1 -q -o ${study_dir}_div
                      --set simulation.time_step=0.004 --set simulation.end_time=0.05
                      --set drive.duration=0.02 --set drive.ramp=0.005
                      --set interface.elements_axial=1 --set interface.elements_circumferential=6
                      --set material.youngs_modulus=1e6 --set simulation.adaptive=false)
set_tests_properties(cli.study.divergence PROPERTIES ENVIRONMENT "${study_env}")
add_test(NAME cli.study.no_table_after_divergence
         COMMAND ${CMAKE_COMMAND} -DF=${study_dir}_div/study.csv
                 -P ${CMAKE_CURRENT_LIST_DIR}/helpers/assert_absent.cmake)
set_tests_properties(cli.study.no_table_after_divergence PROPERTIES DEPENDS cli.study.divergence)
add_test(NAME cli.study.no_case_file_after_divergence
         COMMAND ${CMAKE_COMMAND} -DF=${study_dir}_div/schemes/scheme1_full.h5
                 -P ${CMAKE_CURRENT_LIST_DIR}/helpers/assert_absent.cmake)
set_tests_properties(cli.study.no_case_file_after_divergence PROPERTIES DEPENDS cli.study.divergence)
