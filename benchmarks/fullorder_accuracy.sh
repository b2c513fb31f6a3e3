#!/usr/bin/env bash
# Accuracy of the full order's default adaptive steps (benchmarks/README.md "Full-order accuracy",
# docs/user_guide.md §7): for each case, fixed-step references at halving steps, adaptive runs at a
# ladder of tolerances (each with --estimate-error), then bench_fullorder_accuracy compares them
# (reference ladder and observed order, Richardson reference, NRMSE / peak / force / torque errors,
# estimate / measured, wall time), once against the fixed steps and once against the adaptive
# ladder's own extrapolation.
#
#   benchmarks/fullorder_accuracy.sh [BUILD_DIR]        (default BUILD_DIR = build)
#
# Long: with the defaults about 1.5–2 h on one core of the 2-core machine (Scheme 3's fixed 2.5 µs
# run alone ~20 min). Every simulation runs on one thread under `nice`, one at a time, and its file
# is kept in ACC_WORK: a second run reuses what exists and only compares (delete a file to redo it).
# Knobs (environment):
#   ACC_CASES        cases, from s1 s2 s3 (configs/scheme{1,2,3}.toml, trapezoidal, 8 s), cyc
#                    (Scheme 2, h = 1.2 mm, inner diameter 93 mm, cycloidal 1.5 s, 2 s) and the
#                    windows s1w s2w (first 0.3 s: the peaks right after the ramp's end) and s3w
#                    (Scheme 3, first 2 s), and peer: Scheme 1 swung 1.5° in 0.2 s (a short case
#                    to run beside a peer code; ramps of 0.1 s, 0.2 s simulated)
#                    [default: "s1 s2 s3 cyc"]
#   ACC_REF_STEPS_US fixed steps of the references, each half the one before [10 5 2.5]
#   ACC_TOLERANCES   simulation.tolerance of the adaptive runs [4e-5 2e-5 1e-5 5e-6 2.5e-6]
#   ACC_WORK         directory for the result files [./fullorder_accuracy]
#   ACC_OUTPUT_US    output interval of the references [20], a multiple of every step
#   ACC_REF_RHO      simulation.rho_inf of the fixed-step references [0.9; cyc: 0]. The smooth
#                    cycloidal case needs 0: at 0.9 its references do not converge (the index-1
#                    accelerations show the stiff shell content that rho_inf = 0.9 damps only by
#                    0.9 per step, and more of it the shorter the step; docs/theory.md §5.5a,
#                    benchmarks/README.md "A smooth drive's references")
# The references write every ACC_OUTPUT_US (output.every = ACC_OUTPUT_US / step), the adaptive
# runs every 0.1 ms (the default output.step), a subset of the references' instants. The peaks of
# the references are refined between samples by a parabola; for the sharp peak right after a ramp's
# end (S1: ~40 µs wide) 20 µs samples still over-read it by ~0.3 %: check peaks on the windows with
# ACC_CASES="s1w s2w" ACC_REF_STEPS_US="2.5 1.25" ACC_OUTPUT_US=2.5 (every step written).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$(cd "${1:-$root/build}" && pwd)"
cases="${ACC_CASES:-s1 s2 s3 cyc}"
ref_steps="${ACC_REF_STEPS_US:-10 5 2.5}"
tolerances="${ACC_TOLERANCES:-4e-5 2e-5 1e-5 5e-6 2.5e-6}"
work="${ACC_WORK:-$PWD/fullorder_accuracy}"
output_us="${ACC_OUTPUT_US:-20}"
mastrom="$build/cli/mastrom"
compare="$build/benchmarks/bench_fullorder_accuracy"
for exe in "$mastrom" "$compare"; do
  [[ -x "$exe" ]] || { echo "fullorder_accuracy.sh: missing $exe (build mastrom and bench_fullorder_accuracy)" >&2; exit 1; }
done
mkdir -p "$work"
export OMP_NUM_THREADS=1

