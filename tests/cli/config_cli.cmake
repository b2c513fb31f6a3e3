# ctest entries for the `mastrom` executable and its `config` subcommand (included by
# tests/CMakeLists.txt). Failure cases check the exit code AND the one-line `mastrom: error:` message
# through helpers/run_cli.cmake.
set(mastrom_run_cli ${CMAKE_CURRENT_LIST_DIR}/helpers/run_cli.cmake)

# mastrom_cli_test(name EXIT code|nonzero [STDOUT regex] [STDERR regex] [ONE_LINE] ARGS …)
function(mastrom_cli_test name)
  cmake_parse_arguments(T "ONE_LINE" "EXIT;STDOUT;STDERR;ROUNDTRIP" "ARGS" ${ARGN})
  set(defs -DEXPECT_EXIT=${T_EXIT})
  if(DEFINED T_STDOUT)
    list(APPEND defs "-DSTDOUT_REGEX=${T_STDOUT}")
  endif()
  if(DEFINED T_STDERR)
    list(APPEND defs "-DSTDERR_REGEX=${T_STDERR}")
  endif()
  if(T_ONE_LINE)
    list(APPEND defs -DONE_LINE_STDERR=ON)
  endif()
  if(DEFINED T_ROUNDTRIP)
    list(APPEND defs "-DROUNDTRIP_FILE=${CMAKE_CURRENT_BINARY_DIR}/${T_ROUNDTRIP}")
  endif()
  add_test(NAME ${name}
           COMMAND ${CMAKE_COMMAND} ${defs} -P ${mastrom_run_cli} -- $<TARGET_FILE:mastrom> ${T_ARGS}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
endfunction()

# Success paths.
mastrom_cli_test(cli.help EXIT 0 STDOUT "Usage: mastrom" ARGS --help)
mastrom_cli_test(cli.version EXIT 0 STDOUT "^mastrom [0-9]+\\.[0-9]+\\.[0-9]+" ARGS --version)
mastrom_cli_test(cli.config.help EXIT 0 STDOUT "--set" ARGS config --help)
foreach(n 1 2 3)
  math(EXPR modules "${n} + 1")
  mastrom_cli_test(cli.config.scheme${n} EXIT 0 STDOUT "\\[mast\\]\nmodules = ${modules}\n"
                   ARGS config configs/scheme${n}.toml)
endforeach()
mastrom_cli_test(cli.config.overrides EXIT 0
                 STDOUT "inner_diameter = 0.09 .*thickness = 0.001 .*law = \"cubic\""
                 ARGS config configs/scheme3.toml --set interface.inner_diameter=0.09
                      --set interface.thickness=0.001 --set drive.law=cubic)
mastrom_cli_test(cli.config.roundtrip EXIT 0 ROUNDTRIP config_roundtrip.toml
                 ARGS config configs/scheme2.toml --set interface.inner_diameter=0.085
                      --set simulation.gravity=[0,-9.81,0] --set module.inertia=[1e-3,1e-3,1e-3])

# Failure paths: exit code 2 and exactly one line `mastrom: error: …` naming key and value.
mastrom_cli_test(cli.config.bad_override_value EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: config: interface\\.thickness = -0\\.001 is out of range"
                 ARGS config configs/scheme3.toml --set interface.thickness=-0.001)
mastrom_cli_test(cli.config.malformed_override EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: config: --set \"interface\\.thickness\" is malformed"
                 ARGS config configs/scheme3.toml --set interface.thickness)
mastrom_cli_test(cli.config.unknown_key EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: config: unknown key interface\\.thicknes = 0\\.001"
                 ARGS config configs/scheme3.toml --set interface.thicknes=0.001)
mastrom_cli_test(cli.config.items EXIT 0
                 STDOUT "\\[module\\.2\\].*mass = 0\\.7.*\\[module\\.4\\].*\\[interface\\.1\\]"
                 ARGS config configs/camera_mast.toml --set module.2.mass=0.7)
mastrom_cli_test(cli.config.item_out_of_range EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: config: \\[module\\.5\\] is out of range: item number 5 must satisfy 1 <= K <= 4"
                 ARGS simulate configs/camera_mast.toml --set module.5.mass=1.2 -o item_refused.h5)
mastrom_cli_test(cli.config.item_unknown_key EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: config: unknown key interface\\.2\\.mass = 1\\.2"
                 ARGS config configs/camera_mast.toml --set interface.2.mass=1.2)
mastrom_cli_test(cli.config.missing_file EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: config: cannot read no/such/config\\.toml: "
                 ARGS config no/such/config.toml)
mastrom_cli_test(cli.config.missing_argument EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: CONFIG is required" ARGS config)
mastrom_cli_test(cli.unknown_command EXIT 2 ONE_LINE
                 STDERR "^mastrom: error: unknown command 'simulat'" ARGS simulat)
mastrom_cli_test(cli.unknown_option EXIT 2 ONE_LINE STDERR "^mastrom: error: .*--bogus"
                 ARGS config configs/scheme3.toml --bogus)
