#!/usr/bin/env bash
# Ctrl-C on a running `mastrom simulate`: it must stop at its next progress update (every 0.5 % of
# the steps; 10 s allows for a loaded machine), print exactly one line
# "mastrom: error: simulate: interrupted at t = <time> s; no result written", exit 130, and leave
# neither the result nor its temporary file behind.
#
#   interrupt_simulate.sh MASTROM OUT_DIR -- <simulate arguments without -o>
set -u
mastrom=$1 dir=$2
shift 3
rm -rf "$dir" && mkdir -p "$dir" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }

"$mastrom" simulate "$@" -q -o "$dir/run.h5" >"$dir/stdout" 2>"$dir/stderr" &
pid=$!
# Wait until the integration runs (the drive line on stdout is printed just before the time loop).
for _ in $(seq 1 500); do
  grep -q "^  drive " "$dir/stdout" 2>/dev/null && break
  kill -0 "$pid" 2>/dev/null || fail "the run ended before it could be interrupted"
  sleep 0.01
done
sleep 0.3
kill -INT "$pid"
start=$(date +%s.%N)
wait "$pid"
rc=$?
end=$(date +%s.%N)
[ "$rc" -eq 130 ] || fail "exit code $rc, expected 130; stderr: $(cat "$dir/stderr")"
awk -v a="$start" -v b="$end" 'BEGIN { exit !(b - a < 10.0) }' || fail "took more than 10 s to stop"
[ "$(wc -l <"$dir/stderr")" -eq 1 ] || fail "stderr is not one line: $(cat "$dir/stderr")"
grep -Eq '^mastrom: error: simulate: interrupted at t = [0-9.e+-]+ s; no result written$' \
  "$dir/stderr" || fail "unexpected message: $(cat "$dir/stderr")"
leftovers=$(ls "$dir" | grep -v -e '^stdout$' -e '^stderr$')
[ -z "$leftovers" ] || fail "files left behind: $leftovers"
echo "ok: $(cat "$dir/stderr")"
