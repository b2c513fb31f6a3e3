#!/usr/bin/env bash
# The ROM against the nonlinear full order at a step-converged setting: the ROM's accuracy targets
# (benchmarks/README.md "ROM against the step-converged full order").
#
#   benchmarks/rom_vs_fullorder.sh [BUILD_DIR]        (default BUILD_DIR = build)
#
# Parts (RVF_PARTS, run in this order):
#   main   Scheme 3 (configs/scheme3.toml), 20 modes, 8 s trapezoidal drive; a 3 x 3 grid database
#          over interface.thickness 1.5-2.5 mm x interface.length 40-60 mm; at RVF_MAIN_POINTS
#          random held-out points each method of RVF_MAIN_METHODS against the full order.
#          Targets: NRMSE of the relative end angular acceleration <= 1 %, every peak <= 0.5 %.
#   five   the five-parameter box (thickness 0.5-2 mm, inner diameter 80-100 mm, length 40-60 mm,
#          module mass 0.3-0.7 kg, Young's modulus 60-80 GPa) built by `rom build --adaptive
#          --tolerance 0.03 --max-samples RVF_FIVE_SAMPLES` (rbf; E handled exactly), at
#          RVF_FIVE_POINTS random points. Targets: NRMSE <= 3 %; the database's own estimate at
#          each point within [1/2, 2] x the NRMSE measured against the full order.
#   conv   the reference's convergence: at each point of RVF_CONV_POINTS the full order again at
#          half the reference tolerance; the change (bench_fullorder_accuracy) and every ROM's
#          error against both.
#   xcheck `mastrom validate --set simulation.tolerance=...` at the first 2 points of `main`
#          (cubic): the same numbers as the scripted simulate + rom eval + compare route.
# Per point, besides the interpolated ROMs, the "truth" ROM: the same modal ROM on a direct modal
# solve at the point (a two-sample database along module.mass whose first sample is the point,
# evaluated there), whose error against the full order is the modal model's own (truncation to 20
# modes, linearisation about the locked mast; docs/theory.md §4), and bench_rom_interpolation_error,
# which gives the interpolation error alone (interpolated ROM against the truth ROM) and, for rbf,
# the database's estimate at the point. The points are those `mastrom validate --seed RVF_SEED`
# draws (rom/studies/validation.hpp).
#
# Knobs (environment):
#   RVF_WORK          work directory [/tmp/rom_vs_fullorder]; files that exist are reused (delete
#                     one to redo it), so a second run only tabulates
#   RVF_PARTS         [main five conv xcheck]
#   RVF_TOLERANCE     simulation.tolerance of the full-order references [6.25e-7] (the default
#                     1e-5 errs ~0.7 % on Scheme 3: docs/user_guide.md §7)
#   RVF_SEED          seed of the points [7]
#   RVF_MAIN_POINTS   [10]     RVF_MAIN_METHODS [cubic rbf manifold tracked]
#   RVF_FIVE_POINTS   [20]     RVF_FIVE_SAMPLES [100]
#   RVF_CONV_POINTS   PART:INDEX ... [main:0 main:6 five:0 five:6] (6: the worst of each box)
# Every heavy process runs alone, on one thread (--threads 1, OMP_NUM_THREADS=1, no mpirun), under
# `nice`. Cost on one core: a Scheme 3 reference at 6.25e-7 with its --estimate-error run takes
# 30-65 s of CPU, so the defaults take about 30 minutes (29 min measured on the shared machine). Output: per-point tables and summaries on stdout
# and in RVF_WORK/*.tsv, CPU and wall time of every run in RVF_WORK/times.log.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$(cd "${1:-$root/build}" && pwd)"
work="${RVF_WORK:-/tmp/rom_vs_fullorder}"
parts="${RVF_PARTS:-main five conv xcheck}"
tol="${RVF_TOLERANCE:-6.25e-7}"
seed="${RVF_SEED:-7}"
main_points="${RVF_MAIN_POINTS:-10}"
main_methods="${RVF_MAIN_METHODS:-cubic rbf manifold tracked}"
five_points="${RVF_FIVE_POINTS:-20}"
five_samples="${RVF_FIVE_SAMPLES:-100}"
conv_points="${RVF_CONV_POINTS:-main:0 main:6 five:0 five:6}"
config="$root/configs/scheme3.toml"
mastrom="$build/cli/mastrom"
interp="$build/benchmarks/bench_rom_interpolation_error"
ladder="$build/benchmarks/bench_fullorder_accuracy"
for exe in "$mastrom" "$interp" "$ladder"; do
  [[ -x "$exe" ]] || { echo "rom_vs_fullorder.sh: missing $exe (build mastrom and the benchmarks)" >&2; exit 1; }
