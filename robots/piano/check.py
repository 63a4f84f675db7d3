#!/usr/bin/env python3
"""Checks the written piano scenes from the files alone (pure Python, ~1 minute):

- every OBJ object is a union of closed, outward, non-degenerate meshes;
- start and goal keep 2 cm from every obstacle (exact triangle / box test, obstacles
  taken as the boxes bounding each connected piece of each object: exact for walls,
  conservative for furniture);
- the straight line from start to goal puts a piano vertex 5 cm deep into an obstacle;
- the witness path in witness_paths.yaml runs from start to goal inside the bounds and
  keeps 1 cm clearance at samples between which no piano point moves more than 2 cm,
  so the whole continuous path is collision-free: every scene is solvable;
- with build/apps/gplan present: `gplan check scenes/<scene>.yaml --n 2000`.

    python3 robots/piano/check.py [scene ...]
"""

import math
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)

import geom  # noqa: E402
import passage as ps  # noqa: E402
from geom import Mesh  # noqa: E402

SCENES = ["piano", "piano_detailed", "large_piano"]


def read_obj(path):
    """[(name, Mesh)] of a triangulated OBJ with `o` objects (global vertex indices)."""
    verts, parts = [], []
    cur = None
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                verts.append(tuple(float(x) for x in line.split()[1:4]))
            elif line.startswith("o "):
                cur = (line[2:].strip(), [])
                parts.append(cur)
            elif line.startswith("f "):
                idx = [int(x.split("/")[0]) - 1 for x in line.split()[1:]]
                assert len(idx) == 3, "%s: non-triangle face" % path
                cur[1].append(tuple(idx))
    out = []
    for name, tris in parts:
        used = sorted({i for t in tris for i in t})
        remap = {i: k for k, i in enumerate(used)}
        out.append((name, Mesh([verts[i] for i in used],
                               [tuple(remap[i] for i in t) for t in tris])))
    return out


def component_boxes(name, mesh):
    """Bounding boxes of the connected pieces of a mesh (joined through positions)."""
    key = {}
    pos = [key.setdefault((round(v[0], 6), round(v[1], 6), round(v[2], 6)), len(key))
           for v in mesh.vertices]
    parent = list(range(len(key)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b, c in mesh.triangles:
        r = find(pos[a])
        parent[find(pos[b])] = r
        parent[find(pos[c])] = r
    groups = {}
    for i, v in enumerate(mesh.vertices):
        groups.setdefault(find(pos[i]), []).append(v)
    return [(name, tuple(min(v[k] for v in g) for k in range(3)),
             tuple(max(v[k] for v in g) for k in range(3))) for g in groups.values()]


def read_scene(path):
    text = open(path).read()
    nums = r"\[([^\]]*)\]"

    def vec(s):
        return tuple(float(x) for x in s.split(","))

    def pose(key):
        m = re.search(key + r":\s*\n\s*base:\s*\{xyz:\s*" + nums + r",\s*quat_wxyz:\s*" + nums,
                      text)
        return vec(m.group(1)), geom.quat_normalize(vec(m.group(2)))

    bmin = vec(re.search(r"bounds:\s*\n\s*min:\s*" + nums, text).group(1))
    bmax = vec(re.search(r"\n\s*max:\s*" + nums, text).group(1))
    robot = re.search(r"robot:\s*\n\s*mesh:\s*(\S+)", text).group(1)
    envs = re.findall(r"-\s*mesh:\s*(\S+)", text)
    for key in ("name", "description", "narrowest_passage"):
        assert re.search(r"^%s:" % key, text, re.M), "%s: no %s" % (path, key)
    return {"start": pose("start"), "goal": pose("goal"), "bounds": (bmin, bmax),
            "robot": os.path.join(os.path.dirname(path), robot),
            "envs": [os.path.join(os.path.dirname(path), e) for e in envs]}


def read_witness(path):
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
            geom.quat_angle(a[1], b[1]) < 1e-6)


def check_scene(name, witness, cache):
    t0 = time.time()
    sc = read_scene(os.path.join(ROOT, "scenes", name + ".yaml"))
    if sc["robot"] not in cache:
        parts = read_obj(sc["robot"])
        for nm, m in parts:
            geom.components_closed(m, nm)
        cache[sc["robot"]] = (parts, ps.Robot(parts))
    parts, robot = cache[sc["robot"]]
    boxes = []
    n_env = 0
    for e in sc["envs"]:
        for nm, m in read_obj(e):
            geom.components_closed(m, nm)
            boxes.extend(component_boxes(nm, m))
            n_env += len(m.triangles)
    n_robot = sum(len(m.triangles) for _, m in parts)
    print("%s: robot %d triangles, environment %d triangles (%d obstacle boxes)"
          % (name, n_robot, n_env, len(boxes)), flush=True)
    start, goal = sc["start"], sc["goal"]
    (bmin, bmax) = sc["bounds"]
    for label, pose in (("start", start), ("goal", goal)):
        hit = robot.collides(pose[0], pose[1], boxes, margin=0.02)
        assert not hit, "%s: %s within 2 cm of %s" % (name, label, hit)
        inside = min(min(pose[0][i] - bmin[i], bmax[i] - pose[0][i]) for i in range(3))
        assert inside >= 0.3, "%s: %s only %.2f m inside the bounds" % (name, label, inside)
    print("  start and goal: 2 cm clear of every obstacle, at least 0.3 m inside the bounds")
    for k in range(1, 200):
        t = k / 200
        p = tuple(start[0][i] + t * (goal[0][i] - start[0][i]) for i in range(3))
        hits = robot.vertex_inside(p, geom.slerp(start[1], goal[1], t), boxes, 0.05)
        if hits:
            print("  straight line: at t = %.3f a piano vertex is 5 cm deep in %s" % (t, hits[0]))
            break
    else:
        raise AssertionError("%s: the straight line start -> goal is free" % name)
    path = witness[name]
    assert same_pose(path[0], start) and same_pose(path[-1], goal), \
        "%s: witness path does not run from start to goal" % name
    for p, _ in path:
        assert all(bmin[i] <= p[i] <= bmax[i] for i in range(3)), "%s: waypoint %s out of bounds" \
            % (name, p)
    ok, n = ps.certify_path(robot, path, boxes, clearance=0.01, log=print)
    assert ok, "%s: witness path collides" % name
    print("  witness path: %d waypoints, %d samples, 1 cm clear throughout (%.0f s)"
          % (len(path), n, time.time() - t0), flush=True)
    gplan = os.path.join(ROOT, "build", "apps", "gplan")
    if os.path.exists(gplan):
        r = subprocess.run([gplan, "check", "scenes/%s.yaml" % name, "--n", "2000"], cwd=ROOT,
                           capture_output=True, text=True)
        print("  gplan check (exit %d):\n    %s" % (r.returncode, "\n    ".join(
            (r.stdout + r.stderr).strip().splitlines())))
        assert r.returncode == 0, "%s: gplan check failed" % name
    else:
        print("  (no build/apps/gplan: C++ check skipped)")


def main():
    witness = read_witness(os.path.join(HERE, "witness_paths.yaml"))
    cache = {}
    for name in sys.argv[1:] or SCENES:
        check_scene(name, witness, cache)
    print("all piano scenes check out")


if __name__ == "__main__":
    main()
