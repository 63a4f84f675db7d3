#!/usr/bin/env python3
"""Authoring checks of the written piano scenes, from the files alone (pure Python,
about half a minute):

- every OBJ object is a union of closed, outward, non-degenerate meshes;
- start and goal lie at least 0.3 m inside the bounds;
- the witness path in witness_paths.yaml (the path the layout was designed around)
  runs from start to goal inside the bounds and keeps 1 cm from every obstacle at
  samples between which no piano point moves more than 2 cm, so the whole continuous
  path is free. Obstacles are the boxes bounding each connected piece of each object:
  exact for walls, conservative for furniture.

Start and goal free, the straight line colliding and a path existing are the C++
tests' (tests/planner/shipped_scenes_test.cpp, tests/apps/gplan_plan_test.cpp).

    python3 robots/piano/check.py [scene ...]
"""

import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path[:0] = [HERE, os.path.dirname(HERE)]

import meshlib as ml  # noqa: E402
import passage as ps  # noqa: E402

SCENES = ["piano", "piano_detailed", "large_piano"]


def read_scene(name):
    path = os.path.join(ROOT, "scenes", name + ".yaml")
    sc = ml.read_yaml(path)
    for key in ("name", "description", "narrowest_passage"):
        assert sc.get(key), "%s: no %s" % (path, key)
    folder = os.path.dirname(path)
    sc["robot_path"] = os.path.join(folder, sc["robot"]["mesh"])
    sc["env_paths"] = [os.path.join(folder, o["mesh"]) for o in sc["obstacles"]]
    for key in ("start", "goal"):
        base = sc[key]["base"]
        sc[key] = (tuple(base["xyz"]), ml.quat_normalize(base["quat_wxyz"]))
    return sc


def read_witness(path):
    """{scene: [(position, quaternion)]}."""
    paths, cur = {}, None
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        if not line.startswith(" "):
            cur = paths.setdefault(line.strip().rstrip(":"), [])
        else:
            v = [float(x) for x in line.strip().lstrip("-").strip().strip("[]").split(",")]
            cur.append((tuple(v[:3]), tuple(v[3:])))
    return paths


def same_pose(a, b):
    return (max(abs(a[0][i] - b[0][i]) for i in range(3)) < 1e-6 and
            ml.quat_angle(a[1], b[1]) < 1e-6)


def check_scene(name, witness, robots):
    t0 = time.time()
    sc = read_scene(name)
    if sc["robot_path"] not in robots:
        parts = ml.read_obj(sc["robot_path"])
        for nm, m in parts:
            ml.check_closed(m, nm, min_area=1e-9)
        robots[sc["robot_path"]] = (parts, ps.Robot(parts))
    parts, robot = robots[sc["robot_path"]]
    boxes = []
    n_env = 0
    for path in sc["env_paths"]:
        for nm, m in ml.read_obj(path):
            ml.check_closed(m, nm, min_area=1e-9)
            boxes.extend((nm,) + tuple(ml.point_bounds(piece.vertices))
                         for piece in ml.components(m))
            n_env += len(m)
    print("%s: robot %d triangles, environment %d triangles (%d obstacle boxes), all closed "
          "and outward" % (name, sum(len(m) for _, m in parts), n_env, len(boxes)), flush=True)
    start, goal = sc["start"], sc["goal"]
    bmin, bmax = sc["bounds"]["min"], sc["bounds"]["max"]
    for label, pose in (("start", start), ("goal", goal)):
        inside = min(min(pose[0][i] - bmin[i], bmax[i] - pose[0][i]) for i in range(3))
        assert inside >= 0.3, "%s: %s only %.2f m inside the bounds" % (name, label, inside)
    print("  start and goal at least 0.3 m inside the bounds")
    path = witness[name]
    assert same_pose(path[0], start) and same_pose(path[-1], goal), \
        "%s: witness path does not run from start to goal" % name
    for p, _ in path:
        assert all(bmin[i] <= p[i] <= bmax[i] for i in range(3)), \
            "%s: waypoint %s out of bounds" % (name, p)
    ok, n = ps.certify_path(robot, path, boxes, clearance=0.01, log=print)
    assert ok, "%s: witness path collides" % name
    print("  witness path: %d waypoints, %d samples, 1 cm clear throughout (%.0f s)"
          % (len(path), n, time.time() - t0), flush=True)


def main():
    witness = read_witness(os.path.join(HERE, "witness_paths.yaml"))
    robots = {}
    for name in sys.argv[1:] or SCENES:
        check_scene(name, witness, robots)
    print("all piano scenes check out")


if __name__ == "__main__":
    main()
