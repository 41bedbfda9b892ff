# Sourced by the shell tests: `mfp_test_workspace NAME` makes WORK, a fresh folder named
# after NAME, removed on exit (kept, and named, when MFP_TEST_KEEP is set); DAEMON_PID,
# LOGGER_PID, PLAYER_PID, background processes a script starts (killed on exit; set one
# back to "" once it has been waited for); `fail MESSAGE` prints the message and the
# daemon log the script names in LOG (if any), then exits 1.

mfp_test_workspace() {  # NAME: the work folder's prefix
  WORK=$(mktemp -d "${TMPDIR:-/tmp}/$1.XXXXXX")
  DAEMON_PID=""
  LOGGER_PID=""
  PLAYER_PID=""
  LOG=""
  trap mfp_test_cleanup EXIT
}

mfp_test_cleanup() {
  local pid
  for pid in "$DAEMON_PID" "$LOGGER_PID" "$PLAYER_PID"; do
    [ -n "$pid" ] && kill -KILL "$pid" 2>/dev/null || true
  done
  if [ -n "${MFP_TEST_KEEP:-}" ]; then echo "keeping $WORK"; else rm -rf "$WORK"; fi
}

fail() {
  echo "FAIL: $*"
  [ -n "$LOG" ] && [ -f "$LOG" ] && { echo "--- daemon log ---"; cat "$LOG" || true; }
  exit 1
}
