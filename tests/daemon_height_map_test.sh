#!/bin/bash
# The daemon receiving a height_map_t on MFP_HEIGHT_MAP over real LCM: plays a log
# (mfp-make-log, as_height_map) with lcm-logplayer into a running mfp-daemon, records the
# replies with lcm-logger and checks every one with mfp-check-replies (one reply per
# request, plans valid on the published regions, malformed height maps counted), and that
# the daemon logged the height map as its map. Multicast stays inside a private network
# namespace (tests/netns_helper.sh); it never sends multicast on the host network.
#
# usage: daemon_height_map_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail

SOURCE_DIR=$(realpath "$1")
BUILD_DIR=$(realpath "$2")

source "$SOURCE_DIR/tests/netns_helper.sh"
mfp_enter_private_namespace "$@"

mfp_start_replay_session mfp_daemon_height_map tests/daemon_height_map_scenario.yaml

lcm-logplayer --lcm-url="$URL" "$WORK/requests.lcmlog"

mfp_wait_for_replies "$SCENARIO" "$CONFIG"

mfp_stop_daemon_and_logger

"$BUILD_DIR/tools/mfp-check-replies" "$WORK/replies.lcmlog" --scenario "$SCENARIO" --config "$CONFIG" \
  || { cat "$WORK/check.txt"; fail "replies do not check"; }
grep -q "height_map_t utime" "$LOG" || fail "the daemon logged no height_map_t map"
grep -q "rejected message on MFP_HEIGHT_MAP" "$LOG" || fail "no malformed height_map_t was rejected"
echo "--- daemon log ---"
cat "$LOG"
echo "PASS: daemon_height_map_test"
