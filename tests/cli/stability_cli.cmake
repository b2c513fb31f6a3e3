# The stability check of the linearisation point (modes/stability.hpp, modes/linearize.hpp) through
# the CLI, on the soft, heavy Scheme 3 with gravity across it. Applied at once, gravity gives an
# unstable static equilibrium (a buckling shell, 'shell n=3' at the dense spectrum's −650.78 Hz);
# continuing the load reaches the stable branch, whose first bending mode (2.7472 Hz) is the
# ringing of the nonlinear full order at that angle (2.7476 Hz). `modes` analyses that one and says
# how it got there. (The refusal of an equilibrium that stays unstable is tested in
# tests/modes/test_stability.cpp, which can switch the continuation off.)
set(stab_dir ${CMAKE_CURRENT_BINARY_DIR}/stability)
file(MAKE_DIRECTORY ${stab_dir})
set(stab_soft --set material.youngs_modulus=2.5e8 --set interface.thickness=0.0005
    --set simulation.gravity=[0,-9.81,0] --set modes.angle_deg=0.5 --set module.mass=5)
mastrom_cli_test(cli.stability.modes_continued EXIT 0
                 STDOUT "stable, reached by applying gravity in 20 increments; applied at once it gave an unstable equilibrium \\(1 unstable direction: lowest eigenvalue omega\\^2 = -1\\.6719[0-9]e\\+07 rad\\^2/s\\^2 \\(f = -650\\.7[78][0-9]* Hz\\), shape 'shell n=3'\\).*\n +1 +2\\.747[0-9] .*bending-y.*wrote "
                 ARGS modes configs/scheme3.toml ${stab_soft} --backend dense
                      --set modes.count=4 -q -o ${stab_dir}/continued.h5)
mastrom_cli_test(cli.stability.modes_stable EXIT 0 STDOUT "stability of the equilibrium .*: stable\n"
                 ARGS modes configs/scheme1.toml --backend dense --set modes.count=4 -q
                      -o ${stab_dir}/stable.h5)
mastrom_cli_test(cli.stability.rom_build_continued EXIT 0
                 STDOUT "2 samples.*wrote "
                 ARGS rom build configs/scheme3.toml ${stab_soft} --param module.mass=4.5:5:2
                      --modes 4 --backend dense -q -o ${stab_dir}/continued_db.h5)
