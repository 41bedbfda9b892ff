# Sourced (after tests/netns_helper.sh) by the scripts that send mfp-daemon signals:
# tests/daemon_signals_test.sh, which judges, and bench/sigterm_states.sh, which prints.
# They need WORK, BUILD_DIR/SOURCE_DIR, URL and fail (tests/test_workspace.sh); LOG is the
# daemon log the script is watching and DAEMON_PID the daemon.

# $WORK/daemon.yaml: the hexapod alone (each tool derives it once), plus EXTRA robot files;
# 4 n-step windows, which plan until their time limit; no supersession, so a second
# request of the same robot stays queued behind the first. INITIAL_MAP empty: none.
mfp_write_daemon_config() {  # INITIAL_MAP [EXTRA_ROBOT...]
  local initial_map="$1" extra
  shift
  {
    echo "lcm_url: \"$URL\""
    [ -z "$initial_map" ] || echo "initial_map: \"$initial_map\""
    echo "robots:"
    echo "  - $SOURCE_DIR/config/robots/hexapod.yaml"
    for extra in "$@"; do echo "  - $extra"; done
    echo "default_robot: hexapod"
    echo "limits:"
    echo "  supersede_same_robot: false"
    echo "planner:"
    echo "  window: 24"
  } >"$WORK/daemon.yaml"
}

mfp_wait_for_log() {  # PATTERN SECONDS: until PATTERN is in $LOG, else fail
  local _
  for _ in $(seq 1 $(( $2 * 20 ))); do
    grep -q "$1" "$LOG" && return 0
    sleep 0.05
  done
  fail "no '$1' in the daemon log within $2 s"
}

# SIGTERM to the daemon and wait for it: EXIT_MS, the time to exit [ms], and EXIT_STATUS.
mfp_sigterm_daemon() {
  local t0 t1
  EXIT_STATUS=0
  t0=$(date +%s%N)
  kill -TERM "$DAEMON_PID"
  wait "$DAEMON_PID" || EXIT_STATUS=$?
  t1=$(date +%s%N)
  DAEMON_PID=""
  EXIT_MS=$(( (t1 - t0) / 1000000 ))
}
