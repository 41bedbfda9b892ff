#!/usr/bin/env python3
"""Writes a scenario with a start pad and N small stepping stones (seeded jitter in
position and height) between it and the goal: a planner input with thousands of regions,
for time-limit checks (tests/time_limit_test.sh, README "Time limits").

usage: many_stones.py N OUT.yaml [--seed S] [--time-limit T] [--robot PATH] [--source top_faces|extracted]
"""
import argparse
import math
import random


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("n", type=int)
    ap.add_argument("out")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--time-limit", type=float, default=5.0)
    ap.add_argument("--robot", default="../config/robots/hexapod.yaml")
    ap.add_argument("--source", default="top_faces")
    ap.add_argument("--overlap", action="store_true",
                    help="stones of 0.5 m scattered over a 2 m x 1 m field, each overlapping many")
    ap.add_argument("--pitch", type=float, default=0.09, help="between stone centres [m]")
    a = ap.parse_args()
    rnd = random.Random(a.seed)
    side = max(1, math.ceil(math.sqrt(a.n)))
    pitch = a.pitch  # [m] between stone centres
    size = 2 * pitch / 3  # stones cover 4/9 of the field
    lines = [f"# bench/many_stones.py {a.n} (seed {a.seed}): {a.n} stones of {size:.3f} m",
             f"name: many_stones_{a.n}", f"robot: {a.robot}", "terrain:", "  resolution: 0.01",
             f"  source: {a.source}", "  boxes:",
             "    - {name: pad, center: [-0.55, 0, -0.05], size: [1.0, 1.2, 0.1]}"]
    y0 = -pitch * (side - 1) / 2
    for k in range(a.n):
        i, j = divmod(k, side)
        x = 0.1 + i * pitch + rnd.uniform(-pitch / 9, pitch / 9)
        y = y0 + j * pitch + rnd.uniform(-pitch / 9, pitch / 9)
        if a.overlap:
            size = 0.5
            x, y = rnd.uniform(0.2, 2.0), rnd.uniform(-0.5, 0.5)
        z = rnd.uniform(-0.02, 0.02)
        lines.append("    - {name: s%d, center: [%.4f, %.4f, %.4f], size: [%.4f, %.4f, 0.1]}" % (k, x, y, z - 0.05, size, size))
    goal_x = 1.0 if a.overlap else 0.1 + pitch * (min(side, math.ceil(a.n / side)) - 1) / 2
    lines += ["start: [-0.55, 0, 0]", f"goal: [{goal_x:.3f}, 0, 0]", "max_steps: 60",
              f"time_limit: {a.time_limit}"]
    with open(a.out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
