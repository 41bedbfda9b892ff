#!/bin/bash
# mfp-daemon under signals, over real LCM inside a private network namespace this script
# makes (unshare -n, only lo, with a multicast route; never the host network):
#  1. SIGHUP with a config that lists a robot YAML whose key is a sequence: the reload
#     fails, is logged, and the daemon goes on with the previous configuration.
#  2. SIGTERM while a map is being read (seconds of extraction): exit 0 within 0.5 s;
#     requests sent meanwhile were answered (no_map) without waiting for the map.
#  3. SIGTERM while a 20 s plan runs with a request queued behind it: exit 0 within
#     0.5 s, both requests answered (dropped).
#  4. SIGHUP onto a config that adds a robot derived from a 16-leg URDF (seconds of
#     derivation), then SIGTERM during that reload: exit 0 within 0.5 s.
#  5. SIGTERM during start-up while that robot is derived (before the daemon takes
#     messages): exit 0 within 0.5 s, the start-up abandoned.
# Replies are recorded with lcm-logger and checked with mfp-check-replies.
#
# usage: daemon_signals_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail

SOURCE_DIR=$(realpath "$1")
BUILD_DIR=$(realpath "$2")
DATA="$SOURCE_DIR/tests/data/daemon_signals"

# Runs this script again inside a private network namespace (tests/netns_helper.sh).
source "$SOURCE_DIR/tests/netns_helper.sh"
mfp_enter_private_namespace "$@"
source "$SOURCE_DIR/tests/daemon_signal_helpers.sh"

mfp_test_workspace mfp_daemon_signals

cp "$DATA"/*.yaml "$WORK/"
"$BUILD_DIR/tools/mfp-terrain" "$WORK/fine_map.yaml" --out "$WORK/fine_map.bt" >/dev/null

stop_logger() {
  sleep 0.5
  kill -INT "$LOGGER_PID"; wait "$LOGGER_PID" || true; LOGGER_PID=""
}

write_config() { mfp_write_daemon_config "" "$@"; }  # extra robot files...

# SIGTERM, then the time to exit [ms]; the exit status must be 0.
terminate() {
  mfp_sigterm_daemon
  [ "$EXIT_STATUS" -eq 0 ] || fail "mfp-daemon exited with $EXIT_STATUS on SIGTERM"
  echo "SIGTERM to exit: $EXIT_MS ms"
}

# --- 1 and 2: a failed reload, then SIGTERM during a map extraction ---
write_config
"$BUILD_DIR/tools/mfp-make-log" "$WORK/during_extraction.yaml" --config "$WORK/daemon.yaml" \
  --out "$WORK/extraction.lcmlog"
mfp_start_logger "$WORK/extraction_replies.lcmlog"
mfp_start_daemon "$WORK/daemon1.log" --config "$WORK/daemon.yaml"
write_config "$WORK/bad_robot.yaml"
kill -HUP "$DAEMON_PID"
mfp_wait_for_log "SIGHUP: reload failed, keeping the previous configuration" 20
kill -0 "$DAEMON_PID" 2>/dev/null || fail "mfp-daemon died on a failed reload"
grep "SIGHUP: reload failed" "$LOG"
write_config  # the good one again, for mfp-check-replies

lcm-logplayer --lcm-url="$URL" "$WORK/extraction.lcmlog" &
PLAYER_PID=$!
wait "$PLAYER_PID"; PLAYER_PID=""
mfp_wait_for_log "request 2 rejected (no_map)" 10
sleep 0.3
grep -q "map accepted" "$LOG" && fail "the map was read before SIGTERM: make fine_map.yaml slower"
terminate
[ "$EXIT_MS" -lt 500 ] || fail "exit took $EXIT_MS ms after SIGTERM during a map extraction"
grep -q "map extraction abandoned" "$LOG" || fail "no extraction in progress at SIGTERM"
grep -q "request 1 rejected (no_map)" "$LOG" || fail "request 1 was not answered"
grep -q "publish failed\|could not be published" "$LOG" && fail "a reply was not published"
stop_logger

# --- 3: SIGTERM during a plan, a request queued behind it ---
write_config
"$BUILD_DIR/tools/mfp-make-log" "$WORK/during_plan.yaml" --config "$WORK/daemon.yaml" \
  --out "$WORK/plan.lcmlog"
mfp_start_logger "$WORK/plan_replies.lcmlog"
mfp_start_daemon "$WORK/daemon2.log" --config "$WORK/daemon.yaml"
lcm-logplayer --lcm-url="$URL" "$WORK/plan.lcmlog" &
PLAYER_PID=$!
wait "$PLAYER_PID"; PLAYER_PID=""
sleep 0.5
grep -q "request 10 planned" "$LOG" && fail "the 20 s plan ended before SIGTERM"
terminate
[ "$EXIT_MS" -lt 500 ] || fail "exit took $EXIT_MS ms after SIGTERM during a plan"
grep -q "request 10 planned: dropped" "$LOG" || fail "the plan in progress was not answered"
stop_logger
"$BUILD_DIR/tools/mfp-check-replies" "$WORK/plan_replies.lcmlog" \
  --scenario "$WORK/during_plan.yaml" --config "$WORK/daemon.yaml" \
  || fail "replies to the stopped requests do not check"

# --- 4: SIGTERM during a reload onto a robot that takes seconds to derive ---
python3 "$SOURCE_DIR/tests/sixteen_leg_urdf.py" "$SOURCE_DIR/tests/data/robots/octopod.urdf" "$WORK/sixteen_legs.urdf"
write_config
mfp_start_daemon "$WORK/daemon3.log" --config "$WORK/daemon.yaml"
write_config "$WORK/sixteen_legs.urdf"
kill -HUP "$DAEMON_PID"
mfp_wait_for_log "SIGHUP: reloading" 10
sleep 0.2
grep -q "SIGHUP: configuration reloaded\|SIGHUP: reload failed" "$LOG" \
  && fail "the reload ended before SIGTERM: make the robot slower to derive"
terminate
[ "$EXIT_MS" -lt 500 ] || fail "exit took $EXIT_MS ms after SIGTERM during a reload"
grep -q "the reload in progress is abandoned" "$LOG" || fail "no reload in progress at SIGTERM"

# --- 5: SIGTERM during start-up, the 16-leg robot being derived ---
LOG="$WORK/daemon4.log"
"$BUILD_DIR/tools/mfp-daemon" --config "$WORK/daemon.yaml" 2>"$LOG" &
DAEMON_PID=$!
sleep 1
grep -q "started:" "$LOG" && fail "the start-up ended before SIGTERM: make the robot slower to derive"
terminate
[ "$EXIT_MS" -lt 500 ] || fail "exit took $EXIT_MS ms after SIGTERM during start-up"
grep -q "SIGTERM: stopping during start-up" "$LOG" || fail "no start-up in progress at SIGTERM"

echo "--- daemon log ---"
cat "$LOG"
echo "PASS"
