# cmake -DH5DIFF=<h5diff> -DFIRST=a.h5 -DSECOND=b.h5 -DDATASETS=/x,/y -P same_datasets.cmake
# Fails unless every listed dataset has equal values in both files (h5diff without a tolerance
# reports any difference; it exits 1 for a difference and 2 for a missing object or file).
foreach(f FIRST SECOND)
  if(NOT EXISTS "${${f}}")
    message(FATAL_ERROR "missing file ${${f}}")
  endif()
endforeach()
string(REPLACE "," ";" datasets "${DATASETS}")
set(failed)
foreach(d ${datasets})
  execute_process(COMMAND ${H5DIFF} ${FIRST} ${SECOND} ${d} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  message(STATUS "h5diff ${d}: exit ${rc}")
  if(NOT rc EQUAL 0)
    list(APPEND failed "${d} (h5diff exit ${rc}: ${out}${err})")
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "datasets differ between ${FIRST} and ${SECOND}: ${failed}")
endif()
