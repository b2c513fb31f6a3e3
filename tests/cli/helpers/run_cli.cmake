# Run one command and check its exit code and output; a CLI test driver for ctest (cmake -P).
#
#   cmake -DEXPECT_EXIT=<code|nonzero> [-DSTDOUT_REGEX=…] [-DSTDERR_REGEX=…] [-DONE_LINE_STDERR=ON]
#         [-DROUNDTRIP_FILE=path] -P run_cli.cmake -- <command> <args>…
#
# ONE_LINE_STDERR: stderr must be exactly one line (the `mastrom: error: …` contract).
# ONE_ERROR_LINE: exactly one line of stderr starts with `mastrom: error:` (under mpirun, which adds
#   its own notice after a failed rank).
# ABSENT: this file (and any temporary <file>.tmp.*) must not exist afterwards — a failed run leaves
#   no result file. Removed before the command runs.
# ROUNDTRIP_FILE: stdout (a resolved config) is written there, `<command> config <file>` is run, and
# the two TOML texts must be identical apart from the leading comment lines.
set(cmd)
set(after_dashes OFF)
math(EXPR last "${CMAKE_ARGC} - 1")
foreach(i RANGE 1 ${last})
  if(after_dashes)
    string(REPLACE ";" "\\;" arg "${CMAKE_ARGV${i}}")  # keep an argument with ';' in one piece
    list(APPEND cmd "${arg}")
  elseif("${CMAKE_ARGV${i}}" STREQUAL "--")
    set(after_dashes ON)
  endif()
endforeach()
list(LENGTH cmd ncmd)
if(ncmd EQUAL 0)
  message(FATAL_ERROR "run_cli.cmake: no command after --")
endif()

if(DEFINED ABSENT)
  file(GLOB stale "${ABSENT}" "${ABSENT}.tmp.*")
  if(stale)
    file(REMOVE ${stale})
  endif()
endif()
execute_process(COMMAND ${cmd} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "exit code: ${rc}\n--- stdout ---\n${out}--- stderr ---\n${err}")

if(EXPECT_EXIT STREQUAL "nonzero")
  if(rc EQUAL 0)
    message(FATAL_ERROR "expected a non-zero exit code, got 0")
  endif()
elseif(NOT "${rc}" STREQUAL "${EXPECT_EXIT}")
  message(FATAL_ERROR "expected exit code ${EXPECT_EXIT}, got ${rc}")
endif()
if(DEFINED STDOUT_REGEX AND NOT out MATCHES "${STDOUT_REGEX}")
  message(FATAL_ERROR "stdout does not match: ${STDOUT_REGEX}")
endif()
if(DEFINED STDERR_REGEX AND NOT err MATCHES "${STDERR_REGEX}")
  message(FATAL_ERROR "stderr does not match: ${STDERR_REGEX}")
endif()
if(ONE_LINE_STDERR AND NOT err MATCHES "^[^\n]+\n$")
  message(FATAL_ERROR "stderr is not exactly one line")
endif()
if(ONE_ERROR_LINE)
  string(REGEX MATCHALL "(^|\n)mastrom: error:" error_lines "${err}")
  list(LENGTH error_lines n_error_lines)
  if(NOT n_error_lines EQUAL 1)
    message(FATAL_ERROR "expected one 'mastrom: error:' line, got ${n_error_lines}")
  endif()
endif()
if(DEFINED ABSENT)
  file(GLOB leftovers "${ABSENT}" "${ABSENT}.tmp.*")
  if(leftovers)
    message(FATAL_ERROR "unexpected file(s) after a failed run: ${leftovers}")
  endif()
endif()

if(DEFINED ROUNDTRIP_FILE)
  file(WRITE "${ROUNDTRIP_FILE}" "${out}")
  list(GET cmd 0 exe)
  execute_process(COMMAND "${exe}" config "${ROUNDTRIP_FILE}" RESULT_VARIABLE rc2
                  OUTPUT_VARIABLE out2 ERROR_VARIABLE err2)
  if(NOT rc2 EQUAL 0)
    message(FATAL_ERROR "re-reading the resolved config failed (${rc2}): ${err2}")
  endif()
  # Drop the leading comment lines (they name the source file and the overrides).
  string(REGEX REPLACE "^(#[^\n]*\n)+" "" body "${out}")
  string(REGEX REPLACE "^(#[^\n]*\n)+" "" body2 "${out2}")
  if(NOT body STREQUAL body2)
    message(FATAL_ERROR "round trip changed the configuration:\n${body2}")
  endif()
endif()
