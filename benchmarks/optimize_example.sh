#!/usr/bin/env bash
# The optimisation example of README.md and docs/user_guide.md, timed (numbers in
# benchmarks/README.md "Optimisation confirmed by the full order"):
#   1. a three-parameter Scheme 3 database (interface thickness 1-2 mm, inner diameter 80-100 mm,
#      interface length 40-60 mm; 3 x 3 x 3 grid, default cubic method, stress modes), 1 rank;
#   2. `mastrom optimize`: minimise the mast's mass subject to frequency_1 >= 300 Hz, min margin of
#      safety >= 1 at a yield strength of 270 MPa (aluminium 6061-T6) and peak relative end angular
#      acceleration <= 5 rad/s^2, with the full-order check; wall time end to end (target <= 60 s)
#      and CPU time, and the full order's value of every constraint against its bound.
# Usage: benchmarks/optimize_example.sh [BUILD_DIR]   (default build; ~1 min on an idle machine)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$(cd "${1:-$root/build}" && pwd)"
mastrom="$build/cli/mastrom"
[[ -x "$mastrom" ]] || { echo "optimize_example.sh: missing $mastrom" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
work="$(mktemp -d "${TMPDIR:-/tmp}/mastrom_optimize.XXXXXX")"
trap 'rm -rf "$work"' EXIT
cd "$root"
echo "load before: $(uptime | sed 's/.*load average/load average/')"

/usr/bin/time -f "%e %U" -o "$work/db.time" "$mastrom" rom build configs/scheme3.toml \
  --param interface.thickness=0.001:0.002:3 --param interface.inner_diameter=0.08:0.1:3 \
  --param interface.length=0.04:0.06:3 -q -o "$work/s3db.h5" >"$work/db.log" 2>&1 ||
  { cat "$work/db.log"; exit 1; }
read -r db_wall db_cpu <"$work/db.time"
echo "1. database: 27 samples, ${db_wall} s wall, ${db_cpu} s CPU, $(du -k "$work/s3db.h5" | cut -f1) kB"
grep -E "error measured" "$work/db.log" | sed 's/^ */   /'

status=0
/usr/bin/time -f "%e %U" -o "$work/opt.time" "$mastrom" optimize "$work/s3db.h5" \
  --minimize mass --subject-to "frequency_1 >= 300" --subject-to "min_margin_of_safety >= 1" \
  --subject-to "peak_rel_end_angular_acceleration <= 5" --set material.yield_strength=2.7e8 \
  -q -o "$work/opt.csv" >"$work/opt.log" 2>&1 || status=$?
read -r opt_wall opt_cpu <"$work/opt.time"
sed 's/^/   /' "$work/opt.log"
echo "2. optimize end to end: ${opt_wall} s wall (target <= 60 s), ${opt_cpu} s CPU, exit ${status}"
# Every constraint against the full order, from the record's last round.
/usr/bin/python3 - "$work/opt.csv" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
last = rows[-1]
for key in last:
    if key.startswith("met:"):
        m = key[4:]
        print(f"   {m}: full order {float(last['full_order:' + m]):.6g}, bound "
              f"{float(last['bound:' + m]):.6g}, met {last[key]}")
print(f"   rounds: {len(rows)}")
EOF
echo "load after: $(uptime | sed 's/.*load average/load average/')"
exit "$status"
