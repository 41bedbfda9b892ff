#!/usr/bin/env bash
# The 165-walk population of issue 25, one real scan at a time: 55 walks of 2-10 m between
# certifiable seen-floor points with room for the body, judged on the raw voxels.
# Seed 25 draws five walks each for Go2, ANYmal B, HyQ, A1 and Solo12; seeds 26 and 27
# five each for ANYmal C, Go1 and mfp's hexapod. The zoo URDFs are example-robot-data
# 6.0.0's (tests/robot_zoo_test.sh installs it into MFP_ZOO_VENV). Walks are limited to
# 15 s each: run on an idle machine (the three scans side by side fit two cores).
# Usage: bench/population.sh MFP_TERRAIN_BENCH SCAN.bt [more mfp-terrain-bench flags]
set -euo pipefail
bench="${1:?usage: bench/population.sh MFP_TERRAIN_BENCH SCAN.bt [flags]}"
scan="${2:?usage: bench/population.sh MFP_TERRAIN_BENCH SCAN.bt [flags]}"
shift 2
extra=("$@")
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="${MFP_ZOO_VENV:-$HOME/.cache/mfp/zoo-venv}"
R=$(find "$venv" -type d -path '*share/example-robot-data/robots' 2>/dev/null | head -1)
[ -d "$R" ] || { echo "population: no example-robot-data in $venv; run tests/robot_zoo_test.sh once" >&2; exit 1; }
common=(--scans-only --scan "$scan" --foot-radius 0.03 --clearance 0.55 --walks 5
        --walk-time-limit 15 --walk-details --walk-certifiable --walk-body-room --walk-joined)
seed25=("$R/go2_description/urdf/go2.urdf" "$R/anymal_b_simple_description/robots/anymal.urdf"
        "$R/hyq_description/robots/hyq_no_sensors.urdf" "$R/a1_description/urdf/a1.urdf"
        "$R/solo_description/robots/solo12.urdf")
seed2627=("$R/anymal_c_simple_description/urdf/anymal.urdf" "$R/go1_description/urdf/go1.urdf"
          "$root/config/robots/hexapod.yaml")
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for seed in 25 26 27; do
  robots=("${seed2627[@]}")
  [ "$seed" = 25 ] && robots=("${seed25[@]}")
  args=()
  for r in "${robots[@]}"; do args+=(--walk-robot "$r"); done
  echo "== seed $seed"
  "$bench" "${common[@]}" --walk-seed "$seed" "${args[@]}" ${extra[@]+"${extra[@]}"} | tee -a "$out"
done
# The population is the joined walks (ends joined by certifiable floor); the unjoined
# ones the draw met on the way are a second population, counted apart.
awk -v scan="$(basename "$scan")" '
  /^joined: valid to the goal:/   {v += $6; n += $8}
  /^unjoined: valid to the goal:/ {uv += $6; un += $8}
  END {printf "population %s: %d of %d walks valid to the goal (unjoined: %d of %d)\n", scan, v, n, uv, un}' "$out"
