#!/bin/bash
# Self-test of reorganise_tree.sh: a copy of REPO (branch main) with new files added in
# the old folders (planner/planning/, terrain/, tools/daemon/), reorganised, checked for
# placement, a no-op second run, the include test and the new objects compiling.
# usage: tools/dev/reorganise_tree_selftest.sh REPO SCRIPT_BRANCH  (works in /tmp/robust)
set -uo pipefail
rm -rf /tmp/robust && git clone -q "$1" /tmp/robust -b main && cd /tmp/robust
mkdir -p tools/dev && git -C "$1" archive "$2" tools/dev | tar x
cat > planner/planning/dummy_unit.h <<'X'
#pragma once
// A dummy unit added after the script was written: its header is used by tools/.
#include "planner/base/check.h"
#include "terrain/convex_region.h"
namespace mfp {
int DummyUnit(const ConvexRegion& region);
}  // namespace mfp
X
cat > planner/planning/dummy_unit.cc <<'X'
#include "planner/planning/dummy_unit.h"

#include "planner/base/deadline.h"
#include "planner/planning/goal.h"

namespace mfp {
int DummyUnit(const ConvexRegion& region) { return region.id; }
}  // namespace mfp
X
sed -i 's/^  route_proposals.cc$/  route_proposals.cc\n  dummy_unit.cc/' planner/planning/CMakeLists.txt
cat > terrain/dummy_patch.h <<'X'
#pragma once
// A dummy terrain unit of the extraction library, private to it.
#include "terrain/height_map.h"
namespace mfp {
int DummyPatch();
}  // namespace mfp
X
cat > terrain/dummy_patch.cc <<'X'
#include "terrain/dummy_patch.h"

#include "planner/base/check.h"
#include "terrain/occupancy_map.h"

namespace mfp {
int DummyPatch() { return 1; }
}  // namespace mfp
X
sed -i 's/^  region_extractor.cc$/  region_extractor.cc\n  dummy_patch.cc/' terrain/CMakeLists.txt
cat > terrain/dummy_quality_unit.h <<'X'
#pragma once
// A header-only dummy in terrain/ with no rule: the script places it and warns.
X
cat > tools/daemon/dummy_daemon_unit.h <<'X'
#pragma once
// A dummy daemon unit, used by tools/mfp_daemon.cc.
#include "planner/base/check.h"
#include "tools/daemon/request_queue.h"
X
cat > tools/daemon/dummy_daemon_unit.cc <<'X'
#include "tools/daemon/dummy_daemon_unit.h"
X
sed -i 's/^  udp_counters.cc$/  udp_counters.cc\n  dummy_daemon_unit.cc/' tools/daemon/CMakeLists.txt
sed -i 's|#include "tools/daemon/daemon_config.h"|#include "tools/daemon/daemon_config.h"\n#include "tools/daemon/dummy_daemon_unit.h"|' tools/mfp_daemon.cc
# tools/mfp_plan.cc includes the dummy so it stays public.
sed -i 's|#include "planner/planning/footstep_planner.h"|#include "planner/planning/dummy_unit.h"\n#include "planner/planning/footstep_planner.h"|' tools/mfp_plan.cc
git add -A && git commit -qm "dummy new files"
tools/dev/reorganise_tree.sh > /tmp/robust_run.log 2>&1
grep -E "reorganise_tree|WARN|Trace" /tmp/robust_run.log
git status --short | grep -i dummy
grep -n dummy planner/planning/CMakeLists.txt terrain/*/CMakeLists.txt tools/mfp_plan.cc
grep -rn '#include' planner/planning/dummy_unit.* terrain/extraction/dummy_patch.cc terrain/extraction/internal/dummy_patch.h
git add -A && git commit -qm reorganised
echo "--- second run"; tools/dev/reorganise_tree.sh 2>&1 | grep reorganise_tree; git status --short | wc -l
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER=ccache > /tmp/robust_cfg.log 2>&1; echo configure=$?
python3 tests/include_direction_test.py . build/mfp_library_graph.txt | tail -3
python3 tools/sort_includes.py --check; echo sort_includes=$?
make -C build/planner/planning dummy_unit.cc.o 2>&1 | grep -E "error|warning|Building"
make -C build/terrain/extraction dummy_patch.cc.o 2>&1 | grep -E "error|warning|Building"
make -C build mfp_lcmtypes_gen > /dev/null
make -C build/daemon dummy_daemon_unit.cc.o 2>&1 | grep -E "error|warning|Building"
make -C build/tools mfp_daemon.cc.o mfp_plan.cc.o 2>&1 | grep -E "error|warning|Building"
