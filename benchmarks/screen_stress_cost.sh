#!/usr/bin/env bash
# What the interface stresses cost a screen and a `rom eval` (docs/theory.md §6.5; numbers in
# benchmarks/README.md "Stresses at the cost of vibration"):
#   1. a five-parameter adaptive Scheme 3 database with stress modes (thickness, inner diameter,
#      interface length, module mass, Young's modulus; rbf; 2 MPI ranks), built here;
#   2. `mastrom screen` of SCREEN_DESIGNS_PER_AXIS^5 designs (10^5 by default) on 2 ranks, with
#      and without the stress columns: wall times, designs/s and their ratio (targets: <= 60 s,
#      ratio <= 1.5), and the vibration columns of both tables compared (they must be identical);
#   3. `rom eval` of the main job's case (Scheme 3 between the samples of its 3 x 3 database, the
#      default output step: 25 us = 320 001 samples) with --stress-history: the split of its cost (interpolation, the
#      series, the metrics' pass, the stress peaks, the stress history; the history is to cost no
#      more than the series).
# Usage: benchmarks/screen_stress_cost.sh [BUILD_DIR]   (default build; ~3 min on an idle machine)
# Knobs: SCREEN_DESIGNS_PER_AXIS (10), SCREEN_DB (an existing database for part 2: skips 1),
# SCREEN_DB_SAMPLES (100).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$(cd "${1:-$root/build}" && pwd)"
mastrom="$build/cli/mastrom"
[[ -x "$mastrom" ]] || { echo "screen_stress_cost.sh: missing $mastrom" >&2; exit 1; }
per_axis="${SCREEN_DESIGNS_PER_AXIS:-10}"
samples="${SCREEN_DB_SAMPLES:-100}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
work="$(mktemp -d "${TMPDIR:-/tmp}/mastrom_stress_cost.XXXXXX")"
trap 'rm -rf "$work"' EXIT
cd "$root"
config=configs/scheme3.toml
echo "load before: $(uptime | sed 's/.*load average/load average/')"

db="${SCREEN_DB:-$work/five_db.h5}"
if [[ -z "${SCREEN_DB:-}" ]]; then
  start=$(date +%s.%N)
  mpirun -n 2 "$mastrom" rom build "$config" --set modes.count=20 \
    --param interface.thickness=0.0005:0.002 --param interface.inner_diameter=0.08:0.1 \
    --param interface.length=0.04:0.06 --param module.mass=0.3:0.7 \
    --param material.youngs_modulus=60e9:80e9 --adaptive --tolerance 0.03 \
    --max-samples "$samples" -q -o "$db" >"$work/db.log" 2>&1 || { cat "$work/db.log"; exit 1; }
  awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN { printf "1. database: %.1f s wall (2 ranks)\n", e - s }'
  grep -E "samples" "$work/db.log" | tail -n 1 | sed 's/^/   /'
fi

grid=(--grid "interface.thickness=0.0005:0.002:$per_axis"
      --grid "interface.inner_diameter=0.08:0.1:$per_axis"
      --grid "interface.length=0.04:0.06:$per_axis" --grid "module.mass=0.3:0.7:$per_axis"
      --grid "material.youngs_modulus=60e9:80e9:$per_axis"
      --set material.yield_strength=250e6 -q)
run_screen() {  # run_screen NAME [ARGS...]: wall seconds of a 2-rank screen into $work/NAME.time
  local name="$1"
  shift
  local start end
  start=$(date +%s.%N)
  mpirun -n 2 "$mastrom" screen "$db" "${grid[@]}" "$@" -o "$work/$name.csv" >"$work/$name.log" 2>&1 ||
    { cat "$work/$name.log"; exit 1; }
  end=$(date +%s.%N)
  awk -v s="$start" -v e="$end" 'BEGIN { printf "%.3f", e - s }' >"$work/$name.time"
}
run_screen plain --no-stresses
run_screen stress
designs=$(( per_axis ** 5 ))
plain=$(cat "$work/plain.time")
stress=$(cat "$work/stress.time")
awk -v n="$designs" -v p="$plain" -v s="$stress" 'BEGIN {
  printf "2. screen of %d designs, 2 ranks (whole processes, wall):\n", n;
  printf "   without stresses %.1f s (%.0f designs/s)\n", p, n / p;
  printf "   with stresses    %.1f s (%.0f designs/s)   target <= 60 s\n", s, n / s;
  printf "   ratio with / without: %.2f   target <= 1.5\n", s / p }'
# The vibration columns must not depend on whether the stresses were computed. The stress table
# has its stress columns before the mass and frequencies, so the plain table's columns are picked
# from it by name.
plain_columns() {  # the columns of $work/plain.csv, by name, from the CSV file $1
  awk -F, -v cols="$(head -n 1 "$work/plain.csv")" 'BEGIN { n = split(cols, want, ",") }
    NR == 1 { for (i = 1; i <= NF; ++i) at[$i] = i }
    { line = $(at[want[1]]); for (j = 2; j <= n; ++j) line = line "," $(at[want[j]]); print line }' "$1"
}
if cmp -s "$work/plain.csv" <(plain_columns "$work/stress.csv"); then
  echo "   the vibration columns of both tables are identical"
else
  echo "   WARNING: the vibration columns differ between the two tables"
fi

# 3. The main job's ROM evaluation (scripts/run_main_job.sh steps 3-4) with its cost split.
mpirun -n 2 "$mastrom" rom build "$config" --set modes.count=20 \
  --param interface.thickness=0.0016:0.0026:3 --param interface.length=0.042:0.062:3 -q \
  -o "$work/main_db.h5" >"$work/main_db.log" 2>&1 || { cat "$work/main_db.log"; exit 1; }
"$mastrom" rom eval "$work/main_db.h5" --set interface.thickness=0.002 --set interface.length=0.05 \
  --stress-history -o "$work/eval.h5" >"$work/eval.log" 2>&1 || { cat "$work/eval.log"; exit 1; }
echo "3. rom eval of the main job's case (default output step, 1 thread), with --stress-history:"
grep -E "^  interpolation " "$work/eval.log" | sed 's/^ */   /'
# The outputs are stepped while they are written into the file: their times are on the 'wrote' line.
grep -E "^wrote " "$work/eval.log" | sed 's/^ */   /'
sed -n 's/^wrote .* (output series stepped and written in \([0-9.]*\) us, stress history \([0-9.]*\) us).*/\1 \2/p' "$work/eval.log" |
  awk '{ printf "   stress history / series: %.2f   target <= 1\n", $2 / $1 }'
echo "load after: $(uptime | sed 's/.*load average/load average/')"
