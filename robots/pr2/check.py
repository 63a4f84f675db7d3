#!/usr/bin/env python3
"""Authoring checks of gplanner's PR2 model and its scenes (standard library only).

    python3 robots/pr2/check.py            # meshes, URDF, SRDF, environment, scenes
    python3 robots/pr2/check.py --pairs N  # also: N random configurations, looking for
                                           # contacts of SRDF-disabled pairs

- meshes: every STL closed, outward, no degenerate triangles; triangle counts;
- URDF: four continuous joints without limits, six mimic joints;
- SRDF: its pairs name URDF links, its groups; every pair the PR2 MoveIt configuration
  checks is checked here (when shared/data/pr2_moveit_config is at hand); the reasons
  for disabling pairs: the "Default" pairs touch at the all-zero configuration, and
  (--pairs) which disabled pairs touch in random configurations, the evidence for
  the "Never" pairs. The C++ checker never tests a disabled pair, so this stays here;
  two links touch when GJK finds two of their convex pieces (the connected components
  of their meshes, which generate.py builds convex) intersecting;
- environment: triangles, every part closed;
- scenes: the planar base at start and goal at least 0.5 m inside the bounds.

Start and goal free, the straight line colliding and a path existing are the C++
tests' (tests/planner/shipped_scenes_test.cpp, tests/apps/gplan_plan_test.cpp).
"""

import math
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path[:0] = [HERE, os.path.dirname(HERE)]

import generate  # noqa: E402  (the scene names)
import meshlib as ml  # noqa: E402
from meshlib import cross, dot, sub  # noqa: E402


# ---------------------------------------------------------------------------------------
# GJK: whether the convex hulls of two point sets intersect
# ---------------------------------------------------------------------------------------


def neg(a):
    return (-a[0], -a[1], -a[2])


def _support(pts, d):
    best, bv = None, -1e300
    dx, dy, dz = d
    for p in pts:
        v = p[0] * dx + p[1] * dy + p[2] * dz
        if v > bv:
            bv, best = v, p
    return best


def _mink(A, B, d):
    return sub(_support(A, d), _support(B, neg(d)))


def _same(a, b):
    return dot(a, b) > 0


def _line(s):
    a, b = s
    ab, ao = sub(b, a), neg(a)
    if _same(ab, ao):
        return [a, b], cross(cross(ab, ao), ab)
    return [a], ao


def _triangle(s):
    a, b, c = s
    ab, ac, ao = sub(b, a), sub(c, a), neg(a)
    abc = cross(ab, ac)
    if _same(cross(abc, ac), ao):
        if _same(ac, ao):
            return [a, c], cross(cross(ac, ao), ac)
        return _line([a, b])
    if _same(cross(ab, abc), ao):
        return _line([a, b])
    if _same(abc, ao):
        return [a, b, c], abc
    return [a, c, b], neg(abc)


def _tetra(s):
    a, b, c, d = s
    ab, ac, ad, ao = sub(b, a), sub(c, a), sub(d, a), neg(a)
    abc, acd, adb = cross(ab, ac), cross(ac, ad), cross(ad, ab)
    if _same(abc, ao):
        return _triangle([a, b, c]), False
    if _same(acd, ao):
        return _triangle([a, c, d]), False
    if _same(adb, ao):
        return _triangle([a, d, b]), False
    return (s, None), True


def gjk(A, B):
    """True when the convex hulls of point sets A and B intersect (touching or
    degenerate cases count as intersecting)."""
    d = (1.0, 0.0, 0.0)
    s = [_mink(A, B, d)]
    d = neg(s[0])
    for _ in range(64):
        if dot(d, d) < 1e-24:
            return True
        p = _mink(A, B, d)
        if dot(p, d) <= 0:
            return False
        s = [p] + s
        if len(s) == 2:
            s, d = _line(s)
        elif len(s) == 3:
            s, d = _triangle(s)
        else:
            (s2, d2), inside = _tetra(s)
            if inside:
                return True
            s, d = s2, d2
    return True


def aabb_overlap(a, b):
    return all(a[0][i] < b[1][i] and b[0][i] < a[1][i] for i in range(3))


# ---------------------------------------------------------------------------------------
# The robot's links as convex pieces
# ---------------------------------------------------------------------------------------


class Links:
    def __init__(self, urdf_path):
        self.urdf = ml.Urdf(urdf_path)
        geometry = self.urdf.collision_geometry({"gplanner_robots": os.path.join(ROOT, "robots")})
        self.triangles = 0
        self.pieces = {}  # link -> [points], in the link frame
        split = {}
        for link, items in geometry.items():
            for origin, mesh in items:
                if id(mesh) not in split:  # each STL once (several links share one)
                    ml.check_closed(mesh, link)
                    split[id(mesh)] = [p.vertices for p in ml.components(mesh)]
                self.triangles += len(mesh)
                self.pieces.setdefault(link, []).extend(
                    ml.transform(origin, p) for p in split[id(mesh)])

    def world(self, q):
        """link -> [(points, aabb)] at configuration q ({joint: value}; others at 0 or
        their nearest limit)."""
        poses = self.urdf.fk(ml.IDENTITY, q)
        return {link: [(pts, ml.point_bounds(pts)) for pts in
                       (ml.transform(poses[link], p) for p in pieces)]
                for link, pieces in self.pieces.items()}


def link_aabb(pieces):
    lo = [min(b[0][i] for _, b in pieces) for i in range(3)]
    hi = [max(b[1][i] for _, b in pieces) for i in range(3)]
    return lo, hi


