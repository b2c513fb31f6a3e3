#!/usr/bin/env bash
# The one build behind both hardening jobs (scripts/run_sanitizers.sh and
# scripts/run_fuzzers.sh): clang with AddressSanitizer + UndefinedBehaviorSanitizer on every target,
# the unit tests and the libFuzzer targets (cmake/Sanitizers.cmake, fuzz/CMakeLists.txt), in
# build-hardening/. Builds only the targets named, so whichever job runs second compiles only its
# own executables: the libraries (over half of the compile time) are shared.
#
#   bash scripts/hardening_build.sh test_common test_rom     # after scripts/setup.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=build-hardening
jobs=${MASTROM_JOBS:-2}
(($# > 0)) || { echo "hardening_build: name the targets to build" >&2; exit 2; }
if ! command -v clang++ > /dev/null; then
  echo "hardening_build: clang++ not found (scripts/setup.sh installs it)" >&2
  exit 1
fi

# -O1 with line tables, no -DNDEBUG: the usual sanitizer/libFuzzer trade-off between speed and stack
# traces with line numbers, and Eigen's index and size assertions stay live. Full -g would only add
# compile and link time. One ctest entry per test binary (tests/CMakeLists.txt says why). No -Werror
# here (that stays with the main build, CI=true in setup.sh).
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
  -DMASTROM_SANITIZE=ON -DMASTROM_FUZZ=ON -DMASTROM_BUILD_TESTS=ON -DMASTROM_BUILD_BENCHMARKS=OFF \
  -DMASTROM_TEST_WHOLE_BINARIES=ON \
  -DMASTROM_WERROR=OFF > /dev/null
cmake --build "$build" -j"$jobs" --target "$@"
