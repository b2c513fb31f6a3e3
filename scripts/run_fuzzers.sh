#!/usr/bin/env bash
# Build the libFuzzer targets (fuzz/) into build-hardening/ (clang, ASan + UBSan; the build
# scripts/run_sanitizers.sh shares, scripts/hardening_build.sh) and run each one for a bounded time.
# Exit ≠ 0 when a target finds a crash, a sanitizer report, a leak or a time-out; the input is then
# in build-hardening/artifacts/ (reproduce: build-hardening/fuzz/<target> <file>), and it belongs
# as a regression test in tests/common or tests/rom.
#
#   bash scripts/run_fuzzers.sh                          # 60 s per target
#   MASTROM_FUZZ_SECONDS=600 bash scripts/run_fuzzers.sh # a longer local run
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root=$(pwd)
build=build-hardening
seconds=${MASTROM_FUZZ_SECONDS:-60}

start=$(date +%s)
bash scripts/hardening_build.sh fuzz_config fuzz_rom_database fuzz_rom_database_content \
  make_seed_database
built=$(date +%s)

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
# Leaks inside Open MPI and HDF5's error paths are not ours: .ci/lsan.supp names each and why. The
# suppressions match library and function names deep in the allocation stack, which Debian's
# libraries (no frame pointers) only give to the slow unwinder (fast_unwind_on_malloc=0); Open MPI's
# plugins stay mapped so that their frames have names.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:fast_unwind_on_malloc=0"
export LSAN_OPTIONS="suppressions=$root/.ci/lsan.supp:print_suppressions=0"
export OMPI_MCA_mca_base_component_disable_dlclose=1
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Symbol names in the reports: Debian's clang puts llvm-symbolizer on PATH only through the optional
# "llvm" package.
if ! command -v llvm-symbolizer > /dev/null && [[ -x /usr/lib/llvm-14/bin/llvm-symbolizer ]]; then
  export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer
fi

# The database target starts from a valid file (too big to commit usefully, see the generator).
mkdir -p "$build/seeds/rom_database" "$build/artifacts"
"$build/fuzz/make_seed_database" "$build/seeds/rom_database/seed_2x2.h5"

status=0
run() {  # run <target> <extra libFuzzer flags…> -- <seed dirs…>
  local target=$1; shift
  local flags=()
  while [[ $1 != -- ]]; do flags+=("$1"); shift; done
  shift
  local corpus="$build/corpus/$target"  # grows between local runs; fresh in CI
  mkdir -p "$corpus"
  printf '\n==== %s: %d s\n' "$target" "$seconds"
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: an input that makes the reader
  # allocate gigabytes is a finding as well (libFuzzer reports it as an out-of-memory crash).
  if ! "$build/fuzz/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix="$build/artifacts/$target-" "${flags[@]}" \
      "$corpus" "$@"; then
    echo "run_fuzzers: $target FAILED; inputs: $(ls "$build/artifacts" | grep "^$target-" | tr '\n' ' ')" >&2
    status=1
  fi
}
run fuzz_config -dict=fuzz/config.dict -- fuzz/corpus/config
run fuzz_rom_database -- "$build/seeds/rom_database" fuzz/corpus/rom_database
run fuzz_rom_database_content -- fuzz/corpus/rom_database_content
done_at=$(date +%s)
printf 'fuzzers: build %d s, fuzzing %d s, total %d s (exit %d)\n' "$((built - start))" \
  "$((done_at - built))" "$((done_at - start))" "$status"
exit "$status"
