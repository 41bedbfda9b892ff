#!/bin/bash
# mfp-terrain-bench on files it cannot read (an empty map, a truncated map, a robot without
# legs, a map that is not there): exit 2 with a message naming the file and the problem, never
# an abort.
# usage: terrain_bench_bad_input_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE_DIR=$(realpath "$1")
BUILD_DIR=$(realpath "$2")
source "$SOURCE_DIR/tests/test_workspace.sh"
mfp_test_workspace mfp_terrain_bench_bad_input
BENCH="$BUILD_DIR/bench/mfp-terrain-bench"

: > "$WORK/empty.bt"
"$BUILD_DIR/tools/mfp-terrain" "$SOURCE_DIR/config/scenarios/littledog_flat.yaml" --out "$WORK/flat.bt" > /dev/null
head -c $(( $(stat -c %s "$WORK/flat.bt") / 2 )) "$WORK/flat.bt" > "$WORK/truncated.bt"
cat > "$WORK/no_legs.urdf" <<'URDF'
<?xml version="1.0"?>
<robot name="brick"><link name="base"/></robot>
URDF

# expect_exit_2 WHAT TEXT ARGS...: the bench exits 2 and its stderr holds TEXT.
expect_exit_2() {
  local what=$1 text=$2
  shift 2
  set +e
  "$BENCH" "$@" > "$WORK/out.txt" 2> "$WORK/err.txt"
  local code=$?
  set -e
  [ "$code" -eq 2 ] && grep -q "$text" "$WORK/err.txt" && ! grep -q "terminate called" "$WORK/err.txt" ||
    { echo "FAIL: $what: exit $code: $(cat "$WORK/err.txt")"; exit 1; }
  echo "$what: exit 2: $(cat "$WORK/err.txt")"
}

expect_exit_2 "an empty map" "empty.bt: the map is empty" --scans-only --scan "$WORK/empty.bt"
expect_exit_2 "a truncated map" "truncated.bt: not a valid OctoMap file" --scans-only --scan "$WORK/truncated.bt"
expect_exit_2 "a robot without legs" "no_legs.urdf: no legs found" --scans-only --scan "$WORK/flat.bt" \
  --walk-robot "$WORK/no_legs.urdf" --walks 1
# A map that is not there: CLI11's check names it, with mfp's bad-input code (not CLI11's 105).
expect_exit_2 "a missing map" "missing.bt" --scans-only --scan "$WORK/missing.bt"
