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
# Inside, `mfp_test_workspace NAME` (tests/test_workspace.sh) gives the script a fresh
# WORK folder, `fail`, and the background processes' PIDs killed on exit.
# mfp_start_logger and mfp_start_daemon start the two background processes most scripts
# need (BUILD_DIR and URL set by the script); mfp_start_replay_session does the whole
# set-up of a log replayed into a running daemon.

MFP_NAMESPACE_MARKER="--in-namespace"
# The LCM URL inside the namespace (ttl=0: never past this host); a script may set its own.
: "${URL:=udpm://239.255.76.67:7667?ttl=0}"

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

source "$(dirname "${BASH_SOURCE[0]}")/test_workspace.sh"

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

mfp_start_replay_session() {  # NAME SCENARIO [CONFIG]: SCENARIO and CONFIG (default
  # config/daemon.yaml), both below SOURCE_DIR, set as variables; WORK; the scenario's
  # request log in WORK/requests.lcmlog; the logger recording WORK/replies.lcmlog; the
  # daemon on $URL with CONFIG, its log in WORK/daemon.log (LOG)
  SCENARIO="$SOURCE_DIR/$2"
  CONFIG="$SOURCE_DIR/${3:-config/daemon.yaml}"
  mfp_test_workspace "$1"
  "$BUILD_DIR/tools/mfp-make-log" "$SCENARIO" --config "$CONFIG" --out "$WORK/requests.lcmlog"
  mfp_start_logger "$WORK/replies.lcmlog"
  mfp_start_daemon "$WORK/daemon.log" --config "$CONFIG" --lcm-url "$URL"
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
