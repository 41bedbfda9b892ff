#!/bin/bash
# The robot zoo: every legged robot of the example-robot-data package (PyPI), from its
# URDF alone. For each: the leg count, then two plans checked constraint by constraint
# (mfp-plan --validate): a flat walk to a goal 1.5 body lengths ahead turned 0.3 rad, and
# a step up onto a block of half the derived dz_max; then every footstep is judged against
# the boxes the world was built from (mfp plans on regions extracted from their voxel
# map). Robots with planar legs must be refused with a message that names them. ANYmal C
# also walks 6 m down the scanned corridor of config/scenarios/long/.
#
# The package is installed with pip into a cached virtual environment
# (MFP_ZOO_VENV, default ~/.cache/mfp/zoo-venv); meshes are not needed, only the URDFs.
# usage: robot_zoo_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
SOURCE_DIR=$(realpath "$1")
BUILD_DIR=$(realpath "$2")
VENV="${MFP_ZOO_VENV:-$HOME/.cache/mfp/zoo-venv}"
PACKAGE="example-robot-data==6.0.0"
WORK=$(mktemp -d "${TMPDIR:-/tmp}/mfp_zoo.XXXXXX")
[ -n "${MFP_ZOO_KEEP:-}" ] && echo "zoo: keeping $WORK" || trap 'rm -rf "$WORK"' EXIT

robots_dir() { find "$VENV" -type d -path '*share/example-robot-data/robots' 2>/dev/null | head -1 || true; }
ROBOTS=$(robots_dir)
if [ -z "$ROBOTS" ] || ! "$VENV/bin/pip" show -q example-robot-data >/dev/null 2>&1; then
  echo "zoo: installing $PACKAGE into $VENV"
  mkdir -p "$(dirname "$VENV")"
  python3 -m venv "$VENV"
  "$VENV/bin/pip" install --quiet --disable-pip-version-check --no-deps "$PACKAGE"
  ROBOTS=$(robots_dir)
fi
[ -d "$ROBOTS" ] || { echo "zoo: no robots directory in $VENV" >&2; exit 1; }

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# name, URDF below robots/, legs
WALKERS="a1 a1_description/urdf/a1.urdf 4
go1 go1_description/urdf/go1.urdf 4
go2 go2_description/urdf/go2.urdf 4
b1 b1_description/urdf/b1.urdf 4
laikago laikago_description/urdf/laikago.urdf 4
anymal_b anymal_b_simple_description/robots/anymal.urdf 4
anymal_c anymal_c_simple_description/urdf/anymal.urdf 4
hyq hyq_description/robots/hyq_no_sensors.urdf 4
solo12 solo_description/robots/solo12.urdf 4"
PLANAR="solo8 solo_description/robots/solo.urdf
quadruped quadruped_description/urdf/quadruped.urdf"

# Writes the two scenarios of one robot from its mfp-robot JSON; prints the step height.
make_scenarios() {  # json urdf out_prefix
  python3 - "$@" <<'EOF'
import json, sys
robot = json.load(open(sys.argv[1]))
urdf, out = sys.argv[2], sys.argv[3]
hips_x = [leg["hip"][0] for leg in robot["legs"]]
body = max(hips_x) - min(hips_x)            # body length: front to rear hips [m]
ox = max(abs(leg["nominal_offset"][0]) for leg in robot["legs"])
oy = max(abs(leg["nominal_offset"][1]) for leg in robot["legs"])
margin = 2 * robot["d_lim"] + 0.2
width = 2 * (oy + margin) + 2.0 * body

def box(name, x0, x1, top):
    return ("    - {name: %s, center: [%.4f, 0, %.4f], size: [%.4f, %.4f, %.4f], rpy: [0, 0, 0]}\n"
            % (name, 0.5 * (x0 + x1), 0.5 * (top - 0.1), x1 - x0, width, top + 0.1), (x0, x1, width, top))

def scenario(path, boxes, goal, steps):
    # The true geometry, for judging the plan's footsteps (top faces of the boxes).
    json.dump({"tops": [b[1] for b in boxes], "foot_radius": robot["foot_radius"], "legs": len(robot["legs"])},
              open(path.replace(".yaml", ".truth.json"), "w"))
    boxes = [b[0] for b in boxes]
    with open(path, "w") as f:
        f.write("name: %s\nrobot: %s\nterrain:\n  resolution: 0.01\n  boxes:\n%s"
                "start: [0, 0, 0]\ngoal: [%.4f, 0, %.4f]\nmax_steps: %d\n"
                % (path.rsplit("/", 1)[-1], urdf, "".join(boxes), goal[0], goal[1], steps))

n = len(robot["legs"])
flat_x = 1.5 * body
scenario(out + "_flat.yaml", [box("ground", -ox - margin, flat_x + ox + margin, 0.0)], (flat_x, 0.3), 12 * n)
h = 0.5 * robot["dz_max"]
edge = ox + 0.2 * body                      # the block starts ahead of the front feet
goal_x = edge + ox + 0.3 * body             # every foot of the goal stance on the block
end = goal_x + ox + margin
scenario(out + "_step.yaml", [box("ground", -ox - margin, edge, 0.0), box("block", edge, end, h)],
         (goal_x, 0.0), 12 * n)
print("%.4f %.4f" % (body, h))
EOF
}

