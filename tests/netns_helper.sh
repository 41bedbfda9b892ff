# Sourced by the tests that run mfp-daemon over real LCM multicast. They must never send
# multicast on the host network, so they run inside a private network namespace:
#
#   source "$SOURCE_DIR/tests/netns_helper.sh"
#   mfp_enter_private_namespace "$@"     # the script's own arguments, unchanged
#
# Outside the namespace it checks the tools, then runs the calling script again under
# `unshare -n` with the same arguments plus the marker --in-namespace (the marker is what
# stops the next run from doing the same again). Inside (the last argument is the
# marker) it refuses to go on unless lo is the only interface, and sets lo up with
# multicast and a route for 224.0.0.0/4. It fails loudly, never skips, when the
# namespace cannot be made (unshare -n needs root or CAP_SYS_ADMIN).
#
# Inside, `mfp_test_workspace NAME` gives the script what each of them needs: WORK, a
# fresh folder; DAEMON_PID, LOGGER_PID, PLAYER_PID, the background processes it starts
# (killed on exit; set one back to "" once it has been waited for); fail MESSAGE, which
# prints the message and the daemon log the script names in LOG, then exits 1. On exit
# the processes are killed and WORK removed. mfp_start_logger and mfp_start_daemon start
# the two background processes most scripts need (BUILD_DIR and URL set by the script).

MFP_NAMESPACE_MARKER="--in-namespace"

mfp_enter_private_namespace() {
  local last="${!#}"
  if [ "$#" -eq 0 ] || [ "$last" != "$MFP_NAMESPACE_MARKER" ]; then
    local tool
    for tool in unshare ip lcm-logger lcm-logplayer; do
      command -v "$tool" >/dev/null || { echo "FAIL: $tool not found (tools/debian-packages.txt)"; exit 1; }
    done
    if ! unshare -n true 2>/dev/null; then
      echo "FAIL: cannot create a network namespace (unshare -n needs root or CAP_SYS_ADMIN);"
      echo "      this test never falls back to the host network."
      exit 1
    fi
    exec unshare -n "$0" "$@" "$MFP_NAMESPACE_MARKER"
  fi
  local interfaces
  interfaces=$(ip -o link show | awk -F': ' '{print $2}' | sed 's/@.*//')
  if [ "$interfaces" != "lo" ]; then
    echo "FAIL: expected only lo in the namespace, found: $interfaces"
    exit 1
  fi
  ip link set lo up
  ip link set lo multicast on
  ip route add 224.0.0.0/4 dev lo
}

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
  rm -rf "$WORK"
}

fail() {
  echo "FAIL: $*"
  [ -n "$LOG" ] && [ -f "$LOG" ] && { echo "--- daemon log ---"; cat "$LOG" || true; }
  exit 1
}

mfp_start_logger() {  # OUT: records the daemon's replies, regions and status from $URL
  lcm-logger --quiet --lcm-url="$URL" --channel='MFP_PLAN|MFP_REGIONS|MFP_STATUS' --flush-interval=50 \
    --force "$1" &
  LOGGER_PID=$!
}

mfp_start_daemon() {  # LOG ARGS...: mfp-daemon with ARGS, its log in LOG; waits until it has started
  LOG="$1"
  shift
  "$BUILD_DIR/tools/mfp-daemon" "$@" 2>"$LOG" &
  DAEMON_PID=$!
  for _ in $(seq 1 300); do
    grep -q "started:" "$LOG" && return 0
    kill -0 "$DAEMON_PID" 2>/dev/null || fail "mfp-daemon exited during start-up"
    sleep 0.1
  done
  fail "mfp-daemon did not start within 30 s"
}

mfp_wait_for_replies() {  # SCENARIO CONFIG: until mfp-check-replies stops answering 3 (every
  # request replied) or 240 s pass; then one more heartbeat so the last status counts them all
  local deadline=$((SECONDS + 240)) check
  while :; do
    check=0
    "$BUILD_DIR/tools/mfp-check-replies" "$WORK/replies.lcmlog" --scenario "$1" \
      --config "$2" >"$WORK/check.txt" 2>&1 || check=$?
    [ "$check" -ne 3 ] && break
    kill -0 "$DAEMON_PID" 2>/dev/null || fail "mfp-daemon died"
    if [ $SECONDS -ge $deadline ]; then cat "$WORK/check.txt"; fail "replies incomplete after 240 s"; fi
    sleep 1
  done
  sleep 1
}

mfp_stop_daemon_and_logger() {  # SIGTERM must end the daemon with status 0; the logger is closed
  kill -TERM "$DAEMON_PID"
  local status=0
  wait "$DAEMON_PID" || status=$?
  DAEMON_PID=""
  [ "$status" -eq 0 ] || fail "mfp-daemon exited with $status on SIGTERM"
  kill -INT "$LOGGER_PID"; wait "$LOGGER_PID" || true; LOGGER_PID=""
}
