# An output file carries the root attribute wall_time_s (docs/user_guide.md §5), positive and at
# least every per-item wall time the file records (the run contains each of them).
#   cmake -DH5DUMP=h5dump -DFILE=f.h5 [-DAT_LEAST=/dataset1,/dataset2] -P check_wall_time.cmake
# h5dump prints the values; if(LESS) compares them as floating-point numbers.
function(h5_values path what out)
  execute_process(COMMAND ${H5DUMP} ${what} ${path} ${FILE} RESULT_VARIABLE rc
                  OUTPUT_VARIABLE text ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${FILE}: no ${path} (${err})")
  endif()
  # The values follow the first "DATA {" (a dataset's attributes come after it), as
  # "(i): v, v, ..." lines up to the closing brace.
  string(FIND "${text}" "DATA {" at)
  if(at LESS 0)
    message(FATAL_ERROR "${FILE}: no values in h5dump's output for ${path}")
  endif()
  string(SUBSTRING "${text}" ${at} -1 text)
  string(REGEX REPLACE "^DATA {([^}]*)}.*" "\\1" text "${text}")
  string(REGEX REPLACE "\\([0-9,]+\\):" "" text "${text}")
  string(REGEX MATCHALL "[-+0-9.eE]+" values "${text}")
  set(${out} ${values} PARENT_SCOPE)
endfunction()

h5_values(/wall_time_s -a wall)
list(LENGTH wall n)
if(NOT n EQUAL 1 OR NOT wall GREATER 0)
  message(FATAL_ERROR "${FILE}: wall_time_s = '${wall}', expected one positive number")
endif()
message(STATUS "wall_time_s = ${wall}")
string(REPLACE "," ";" datasets "${AT_LEAST}")
foreach(d ${datasets})
  h5_values(${d} -d values)
  foreach(v ${values})
    if(wall LESS v)
      message(FATAL_ERROR "${FILE}: wall_time_s = ${wall} < ${v}, a part of the run (${d})")
    endif()
  endforeach()
endforeach()
