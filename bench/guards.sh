#!/usr/bin/env bash
# Behaviour guards for refactors and performance changes: Table I's 12- and 24-step
# instances (node and QP counts, optima), the scenarios (steps, status, nodes, QPs,
# objective, goal) and 16 generated courses, each written to OUT.{table,scen,courses}.
# Compare two runs with bench/guards_compare.sh OLD NEW (made on an idle machine:
# time-limited rows vary with load).
# Usage: bench/guards.sh BUILD/bench/mfp-bench OUT_PREFIX
set -euo pipefail
bench="${1:?usage: bench/guards.sh MFP_BENCH OUT_PREFIX}"
out="${2:?usage: bench/guards.sh MFP_BENCH OUT_PREFIX}"
mkdir -p "$(dirname "$out")"
"$bench" --table-only --sizes 12 24 --time-limit 20 >"$out.table"
"$bench" --scenarios-only >"$out.scen"
"$bench" --courses 16 --course-time-limit 6 >"$out.courses"
echo "guards written: $out.table $out.scen $out.courses"
