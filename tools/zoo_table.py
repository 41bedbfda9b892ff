#!/usr/bin/env python3
"""The robot zoo table of docs/robots.md: for every legged robot of example-robot-data,
mfp-robot's derived values beside the robot's published standing pose.

The published pose is the package's own SRDF group state "standing" (the pose
example_robot_data.load(name).q0 gives): its root height above the ground, and the hip
height above the foot points at its joint angles (forward kinematics of the URDF here),
which is what mfp's stance_height measures.

usage: tools/zoo_table.py BUILD_DIR [VENV]   (VENV: the zoo test's, ~/.cache/mfp/zoo-venv)
"""
import glob
import json
import math
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

ROBOTS = [  # name, URDF, SRDF, group state
    ("A1", "a1_description/urdf/a1.urdf", "a1_description/srdf/a1.srdf", "standing"),
    ("Go1", "go1_description/urdf/go1.urdf", "go1_description/srdf/go1.srdf", "standing"),
    ("Go2", "go2_description/urdf/go2.urdf", "go2_description/srdf/go2.srdf", "standing"),
    ("B1", "b1_description/urdf/b1.urdf", "b1_description/srdf/b1.srdf", "standing"),
    ("Laikago", "laikago_description/urdf/laikago.urdf", None, None),
    ("ANYmal B", "anymal_b_simple_description/robots/anymal.urdf", "anymal_b_simple_description/srdf/anymal.srdf", "standing"),
    ("ANYmal C", "anymal_c_simple_description/urdf/anymal.urdf", "anymal_c_simple_description/srdf/anymal.srdf", "standing"),
    ("HyQ", "hyq_description/robots/hyq_no_sensors.urdf", "hyq_description/srdf/hyq.srdf", "standing"),
    ("Solo 12", "solo_description/robots/solo12.urdf", "solo_description/srdf/solo.srdf", "standing"),
    ("Solo 8", "solo_description/robots/solo.urdf", "solo_description/srdf/solo.srdf", "standing"),
    ("2-DoF quadruped", "quadruped_description/urdf/quadruped.urdf", None, None),
]


def rot(axis, angle):
    x, y, z = axis
    n = math.sqrt(x * x + y * y + z * z)
    x, y, z = x / n, y / n, z / n
    c, s, t = math.cos(angle), math.sin(angle), 1 - math.cos(angle)
    return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c]]


def rpy(r, p, y):
    return mat(rot((0, 0, 1), y), mat(rot((0, 1, 0), p), rot((1, 0, 0), r)))


def mat(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def apply(T, v):
    R, t = T
    return [sum(R[i][k] * v[k] for k in range(3)) + t[i] for i in range(3)]


def compose(A, B):
    return (mat(A[0], B[0]), apply(A, B[1]))


def numbers(text, n):
    return [float(v) for v in text.split()] if text else [0.0] * n


def chain_pose(urdf, link, q):
    """Pose of `link` in the root frame at joint positions q, and the first movable joint's origin."""
    joints = {}
    for j in urdf.findall("joint"):
        joints[j.find("child").get("link")] = j
    path = []
    while link in joints:
        path.append(joints[link])
        link = joints[link].find("parent").get("link")
    T = ([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [0, 0, 0])
    hip = None
    for j in reversed(path):
        o = j.find("origin")
        xyz = numbers(o.get("xyz") if o is not None else None, 3)
        r = numbers(o.get("rpy") if o is not None else None, 3)
        T = compose(T, (rpy(*r), xyz))
        if j.get("type") in ("revolute", "continuous"):
            if hip is None:
                hip = T[1]
            a = j.find("axis")
            axis = numbers(a.get("xyz") if a is not None else "1 0 0", 3)
            T = compose(T, (rot(axis, q.get(j.get("name"), 0.0)), [0, 0, 0]))
    return T, hip


def foot_point(urdf, foot):
    for l in urdf.findall("link"):
        if l.get("name") != foot:
            continue
        for c in l.findall("collision"):
            if c.find("geometry/sphere") is not None:
                o = c.find("origin")
                return numbers(o.get("xyz") if o is not None else None, 3)
    return [0.0, 0.0, 0.0]


def standing(srdf_path, state):
    root = ET.parse(srdf_path).getroot()
    for g in root.findall("group_state"):
        if g.get("name") == state:
            q, root_z = {}, None
            for j in g.findall("joint"):
                values = numbers(j.get("value"), 1)
                if j.get("name") == "root_joint":
                    root_z = values[2]
                else:
                    q[j.get("name")] = values[0]
            return q, root_z
    return None, None


def main():
    build = sys.argv[1]
    venv = sys.argv[2] if len(sys.argv) > 2 else os.path.expanduser("~/.cache/mfp/zoo-venv")
    robots_dir = glob.glob(os.path.join(venv, "**/share/example-robot-data/robots"), recursive=True)[0]
    print("| robot | legs | stance height (derived) | published standing pose: hip above feet | ratio | root height in it | d_lim | dz_max | max yaw change |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, urdf_rel, srdf_rel, state in ROBOTS:
        urdf_path = os.path.join(robots_dir, urdf_rel)
        run = subprocess.run([os.path.join(build, "tools/mfp-robot"), urdf_path, "--json", "-"],
                             capture_output=True, text=True)
        if run.returncode != 0:
            message = run.stderr.strip().split(": ", 2)[-1]
            print("| %s | refused | %s | | | | | | |" % (name, message[:120]))
            continue
        text = run.stdout
        robot = json.loads(text[text.index("{"):])
        feet = []
        for line in robot["provenance"]:
            if "foot link '" in line and line.startswith("legs["):
                feet.append(line.split("foot link '")[1].split("'")[0])
        published, root_z = "—", "—"
        ratio = ""
        if srdf_rel:
            q, rz = standing(os.path.join(robots_dir, srdf_rel), state)
            urdf = ET.parse(urdf_path).getroot()
            heights = []
            for foot in feet:
                T, hip = chain_pose(urdf, foot, q)
                heights.append(hip[2] - apply(T, foot_point(urdf, foot))[2])
            h = sum(heights) / len(heights)
            published = "%.3f m" % h
            root_z = "%.3f m" % rz if rz is not None else "—"
            ratio = "%.2f" % (robot["stance_height"] / h)
        print("| %s | %d | %.3f m | %s | %s | %s | %.3f m | %.3f m | %.3f rad |" % (
            name, len(robot["legs"]), robot["stance_height"], published, ratio, root_z, robot["d_lim"],
            robot["dz_max"], robot["max_yaw_change"]))


if __name__ == "__main__":
    main()
