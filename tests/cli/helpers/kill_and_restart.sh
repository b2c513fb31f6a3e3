#!/usr/bin/env bash
# Crash safety of `mastrom simulate --checkpoint-every`: a run killed with SIGKILL after
# it wrote a checkpoint leaves no result file under the final name, and `--restart` from the
# checkpoint it left finishes with datasets equal, value for value, to an uninterrupted run's. The
# outputs are streamed (fixed and adaptive steps): the killed run leaves the file it was writing under its
# temporary name, which the restart rebuilds its result from and then removes; a run killed twice
# leaves no temporary file behind either. A run stopped by SIGTERM leaves its result marked
# incomplete, and a restart from its checkpoint rebuilds from that.
#
#   kill_and_restart.sh MASTROM H5DIFF OUT_DIR -- <simulate arguments without -o>
set -u
mastrom=$1 h5diff=$2 dir=$3
shift 4
rm -rf "$dir" && mkdir -p "$dir" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }
# signal_after_checkpoint SIGNAL OUT ARGS...: run with a checkpoint every 40 steps to $ck
# ($dir/ck.h5 unless set), send SIGNAL 0.1 s after the first checkpoint appeared (so it may land
# anywhere, also inside a later checkpoint write) and set rc to the exit code.
signal_after_checkpoint() {
  local signal=$1 out=$2 ck=${ck:-$dir/ck.h5}
  shift 2
  rm -f "$ck"
  "$mastrom" simulate "$@" -o "$out" --checkpoint-every 0.04s --checkpoint "$ck" &
  local pid=$!
  for _ in $(seq 1 6000); do
    [ -e "$ck" ] && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.01
  done
  [ -e "$ck" ] || { kill -9 "$pid" 2>/dev/null; fail "no checkpoint appeared"; }
  sleep 0.1
  kill -"$signal" "$pid" 2>/dev/null
  wait "$pid"
  rc=$?
}

# 1. The uninterrupted reference; it checkpoints too (every 700 steps) and must delete its
#    checkpoint.
"$mastrom" simulate "$@" -o "$dir/full.h5" --checkpoint-every 700 || fail "reference run failed"
[ -e "$dir/full.checkpoint.h5" ] && fail "a finished run left its checkpoint behind"

# 2. The same run with a checkpoint every 40 steps, killed 0.1 s after its first checkpoint. The
#    interval is given in simulated seconds (0.04 s = 40 steps of 1 ms), the form a user plans with.
signal_after_checkpoint KILL "$dir/killed.h5" "$@"
[ "$rc" -eq 137 ] || fail "the run was not killed mid-run (exit $rc): make it longer"
[ -e "$dir/killed.h5" ] && fail "the killed run left a result file under the final name"
streaming=0
ls "$dir"/killed.h5.tmp.* >/dev/null 2>&1 && streaming=1

# 3. Continue from whatever complete checkpoint the kill left.
out=$("$mastrom" simulate "$@" --restart "$dir/ck.h5" -o "$dir/restarted.h5") ||
  fail "restart failed"
echo "$out"
echo "$out" | grep -q "restarting from .* at step [1-9]" || fail "restart did not report its step"
ls "$dir"/killed.h5.tmp.* >/dev/null 2>&1 &&
  fail "the restart left the killed run's file behind: $(ls "$dir"/killed.h5.tmp.*)"

# 4. Every dataset of the result equals the uninterrupted run's.
same_as_full() {
  for d in /time /drive/angle /drive/rate /drive/acceleration /end/angular_acceleration \
           /end/relative_angular_acceleration /end/position /end/acceleration /joint/force \
           /joint/torque /solver/newton_iterations /solver/constraint_residual; do
    "$h5diff" "$dir/full.h5" "$1" "$d" || fail "$d of $1 differs from the uninterrupted run"
  done
  echo "$1 equals the uninterrupted run in every dataset"
}
same_as_full "$dir/restarted.h5"
[ "$streaming" -eq 1 ] || exit 0

# 5a. Killed twice: the first restart checkpoints too (to ck2.h5) and is killed after its first
#     checkpoint; the second restarts from ck2.h5. The first leg's temporary file is gone once the
#     second leg's checkpoint names its own; the last leg removes the second's: none is left.
signal_after_checkpoint KILL "$dir/twice.h5" "$@"
[ "$rc" -eq 137 ] || fail "the first leg was not killed mid-run (exit $rc)"
ck="$dir/ck2.h5" signal_after_checkpoint KILL "$dir/twice.h5" "$@" --restart "$dir/ck.h5"
[ "$rc" -eq 137 ] || fail "the second leg was not killed mid-run (exit $rc)"
[ "$(ls "$dir"/twice.h5.tmp.* 2>/dev/null | wc -l)" -eq 1 ] ||
  fail "after the second leg's checkpoint the first leg's file is still there: $(ls "$dir"/twice.h5.tmp.*)"
"$mastrom" simulate "$@" --restart "$dir/ck2.h5" -o "$dir/twice.h5" >/dev/null ||
  fail "second restart failed"
ls "$dir"/twice.h5.tmp.* >/dev/null 2>&1 &&
  fail "a run restarted twice left a temporary file behind: $(ls "$dir"/twice.h5.tmp.*)"
same_as_full "$dir/twice.h5"

# 5. Streamed: the same run stopped by SIGTERM after its first checkpoint writes its result marked
#    incomplete (exit 130); a restart from its checkpoint rebuilds the outputs from that file.
signal_after_checkpoint TERM "$dir/termed.h5" "$@"
[ "$rc" -eq 130 ] || fail "the SIGTERM run did not stop as interrupted (exit $rc)"
[ -e "$dir/termed.h5" ] || fail "the SIGTERM run left no result"
out=$("$mastrom" simulate "$@" --restart "$dir/ck.h5" -o "$dir/termed_restarted.h5") ||
  fail "restart after SIGTERM failed"
same_as_full "$dir/termed_restarted.h5"
