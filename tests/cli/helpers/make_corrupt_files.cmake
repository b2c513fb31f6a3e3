# Damaged copies of a good HDF5 file, for the failure-mode tests (failure_modes.cmake):
#   cmake -DSOURCE=good.h5 -DOUT=<dir>/<stem> -P make_corrupt_files.cmake
# writes <stem>_truncated.h5 (the first 3000 bytes: the superblock survives, the rest is cut off),
# <stem>_metadata.h5 (256 zero bytes over the root object header at offset 100),
# <stem>_data.h5 (256 zero bytes at offset 3000, inside the data) and <stem>_random.h5 (4 KiB of
# random text, no HDF5 signature). Uses head and dd (coreutils).
if(NOT EXISTS "${SOURCE}")
  message(FATAL_ERROR "missing ${SOURCE}")
endif()
execute_process(COMMAND head -c 3000 ${SOURCE} OUTPUT_FILE ${OUT}_truncated.h5 RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "head failed")
endif()
foreach(case metadata:100 data:3000)
  string(REPLACE ":" ";" parts ${case})
  list(GET parts 0 name)
  list(GET parts 1 offset)
  file(COPY_FILE ${SOURCE} ${OUT}_${name}.h5)
  execute_process(COMMAND dd if=/dev/zero of=${OUT}_${name}.h5 bs=1 seek=${offset} count=256
                          conv=notrunc RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "dd failed")
  endif()
endforeach()
string(RANDOM LENGTH 4096 RANDOM_SEED 7 noise)
file(WRITE ${OUT}_random.h5 "${noise}")
