# Sourced by the interrupt tests (interrupt_simulate.sh, interrupt_rom_eval.sh), which define
# fail(). check_incomplete_file H5DUMP FILE T_STOP SAMPLES: FILE is valid HDF5 marked incomplete
# (root attribute complete = 0), its stopped_at_s is T_STOP (the time the one-line message printed),
# and /time has SAMPLES rows and ends at stopped_at_s. Sets rows.
check_incomplete_file() {
  local h5dump=$1 file=$2 t_stop=$3 samples=$4 complete stopped last
  complete=$("$h5dump" -a /complete "$file" 2>&1) || fail "h5dump cannot read the file: $complete"
  echo "$complete" | grep -Eq '\(0\): 0$' || fail "complete is not 0: $complete"
  stopped=$("$h5dump" -a /stopped_at_s -m %.17g "$file" | grep -Eo '\([0-9]+\): [0-9.e+-]+' | cut -d' ' -f2)
  awk -v a="$stopped" -v b="$t_stop" 'BEGIN { d = a - b; exit !(d < 1e-5 * a + 1e-9 && -d < 1e-5 * a + 1e-9) }' ||
    fail "stopped_at_s = $stopped, message says $t_stop"
  rows=$("$h5dump" -H -d /time "$file" | grep -Eo 'DATASPACE +SIMPLE \{ \( [0-9]+' | grep -Eo '[0-9]+$')
  [ "$rows" = "$samples" ] || fail "/time has $rows rows, the message says $samples"
  last=$("$h5dump" -d "/time[$((rows - 1))]" -m %.17g "$file" | grep -Eo '\([0-9]+\): [0-9.e+-]+' | cut -d' ' -f2)
  awk -v a="$last" -v b="$stopped" 'BEGIN { exit !(a == b) }' || fail "/time ends at $last, not at stopped_at_s = $stopped"
}
