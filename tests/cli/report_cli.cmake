# ctest entries for `mastrom report` (report/mastrom_report.py, cli/cmd_report.cpp; included by
# tests/CMakeLists.txt). The Python suite tests/report/test_report.py runs under Debian's
# /usr/bin/python3 (the only interpreter that sees python3-h5py and python3-matplotlib):
#   report.synthetic.1, .2  (halves of one class) deployment (full-order + rom), modes, screen and validation files written by
#                     the test -> figures (PNG signature, > 1 kB, SVG twin) and index.html whose numbers
#                     equal the HDF5 values to the printed precision; reproducible bytes
#   report.real_run   a short Scheme 1 `mastrom simulate` (0.05 s), then `mastrom report`: same checks
#   report.errors     missing, non-HDF5, foreign, broken files, missing Python module: exit != 0 and
#                     one line on stderr
set(mastrom_python /usr/bin/python3)
set(mastrom_report_tests ${PROJECT_SOURCE_DIR}/tests/report/test_report.py)
if(EXISTS ${mastrom_python})
  # SyntheticTests, the longest class (≈ 100 s loaded, two tests most of it), runs as two
  # interleaved halves (test_report.py --shard K/N) that ctest can run side by side.
  foreach(suite synthetic.1:SyntheticTests:0/2 synthetic.2:SyntheticTests:1/2
                real_run:RealRunTests errors:ErrorTests modal_run:ModalRunTests study:StudyTests)
    string(REPLACE ":" ";" parts ${suite})
    list(GET parts 0 name)
    list(GET parts 1 test_class)
    set(shard)
    list(LENGTH parts count)
    if(count GREATER 2)
      list(GET parts 2 part)
      set(shard --shard ${part})
    endif()
    add_test(NAME report.${name}
             COMMAND ${mastrom_python} ${mastrom_report_tests} -v ${test_class} ${shard}
             WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
    set_tests_properties(report.${name} PROPERTIES
                         ENVIRONMENT
                         "MASTROM_EXE=$<TARGET_FILE:mastrom>;MASTROM_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
                         TIMEOUT 300 LABELS "report")
  endforeach()
else()
  message(STATUS "mastrom: ${mastrom_python} not found, report.* tests not registered "
                 "(install python3-h5py and python3-matplotlib)")
endif()

# The CLI contract through the shared driver of config_cli.cmake (included before this file).
if(COMMAND mastrom_cli_test)
  mastrom_cli_test(report.cli.help EXIT 0 STDOUT "Usage: mastrom report .*--out" ARGS report --help)
  mastrom_cli_test(report.cli.no_file EXIT 2 ONE_LINE STDERR "^mastrom: error: FILE is required"
                   ARGS report)
  mastrom_cli_test(report.cli.missing_file EXIT 2 ONE_LINE
                   STDERR "^mastrom: error: report: cannot read 'no/such/result\\.h5': no such file"
                   ARGS report no/such/result.h5)
  mastrom_cli_test(report.cli.not_hdf5 EXIT 2 ONE_LINE
                   STDERR "^mastrom: error: report: 'configs/scheme1\\.toml' is not an HDF5 file"
                   ARGS report configs/scheme1.toml)
endif()
