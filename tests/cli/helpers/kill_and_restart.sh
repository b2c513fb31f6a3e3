#!/usr/bin/env bash
# Crash safety of `mastrom simulate --checkpoint-every`: a run killed with SIGKILL after
# it wrote a checkpoint leaves no result file, and `--restart` from the checkpoint it left finishes
# with datasets equal, value for value, to an uninterrupted run's.
#
#   kill_and_restart.sh MASTROM H5DIFF OUT_DIR -- <simulate arguments without -o>
set -u
mastrom=$1 h5diff=$2 dir=$3
shift 4
rm -rf "$dir" && mkdir -p "$dir" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }

# 1. The uninterrupted reference; it checkpoints too (every 700 steps) and must delete its
#    checkpoint. (Every checkpoint holds the whole series so far: a short interval over a long run
#    costs time quadratic in its length.)
"$mastrom" simulate "$@" -o "$dir/full.h5" --checkpoint-every 700 || fail "reference run failed"
[ -e "$dir/full.checkpoint.h5" ] && fail "a finished run left its checkpoint behind"

# 2. The same run with a checkpoint every 40 steps, killed 0.1 s after its first checkpoint, so the
#    kill may land anywhere, also inside a later checkpoint write. The interval is given in
#    simulated seconds (0.04 s = 40 steps of 1 ms), the form a user plans with.
"$mastrom" simulate "$@" -o "$dir/killed.h5" --checkpoint-every 0.04s --checkpoint "$dir/ck.h5" &
pid=$!
for _ in $(seq 1 6000); do
  [ -e "$dir/ck.h5" ] && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.01
done
[ -e "$dir/ck.h5" ] || { kill -9 "$pid" 2>/dev/null; fail "no checkpoint appeared"; }
sleep 0.1
kill -9 "$pid" 2>/dev/null
wait "$pid"
rc=$?
[ "$rc" -eq 137 ] || fail "the run was not killed mid-run (exit $rc): make it longer"
ls "$dir"/killed.h5* >/dev/null 2>&1 && fail "the killed run left a result file: $(ls "$dir"/killed.h5*)"

# 3. Continue from whatever complete checkpoint the kill left.
out=$("$mastrom" simulate "$@" --restart "$dir/ck.h5" -o "$dir/restarted.h5") ||
  fail "restart failed"
echo "$out"
echo "$out" | grep -q "restarting from .* at step [1-9]" || fail "restart did not report its step"

# 4. Every dataset of the result equals the uninterrupted run's.
for d in /time /drive/angle /drive/rate /drive/acceleration /end/angular_acceleration \
         /end/relative_angular_acceleration /end/position /end/acceleration /joint/force \
         /joint/torque /solver/newton_iterations /solver/constraint_residual; do
  "$h5diff" "$dir/full.h5" "$dir/restarted.h5" "$d" || fail "$d differs from the uninterrupted run"
done
echo "restarted run equals the uninterrupted run in every dataset"