done
mkdir -p "$work"
export OMP_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
common=(--set modes.count=20)
half_tol=$(awk -v t="$tol" 'BEGIN { printf "%g", t / 2 }')
start=$(date +%s)

# timed LOG OUT CMD...: run CMD (writing OUT.part.h5) unless OUT exists; time and log it.
timed() {
  local log="$1" out="$2"
  shift 2
  [[ -f "$out" ]] && return 0
  echo "  $(date +%T) $(basename "$out")" >&2
  /usr/bin/time -f "$(basename "$out") %U %S %e" -a -o "$work/times.log" nice -n 10 "$@" \
    -o "$out.part.h5" >"$log" 2>&1 || { cat "$log" >&2; exit 1; }
  mv "$out.part.h5" "$out"
  rm -f "$out.part.xdmf"  # simulate's ParaView file, naming the temporary name
}

# point_sets PART INDEX: the point's --set arguments (from the interpolation benchmark's list).
point_sets() {
  sed -n "$(($2 + 1))p" "$work/$1_points.txt" | awk '{ for (i = 1; i <= NF; ++i) printf "--set %s ", $i }'
}

# points PART DB COUNT METHOD: bench_rom_interpolation_error at the validate points; the first call
# also writes PART_points.txt, one "key=value ..." line per point.
points() {
  local out="$work/$1_interp_$4.txt"
  [[ -f "$out" ]] || nice -n 10 "$interp" "$2" "$3" "$4" "$seed" >"$out"
  [[ -f "$work/$1_points.txt" ]] ||
    awk -F': nrmse ' '/^  [a-z].*: nrmse / { p = $1; sub(/^ +/, "", p); gsub(/, /, " ", p); print p }' \
      "$out" >"$work/$1_points.txt"
}

# full PART INDEX TOL [--estimate-error]: the full-order reference at the point.
full() {
  local base="$work/$1_p$2_full_$3"
  # shellcheck disable=SC2046
  timed "$base.log" "$base.h5" "$mastrom" simulate "$config" "${common[@]}" $(point_sets "$1" "$2") \
    --set "simulation.tolerance=$3" "${@:4}" --threads 1 -q
}

# truth PART INDEX: the ROM on a direct modal solve at the point (sample 0 of a two-sample database
# along module.mass, evaluated at that sample, where every method returns it exactly).
truth() {
  local sets mass base="$work/$1_p$2_truth"
  sets=$(point_sets "$1" "$2")
  mass=$(tr ' ' '\n' <<<"$sets" | sed -n 's/^module\.mass=//p')
  mass="${mass:-$("$mastrom" config "$config" | sed -n 's/^mass *= *\([0-9.eE+-]*\).*/\1/p' | head -n 1)}"
  local hi
  hi=$(awk -v m="$mass" 'BEGIN { printf "%.17g", m * (1 + 1e-6) }')
  # shellcheck disable=SC2086
  timed "${base}_db.log" "${base}_db.h5" "$mastrom" rom build "$config" "${common[@]}" $sets \
    --set "module.mass=$mass" --param "module.mass=$mass:$hi:2" --no-stresses -q
  timed "$base.log" "$base.h5" "$mastrom" rom eval "${base}_db.h5" --method tracked --no-stresses
}

# rom PART INDEX DB METHOD: the interpolated ROM at the point.
rom() {
  local base="$work/$1_p$2_$4"
  # shellcheck disable=SC2046
  timed "$base.log" "$base.h5" "$mastrom" rom eval "$3" --method "$4" --no-stresses \
    $(point_sets "$1" "$2")
}

