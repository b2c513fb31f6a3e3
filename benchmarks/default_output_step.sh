#!/usr/bin/env bash
# Cost of the default output step (docs/theory.md §5.4a): the real default runs of Scheme 1 and
# Scheme 3 (8 s, default tolerance and threads) with output.step unset — chosen from the modes at
# the start, here capped by the 256 MB bound — against the same runs with output.step = 1e-4, the
# fixed default of earlier versions. Same binary, runs alternated, so the ratios share the load.
# Prints per scheme: the chosen step line, wall time and file size of each and their ratios, and
# the load (uptime) before and after.
#
#   benchmarks/default_output_step.sh [BUILD_DIR]     (default BUILD_DIR = build)
#
# Knobs: STEP_SCHEMES ("scheme1 scheme3"), STEP_REPEATS (1).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$(cd "${1:-$root/build}" && pwd)"
mastrom="$build/cli/mastrom"
[[ -x "$mastrom" ]] || { echo "default_output_step.sh: missing $mastrom (build it first)" >&2; exit 1; }
schemes=(${STEP_SCHEMES:-scheme1 scheme3})
repeats=${STEP_REPEATS:-1}
work="$(mktemp -d "${TMPDIR:-/tmp}/mastrom_output_step.XXXXXX")"
trap 'rm -rf "$work"' EXIT
cd "$root"

# run NAME [extra args]: the whole process's wall seconds (the modal solve of the choice included)
# and the file's bytes
run() {
  local name=$1; shift
  /usr/bin/time -f %e -o "$work/$name.wall" "$mastrom" simulate "$@" -q -o "$work/$name.h5" \
    > "$work/$name.out"
  echo "$(cat "$work/$name.wall") $(stat -c %s "$work/$name.h5")"
}

echo "load before: $(uptime)"
for s in "${schemes[@]}"; do
  for ((r = 1; r <= repeats; ++r)); do
    read -r w_old b_old < <(run "${s}_fixed" "configs/$s.toml" --set output.step=1e-4)
    read -r w_new b_new < <(run "${s}_default" "configs/$s.toml")
    echo "$s: $(sed -n 's/^  \(output step .*\)/\1/p' "$work/${s}_default.out")"
    awk -v s="$s" -v wo="$w_old" -v wn="$w_new" -v bo="$b_old" -v bn="$b_new" 'BEGIN {
      printf "%s: wall %.2f s (output.step = 1e-4) -> %.2f s (default): %.2f x; file %.1f MB -> %.1f MB: %.2f x\n",
             s, wo, wn, wn / wo, bo / 1e6, bn / 1e6, bn / bo }'
  done
done
echo "load after: $(uptime)"
