#!/bin/bash
# Prints how long mfp-plan and mfp-regions take against their time limits on hostile
# inputs: terrains of 1,000 and 3,000 small stones (bench/many_stones.py, grid and
# overlapping) planned with time_limit 5 s, and a 0.1 mm map (the flat course relabelled).
# Wall seconds of the whole process (start-up and loading included), one row per input.
# usage: bench/time_limits.sh [BUILD_DIR]   (default: build)
set -euo pipefail
SOURCE_DIR=$(cd "$(dirname "$0")/.." && pwd)
BUILD_DIR=$(realpath "${1:-$SOURCE_DIR/build}")
WORK=$(mktemp -d "${TMPDIR:-/tmp}/mfp_time_limits.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
ROBOT="$SOURCE_DIR/config/robots/hexapod.yaml"

wall() {  # wall seconds and exit code of a command, its output discarded
  local start end code
  start=$(date +%s%N)
  set +e
  "$@" > "$WORK/out" 2>&1
  code=$?
  set -e
  end=$(date +%s%N)
  local ms=$(( (end - start) / 1000000 ))
  printf "%3d.%02d %4d" $((ms / 1000)) $(((ms % 1000) / 10)) "$code"
}

printf "%-44s %8s %6s %4s\n" "input" "limit_s" "wall_s" "exit"
for n in 1000 3000; do
  for layout in grid overlap; do
    flag=""; [ "$layout" = overlap ] && flag="--overlap"
    python3 "$SOURCE_DIR/bench/many_stones.py" "$n" "$WORK/s.yaml" --robot "$ROBOT" $flag
    printf "%-44s %8s %s\n" "mfp-plan, $n stones ($layout)" 5 "$(wall "$BUILD_DIR/tools/mfp-plan" --scenario "$WORK/s.yaml")"
  done
done
"$BUILD_DIR/tools/mfp-terrain" "$SOURCE_DIR/config/scenarios/hexapod_flat.yaml" --out "$WORK/flat.bt" > /dev/null
sed -b 's/^res 0\.02$/res 0.0001/' "$WORK/flat.bt" > "$WORK/fine.bt"
printf "%-44s %8s %s\n" "mfp-regions, 0.1 mm map" 1 "$(wall "$BUILD_DIR/tools/mfp-regions" "$WORK/fine.bt" --time-limit 1)"
printf "%-44s %8s %s\n" "mfp-plan, 0.1 mm map" 1 \
  "$(wall "$BUILD_DIR/tools/mfp-plan" --robot "$ROBOT" --terrain "$WORK/fine.bt" --start 0,0,0 --goal 1,0,0 --time-limit 1)"
