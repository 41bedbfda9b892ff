#!/usr/bin/env python3
"""Plans a Unitree Go1 up a flight of stairs given as a numpy height map, and draws it.

Run after the README's two commands (tools/setup.sh, tools/demo.sh):

    PYTHONPATH=build/python python3 examples/plan_on_stairs.py [--out stairs.png]

The robot is the Go1 URDF of example-robot-data (PyPI), read from its URDF alone; the
package is pip-installed once into a cached virtual environment (as tests/robot_zoo_test.sh
does; only its URDF files are read, no meshes). The picture has a top view (heights, the
regions mfp extracted, the footsteps) and a side view (the stairs' profile and the feet).
"""
import argparse
import os
import pathlib
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")  # files only: runs without a display
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import mfp  # noqa: E402  (PYTHONPATH=build/python)

PACKAGE = "example-robot-data==6.0.0"
VENV = pathlib.Path(os.environ.get("MFP_ZOO_VENV", pathlib.Path.home() / ".cache/mfp/zoo-venv"))


def go1_urdf():
    """The Go1 URDF of example-robot-data, pip-installed into VENV on first use."""
    found = list(VENV.glob("**/share/example-robot-data/robots/go1_description/urdf/go1.urdf"))
    if not found:
        print(f"installing {PACKAGE} into {VENV} (once)")
        subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True)
        subprocess.run([str(VENV / "bin/pip"), "install", "--quiet", "--disable-pip-version-check",
                        "--no-deps", PACKAGE], check=True)
        found = list(VENV.glob("**/share/example-robot-data/robots/go1_description/urdf/go1.urdf"))
    return str(found[0])


def stairs(resolution):
    """A 4 m x 1.6 m height map: floor, four 5 cm steps with 30 cm treads, a landing.
    heights[i, j] is the cell centred at (x0 + i * resolution, y0 + j * resolution)."""
    origin = (-1.0, -0.8)
    x = origin[0] + resolution * np.arange(int(round(4.0 / resolution)))
    y = origin[1] + resolution * np.arange(int(round(1.6 / resolution)))
    step = np.clip(np.floor((x - 0.3) / 0.3) + 1, 0, 4)  # 0 on the floor, 4 on the landing
    heights = np.repeat((0.05 * step)[:, None], len(y), axis=1)
    rng = np.random.default_rng(1)
    heights += rng.normal(0.0, 0.002, heights.shape)  # a depth camera's noise
    heights[(x > 2.4)[:, None] & (np.abs(y) > 0.55)[None, :]] = np.nan  # never seen
    return heights, origin


def draw(heights, origin, resolution, regions, plan, goal, out):
    steps = plan.footsteps
    fig, (top, side) = plt.subplots(2, 1, figsize=(9, 7), gridspec_kw={"height_ratios": [1.3, 1]})
    extent = (origin[0] - resolution / 2, origin[0] + resolution * (heights.shape[0] - 0.5),
              origin[1] - resolution / 2, origin[1] + resolution * (heights.shape[1] - 0.5))
    image = top.imshow(heights.T, origin="lower", extent=extent, cmap="Greys", interpolation="nearest")
    fig.colorbar(image, ax=top, label="height [m] (white: unknown)")
    for r in regions:
        v = np.vstack([r["vertices"], r["vertices"][:1]])
        top.plot(v[:, 0], v[:, 1], color="tab:green", lw=0.8)
    for leg in range(int(steps[:, 0].max()) + 1):
        mine = steps[steps[:, 0] == leg]
        top.plot(mine[:, 1], mine[:, 2], "o-", ms=3, lw=0.6, label=f"leg {leg}")
    top.plot(goal[0], goal[1], "r*", ms=12, label="goal")
    top.set_aspect("equal")
    top.set_title(f"top view: {plan.status}, {len(steps)} footsteps, regions in green")
    top.legend(loc="upper left", fontsize=7)
    x = origin[0] + resolution * np.arange(heights.shape[0])
    side.plot(x, heights[:, heights.shape[1] // 2], color="0.3", lw=1, label="height map (y = 0)")
    side.scatter(steps[:, 1], steps[:, 3], c=steps[:, 0], cmap="tab10", s=14, zorder=3, label="footsteps")
    side.set_xlabel("x [m]")
    side.set_ylabel("z [m]")
    side.set_title("side view")
    side.legend(loc="upper left", fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="stairs_plan.png", help="picture to write")
    parser.add_argument("--time-limit", type=float, default=60.0, help="seconds for the plan")
    args = parser.parse_args()

    robot = mfp.load_robot(go1_urdf())
    resolution = 0.02
    heights, origin = stairs(resolution)
    terrain = mfp.Terrain.from_height_map(heights, resolution=resolution, origin=origin)
    goal = (2.0, 0.0, 0.0)
    plan = mfp.plan(robot, terrain, start=(0.0, 0.0, 0.0), goal=goal, time_limit=args.time_limit)
    print(f"{robot.name}: {plan.status}, reaches goal: {plan.reaches_goal}, "
          f"{len(plan.footsteps)} footsteps, {plan.solve_time:.2f} s" + (f" ({plan.message})" if plan.message else ""))
    for leg, x, y, z, yaw in plan.footsteps[-robot.num_legs:]:
        print(f"  final foot of leg {int(leg)} ({robot.leg_names[int(leg)]}): ({x:.3f}, {y:.3f}, {z:.3f})")
    draw(heights, origin, resolution, terrain.regions_for(robot), plan, goal, args.out)
    print(f"wrote {args.out}")
    return 0 if plan.reaches_goal else 3


if __name__ == "__main__":
    sys.exit(main())
