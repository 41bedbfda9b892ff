#!/bin/bash
# mfp-replay over a scenario log (file:// provider, no network): every request answered
# and checked, the same as the live daemon_replay_test.
# usage: daemon_offline_replay_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE_DIR=$(realpath "$1")
BUILD_DIR=$(realpath "$2")
SCENARIO="$SOURCE_DIR/tests/daemon_replay_scenario.yaml"
CONFIG="$SOURCE_DIR/config/daemon.yaml"
source "$SOURCE_DIR/tests/test_workspace.sh"
mfp_test_workspace mfp_offline_replay

"$BUILD_DIR/tools/mfp-make-log" "$SCENARIO" --config "$CONFIG" --out "$WORK/requests.lcmlog"
"$BUILD_DIR/tools/mfp-replay" "$WORK/requests.lcmlog" --config "$CONFIG" --out "$WORK/replies.lcmlog"
"$BUILD_DIR/tools/mfp-check-replies" "$WORK/replies.lcmlog" --scenario "$SCENARIO" --config "$CONFIG"

# A log whose event claims 2^31 - 1 bytes (crashed inside liblcm's reader): exit 2, the
# message names the event and the claim; the valid events before it were replayed.
cp "$WORK/requests.lcmlog" "$WORK/hostile.lcmlog"
printf '\xed\xa1\xda\x01\0\0\0\0\0\0\0\x63\0\0\0\0\0\0\0\0\0\0\0\x0f\x7f\xff\xff\xffMFP_TERRAIN_MAPabcd' \
  >> "$WORK/hostile.lcmlog"
set +e
"$BUILD_DIR/tools/mfp-replay" "$WORK/hostile.lcmlog" --config "$CONFIG" --out "$WORK/h.lcmlog" \
  2> "$WORK/hostile.err"
code=$?
set -e
cat "$WORK/hostile.err"
[ "$code" -eq 2 ] || { echo "FAIL: mfp-replay on a log claiming 2^31-1 bytes exited $code, not 2"; exit 1; }
grep -q "2147483647 data bytes but only 19 remain" "$WORK/hostile.err" ||
  { echo "FAIL: the error does not name the bad length"; exit 1; }
# Not an LCM log at all.
head -c 1000 /dev/urandom > "$WORK/random.lcmlog"
set +e
"$BUILD_DIR/tools/mfp-replay" "$WORK/random.lcmlog" --config "$CONFIG" --out "$WORK/r.lcmlog" 2> "$WORK/random.err"
code=$?
set -e
[ "$code" -eq 2 ] && grep -q "no sync word" "$WORK/random.err" ||
  { echo "FAIL: mfp-replay on random bytes exited $code: $(cat "$WORK/random.err")"; exit 1; }
echo "hostile logs: exit 2 with a message"
# An mfp-plan scenario given where a replay scenario belongs: exit 2, the message says which file is wanted.
set +e
"$BUILD_DIR/tools/mfp-make-log" "$SOURCE_DIR/config/scenarios/hexapod_flat.yaml" --config "$CONFIG" \
  --out "$WORK/plan_scenario.lcmlog" 2> "$WORK/plan_scenario.err"
code=$?
set -e
[ "$code" -eq 2 ] && grep -q "an mfp-plan scenario.*tests/daemon_replay_scenario.yaml" "$WORK/plan_scenario.err" ||
  { echo "FAIL: mfp-make-log on an mfp-plan scenario exited $code: $(cat "$WORK/plan_scenario.err")"; exit 1; }
echo "an mfp-plan scenario: exit 2 naming the replay scenario wanted"
