# The stability check of the linearisation point (modes/stability.hpp) through the CLI, on the soft,
# heavy Scheme 3 with gravity across it whose static equilibrium is unstable (a buckled shell):
# `modes` refuses it in one line naming the unstable shape and its eigenvalue (the dense spectrum's
# −650.78 Hz) and writes no file; --allow-unstable writes the modes flagged; `rom build` refuses the
# unstable sample the same way.
set(stab_dir ${CMAKE_CURRENT_BINARY_DIR}/stability)
file(MAKE_DIRECTORY ${stab_dir})
set(stab_soft --set material.youngs_modulus=2.5e8 --set interface.thickness=0.0005
    --set simulation.gravity=[0,-9.81,0] --set modes.angle_deg=0.5)
mastrom_cli_test(cli.stability.modes_refused EXIT 3 ONE_LINE
                 STDERR "^mastrom: error: the static equilibrium at the locked angle 0\\.5 deg is unstable \\(1 unstable direction: lowest eigenvalue omega\\^2 = -1\\.6719[0-9]e\\+07 rad\\^2/s\\^2 \\(f = -650\\.7[78][0-9]* Hz\\), shape 'shell n=3'\\).*--allow-unstable"
                 ARGS modes configs/scheme3.toml ${stab_soft} --set module.mass=5
                      -o ${stab_dir}/refused.h5)
add_test(NAME cli.stability.modes_refused_no_file
         COMMAND ${CMAKE_COMMAND} -DF=${stab_dir}/refused.h5
                 -P ${CMAKE_CURRENT_LIST_DIR}/helpers/assert_absent.cmake)
set_tests_properties(cli.stability.modes_refused_no_file PROPERTIES
                     DEPENDS cli.stability.modes_refused)
mastrom_cli_test(cli.stability.modes_allowed EXIT 0
                 STDOUT "1 unstable direction.*WARNING: unstable equilibrium.*wrote "
                 ARGS modes configs/scheme3.toml ${stab_soft} --set module.mass=5 --allow-unstable
                      --backend dense --set modes.count=4 -q -o ${stab_dir}/allowed.h5)
mastrom_cli_test(cli.stability.modes_stable EXIT 0 STDOUT "stability of the equilibrium .*: stable"
                 ARGS modes configs/scheme1.toml --backend dense --set modes.count=4 -q
                      -o ${stab_dir}/stable.h5)
mastrom_cli_test(cli.stability.rom_build_refused EXIT 3 ONE_LINE
                 STDERR "^mastrom: error: rom build: sample [0-9]+ \\(module\\.mass=5\\.0\\): the static equilibrium .* is unstable .*shell n=3"
                 ARGS rom build configs/scheme3.toml ${stab_soft} --param module.mass=4.5:5:2
                      --modes 4 --backend dense -q -o ${stab_dir}/unstable_db.h5)
