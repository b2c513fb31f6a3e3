#!/usr/bin/env bash
# The sanitizer variant of the test suite (issue #7): builds the libraries, the `mastrom`
# executable and the unit tests with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DMASTROM_SANITIZE=ON, cmake/Sanitizers.cmake) into build-asan/ (no benchmarks) and runs ctest
# there. Any ASan/UBSan report or leak in our code fails the run (exit ≠ 0).
#
#   bash scripts/run_sanitizers.sh          # after scripts/setup.sh (packages installed)
#   MASTROM_JOBS=1 bash scripts/run_sanitizers.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root=$(pwd)
build=build-asan
jobs=${MASTROM_JOBS:-2}

# -O1 -g: line numbers in the reports at a bearable speed; no -DNDEBUG, so Eigen's index and size
# assertions are live as well. -Werror stays with the main build (CI=true in setup.sh): GCC's
# sanitizer instrumentation adds false -Wmaybe-uninitialized / -Wstringop-* warnings.
start=$(date +%s)
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DMASTROM_SANITIZE=ON -DMASTROM_BUILD_TESTS=ON -DMASTROM_BUILD_BENCHMARKS=OFF -DMASTROM_WERROR=OFF
cmake --build "$build" -j"$jobs"
built=$(date +%s)

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
# Leaks inside Open MPI / HDF5 are not ours: .ci/lsan.supp names each library and why. Its entries
# match names deep in the allocation stack, which Debian's libraries (built without frame pointers)
# only give to the slow unwinder: fast_unwind_on_malloc=0 (≈ 1.7× the wall time of test_common), and
# Open MPI's plugins stay mapped at exit so that their frames have names.
# abort_on_error: a report ends the process with a signal that ctest counts as a failure even when
# the test body itself already passed.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:fast_unwind_on_malloc=0:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export LSAN_OPTIONS="suppressions=$root/.ci/lsan.supp:print_suppressions=0"
export OMPI_MCA_mca_base_component_disable_dlclose=1
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
status=0
ctest --test-dir "$build" --output-on-failure || status=$?
done_at=$(date +%s)
printf 'sanitizers: build %d s, tests %d s, total %d s (exit %d)\n' "$((built - start))" \
  "$((done_at - built))" "$((done_at - start))" "$status"
exit "$status"