# errors FULL ROM: "nrmse peak_rel peak_abs residual force torque rms full_est" in % (compare).
errors() {
  "$mastrom" compare "$1" "$2" | awk '
    / nrmse_rel_end/ { n = $2 } / peak_rel_end/ { pr = $2 } / peak_abs_end/ { pa = $2 }
    / residual_rel_end/ { re = $2 } / peak_joint_force/ { f = $2 } / peak_drive_torque/ { t = $2 }
    / rms_rel_end/ { r = $2 }
    /own estimated error/ { e = $0; sub(/.*NRMSE /, "", e); sub(/,.*/, "", e) }
    END { v = n " " pr " " pa " " re " " f " " t " " r " " e; gsub(/%/, "", v); print v }'
}

# interp_error PART METHOD INDEX: "nrmse_vs_truth estimate" in % from the interpolation benchmark.
interp_error() {
  awk -v i="$3" '/^  [a-z].*: nrmse / { if (k++ == i) {
      sub(/.*: nrmse /, ""); n = $1; e = $0; sub(/.*%  estimate /, "", e); sub(/ %.*/, "", e)
      print n, (e + 0 < 0 ? "-" : e) } }' "$work/$1_interp_$2.txt"
}

# table PART METHODS...: per point and method the errors against the full order, the truth ROM's,
# the interpolation error alone; then max / median per method (→ PART_table.tsv).
table() {
  local part="$1" n
  shift
  n=$(wc -l <"$work/${part}_points.txt")
  local tsv="$work/${part}_table.tsv"
  echo -e "point\tmethod\tnrmse\tpeak_rel\tpeak_abs\tresidual\tforce\ttorque\trms\tfull_est\tinterp_only\testimate" >"$tsv"
  for ((i = 0; i < n; ++i)); do
    local ref="$work/${part}_p${i}_full_$tol.h5"
    for m in "$@"; do
      read -r -a e <<<"$(errors "$ref" "$work/${part}_p${i}_$m.h5")"
      read -r -a x <<<"$(interp_error "$part" "$m" "$i")"
      echo -e "$i\t$m\t${e[*]:0:8}\t${x[0]}\t${x[1]}" | tr ' ' '\t' >>"$tsv"
    done
    read -r -a e <<<"$(errors "$ref" "$work/${part}_p${i}_truth.h5")"
    echo -e "$i\ttruth\t${e[*]:0:8}\t-\t-" | tr ' ' '\t' >>"$tsv"
  done
  printf '\n=== %s: errors against the full order at tolerance %s (%%; interp_only = against the truth ROM) ===\n' "$part" "$tol"
  column -t "$tsv"
  printf -- '--- %s summary (%%): NRMSE max / median, worst peak metric (peak rel, abs, residual, force, torque), full order'"'"'s own estimate max ---\n' "$part"
  for m in "$@" truth; do
    printf '  %-9s NRMSE max %s median %s  worst peak %s  full-est max %s  interp-only max %s\n' "$m" \
      "$(column_stats "$tsv" "$m" 3 max)" "$(column_stats "$tsv" "$m" 3 median)" \
      "$(awk -F'\t' -v m="$m" 'NR > 1 && $2 == m { for (c = 4; c <= 8; ++c) print $c }' "$tsv" | stats max)" \
      "$(column_stats "$tsv" "$m" 10 max)" "$(column_stats "$tsv" "$m" 11 max)"
  done
}

# stats max|median|min: of the numbers on stdin, one a line ("-" when there are none).
stats() {
  sort -g | awk -v what="$1" '$1 != "-" { v[++n] = $1 }
    END { if (n == 0) { print "-"; exit }
          if (what == "max") x = v[n]; else if (what == "min") x = v[1]
          else x = (n % 2) ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
          printf "%.3f\n", x }'
}

# column_stats TSV METHOD COLUMN max|median|min: over the rows of METHOD.
column_stats() {
  awk -F'\t' -v m="$2" -v c="$3" 'NR > 1 && $2 == m { print $c }' "$1" | stats "$4"
}

