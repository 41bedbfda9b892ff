#!/bin/bash
# The daemon over real LCM: plays a log with lcm-logplayer into a running mfp-daemon,
# records the replies with lcm-logger and checks every one with mfp-check-replies.
# Multicast stays inside a private network namespace this script makes (unshare -n,
# only lo, with a multicast route); it never sends multicast on the host network.
# It fails loudly (never skips) when the namespace cannot be made.
#
# usage: daemon_replay_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail

SOURCE_DIR=$(realpath "$1")
BUILD_DIR=$(realpath "$2")

# Runs this script again inside a private network namespace (tests/netns_helper.sh).
source "$SOURCE_DIR/tests/netns_helper.sh"
mfp_enter_private_namespace "$@"

mfp_start_replay_session mfp_daemon_replay tests/daemon_replay_scenario.yaml

# SIGHUP reloads the config while it runs.
kill -HUP "$DAEMON_PID"

lcm-logplayer --lcm-url="$URL" "$WORK/requests.lcmlog"

mfp_wait_for_replies "$SCENARIO" "$CONFIG"

# SIGTERM: a clean exit with status 0.
mfp_stop_daemon_and_logger

# The final check, on the complete log.
"$BUILD_DIR/tools/mfp-check-replies" "$WORK/replies.lcmlog" --scenario "$SCENARIO" --config "$CONFIG" \
  || fail "replies do not check"
grep -q "SIGHUP: configuration reloaded" "$WORK/daemon.log" || fail "no reload logged after SIGHUP"
grep -q "SIGTERM: stopping" "$WORK/daemon.log" || fail "no clean stop logged"
grep -Eq '^[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9:.]+Z mfp-daemon: ' "$WORK/daemon.log" \
  || fail "daemon log lines carry no timestamps"
echo "--- daemon log ---"
cat "$WORK/daemon.log"

# SIGINT: also a clean exit with status 0.
mfp_start_daemon "$WORK/daemon2.log" --config "$CONFIG" --lcm-url "$URL"
kill -INT "$DAEMON_PID"
status=0
wait "$DAEMON_PID" || status=$?
DAEMON_PID=""
[ "$status" -eq 0 ] || { cat "$WORK/daemon2.log"; fail "mfp-daemon exited with $status on SIGINT"; }
grep -q "SIGINT: stopping" "$WORK/daemon2.log" || fail "no clean stop logged after SIGINT"
echo "PASS"
