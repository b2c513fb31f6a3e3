# Two ROM database files hold the same content: their stored content checksums
# ("fnv1a64:<16 hex digits>", rom/database/database_io.hpp) are equal. The checksum covers every dataset, so
# this compares the data without comparing HDF5's own bookkeeping (object timestamps).
#   cmake -DFIRST=a.h5 -DSECOND=b.h5 -P same_checksum.cmake
foreach(f FIRST SECOND)
  if(NOT EXISTS "${${f}}")
    message(FATAL_ERROR "missing file ${${f}}")
  endif()
  file(STRINGS "${${f}}" sum_${f} REGEX "fnv1a64:[0-9a-f][0-9a-f][0-9a-f][0-9a-f]" LIMIT_COUNT 1)
  string(REGEX MATCH "fnv1a64:[0-9a-f]+" sum_${f} "${sum_${f}}")
  if(sum_${f} STREQUAL "")
    message(FATAL_ERROR "no content checksum in ${${f}}")
  endif()
endforeach()
message(STATUS "${FIRST}: ${sum_FIRST}\n${SECOND}: ${sum_SECOND}")
if(NOT sum_FIRST STREQUAL sum_SECOND)
  message(FATAL_ERROR "the two databases differ")
endif()