def touch(PA, PB):
    """Whether two links (lists of world pieces) touch."""
    if not aabb_overlap(link_aabb(PA), link_aabb(PB)):
        return False
    return any(aabb_overlap(ba, bb) and gjk(pa, pb) for pa, ba in PA for pb, bb in PB)


def sorted_pairs(links):
    return [tuple(sorted((a, b))) for i, a in enumerate(links) for b in links[i + 1:]]


# ---------------------------------------------------------------------------------------


def main():
    args = sys.argv[1:]
    failures = []

    def check(cond, msg):
        print(("  ok    " if cond else "  FAIL  ") + msg)
        if not cond:
            failures.append(msg)

    print("model")
    robot = Links(os.path.join(HERE, "pr2.urdf"))
    urdf = robot.urdf
    check(27000 <= robot.triangles <= 33000,
          "robot collision triangles %d (target about 30,000), %d convex pieces; every STL "
          "closed, outward, no degenerate triangles"
          % (robot.triangles, sum(len(p) for p in robot.pieces.values())))
    dis, groups = ml.read_srdf(os.path.join(HERE, "pr2.srdf"))
    check(all(a in urdf.link_el and b in urdf.link_el for a, b in dis),
          "SRDF pairs name URDF links")
    check({"left_arm", "right_arm", "torso", "arms"} <= set(groups),
          "SRDF groups " + ", ".join(sorted(groups)))
    coll = [l for l in urdf.links if l in robot.pieces]
    adjacent = {tuple(sorted((j.parent, j.child))) for j in urdf.joints}
    checked = [p for p in sorted_pairs(coll) if p not in dis and p not in adjacent]
    print("  %d collision links, %d disabled pairs, %d checked pairs"
          % (len(coll), len(dis), len(checked)))
    cont = [j for j in urdf.joints if j.type == "continuous"]
    check(len(cont) == 4 and all(j.lower is None for j in cont),
          "continuous joints without limits: " + ", ".join(sorted(j.name for j in cont)))
    mim = [j.name for j in urdf.joints if j.mimic]
    check(len(mim) == 6, "mimic joints: " + ", ".join(sorted(mim)))

    ref = os.path.join(ROOT, "..", "shared", "data", "pr2_moveit_config", "config", "pr2.srdf")
    if os.path.exists(ref):
        rdis, _ = ml.read_srdf(ref)
        ref_checked = [p for p in sorted_pairs(coll) if p not in rdis]
        missing = [p for p in ref_checked if p in dis]
        check(not missing, "every pair the reference PR2 SRDF checks is checked here (%d of them), "
              "every pair disabled here is disabled there" % len(ref_checked)
              + ("; missing: %s" % missing[:5] if missing else ""))
    else:
        print("  (no shared/data/pr2_moveit_config: the comparison with the PR2's SRDF skipped)")

    # every "Default" pair touches at the all-zero configuration: the reason it is disabled
    W = robot.world({})
    contacts = [p for p in dis if dis[p] == "Default"]
    touching = [p for p in contacts if touch(W[p[0]], W[p[1]])]
    check(len(touching) == len(contacts), "SRDF Default pairs in contact at zero: %d of %d"
          % (len(touching), len(contacts)))

    env = ml.read_obj(os.path.join(ROOT, "scenes", "environments", "pr2_table_shelf.obj"))
    for name, mesh in env:
        ml.check_closed(mesh, name)
    ntri = sum(len(m) for _, m in env)
    check(2000 <= ntri <= 4000, "environment triangles %d (target 2,000-4,000), %d parts, each "
          "closed and outward" % (ntri, len(env)))

    for name in generate.SCENES:
        scene = ml.read_yaml(os.path.join(ROOT, "scenes", name + ".yaml"))
        if "bounds" in scene:
            (a, b), (c, d) = scene["bounds"]["min"], scene["bounds"]["max"]
            for which in ("start", "goal"):
                x, y = scene[which]["base"]["xy"]
                check(a + 0.5 < x < c - 0.5 and b + 0.5 < y < d - 0.5,
                      "%s: %s base at least 0.5 m inside the bounds" % (name, which))

    if "--pairs" in args:
        sample_pairs(robot, dis, int(args[args.index("--pairs") + 1]))
    print("\n%s" % ("all checks passed" if not failures else "%d FAILED" % len(failures)))
    return 1 if failures else 0


def sample_pairs(robot, dis, n):
    """Random configurations over all joint ranges; reports the disabled (non-adjacent)
    pairs that come into contact (generate.py keeps those checked)."""
    rng = random.Random(12345)
    joints = robot.urdf.actuated()
    hits = {}
    pairs = [p for p, r in dis.items() if r != "Adjacent"]
    for k in range(n):
        q = {j.name: rng.uniform(*((j.lower, j.upper) if j.lower is not None
                                   else (-math.pi, math.pi))) for j in joints}
        W = robot.world(q)
        for a, b in pairs:
            if touch(W[a], W[b]):
                hits[(a, b)] = hits.get((a, b), 0) + 1
        if (k + 1) % 500 == 0:
            print("  %d samples, %d disabled pairs in contact so far" % (k + 1, len(hits)),
                  flush=True)
    print("disabled pairs in contact (count of %d samples):" % n)
    for p, c in sorted(hits.items(), key=lambda x: -x[1]):
        print("  %4d  %s %s  (%s)" % (c, p[0], p[1], dis[p]))


if __name__ == "__main__":
    sys.exit(main())
