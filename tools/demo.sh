#!/usr/bin/env bash
# One command from a fresh clone to a picture: installs what is missing, builds, plans
# the default scenario (the hexapod on the seed paper's 13-region stepping stones, goal
# 2 m ahead turned 45 degrees), prints a summary (mfp-plan's last log line: status,
# steps, objective, time) and writes plan.svg and plan.json.
# Another scenario: tools/demo.sh config/scenarios/NAME.yaml
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
scenario="${1:-$root/config/scenarios/hexapod_stepping_stones_45.yaml}"
"$root/tools/setup.sh"
build="${MFP_BUILD_DIR:-$root/build}"
set +e
"$build/tools/mfp-plan" --scenario "$scenario" --svg "$root/plan.svg" --json "$root/plan.json" --validate
code=$?
set -e
echo "picture: $root/plan.svg   plan: $root/plan.json"
exit $code
