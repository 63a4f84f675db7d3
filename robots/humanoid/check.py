#!/usr/bin/env python3
"""Authoring checks of the humanoid and its scene in pure Python (from any directory):

- URDF: root `pelvis`, 32 revolute joints with complete limits, every link with a
  collision mesh and inertia;
- meshes: closed, outward winding, no degenerate triangles, triangle totals in range;
- SRDF: the group holds the 32 joints, as the scene's planned_joints do; disabled
  pairs name real links;
- scene: its keys, a floating base, one mesh obstacle, the pelvis at start and goal
  at least 0.1 m inside the bounds.

Start and goal free, the straight line colliding and a path existing are the C++
tests' (tests/planner/shipped_scenes_test.cpp, tests/apps/gplan_plan_test.cpp); joint
values within their limits, the scene loader's. That the zero pose is free of
self-collision holds by construction: generate.py disables every pair that comes
within 1 cm there.
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))

import meshlib as ml  # noqa: E402

SCENE = os.path.join(ROOT, "scenes", "humanoid.yaml")
ROBOT_TRIS = (25200, 30800)
ENV_TRIS = (3150, 3850)


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def main():
    scene = ml.read_yaml(SCENE)
    sdir = os.path.dirname(SCENE)
    for key in ("name", "description", "narrowest_passage", "robot", "obstacles", "bounds",
                "start", "goal"):
        if key not in scene:
            fail("scene lacks %s" % key)
    rob = scene["robot"]
    if rob.get("base") != "floating":
        fail("base must be floating")
    packages = {k: os.path.normpath(os.path.join(sdir, v)) for k, v in rob["packages"].items()}
    urdf = ml.Urdf(os.path.normpath(os.path.join(sdir, rob["urdf"])))
    if urdf.root != "pelvis":
        fail("root link is %s" % urdf.root)
    act = urdf.actuated()
    if len(act) != 32 or any(j.type != "revolute" for j in act):
        fail("expected 32 revolute joints, got %d" % len(act))
    for j in act:
        if any(j.limit.get(k) is None for k in ("lower", "upper", "effort", "velocity")):
            fail("%s: incomplete <limit>" % j.name)
        if not j.lower < j.upper:
            fail("%s: empty range" % j.name)
    for name, el in urdf.link_el.items():
        if el.find("collision") is None or el.find("inertial") is None:
            fail("link %s lacks collision or inertial" % name)

    total = 0
    for link, items in sorted(urdf.collision_geometry(packages).items()):
        for _, mesh in items:
            try:
                ml.check_closed(mesh, link)
            except AssertionError as e:
                fail(str(e))
            total += len(mesh)
    if not ROBOT_TRIS[0] <= total <= ROBOT_TRIS[1]:
        fail("robot has %d triangles, want %s" % (total, ROBOT_TRIS))
    print("robot: %d links, %d revolute joints, %d triangles, meshes closed and outward"
          % (len(urdf.links), len(act), total))

    disabled, groups = ml.read_srdf(os.path.normpath(os.path.join(sdir, rob["srdf"])))
    joints = sorted(j.name for j in act)
    group = sorted(j for g in groups.values() for j in g)
    if group != joints or sorted(rob["planned_joints"]) != joints:
        fail("SRDF group / planned_joints do not match the 32 URDF joints")
    for a, b in disabled:
        if a not in urdf.link_el or b not in urdf.link_el:
            fail("disable_collisions names unknown link %s/%s" % (a, b))
    print("srdf: %d disabled pairs, the group and planned_joints are the 32 joints"
          % len(disabled))

    obs = scene["obstacles"]
    if len(obs) != 1 or "mesh" not in obs[0]:
        fail("expected one mesh obstacle")
    env = ml.read_obj(os.path.normpath(os.path.join(sdir, obs[0]["mesh"])))
    for name, mesh in env:
        try:
            ml.check_closed(mesh, name)
        except AssertionError as e:
            fail("obstacle " + str(e))
    env_tris = sum(len(m) for _, m in env)
    if not ENV_TRIS[0] <= env_tris <= ENV_TRIS[1]:
        fail("environment has %d triangles, want %s" % (env_tris, ENV_TRIS))
    print("environment: %d parts, %d triangles, all closed and outward" % (len(env), env_tris))

    lo, hi = scene["bounds"]["min"], scene["bounds"]["max"]
    for key in ("start", "goal"):
        xyz = scene[key]["base"]["xyz"]
        if not all(lo[i] + 0.1 <= xyz[i] <= hi[i] - 0.1 for i in range(3)):
            fail("%s pelvis %s not well inside the bounds" % (key, xyz))
    print("start and goal: the pelvis at least 0.1 m inside the bounds")
    print("OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
