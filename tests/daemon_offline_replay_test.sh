#!/bin/bash
# mfp-replay over a scenario log (file:// provider, no network): every request answered
# and checked, the same as the live daemon_replay_test.
# usage: daemon_offline_replay_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE_DIR=$(realpath "$1")
BUILD_DIR=$(realpath "$2")
SCENARIO="$SOURCE_DIR/tests/daemon_replay_scenario.yaml"
CONFIG="$SOURCE_DIR/config/daemon.yaml"
WORK=$(mktemp -d "${TMPDIR:-/tmp}/mfp_offline_replay.XXXXXX")
trap 'rm -rf "$WORK"' EXIT

"$BUILD_DIR/tools/mfp-make-log" "$SCENARIO" --config "$CONFIG" --out "$WORK/requests.lcmlog"
"$BUILD_DIR/tools/mfp-replay" "$WORK/requests.lcmlog" --config "$CONFIG" --out "$WORK/replies.lcmlog"
"$BUILD_DIR/tools/mfp-check-replies" "$WORK/replies.lcmlog" --scenario "$SCENARIO" --config "$CONFIG"
