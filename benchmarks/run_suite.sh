#!/usr/bin/env bash
# The benchmark suite (see benchmarks/README.md): one run, ≤ 5 minutes on the 2-core CI
# machine, prints every speed figure the project targets with the targets next to them.
#
#   benchmarks/run_suite.sh [BUILD_DIR]          (default BUILD_DIR = build)
#   cmake --build BUILD_DIR --target bench_suite (builds what it needs, then runs this script)
#
# Knobs (environment): SUITE_FULL_END_S (simulated seconds of the full-order run, 0.4, ≥ 0.3),
# SUITE_MODES_MAX_DOFS (largest SLEPc model, 110000), SUITE_ARPACK_MAX_DOFS (10000),
# SUITE_SCREEN_N (grid points per screen axis, 15).
# CPU times come from getrusage (/usr/bin/time, Google Benchmark's CPU column); wall times are
# printed too but on a shared machine only CPU times are comparable between runs.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$(cd "${1:-$root/build}" && pwd)"
full_end_s="${SUITE_FULL_END_S:-0.4}"
modes_max_dofs="${SUITE_MODES_MAX_DOFS:-110000}"
arpack_max_dofs="${SUITE_ARPACK_MAX_DOFS:-10000}"
screen_n="${SUITE_SCREEN_N:-15}"

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
mastrom="$build/cli/mastrom"
for exe in "$mastrom" "$build/benchmarks/bench_fullorder_shell_element" \
           "$build/benchmarks/bench_fullorder_deployment" \
           "$build/benchmarks/bench_modes_scaling" "$build/benchmarks/bench_rom_deployment"; do
  [[ -x "$exe" ]] || { echo "run_suite.sh: missing $exe (build the bench_suite target)" >&2; exit 1; }
done
work="$(mktemp -d "${TMPDIR:-/tmp}/mastrom_suite.XXXXXX")"
trap 'rm -rf "$work"' EXIT
suite_start=$(date +%s)
cd "$root"

section() { printf '\n=== %s ===\n' "$1"; }
# cpu_of FILE: user + sys seconds written by /usr/bin/time -f '%U %S %e' (last line).
cpu_of() { tail -n 1 "$1" | awk '{ printf "%.3f", $1 + $2 }'; }
wall_of() { tail -n 1 "$1" | awk '{ printf "%.3f", $3 }'; }

# ------------------------------------------------------------------------------------------------
section "1. ANCF shell element (Scheme 3 panel, R = 41 mm, a = 25 mm, b = 2piR/8), CPU us/element"
"$build/benchmarks/bench_fullorder_shell_element" \
  --benchmark_filter='BM_(InternalForce|ElasticForceAndTangent)/(4|5)$|BM_DampingForceAndTangents' \
  --benchmark_min_time=0.2 --benchmark_color=false --benchmark_format=csv 2>/dev/null >"$work/element.csv"
awk -F, 'NR > 1 && $1 ~ /BM_/ { gsub(/"/, "", $1);
          printf "  %-36s %8.2f us CPU (%s)\n", $1, $4, $5 }' "$work/element.csv"
echo "  (InternalForce = elastic + Kelvin-Voigt force of the time stepping; /4 = 4x4 Gauss, the mast default)"

# ------------------------------------------------------------------------------------------------
section "2. Full order, Scheme 3 default mesh (configs/scheme3.toml), dt = 100 us, 3 deg drive"
# A short deployment with the paper's ramps and cruise rate (0.1 s ramps to 15 deg/s, 3 deg in
# 0.3 s), then residual vibration: `simulate` needs the record to outlast the drive.
/usr/bin/time -f '%U %S %e' -o "$work/full.time" \
  "$mastrom" simulate configs/scheme3.toml --threads 1 --set "simulation.end_time=$full_end_s" \
  --set drive.angle_deg=3 --set drive.duration=0.3 --set drive.ramp=0.1 \
  -o "$work/full.h5" -q >"$work/full.log" 2>&1 || { cat "$work/full.log"; exit 1; }
grep -E "DOFs|Newton" "$work/full.log" | sed 's/^/  /'
full_cpu=$(cpu_of "$work/full.time")
full_wall=$(wall_of "$work/full.time")
awk -v c="$full_cpu" -v w="$full_wall" -v T="$full_end_s" 'BEGIN {
  steps = T / 1e-4;
  printf "  %.3f s simulated, 1 thread: CPU %.2f s, wall %.2f s (set-up included)\n", T, c, w;
  printf "  CPU / simulated time  = %.2f x real time   (1 thread: CPU time is work)\n", c / T;
  printf "  CPU per step          = %.3f ms\n", 1e3 * c / steps }'
# The default: two threads (pipelined steps); real time is judged by the wall clock.
/usr/bin/time -f '%U %S %e' -o "$work/full2.time" \
  "$mastrom" simulate configs/scheme3.toml --threads 2 --set "simulation.end_time=$full_end_s" \
  --set drive.angle_deg=3 --set drive.duration=0.3 --set drive.ramp=0.1 \
  -o "$work/full2.h5" -q >"$work/full2.log" 2>&1 || { cat "$work/full2.log"; exit 1; }
awk -v w="$(wall_of "$work/full2.time")" -v T="$full_end_s" 'BEGIN {
  printf "  2 threads (default): wall %.2f s = %.2f x real time (target <= 1; set-up included)\n",
         w, w / T }'
