#!/usr/bin/env python3
"""Largest reference/reachability box excess of plan JSON files under exact R(yaw)
(signed: negative when every footstep is inside its boxes by that much).

Recomputed from the plan JSON alone (DESIGN's plan JSON plus the README's extensions):
for footstep i >= n, p_i is the centre of contacts of the n latest footsteps ending at i
(footsteps before the plan are the start stance), r_nom,i = p_i + R(yaw_i) o_leg(i) with
yaw_i the footstep's own `yaw`, and the excesses are |f_i - r_nom,i|_inf - l_bnd and
|f_i - r_nom,i-n|_inf - d_lim (for a robot whose reach_shape is octagon or hexadecagon, also
|cos(phi) dx + sin(phi) dy| - d_lim of f_i - r_nom,i-n for its other faces' normals phi; nan
for reach_shape footprint, whose polygons the plan JSON does not carry). Also prints the final footstep's yaw and the yaw the final
feet imply (2-D Procrustes against the nominal offsets), to compare with a goal yaw.

    bench/exact_excess.py plan1.json [plan2.json ...] [--goal-yaw RAD]
"""
import argparse
import json
import math

SIDES = {"box": 4, "octagon": 8, "hexadecagon": 16}


def excess(plan):
    robot = plan["robot"]
    n = len(robot["legs"])
    steps = plan["footsteps"]
    offsets = [leg["nominal_offset"] for leg in robot["legs"]]

    def pos(j):
        while j < 0:
            j += n
        return steps[j]["x"], steps[j]["y"]

    def nominal(j):
        px = sum(pos(k)[0] for k in range(j - n + 1, j + 1)) / n
        py = sum(pos(k)[1] for k in range(j - n + 1, j + 1)) / n
        s = steps[max(j, 0)]
        ox, oy = offsets[s["leg"]]
        c, si = math.cos(s["yaw"]), math.sin(s["yaw"])
        return px + c * ox - si * oy, py + si * ox + c * oy

    ref = reach = -math.inf
    if robot.get("reach_shape") == "footprint":
        # Each leg's footprint polygon is not in the plan JSON: mfp-plan --validate checks it.
        return math.nan, math.nan, steps[-1]["yaw"], math.nan
    for i in range(n, len(steps)):
        f = pos(i)
        a = nominal(i)
        b = nominal(i - n)
        ref = max(ref, max(abs(f[0] - a[0]), abs(f[1] - a[1])) - robot["l_bnd"])
        dx, dy = f[0] - b[0], f[1] - b[1]
        reach = max(reach, max(abs(dx), abs(dy)) - robot["d_lim"])
        sides = SIDES.get(robot.get("reach_shape", "box"), 4)
        for k in range(1, sides // 2):
            phi = 2.0 * math.pi * k / sides
            reach = max(reach, abs(math.cos(phi) * dx + math.sin(phi) * dy) - robot["d_lim"])
    # Yaw the final feet imply.
    feet = {s["leg"]: (s["x"], s["y"]) for s in steps[-n:]}
    cx = sum(f[0] for f in feet.values()) / n
    cy = sum(f[1] for f in feet.values()) / n
    mx = sum(o[0] for o in offsets) / n
    my = sum(o[1] for o in offsets) / n
    sin_sum = cos_sum = 0.0
    for k, (ox, oy) in enumerate(offsets):
        ox, oy = ox - mx, oy - my
        dx, dy = feet[k][0] - cx, feet[k][1] - cy
        cos_sum += ox * dx + oy * dy
        sin_sum += ox * dy - oy * dx
    return ref, reach, steps[-1]["yaw"], math.atan2(sin_sum, cos_sum)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("plans", nargs="+")
    parser.add_argument("--goal-yaw", type=float, default=None)
    args = parser.parse_args()
    print(f"{'plan':40s} {'ref_exc_m':>11s} {'reach_exc_m':>11s} {'last_yaw':>9s} {'feet_yaw':>9s} {'reaches':>7s}")
    for path in args.plans:
        with open(path) as f:
            plan = json.load(f)
        if len(plan["footsteps"]) <= len(plan["robot"]["legs"]):
            print(f"{path:40s} (no step)")
            continue
        ref, reach, last_yaw, feet_yaw = excess(plan)
        print(f"{path:40s} {ref:11.3e} {reach:11.3e} {last_yaw:9.4f} {feet_yaw:9.4f} "
              f"{str(plan['reaches_goal']):>7s}")


if __name__ == "__main__":
    main()
