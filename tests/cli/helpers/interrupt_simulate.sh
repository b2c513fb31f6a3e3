#!/usr/bin/env bash
# SIGINT (Ctrl-C) or SIGTERM on a running `mastrom simulate`: it must stop within one step of the
# signal (10 s allows for a loaded machine), print exactly one line
# "mastrom: error: simulate: interrupted at t = <time> s; wrote the <N> output samples computed to
# <file>, marked incomplete (root attribute complete = 0)", exit 130, and leave a valid HDF5 file
# under the final name whose root attribute complete is 0, whose stopped_at_s is the time printed,
# and whose /time ends there — and no temporary file. Unless the arguments say --no-stresses, the
# interface stress histories (streamed beside the series) reach the same last instant: every
# /interfaces/K dataset that grows with the run has as many rows as /time.
#
#   interrupt_simulate.sh MASTROM H5DUMP INT|TERM OUT_DIR -- <simulate arguments without -o>
set -u
mastrom=$1 h5dump=$2 signal=$3 dir=$4
shift 5
rm -rf "$dir" && mkdir -p "$dir" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }
# shellcheck source=incomplete_file.sh
source "$(dirname "${BASH_SOURCE[0]}")/incomplete_file.sh"

"$mastrom" simulate "$@" -q -o "$dir/run.h5" >"$dir/stdout" 2>"$dir/stderr" &
pid=$!
# Wait until the integration runs (the drive line on stdout is printed just before the time loop).
for _ in $(seq 1 500); do
  grep -q "^  drive " "$dir/stdout" 2>/dev/null && break
  kill -0 "$pid" 2>/dev/null || fail "the run ended before it could be interrupted"
  sleep 0.01
done
sleep 0.3
kill -"$signal" "$pid"
start=$(date +%s.%N)
wait "$pid"
rc=$?
end=$(date +%s.%N)
[ "$rc" -eq 130 ] || fail "exit code $rc, expected 130; stderr: $(cat "$dir/stderr")"
awk -v a="$start" -v b="$end" 'BEGIN { exit !(b - a < 10.0) }' || fail "took more than 10 s to stop"
[ "$(wc -l <"$dir/stderr")" -eq 1 ] || fail "stderr is not one line: $(cat "$dir/stderr")"
line=$(cat "$dir/stderr")
re='^mastrom: error: simulate: interrupted at t = ([0-9.e+-]+) s; wrote the ([0-9]+) output samples computed to .*run\.h5, marked incomplete \(root attribute complete = 0\)$'
[[ $line =~ $re ]] || fail "unexpected message: $line"
t_stop=${BASH_REMATCH[1]} samples=${BASH_REMATCH[2]}
leftovers=$(ls "$dir" | grep -v -e '^stdout$' -e '^stderr$' -e '^run\.h5$' -e '^run\.xdmf$' -e '^run\.checkpoint\.h5$')
[ -z "$leftovers" ] || fail "files left behind: $leftovers"
[ -f "$dir/run.h5" ] || fail "no result file"
# Valid HDF5, marked incomplete, stopped where the message says, with that many samples.
check_incomplete_file "$h5dump" "$dir/run.h5" "$t_stop" "$samples"
"$h5dump" -a /metrics/peak_rel_end_angular_acceleration "$dir/run.h5" >/dev/null ||
  fail "no metrics of the samples computed"
case " $* " in
  *" --no-stresses "*) ;;
  *)
    for d in max_von_mises base/force base/bending_moment tip/moment tip/axial_force; do
      n=$("$h5dump" -H -d "/interfaces/1/$d" "$dir/run.h5" | grep -Eo 'DATASPACE +SIMPLE \{ \( [0-9]+' | grep -Eo '[0-9]+$')
      [ "$n" = "$rows" ] || fail "/interfaces/1/$d has '$n' rows, /time has $rows"
    done
    "$h5dump" -a /interfaces/1/peak/von_mises_pa "$dir/run.h5" >/dev/null ||
      fail "no interface stress peak of the samples computed"
    ;;
esac
echo "ok: $line"
