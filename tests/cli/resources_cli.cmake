# Inputs that would exhaust the machine are refused before any work (common/resource_budget.hpp):
# one line naming what is needed, the keys that drive it with their values and what the machine
# has; exit code 2; no result file, not even a temporary one. The sizes are far past any machine
# (a typo of 100000 modules, a horizon of 1e9 s, grids of 1e9 points), so the tests do not depend
# on this one's memory or disk.
include(${CMAKE_CURRENT_LIST_DIR}/helpers/cli_test_functions.cmake)

set(res_dir ${CMAKE_CURRENT_BINARY_DIR}/resources_cli)
file(MAKE_DIRECTORY ${res_dir})
set(res_out ${res_dir}/result.h5)
set(res_db ${CMAKE_CURRENT_BINARY_DIR}/rom_cli_db1.h5)
set(res_memory ", more than the [0-9.]+ [kMGTPE]?B available \\(MemAvailable\\); reduce them, or pass --allow-large to run anyway$")
set(res_disk "more than the [0-9.]+ [kMGTPE]?B free on the output's file system; reduce them, or pass --allow-large to run anyway$")

mastrom_failure_test(resources.simulate.modules EXIT 2 ONE_LINE ABSENT ${res_out}
                     STDERR "^mastrom: error: simulate would need about [0-9.]+ [GTP]B of memory \\(.*\\)${res_memory}"
                     ARGS simulate configs/scheme3.toml --set mast.modules=100000 -o ${res_out})
mastrom_failure_test(resources.simulate.modules_named EXIT 2 ONE_LINE ABSENT ${res_out}
                     STDERR "\\(mast\\.modules = 100000, interface\\.elements_axial = 2, interface\\.elements_circumferential = 8: 2\\.28e\\+07 DOFs, 1\\.6e\\+06 shell elements"
                     ARGS simulate configs/scheme3.toml --set mast.modules=100000 -o ${res_out})
# A default output step is chosen after the mast is checked, so the mast alone is named above.
# The horizon: every run streams its series (and stress histories), with checkpoints too (an
# adaptive one's checkpoint carries a few step points, not the series), so what grows with it is
# the result on disk, for a checkpointed run as for a plain one.
# A default output step is capped (docs/theory.md §5.4a), so these runs set the step whose
# samples grow with the horizon.
mastrom_failure_test(resources.simulate.horizon_checkpointed EXIT 2 ONE_LINE ABSENT ${res_out}
                     STDERR "^mastrom: error: simulate would write about [0-9.]+ [PE]B \\(simulation\\.end_time = 1000000000, output\\.step = 0\\.0001.*: 1e\\+13 output samples\\), ${res_disk}"
                     ARGS simulate configs/scheme3.toml --set simulation.end_time=1e9
                          --set output.step=1e-4 --checkpoint-every 1000 -o ${res_out})
mastrom_failure_test(resources.simulate.horizon_result EXIT 2 ONE_LINE ABSENT ${res_out}
                     STDERR "^mastrom: error: simulate would write about [0-9.]+ [PE]B \\(simulation\\.end_time = 1000000000, output\\.step = 0\\.0001: 1e\\+13 output samples\\), ${res_disk}"
                     ARGS simulate configs/scheme3.toml --set simulation.end_time=1e9 --no-stresses
                          --set output.step=1e-4
                          -o ${res_out})
mastrom_failure_test(resources.modes.dense EXIT 2 ONE_LINE ABSENT ${res_out}
                     STDERR "^mastrom: error: modes would need about [0-9.]+ [GTP]B of memory \\(mast\\.modules = 200, .*modes\\.backend = dense: 4\\.54e\\+04 DOFs in dense matrices\\)${res_memory}"
                     ARGS modes configs/scheme3.toml --set mast.modules=200 --backend dense
                          -o ${res_out})
mastrom_failure_test(resources.rom_build.grid EXIT 2 ONE_LINE ABSENT ${res_out}
                     STDERR "^mastrom: error: rom build would need about [0-9.]+ [GTP]B of memory \\(.*--param = interface\\.thickness=0\\.001:0\\.002:10000, --param = module\\.mass=0\\.4:0\\.6:10000.*1e\\+08 samples x 6 modes\\)${res_memory}"
                     ARGS rom build configs/scheme1.toml --param interface.thickness=0.001:0.002:10000
                          --param module.mass=0.4:0.6:10000 --modes 6 -o ${res_out})
# The database-driven commands: the small database of rom_cli.cmake (fixture rom_db).
mastrom_failure_test(resources.rom_eval.horizon EXIT 2 ONE_LINE ABSENT ${res_out}
                     STDERR "^mastrom: error: rom eval would need about [0-9.]+ [GTPE]B of memory \\(.*simulation\\.end_time = 1000000000.*metric samples held, every 0\\.0001 s\\)${res_memory}"
                     ARGS rom eval ${res_db} --set simulation.end_time=1e9 --set output.step=1e-4
                          -o ${res_out})
mastrom_failure_test(resources.screen.grid EXIT 2 ONE_LINE ABSENT ${res_out}
                     STDERR "^mastrom: error: screen would need about [0-9.]+ [GTP]B of memory \\(--grid = interface\\.thickness=0\\.001:0\\.002:1000, --grid = module\\.mass=0\\.4:0\\.6:1000, --grid = drive\\.duration=5:7:1000: 1e\\+09 designs x [0-9]+ columns\\)${res_memory}"
                     ARGS screen ${res_db} --grid interface.thickness=0.001:0.002:1000
                          --grid module.mass=0.4:0.6:1000 --grid drive.duration=5:7:1000
                          -o ${res_out})
mastrom_failure_test(resources.validate.horizon EXIT 2 ONE_LINE ABSENT ${res_out}
                     STDERR "^mastrom: error: validate would need about [0-9.]+ [GTPE]B of memory \\(.*simulation\\.end_time = 1000000000.*output samples held\\)${res_memory}"
                     ARGS validate ${res_db} --points 1 --set simulation.end_time=1e9 -o ${res_out})
set_tests_properties(resources.rom_eval.horizon resources.screen.grid resources.validate.horizon
                     PROPERTIES FIXTURES_REQUIRED rom_db)
