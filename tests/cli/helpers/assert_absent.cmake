# cmake -DF=<path> -P assert_absent.cmake: fail when <path> or any <path>.tmp.* exists (a failed run
# must leave no result file, not even a partial one).
file(GLOB leftovers "${F}" "${F}.tmp.*")
if(leftovers)
  message(FATAL_ERROR "unexpected file(s) after a failed run: ${leftovers}")
endif()