# case_args CASE: the configuration and overrides of one case.
case_args() {
  case "$1" in
    s1) echo "$root/configs/scheme1.toml" ;;
    s2) echo "$root/configs/scheme2.toml" ;;
    s3) echo "$root/configs/scheme3.toml" ;;
    cyc) echo "$root/configs/scheme2.toml --set interface.thickness=0.0012" \
              "--set interface.inner_diameter=0.093 --set drive.law=cycloidal" \
              "--set drive.duration=1.5 --set simulation.end_time=2" ;;
    peer) echo "$root/configs/scheme1.toml --set drive.angle_deg=1.5 --set drive.duration=0.2" \
               "--set simulation.end_time=0.2" ;;
    s1w) echo "$root/configs/scheme1.toml --set simulation.end_time=0.3" ;;
    s2w) echo "$root/configs/scheme2.toml --set simulation.end_time=0.3" ;;
    s3w) echo "$root/configs/scheme3.toml --set simulation.end_time=2" ;;
    *) echo "fullorder_accuracy.sh: unknown case '$1' (s1 s2 s3 cyc peer s1w s2w s3w)" >&2; exit 1 ;;
  esac
}

# ref_rho CASE: the spectral radius of the case's fixed-step references.
ref_rho() {
  if [[ -n "${ACC_REF_RHO:-}" ]]; then echo "$ACC_REF_RHO"
  elif [[ "$1" == cyc ]]; then echo 0
  else echo 0.9
  fi
}

# run OUT LOG ARGS...: one simulation into OUT unless it exists (written under a temporary name).
run() {
  local out="$1" log="$2"
  shift 2
  [[ -f "$out" ]] && return 0
  echo "  $(date +%T) running $(basename "$out")" >&2
  /usr/bin/time -f '%U %S %e' -o "${out%.h5}.time" nice -n 10 "$mastrom" simulate "$@" \
    --threads 1 -q -o "$out.part.h5" >"$log" 2>&1 || { cat "$log" >&2; exit 1; }
  mv "$out.part.h5" "$out"
}

for c in $cases; do
  read -r -a args <<<"$(case_args "$c")"
  refs=()
  rho=$(ref_rho "$c")
  for h in $ref_steps; do
    every=$(awk -v h="$h" -v o="$output_us" 'BEGIN { e = o / h; if (e != int(e)) exit 1; print e }') ||
      { echo "fullorder_accuracy.sh: $output_us us is not a multiple of the step $h us" >&2; exit 1; }
    out="$work/${c}_fixed_${h}us_rho${rho}.h5"
    run "$out" "${out%.h5}.log" "${args[@]}" --set simulation.adaptive=false \
      --set "simulation.time_step=${h}e-6" --set "output.every=$every" \
      --set "simulation.rho_inf=$rho"
    refs+=(--ref "$out")
  done
  runs=()
  for tol in $tolerances; do
    out="$work/${c}_tol_${tol}.h5"
    run "$out" "$work/${c}_tol_${tol}.log" "${args[@]}" --set "simulation.tolerance=$tol" \
      --estimate-error
    runs+=("$out")
  done
  printf '\n=== case %s: %s ===\n' "$c" "${args[*]}"
  "$compare" "${refs[@]}" "${runs[@]}"
  # The same runs against their own ladder: Richardson of the two tightest tolerances with the
  # order of the tolerance ladder, 2/3 per halving (the reference for Scheme 3, whose fixed steps
  # do not converge below 10 us; benchmarks/README.md).
  ladder=()
  for out in "${runs[@]}"; do ladder+=(--ref "$out"); done
  printf -- '--- case %s against its adaptive ladder (--order 0.667) ---\n' "$c"
  "$compare" --order 0.667 "${ladder[@]}" "${runs[@]}"
  echo "# process times (the adaptive runs include their --estimate-error run at 8x the tolerance):"
  for out in "${refs[@]}" "${runs[@]}"; do
    [[ "$out" == --ref ]] && continue
    t="${out%.h5}.time"
    [[ -f "$t" ]] && tail -n 1 "$t" |
      awk -v f="$(basename "$out")" '{ printf "  %-28s CPU %8.1f s  wall %8.1f s\n", f, $1 + $2, $3 }'
    grep -E "wall time|rejected|accepted above" "${out%.h5}.log" | sed 's/^/      /' || true
  done
done
