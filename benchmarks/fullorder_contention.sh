#!/usr/bin/env bash
# Two full-order runs sharing the two cores: each asks for two threads, as on a workstation where
# another job (or another rank of validate / study) runs beside it. How much slower is each than
# alone? The target is ≤ 2.2 × (two runs on two cores cannot both keep their alone time; 2 × is
# the fair share). Also times the same run on one thread alone, and prints how many steps each run
# put on one thread (fullorder/thread_tuner.hpp).
#
#   benchmarks/fullorder_contention.sh [BUILD_DIR]        (default BUILD_DIR = build)
#
# Knobs (environment): CONTENTION_CONFIG (configs/scheme3.toml), CONTENTION_END_S (simulated
# seconds, 0.4), CONTENTION_RUNS (repetitions of each measurement, 3; medians are printed).
# Meaningful only on an otherwise idle machine: "alone" must be alone.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$(cd "${1:-$root/build}" && pwd)"
config="${CONTENTION_CONFIG:-$root/configs/scheme3.toml}"
end_s="${CONTENTION_END_S:-0.4}"
runs="${CONTENTION_RUNS:-3}"
mastrom="$build/cli/mastrom"
[[ -x "$mastrom" ]] || { echo "fullorder_contention.sh: missing $mastrom (build it first)" >&2; exit 1; }
work="$(mktemp -d "${TMPDIR:-/tmp}/mastrom_contention.XXXXXX")"
trap 'rm -rf "$work"' EXIT

# simulate NAME THREADS: one run; its wall seconds in NAME.time, its report in NAME.log.
simulate() {
  /usr/bin/time -f '%e' -o "$work/$1.time" \
    "$mastrom" simulate "$config" --set simulation.end_time="$end_s" --threads "$2" -q \
    -o "$work/$1.h5" >"$work/$1.log" 2>&1
}
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
one_thread_steps() {
  grep -o '^ *[0-9]* of [0-9]* steps' "$work/$1.log" | awk '{ print $1 "/" $3 }' || echo "0"
}

alone2=() alone1=() pair=() pair_one=()
for ((k = 1; k <= runs; ++k)); do
  simulate "alone2_$k" 2
  alone2+=("$(cat "$work/alone2_$k.time")")
  simulate "alone1_$k" 1
  alone1+=("$(cat "$work/alone1_$k.time")")
  simulate "a_$k" 2 & pid_a=$!
  simulate "b_$k" 2 & pid_b=$!
  wait "$pid_a" "$pid_b"
  ta=$(cat "$work/a_$k.time") tb=$(cat "$work/b_$k.time")
  pair+=("$(awk -v a="$ta" -v b="$tb" 'BEGIN { print (a > b ? a : b) }')")
  pair_one+=("$(one_thread_steps "a_$k") $(one_thread_steps "b_$k")")
  cmp -s <(h5dump -d /end/relative_angular_acceleration "$work/a_$k.h5" | tail -n +3) \
         <(h5dump -d /end/relative_angular_acceleration "$work/alone1_$k.h5" | tail -n +3) ||
    { echo "fullorder_contention.sh: a shared run's result differs from the one-thread run" >&2; exit 1; }
done

m2=$(printf '%s\n' "${alone2[@]}" | median)
m1=$(printf '%s\n' "${alone1[@]}" | median)
mp=$(printf '%s\n' "${pair[@]}" | median)
printf 'full order, %s, %s s simulated, %s repetitions (medians of wall seconds)\n' \
  "$(basename "$config")" "$end_s" "$runs"
printf '  alone, 2 threads:                     %8.2f s   (runs: %s)\n' "$m2" "${alone2[*]}"
printf '  alone, 1 thread:                      %8.2f s   (runs: %s)\n' "$m1" "${alone1[*]}"
printf '  two at once, 2 threads each (slower): %8.2f s   (runs: %s)\n' "$mp" "${pair[*]}"
printf '  steps on one thread in the shared runs (a b, per repetition): %s\n' "${pair_one[*]}"
awk -v p="$mp" -v a="$m2" 'BEGIN { r = p / a;
  printf "  shared / alone (2 threads): %.2f x   target <= 2.2 x: %s\n", r, (r <= 2.2 ? "met" : "NOT met") }'
echo "  results of every shared run equal the one-thread run's bit for bit"
