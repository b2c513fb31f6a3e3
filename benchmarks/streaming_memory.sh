#!/usr/bin/env bash
# Peak memory of `mastrom simulate` against the horizon: the time series are streamed to the file
# (fullorder/result_stream.hpp), and so are the interface stress histories, resampled onto the
# output instants while the run goes (fullorder/interface_stress_stream.hpp), so with and without
# the stresses the peak RSS must not grow with simulation.end_time while the file does. With
# --estimate-error the run keeps only r for the comparison (8 bytes per output instant) and its
# second run keeps nothing, so that column stays flat as well. With --checkpoint-every the outputs
# are streamed too, with adaptive and fixed steps (a checkpoint names the file holding them; an
# adaptive one carries the continuous response's window of four step points), so both checkpoint
# columns (the stresses on, a checkpoint every 5 s) must stay flat. Coarse Scheme 1 (1 x 6 ring)
# held after a 1 s swing, outputs every 1 ms, one thread. The last column is `rom eval
# --stress-history` of the same case on a 2-sample database (6 modes): its series and history are
# stepped into the file block by block (cli/rom_eval_output.hpp writeStreamedRomEvaluationFile), so
# what still grows is its metrics' pass (rom/studies/rom_evaluation.cpp: the drive sampled on the
# metrics' grid, which output.step = 1 ms makes the output grid, and the states the stress peaks'
# refinement keeps, about 0.25 kB per sample).
# Prints, per horizon: output samples, file size, peak RSS of each variant and its ratio to the
# shortest horizon's.
#
#   benchmarks/streaming_memory.sh [BUILD_DIR]     (default BUILD_DIR = build)
#
# Knobs: STREAM_HORIZONS (simulated seconds, "10 40 160").
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="$(cd "${1:-$root/build}" && pwd)"
mastrom="$build/cli/mastrom"
[[ -x "$mastrom" ]] || { echo "streaming_memory.sh: missing $mastrom (build it first)" >&2; exit 1; }
horizons=(${STREAM_HORIZONS:-10 40 160})
work="$(mktemp -d "${TMPDIR:-/tmp}/mastrom_streaming.XXXXXX")"
trap 'rm -rf "$work"' EXIT
export OMP_NUM_THREADS=1

args=(configs/scheme1.toml -q --threads 1 --set interface.elements_axial=1
      --set interface.elements_circumferential=6 --set drive.duration=1.0 --set drive.ramp=0.05
      --set drive.angle_deg=10 --set output.step=1e-3)

# run NAME END [extra args]: peak RSS [kB] in NAME.rss, the file's bytes in NAME.bytes
run() {
  local name=$1 end=$2
  shift 2
  (cd "$root" && /usr/bin/time -f '%M' -o "$work/$name.rss" "$mastrom" simulate "${args[@]}" \
     --set simulation.end_time="$end" "$@" -o "$work/$name.h5" >"$work/$name.log" 2>&1)
  stat -c %s "$work/$name.h5" >"$work/$name.bytes"
  rm -f "$work/$name.h5" "$work/$name.xdmf" "$work/$name.checkpoint.h5"
}

# rom_eval NAME END: as run, for `rom eval` on the database built below
rom_eval() {
  local name=$1 end=$2
  (cd "$root" && /usr/bin/time -f '%M' -o "$work/$name.rss" "$mastrom" rom eval "$work/db.h5" -q \
     --set drive.duration=1.0 --set drive.ramp=0.05 --set drive.angle_deg=10 --set output.step=1e-3 \
     --set simulation.end_time="$end" --stress-history -o "$work/$name.h5" >"$work/$name.log" 2>&1)
  rm -f "$work/$name.h5"
}
(cd "$root" && "$mastrom" rom build configs/scheme1.toml -q --set interface.elements_axial=1 \
   --set interface.elements_circumferential=6 --param interface.thickness=0.0015:0.0025:2 \
   --modes 6 --backend dense -o "$work/db.h5" >"$work/db.log" 2>&1)

echo "# streaming_memory: peak RSS of simulate against the horizon ($(uptime | sed 's/.*load/load/'))"
printf "%10s %10s %10s | %14s %6s | %14s %6s | %14s %6s | %14s %6s | %14s %6s | %14s %6s\n" \
  "end [s]" "samples" "file [MB]" "streamed [MB]" "ratio" "+estimate [MB]" "ratio" \
  "+stresses [MB]" "ratio" "adapt+ckpt [MB]" "ratio" "fixed+ckpt [MB]" "ratio" "rom eval [MB]" "ratio"
base_s="" base_e="" base_t="" base_c="" base_f="" base_r=""
for end in "${horizons[@]}"; do
  run s "$end" --no-stresses
  run e "$end" --no-stresses --estimate-error
  run t "$end"
  # Adaptive steps (the default), with the stresses, a checkpoint every 5 s.
  run c "$end" --checkpoint-every 5s
  # Fixed 1 ms steps (one per output instant), with the stresses, a checkpoint every 5 s.
  run f "$end" --set simulation.adaptive=false --set simulation.time_step=1e-3 --checkpoint-every 5s
  rom_eval r "$end"
  s=$(cat "$work/s.rss") e=$(cat "$work/e.rss") t=$(cat "$work/t.rss") c=$(cat "$work/c.rss")
  f=$(cat "$work/f.rss") r=$(cat "$work/r.rss")
  : "${base_s:=$s}" "${base_e:=$e}" "${base_t:=$t}" "${base_c:=$c}" "${base_f:=$f}" "${base_r:=$r}"
  samples=$(awk -v e="$end" 'BEGIN { printf "%d", e / 1e-3 + 1 }')
  awk -v h="$end" -v n="$samples" -v b="$(cat "$work/s.bytes")" -v s="$s" -v e="$e" -v t="$t" \
      -v c="$c" -v f="$f" -v r="$r" -v bs="$base_s" -v be="$base_e" -v bt="$base_t" \
      -v bc="$base_c" -v bf="$base_f" -v br="$base_r" 'BEGIN {
    printf "%10g %10d %10.1f | %14.1f %6.2f | %14.1f %6.2f | %14.1f %6.2f | %14.1f %6.2f | %14.1f %6.2f | %14.1f %6.2f\n",
           h, n, b / 1e6, s / 1024, s / bs, e / 1024, e / be, t / 1024, t / bt, c / 1024, c / bc,
           f / 1024, f / bf, r / 1024, r / br }'
done
echo "# target: the streamed, +estimate, +stresses, adapt+ckpt and fixed+ckpt columns' ratios stay 1 (within ~5 %) while the file grows with the horizon"