# Every footstep on a top face of the boxes the world was built from (inset by the foot
# radius, at that face's height); with `final_top`, every foot of the final stance there.
judge() {  # plan.json truth.json [final_top]
  python3 - "$@" <<'EOF'
import json, sys
plan, truth = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
r, tol_xy, tol_z = truth["foot_radius"], 1e-3, 0.011  # tol_z: the map's 0.01 m voxels
bad = []
steps = plan["footsteps"]
for f in steps:
    on = [t for t in truth["tops"] if t[0] + r - tol_xy <= f["x"] <= t[1] - r + tol_xy
          and abs(f["y"]) <= t[2] / 2 - r + tol_xy and abs(f["z"] - t[3]) <= tol_z]
    if not on:
        bad.append("footstep %d (leg %d) at (%.3f, %.3f, %.3f) is on no top face" % (f["index"], f["leg"], f["x"], f["y"], f["z"]))
if len(sys.argv) > 3:
    top = float(sys.argv[3])
    for f in steps[-truth["legs"]:]:
        if abs(f["z"] - top) > tol_z:
            bad.append("final footstep %d at z %.3f, not on the block (%.3f)" % (f["index"], f["z"], top))
print("\n".join(bad))
sys.exit(1 if bad else 0)
EOF
}

while read -r name urdf legs; do
  path="$ROBOTS/$urdf"
  if ! "$BUILD_DIR/tools/mfp-robot" "$path" --json "$WORK/$name.json" >"$WORK/$name.robot" 2>&1; then
    fail "$name: mfp-robot refused the URDF: $(tail -1 "$WORK/$name.robot")"
    continue
  fi
  got=$(python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["legs"]))' "$WORK/$name.json")
  [ "$got" = "$legs" ] || { fail "$name: $got legs, expected $legs"; continue; }
  read -r body step < <(make_scenarios "$WORK/$name.json" "$path" "$WORK/$name")
  for walk in flat step; do
    log="$WORK/${name}_$walk.log"
    if ! "$BUILD_DIR/tools/mfp-plan" --scenario "$WORK/${name}_$walk.yaml" --validate \
         --time-limit 30 --json "$WORK/${name}_$walk.plan.json" >"$log" 2>&1; then
      fail "$name $walk: mfp-plan exit $?: $(tail -3 "$log" | tr '\n' ' ')"
      continue
    fi
    final_top=""
    [ "$walk" = step ] && final_top="$step"
    if ! judged=$(judge "$WORK/${name}_$walk.plan.json" "$WORK/${name}_$walk.truth.json" $final_top); then
      fail "$name $walk: against the true geometry: $judged"
      continue
    fi
    echo "ok: $name $walk (body $body m, step $step m): $(grep -o 'status .*' "$log" | tail -1 | cut -c1-110)"
  done
done <<<"$WALKERS"

while read -r name urdf; do
  if "$BUILD_DIR/tools/mfp-robot" "$ROBOTS/$urdf" >"$WORK/$name.robot" 2>&1; then
    fail "$name: planar legs accepted"
  else
    code=$?
    [ "$code" = 2 ] || fail "$name: exit $code, expected 2"
    grep -q "is planar" "$WORK/$name.robot" || fail "$name: message does not name planar legs: $(cat "$WORK/$name.robot")"
    echo "ok: $name refused: $(head -c 160 "$WORK/$name.robot")"
  fi
done <<<"$PLANAR"

# ANYmal C walks 6 m down the scanned corridor (8 cm voxels, doors, ceiling, noise) of
# config/scenarios/long/: the goal reached, every constraint kept, and every footstep on
# the true floor with its foot radius + the 1 cm edge margin around it (mfp-terrain).
corridor="$SOURCE_DIR/config/scenarios/long/littledog_corridor_scan.yaml"
anymal="$ROBOTS/anymal_c_simple_description/urdf/anymal.urdf"
sed -e "s#^robot: .*#robot: $anymal#" -e "s#^name: .*#name: anymal_c_corridor_scan#" "$corridor" \
  >"$WORK/anymal_c_corridor.yaml"
log="$WORK/anymal_c_corridor.log"
if ! "$BUILD_DIR/tools/mfp-plan" --scenario "$WORK/anymal_c_corridor.yaml" --validate --time-limit 120 \
     --json "$WORK/anymal_c_corridor.plan.json" >"$log" 2>&1; then
  fail "anymal_c corridor: mfp-plan exit $?: $(tail -3 "$log" | tr '\n' ' ')"
elif ! grep -q '"reaches_goal": *true' "$WORK/anymal_c_corridor.plan.json"; then
  fail "anymal_c corridor: the plan does not reach the goal: $(grep -o 'status .*' "$log" | tail -1)"
else
  radius=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["foot_radius"] + 0.01)' "$WORK/anymal_c.json")
  if ! checked=$("$BUILD_DIR/tools/mfp-terrain" "$WORK/anymal_c_corridor.yaml" \
                 --check-plan "$WORK/anymal_c_corridor.plan.json" --radius "$radius" 2>&1); then
    fail "anymal_c corridor: against the true floor: $checked"
  else
    echo "ok: anymal_c corridor: $(grep -o 'status .*' "$log" | tail -1 | cut -c1-110); $(echo "$checked" | tail -1)"
  fi
fi

[ "$failures" = 0 ] || { echo "zoo: $failures failures"; exit 1; }
echo "zoo: all robots passed"
