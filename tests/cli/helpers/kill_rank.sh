#!/usr/bin/env bash
# A killed MPI rank (failure modes): `mpirun -n 2 mastrom …` in which rank 1 is killed with
# SIGKILL mid-run must end with a non-zero exit code, say which rank died, and leave no result file.
#
#   kill_rank.sh MPIEXEC OUTPUT_FILE -- mastrom <arguments writing OUTPUT_FILE>
set -u
mpiexec=$1 output=$2
shift 3
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -f "$output" "$output".tmp.*
err=$(mktemp)
"$mpiexec" -n 2 "$@" 2>"$err" &
launcher=$!
# Rank 1 is the child of mpirun whose environment says so (Open MPI / PMIx).
victim=
for _ in $(seq 1 3000); do
  for child in $(pgrep -P "$launcher" 2>/dev/null); do
    if tr '\0' '\n' < "/proc/$child/environ" 2>/dev/null |
        grep -qE '^(OMPI_COMM_WORLD_RANK|PMIX_RANK|PMI_RANK)=1$'; then
      victim=$child
    fi
  done
  [ -n "$victim" ] && break
  kill -0 "$launcher" 2>/dev/null || break
  sleep 0.01
done
[ -n "$victim" ] || { kill "$launcher" 2>/dev/null; fail "rank 1 was not found"; }
sleep 1  # let the ranks start working
kill -9 "$victim"
wait "$launcher"
rc=$?
cat "$err" >&2
echo "exit code: $rc"
[ "$rc" -ne 0 ] || fail "mpirun exited 0 after a rank was killed"
grep -qiE "signal 9|killed" "$err" || fail "stderr does not say that a rank was killed"
ls "$output" "$output".tmp.* >/dev/null 2>&1 && fail "a result file was left: $(ls "$output"*)"
rm -f "$err"
echo "killed rank: exit $rc, no result file"
