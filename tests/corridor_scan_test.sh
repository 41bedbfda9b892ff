#!/bin/bash
# The hexapod and the quadruped of config/robots/ walk 6 m down the scanned corridor of
# config/scenarios/long/ (8 cm voxels, walls with doors, a ceiling, free space cast from
# sensor poses, floor noise, outliers): each plan reaches its goal with every constraint
# kept (mfp-plan --validate), and every footstep stands on the true floor with its foot
# radius + the 1 cm edge margin around it, judged by mfp-terrain against the boxes the map
# was made from (never against mfp's own regions).
#
# usage: corridor_scan_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE_DIR=$(realpath "$1")
BUILD_DIR=$(realpath "$2")
WORK=$(mktemp -d "${TMPDIR:-/tmp}/mfp_corridor_scan.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

for robot in hexapod littledog; do
  scenario="$SOURCE_DIR/config/scenarios/long/${robot}_corridor_scan.yaml"
  plan="$WORK/$robot.plan.json"
  log="$WORK/$robot.log"
  if ! "$BUILD_DIR/tools/mfp-plan" --scenario "$scenario" --validate --json "$plan" >"$log" 2>&1; then
    fail "$robot: mfp-plan exit $?: $(tail -3 "$log" | tr '\n' ' ')"
    continue
  fi
  grep -q '"reaches_goal": *true' "$plan" || { fail "$robot: the plan does not reach the goal"; continue; }
  radius=$("$BUILD_DIR/tools/mfp-robot" "$SOURCE_DIR/config/robots/$robot.yaml" --json "$WORK/$robot.robot.json" >/dev/null &&
           python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["foot_radius"] + 0.01)' "$WORK/$robot.robot.json")
  if ! checked=$("$BUILD_DIR/tools/mfp-terrain" "$scenario" --check-plan "$plan" --radius "$radius" 2>&1); then
    fail "$robot: against the true floor: $(echo "$checked" | tail -3 | tr '\n' ' ')"
    continue
  fi
  echo "ok: $robot: $(grep -o 'status .*' "$log" | tail -1 | cut -c1-100); $(echo "$checked" | tail -1)"
done
[ "$failures" = 0 ] || { echo "corridor: $failures failures"; exit 1; }