for part in $parts; do
  case "$part" in
    main)
      db="$work/main_db.h5"
      timed "$work/main_db.log" "$db" "$mastrom" rom build "$config" "${common[@]}" \
        --param interface.thickness=0.0015:0.0025:3 --param interface.length=0.04:0.06:3 --no-stresses -q
      for m in $main_methods; do points main "$db" "$main_points" "$m"; done
      for ((i = 0; i < main_points; ++i)); do
        full main "$i" "$tol" --estimate-error
        truth main "$i"
        for m in $main_methods; do rom main "$i" "$db" "$m"; done
      done
      # shellcheck disable=SC2086
      table main $main_methods
      ;;
    five)
      db="$work/five_db.h5"
      timed "$work/five_db.log" "$db" "$mastrom" rom build "$config" "${common[@]}" \
        --param interface.thickness=0.0005:0.002 --param interface.inner_diameter=0.08:0.1 \
        --param interface.length=0.04:0.06 --param module.mass=0.3:0.7 \
        --param material.youngs_modulus=60e9:80e9 --adaptive --tolerance 0.03 \
        --max-samples "$five_samples" --no-stresses
      grep -E 'samples|estimate' "$work/five_db.log" | tail -n 4
      points five "$db" "$five_points" rbf
      for ((i = 0; i < five_points; ++i)); do
        full five "$i" "$tol" --estimate-error
        truth five "$i"
        rom five "$i" "$db" rbf
      done
      table five rbf
      echo "--- five: the database's estimate at each point / NRMSE against the full order (target [0.5, 2]) ---"
      awk -F'\t' 'NR > 1 && $2 == "rbf" { printf "  point %s: estimate %.3f %% / measured %.3f %% = %.2f\n", $1, $12, $3, $12 / $3 }' \
        "$work/five_table.tsv" | tee "$work/five_ratio.txt"
      printf '  ratio min %s median %s max %s\n' "$(awk '{ print $NF }' "$work/five_ratio.txt" | stats min)" \
        "$(awk '{ print $NF }' "$work/five_ratio.txt" | stats median)" \
        "$(awk '{ print $NF }' "$work/five_ratio.txt" | stats max)"
      ;;
    conv)
      printf '\n=== the reference'"'"'s convergence: tolerance %s against %s ===\n' "$tol" "$half_tol"
      for pi in $conv_points; do
        p="${pi%%:*}" i="${pi##*:}"
        full "$p" "$i" "$half_tol"
        ref="$work/${p}_p${i}_full_$tol.h5" fine="$work/${p}_p${i}_full_$half_tol.h5"
        printf -- '--- %s point %s: %s ---\n' "$p" "$i" "$(sed -n "$((i + 1))p" "$work/${p}_points.txt")"
        (cd "$work" && "$ladder" --order 0.667 --ref "${ref##*/}" --ref "${fine##*/}" "${ref##*/}" \
          "${fine##*/}" | sed -n '1,4p')
        echo "  ROM errors (NRMSE / peak rel, %) against the reference at $tol and at $half_tol:"
        for f in "$work/${p}_p${i}_"*.h5; do
          m="${f##*_p"${i}"_}" m="${m%.h5}"
          [[ "$m" == full_* || "$m" == truth_db || "$m" == *.part ]] && continue
          read -r -a a <<<"$(errors "$ref" "$f")"
          read -r -a b <<<"$(errors "$fine" "$f")"
          printf '    %-9s %8s / %-8s  %8s / %-8s\n' "$m" "${a[0]}" "${a[1]}" "${b[0]}" "${b[1]}"
        done
      done
      ;;
    xcheck)
      out="$work/xcheck_validate.h5"
      timed "$work/xcheck_validate.log" "$out" "$mastrom" validate "$work/main_db.h5" --points 2 \
        --seed "$seed" --method cubic --set "simulation.tolerance=$tol"
      printf '\n=== xcheck: mastrom validate --set simulation.tolerance=%s (cubic, first 2 points) ===\n' "$tol"
      grep -E '^(point|[0-9] )' "$work/xcheck_validate.log"
      echo "  the scripted route at the same points (nrmse peak_rel peak_abs force torque full_est):"
      awk -F'\t' 'NR > 1 && $2 == "cubic" && $1 < 2 { print "  " $1, $3, $4, $5, $7, $8, $10 }' \
        "$work/main_table.tsv"
      ;;
    *) echo "rom_vs_fullorder.sh: unknown part '$part' (main five conv xcheck)" >&2; exit 1 ;;
  esac
done
echo "# process times (user system wall, s):"
sed 's/^/  /' "$work/times.log"
awk '{ c += $2 + $3; w += $4 } END { printf "# all runs: CPU %.0f s, wall %.0f s\n", c, w }' "$work/times.log"
printf '# campaign wall time this invocation: %d s\n' "$(($(date +%s) - start))"
