#!/usr/bin/env bash
# SIGINT or SIGTERM on a running `mastrom rom eval -o FILE` (cli/rom_eval_output.hpp): the file's
# series is written a block of 4096 instants at a time and the signal is seen between blocks, so
# the command must print exactly one line "mastrom: error: rom eval: interrupted at t = <time> s;
# wrote the <N> output samples up to it to <file>, marked incomplete (root attribute complete =
# 0)", exit 130, and leave a valid HDF5 file under the final name whose root attribute complete is
# 0, whose stopped_at_s is the time printed, whose /time ends there with N rows (a whole number of
# blocks), whose stress history has as many rows — and no temporary file. The database: coarse
# Scheme 1 (1 x 6 ring), two thicknesses, 6 modes; the evaluation: 160 s at 1 ms outputs with
# --stress-history (160 001 samples, 40 blocks), so the signal lands while it computes or writes.
#
#   interrupt_rom_eval.sh MASTROM H5DUMP INT|TERM OUT_DIR
set -u
mastrom=$1 h5dump=$2 signal=$3 dir=$4
rm -rf "$dir" && mkdir -p "$dir" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }
# shellcheck source=incomplete_file.sh
source "$(dirname "${BASH_SOURCE[0]}")/incomplete_file.sh"

"$mastrom" rom build configs/scheme1.toml -q --set interface.elements_axial=1 \
  --set interface.elements_circumferential=6 --param interface.thickness=0.0015:0.0025:2 \
  --modes 6 --backend dense -o "$dir/db.h5" >"$dir/build.log" 2>&1 || fail "rom build failed"

"$mastrom" rom eval "$dir/db.h5" -q --set drive.duration=1.0 --set drive.ramp=0.05 \
  --set drive.angle_deg=10 --set output.step=1e-3 --set simulation.end_time=160 \
  --stress-history -o "$dir/eval.h5" >"$dir/stdout" 2>"$dir/stderr" &
pid=$!
# Signal once the handlers are installed (main() does it before parsing the command line): the
# process then catches SIGTERM (bit 15 of SigCgt in /proc/PID/status). The database read, the
# interpolation, the evaluation and the 40 blocks take longer than the signal's delivery.
for _ in $(seq 1 1000); do
  caught=$(awk '/^SigCgt:/ { print $2 }' "/proc/$pid/status" 2>/dev/null) || break
  [ -n "$caught" ] && (( (16#$caught >> 14) & 1 )) && break
  sleep 0.005
done
kill -"$signal" "$pid"
wait "$pid"
rc=$?
[ "$rc" -eq 130 ] || fail "exit code $rc, expected 130 (0: the signal came after the last block); stderr: $(cat "$dir/stderr")"
[ "$(wc -l <"$dir/stderr")" -eq 1 ] || fail "stderr is not one line: $(cat "$dir/stderr")"
line=$(cat "$dir/stderr")
re='^mastrom: error: rom eval: interrupted at t = ([0-9.e+-]+) s; wrote the ([0-9]+) output samples up to it to .*eval\.h5, marked incomplete \(root attribute complete = 0\)$'
[[ $line =~ $re ]] || fail "unexpected message: $line"
t_stop=${BASH_REMATCH[1]} samples=${BASH_REMATCH[2]}
[ $((samples % 4096)) -eq 0 ] || fail "$samples samples: not a whole number of blocks"
leftovers=$(ls "$dir" | grep -v -e '^stdout$' -e '^stderr$' -e '^eval\.h5$' -e '^db\.h5$' -e '^build\.log$')
[ -z "$leftovers" ] || fail "files left behind: $leftovers"
check_incomplete_file "$h5dump" "$dir/eval.h5" "$t_stop" "$samples"
n=$("$h5dump" -H -d /interfaces/1/max_von_mises "$dir/eval.h5" | grep -Eo 'DATASPACE +SIMPLE \{ \( [0-9]+' | grep -Eo '[0-9]+$')
[ "$n" = "$rows" ] || fail "/interfaces/1/max_von_mises has '$n' rows, /time has $rows"
"$h5dump" -a /metrics/peak_rel_end_angular_acceleration "$dir/eval.h5" >/dev/null || fail "no metrics"
echo "ok: $line"
