#!/usr/bin/env bash
# The sanitizer job: the unit tests (the GoogleTest binaries test_common, test_statistics,
# test_fullorder, test_modes, test_rom, each one ctest entry running the whole binary, or two
# entries by GoogleTest's sharding for the two longest, less the tests tests/CMakeLists.txt names
# as physics at full size) built with AddressSanitizer + UndefinedBehaviorSanitizer
# by clang into build-hardening/ (scripts/hardening_build.sh, shared with scripts/run_fuzzers.sh).
# Any ASan/UBSan report or leak in our code fails the run (exit ≠ 0). The CLI tests (tests/cli) stay
# with the main suite: they drive the same library code through the executable and would add ≈ 30 %
# to the run time under ASan.
#
#   bash scripts/run_sanitizers.sh          # after scripts/setup.sh (packages installed)
#   MASTROM_JOBS=1 bash scripts/run_sanitizers.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root=$(pwd)
build=build-hardening
jobs=${MASTROM_JOBS:-2}

# clang, not GCC: GCC compiles this code ≈ 2× slower (CPU, rom/offline/database_build.cpp: 52 s vs 27 s),
# which outweighs clang's slower sanitized tests (≈ 1.4–1.7× CPU per test), and the fuzzers reuse
# clang's libraries. Measured 2026-11-22 in fresh clones: GCC job ≈ 2 170 CPU-s plus ≈ 375 for a
# separate clang build of the fuzzers; this job ≈ 1 760 CPU-s, after which the fuzzers build in 20 s.
start=$(date +%s)
binaries=(test_common test_statistics test_fullorder test_modes test_rom)
bash scripts/hardening_build.sh "${binaries[@]}"
built=$(date +%s)

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
# Leaks inside Open MPI / HDF5 are not ours: .ci/lsan.supp names each library and why. Its entries
# match names deep in the allocation stack, which Debian's libraries (built without frame pointers)
# only give to the slow unwinder: fast_unwind_on_malloc=0 (≈ 1.7× the wall time of test_common;
# the binaries that never start MPI switch it back, tests/CMakeLists.txt), and
# Open MPI's plugins stay mapped at exit so that their frames have names.
# abort_on_error: a report ends the process with a signal that ctest counts as a failure even when
# the test body itself already passed.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:fast_unwind_on_malloc=0:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export LSAN_OPTIONS="suppressions=$root/.ci/lsan.supp:print_suppressions=0"
export OMPI_MCA_mca_base_component_disable_dlclose=1
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Symbol names in the reports: Debian's clang puts llvm-symbolizer on PATH only through the optional
# "llvm" package.
if ! command -v llvm-symbolizer > /dev/null && [[ -x /usr/lib/llvm-14/bin/llvm-symbolizer ]]; then
  export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer
fi
# -j: two binaries at a time on the 2-core machine, the longest first (ctest's own cost record
# after the first run). --no-tests=error: a pattern that matches nothing must not pass.
status=0
pattern="^($(IFS='|'; echo "${binaries[*]}"))(\\.shard[0-9]+)?\$"
ctest --test-dir "$build" -R "$pattern" -j"$jobs" --no-tests=error --output-on-failure || status=$?
done_at=$(date +%s)
printf 'sanitizers: build %d s, tests %d s, total %d s (exit %d)\n' "$((built - start))" \
  "$((done_at - built))" "$((done_at - start))" "$status"
exit "$status"
