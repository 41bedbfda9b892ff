"""The Python module: height maps from numpy, plans, regions, errors, and the JSON of
mfp-plan on the same input. Plans are judged against the true heights the arrays were
made from."""
import json
import subprocess
import threading
import time

import numpy as np
import pytest

import mfp
from conftest import BUILD_DIR, SOURCE_DIR

HEXAPOD = str(SOURCE_DIR / "config/robots/hexapod.yaml")
RES = 0.02
ORIGIN = (-0.6, -0.6)


def step_heights():
    """Ground at z = 0 for x < 0.6 m, a 4 cm step beyond, 2.6 m x 1.2 m, with an unknown
    (NaN) patch at the far side; heights[i, j] at ORIGIN + (i, j) * RES."""
    x = ORIGIN[0] + RES * np.arange(131)
    y = ORIGIN[1] + RES * np.arange(61)
    xx, _ = np.meshgrid(x, y, indexing="ij")
    heights = np.where(xx < 0.6 - 1e-9, 0.0, 0.04)
    heights[(x > 1.7)[:, None] & (np.abs(y) < 0.1)[None, :]] = np.nan
    return heights


def true_height(x, y):
    return 0.0 if x < 0.6 else 0.04


def test_plans_onto_the_step_with_every_foot_on_the_true_surface():
    robot = mfp.load_robot(HEXAPOD)
    terrain = mfp.Terrain.from_height_map(step_heights(), resolution=RES, origin=ORIGIN)
    plan = mfp.plan(robot, terrain, start=(0.0, 0.0, 0.0), goal=(1.0, 0.0, 0.0), time_limit=60.0)
    assert plan.reaches_goal, plan.message
    assert plan.status in ("optimal", "feasible")
    steps = plan.footsteps
    assert steps.shape[1] == 5 and steps.shape[0] > robot.num_legs
    for leg, x, y, z, _ in steps:
        assert 0 <= leg < robot.num_legs
        # Within the regions' plane slab (half a cell) of the true height.
        assert abs(z - true_height(x, y)) <= 0.5 * RES + 1e-6, (x, y, z)
        assert abs(x - 0.6) > robot.foot_radius, "a foot on the step's edge"


def test_regions_are_planes_with_their_vertices_inside():
    terrain = mfp.Terrain.from_height_map(step_heights(), resolution=RES, origin=ORIGIN)
    regions = terrain.regions
    assert len(regions) >= 2
    for r in regions:
        assert r["A"].shape[1] == 3 and r["A"].shape[0] == r["b"].shape[0]
        assert abs(np.linalg.norm(r["normal"]) - 1.0) < 1e-9
        assert np.all(r["vertices"] @ r["A"].T <= r["b"] + 1e-6)
        for x, y, z in r["vertices"]:
            assert abs(z - true_height(x, y)) < 0.005
            assert not (x > 1.7 - RES and abs(y) < 0.1 + RES), "a region over unknown cells"


def run_cli(*args):
    return subprocess.run([str(BUILD_DIR / "tools/mfp-plan"), *args], capture_output=True, text=True)


def cli_message(result):
    assert result.returncode == 2, result.stderr
    return result.stderr.strip().splitlines()[-1].removeprefix("mfp-plan: ")


def test_json_equals_mfp_plan_on_the_same_height_map(tmp_path):
    heights = step_heights().astype(np.float32)
    np.save(tmp_path / "step.npy", heights)
    (tmp_path / "step.yaml").write_text(f"resolution: {RES}\norigin: [{ORIGIN[0]}, {ORIGIN[1]}]\n")
    out = tmp_path / "plan.json"
    cli = run_cli("--robot", HEXAPOD, "--terrain", str(tmp_path / "step.npy"), "--start", "0,0,0",
                  "--goal", "0.5,0.1,0.2", "--time-limit", "60", "--window", "6", "--json", str(out), "--quiet")
    assert cli.returncode == 0, cli.stderr
    robot = mfp.load_robot(HEXAPOD)
    for terrain in (mfp.Terrain.from_file(str(tmp_path / "step.npy")),
                    mfp.Terrain.from_height_map(heights, resolution=RES, origin=ORIGIN)):
        plan = mfp.plan(robot, terrain, start=(0, 0, 0), goal=(0.5, 0.1, 0.2), time_limit=60.0,
                        options={"window": 6})
        ours, theirs = json.loads(plan.to_json()), json.loads(out.read_text())
        for doc in (ours, theirs):
            doc.pop("solve_time_s")
        assert ours == theirs