if ! command -v h5dump >/dev/null; then
  echo "  (h5dump not found: the 1- and 2-thread series were not compared)"
elif cmp -s <(h5dump -d /joint/torque "$work/full.h5" | tail -n +2) \
            <(h5dump -d /joint/torque "$work/full2.h5" | tail -n +2); then
  echo "  (1 and 2 threads: identical joint torque series)"
else
  echo "  WARNING: the 1- and 2-thread joint torque series differ"
fi
echo "  per cruise step without the set-up (bench_fullorder_deployment, steps 1000..3000):"
"$build/benchmarks/bench_fullorder_deployment" 2>/dev/null | sed 's/\x1b\[[0-9;]*m//g' |
  grep -E "^DeploymentSteps.*_median|full order" | sed 's/^/    /'

# ------------------------------------------------------------------------------------------------
section "3. 20 lowest modes vs DOF count (Scheme 1, refined interface; wall s on 1 rank)"
{
  "$build/benchmarks/bench_modes_scaling" --backends dense --max-dofs 1000 --count 20
  "$build/benchmarks/bench_modes_scaling" --backends arpack --max-dofs "$arpack_max_dofs" --count 20 |
    grep -v '^#'
  "$build/benchmarks/bench_modes_scaling" --backends slepc --max-dofs "$modes_max_dofs" --count 20 |
    grep -v '^#'
} 2>&1 | tee "$work/modes.txt" | sed 's/^/  /'
# Least-squares slope of log(solve + linearize time) against log(DOFs) per backend, over the rows
# with ≥ 5000 DOFs for the sparse solvers (below that, fixed costs dominate) and all rows for dense
# (bounded at 1000 DOFs: the 2616-DOF dense solve alone takes ~15 s).
awk '$1 !~ /^#/ && NF >= 11 && ($4 == "dense" || $2 >= 5000) {
       b = $4; x = log($2); y = log($6 + $7); n[b]++; sx[b] += x; sy[b] += y; sxx[b] += x * x;
       sxy[b] += x * y; if ($2 > big[b]) { big[b] = $2; tbig[b] = $9 } }
     END { for (b in n) if (n[b] >= 2) {
       slope = (n[b] * sxy[b] - sx[b] * sy[b]) / (n[b] * sxx[b] - sx[b] * sx[b]);
       printf "  %-7s cost ~ DOFs^%.2f (fit over %d meshes); largest %d DOFs: %.2f s total\n",
              b, slope, n[b], big[b], tbig[b] } }' "$work/modes.txt"
echo "  (target: 1e5 unknowns <= 30 s)"

# ------------------------------------------------------------------------------------------------
section "4. ROM one deployment (8 s Scheme 3) and ROM-vs-full speed-up (bench_rom_deployment)"
"$build/benchmarks/bench_rom_deployment" \
  --benchmark_filter='^RomDeployment/modes:(10|20)/step_us:1000$|^RomDeploymentMetrics/modes:10/step_us:1000$' \
  --benchmark_color=false 2>&1 | sed 's/\x1b\[[0-9;]*m//g' | tee "$work/rom.txt" |
  grep -E "^RomDeployment|Summary|deployment|metrics" | sed 's/^/  /'
# CPU ms of the 10-mode deployment, from the program's summary line.
rom10_ms=$(sed -n 's/.*8 s deployment, 10 modes, 1 ms output: \([0-9.]*\) ms.*/\1/p' "$work/rom.txt")
rom10_ms="${rom10_ms:-0}"
awk -v c="$full_cpu" -v T="$full_end_s" -v r="$rom10_ms" 'BEGIN {
  full8 = c / T * 8.0;
  printf "  full order, 8 s deployment (CPU, extrapolated from section 2): %.1f s\n", full8;
  if (r > 0) printf "  ROM (10 modes, 1 ms output): %.3f ms CPU -> full / ROM = %.3g (target >= 1e4)\n",
                    r, full8 / (r / 1e3) }'

# ------------------------------------------------------------------------------------------------
section "5. Screen throughput (mastrom screen, Scheme 3 database 2 x 2, ${screen_n} x ${screen_n} x 2 designs)"
/usr/bin/time -f '%U %S %e' -o "$work/db.time" \
  "$mastrom" rom build configs/scheme3.toml --param interface.thickness=0.001:0.002:2 \
  --param interface.inner_diameter=0.085:0.1:2 --modes 10 --backend dense -q \
  -o "$work/db.h5" >"$work/db.log" 2>&1 || { cat "$work/db.log"; exit 1; }
echo "  database build: $(cpu_of "$work/db.time") s CPU"
screen_args=(screen "$work/db.h5" --grid "interface.thickness=0.001:0.002:$screen_n"
             --grid "interface.inner_diameter=0.085:0.1:$screen_n" --grid drive.law=trapezoidal,cycloidal -q)
"$mastrom" "${screen_args[@]}" -o "$work/screen1.csv" 2>&1 | grep -o "[0-9]* designs x.*" |
  sed 's/^/  1 rank : /'
mpirun -n 2 "$mastrom" "${screen_args[@]}" -o "$work/screen2.csv" 2>&1 | grep -o "[0-9]* designs x.*" |
  sed 's/^/  2 ranks: /'
cmp -s "$work/screen1.csv" "$work/screen2.csv" && echo "  1- and 2-rank tables identical" ||
  echo "  WARNING: 1- and 2-rank tables differ"

section "suite finished in $(( $(date +%s) - suite_start )) s wall"
