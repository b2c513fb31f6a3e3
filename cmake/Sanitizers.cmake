# Hardening builds: sanitizers for the unit tests, libFuzzer targets for the parsers.
#
# MASTROM_SANITIZE=ON: AddressSanitizer + UndefinedBehaviorSanitizer on every target of this project
# (libraries, tests, the executable; prebuilt system libraries stay uninstrumented). UB aborts the
# process (-fno-sanitize-recover) so that ctest sees a failure instead of a log line.
# scripts/run_sanitizers.sh builds the unit tests this way and runs them (ctest -L unit).
option(MASTROM_SANITIZE "Build with -fsanitize=address,undefined (CI variant)" OFF)
# MASTROM_FUZZ=ON: the libFuzzer targets in fuzz/ as well (needs clang). One clang build with both
# options serves scripts/run_sanitizers.sh and scripts/run_fuzzers.sh (build-hardening/,
# scripts/hardening_build.sh): the libraries are compiled once for both jobs.
option(MASTROM_FUZZ "Build the libFuzzer targets in fuzz/ (clang only)" OFF)

if(MASTROM_SANITIZE OR MASTROM_FUZZ)
  set(mastrom_sanitizer_flags -fsanitize=address,undefined -fno-omit-frame-pointer
                              -fno-sanitize-recover=undefined)
  add_compile_options(${mastrom_sanitizer_flags})
  add_link_options(${mastrom_sanitizer_flags})
endif()

if(MASTROM_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "MASTROM_FUZZ=ON needs clang (libFuzzer): configure with "
                        "-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang")
  endif()
  # Coverage instrumentation (-fsanitize=fuzzer-no-link) goes only on the libraries the fuzz
  # targets test and on the targets themselves (fuzz/CMakeLists.txt), not on every target: in the
  # shared build the unit tests run the full-order and modal solvers, where a callback on every
  # integer comparison (trace-cmp) would only slow the sanitizer job down.
  # Debian's toml++ is a prebuilt shared library, invisible to the fuzzer's coverage feedback and to
  # ASan. Compile it header-only into our code instead; the package's config file keeps a target that
  # exists already, so this must come before find_package(tomlplusplus) (Dependencies.cmake).
  add_library(tomlplusplus::tomlplusplus INTERFACE IMPORTED)
  target_compile_definitions(tomlplusplus::tomlplusplus INTERFACE TOML_HEADER_ONLY=1)
  # toml++'s internal assertions as in the shipped (NDEBUG) library; see the header for why.
  target_compile_options(tomlplusplus::tomlplusplus INTERFACE
                         "SHELL:-include ${PROJECT_SOURCE_DIR}/fuzz/toml_release_asserts.hpp")
endif()