def test_bad_input_raises_value_error_with_the_cli_message(tmp_path):
    missing = str(tmp_path / "nothing.urdf")
    with pytest.raises(ValueError) as error:
        mfp.load_robot(missing)
    np.save(tmp_path / "flat.npy", np.zeros((10, 10), np.float32))
    (tmp_path / "flat.yaml").write_text("resolution: 0.02\norigin: [0, 0]\n")
    cli = run_cli("--robot", missing, "--terrain", str(tmp_path / "flat.npy"), "--start", "0,0,0", "--goal", "1,0,0")
    assert str(error.value) == cli_message(cli)

    (tmp_path / "flat.yaml").write_text("resolution: 0.02\n")
    with pytest.raises(ValueError) as error:
        mfp.Terrain.from_file(str(tmp_path / "flat.npy"))
    cli = run_cli("--robot", HEXAPOD, "--terrain", str(tmp_path / "flat.npy"), "--start", "0,0,0", "--goal", "1,0,0")
    assert str(error.value) == cli_message(cli)
    assert "origin" in str(error.value)

    robot = mfp.load_robot(HEXAPOD)
    terrain = mfp.Terrain.from_height_map(step_heights(), resolution=RES, origin=ORIGIN)
    with pytest.raises(ValueError) as error:
        mfp.plan(robot, terrain, start=(0, 0, 0), goal=(30.0, 0, 0))
    np.save(tmp_path / "step.npy", step_heights().astype(np.float32))
    (tmp_path / "step.yaml").write_text(f"resolution: {RES}\norigin: [{ORIGIN[0]}, {ORIGIN[1]}]\n")
    cli = run_cli("--robot", HEXAPOD, "--terrain", str(tmp_path / "step.npy"), "--start", "0,0,0", "--goal", "30,0,0")
    assert str(error.value) == cli_message(cli)


def test_bad_arrays_and_options_raise_value_error():
    with pytest.raises(ValueError, match="2-D"):
        mfp.Terrain.from_height_map(np.zeros(5), resolution=RES)
    with pytest.raises(ValueError, match="resolution"):
        mfp.Terrain.from_height_map(np.zeros((5, 5)), resolution=-1.0)
    with pytest.raises(ValueError, match="height inf"):
        mfp.Terrain.from_height_map(np.full((5, 5), np.inf), resolution=RES)
    robot = mfp.load_robot(HEXAPOD)
    terrain = mfp.Terrain.from_height_map(step_heights(), resolution=RES, origin=ORIGIN)
    with pytest.raises(ValueError, match="unknown key 'windw'"):
        mfp.plan(robot, terrain, start=(0, 0, 0), goal=(1, 0, 0), options={"windw": 4})
    with pytest.raises(ValueError, match="start"):
        mfp.plan(robot, terrain, start=(0, 0), goal=(1, 0, 0))


def test_a_goal_beyond_reach_is_a_result_not_an_exception():
    # The goal is on the map, but the unknown patch walls it off in 4 steps: a status.
    robot = mfp.load_robot(HEXAPOD)
    terrain = mfp.Terrain.from_height_map(step_heights(), resolution=RES, origin=ORIGIN)
    plan = mfp.plan(robot, terrain, start=(0, 0, 0), goal=(1.6, 0, 0), time_limit=20.0, options={"max_steps": 4})
    assert not plan.reaches_goal
    assert plan.message, "a plan that stops short says why"


def test_the_gil_is_released_while_planning():
    robot = mfp.load_robot(HEXAPOD)
    terrain = mfp.Terrain.from_height_map(step_heights(), resolution=RES, origin=ORIGIN)
    count = [0]
    stop = threading.Event()

    def spin():
        while not stop.is_set():
            count[0] += 1

    thread = threading.Thread(target=spin)
    thread.start()
    time.sleep(0.05)
    before = count[0]
    plan = mfp.plan(robot, terrain, start=(0, 0, 0), goal=(1.0, 0, 0), time_limit=60.0)
    during = count[0] - before
    stop.set()
    thread.join()
    assert plan.reaches_goal
    # With the GIL held for the whole call the other thread could not have run at all.
    assert during > 10000, during
