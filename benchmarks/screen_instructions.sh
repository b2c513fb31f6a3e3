#!/usr/bin/env bash
# Instructions per design of a ROM screen, with and without the interface stresses (callgrind,
# 1 rank): the figure that compares across sessions when the machine is shared and wall times are
# not (numbers in benchmarks/README.md "ROM speed with stresses, third pass").
#   SCREEN_DB (required): a five-parameter Scheme 3 database with stress modes, e.g. the one
#   benchmarks/screen_stress_cost.sh builds; SCREEN_DESIGNS_PER_AXIS (3): 3^5 = 243 designs
#   inside the database's box (each axis from 7 % to 93 % of its range). Not its corners: there
#   the rbf interpolation of the stress rows combines few samples (1.2 M instructions a design
#   against 23 M inside, benchmarks/README.md "ROM speed, fifth pass"), so a corner grid
#   understated the stresses' cost by 4 x.
# Prints the inclusive instructions of screenDesignRange (the per-design loop: interpolation,
# metrics' pass, stress peaks, mass and frequencies) per design for both screens, their ratio
# (target of the stresses: <= 1.5), and the stress peaks' own share (StressBlockRecord::peaks).
# Usage: SCREEN_DB=db.h5 benchmarks/screen_instructions.sh [BUILD_DIR]   (~3 min)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$(cd "${1:-$root/build}" && pwd)"
mastrom="$build/cli/mastrom"
[[ -x "$mastrom" ]] || { echo "screen_instructions.sh: missing $mastrom" >&2; exit 1; }
[[ -n "${SCREEN_DB:-}" && -f "$SCREEN_DB" ]] ||
  { echo "screen_instructions.sh: set SCREEN_DB to a five-parameter database" >&2; exit 1; }
command -v valgrind >/dev/null || { echo "screen_instructions.sh: needs valgrind" >&2; exit 1; }
per_axis="${SCREEN_DESIGNS_PER_AXIS:-3}"
designs=$(( per_axis ** 5 ))
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
work="$(mktemp -d "${TMPDIR:-/tmp}/mastrom_screen_ir.XXXXXX")"
trap 'rm -rf "$work"' EXIT
grid=(--grid "interface.thickness=0.0006:0.0019:$per_axis"
      --grid "interface.inner_diameter=0.082:0.098:$per_axis"
      --grid "interface.length=0.042:0.058:$per_axis" --grid "module.mass=0.35:0.65:$per_axis"
      --grid "material.youngs_modulus=62e9:78e9:$per_axis"
      --set material.yield_strength=250e6 -q)
inclusive() {  # inclusive Ir of the first function matching $2 in callgrind file $1
  # (awk reads to the end: grep -m1 closed the pipe, and pipefail ended the script with SIGPIPE)
  callgrind_annotate --inclusive=yes "$1" 2>/dev/null |
    awk -v pattern="$2" '!found && index($0, pattern) { gsub(",", "", $1); print $1; found = 1 }'
}
for kind in plain stress; do
  extra=()
  [[ $kind == plain ]] && extra=(--no-stresses)
  valgrind --tool=callgrind --callgrind-out-file="$work/$kind.cg" "$mastrom" screen "$SCREEN_DB" \
    "${grid[@]}" "${extra[@]}" -o "$work/$kind.csv" >"$work/$kind.log" 2>&1 ||
    { cat "$work/$kind.log"; exit 1; }
done
plain=$(inclusive "$work/plain.cg" "rom::screenDesignRange")
stress=$(inclusive "$work/stress.cg" "rom::screenDesignRange")
peaks=$(inclusive "$work/stress.cg" "rom::StressBlockRecord::peaks")
awk -v n="$designs" -v p="$plain" -v s="$stress" -v k="$peaks" 'BEGIN {
  printf "screen of %d designs, 1 rank, callgrind (instructions per design):\n", n;
  printf "  without stresses %.2f M\n", p / n / 1e6;
  printf "  with stresses    %.2f M   (stress peaks %.2f M)\n", s / n / 1e6, k / n / 1e6;
  printf "  ratio with / without: %.2f   target <= 1.5\n", s / p }'
