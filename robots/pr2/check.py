#!/usr/bin/env python3
"""Checks gplanner's PR2 model and its scenes in pure Python (standard library only).

    python3 robots/pr2/check.py            # meshes, URDF/SRDF, both scenes
    python3 robots/pr2/check.py --pairs N  # also: N random configurations, looking for
                                           # contacts of SRDF-disabled pairs
    python3 robots/pr2/check.py --witness  # also: a collision-free witness path for each
                                           # scene (RRT-Connect on this file's own collision
                                           # test; some 10-20 minutes)

What it does:
  - reads the generated URDF (forward kinematics: origin xyz/rpy, then the rotation about
    the axis or the translation along it; mimic joints), the SRDF and the binary STLs;
  - meshes: closed (every edge used twice, in opposite directions), outward (positive
    volume), no degenerate triangles, no NaNs; each link mesh splits into convex pieces
    (its connected components); triangle counts;
  - start and goal of both scenes: per-link AABBs against every obstacle part's AABB, and
    where those overlap, the link's convex pieces against the part with GJK and a clearance
    margin; every SRDF-checked link pair the same way (self-collision); the all-zero
    configuration too (self-collision);
  - the straight line between start and goal: a sample where a robot mesh vertex lies
    strictly inside an obstacle box (table top or shelf board), and the robot's pieces
    intersect that part (GJK);
  - runs build/apps/gplan check on both scenes when the tool has been built.
"""

import math
import os
import random
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import generate  # noqa: E402  (scene definitions, link lists)

MARGIN_ENV = 0.02     # required clearance robot <-> environment at start and goal (m)
MARGIN_SELF = 0.02    # required clearance between checked link pairs at start and goal (m)
MARGIN_JOINT = 0.005  # ... for pairs whose gap is set by the joint's design, not the pose
JOINT_GAPS = {"forearm_link|wrist_roll_link", "forearm_link|gripper_palm_link",
              "forearm_roll_link|upper_arm_link", "forearm_link|upper_arm_link"}


def pair_margin(a, b):
    """The wrist clevis and the elbow clevis keep their links a few mm apart at any pose."""
    if a[:2] == b[:2] and (a[2:] + "|" + b[2:] in JOINT_GAPS or b[2:] + "|" + a[2:] in JOINT_GAPS):
        return MARGIN_JOINT
    return MARGIN_SELF

# ---------------------------------------------------------------------------------------
# small linear algebra
# ---------------------------------------------------------------------------------------


def rpy_matrix(r, p, y):
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]


def axis_angle(a, q):
    x, y, z = a
    n = math.sqrt(x * x + y * y + z * z)
    x, y, z = x / n, y / n, z / n
    c, s, C = math.cos(q), math.sin(q), 1 - math.cos(q)
    return [[c + x * x * C, x * y * C - z * s, x * z * C + y * s],
            [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
            [z * x * C - y * s, z * y * C + x * s, c + z * z * C]]


def mat_mul(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def mat_vec(A, v):
    return [A[0][0] * v[0] + A[0][1] * v[1] + A[0][2] * v[2],
            A[1][0] * v[0] + A[1][1] * v[1] + A[1][2] * v[2],
            A[2][0] * v[0] + A[2][1] * v[1] + A[2][2] * v[2]]


def compose(T1, T2):
    R1, t1 = T1
    R2, t2 = T2
    return mat_mul(R1, R2), [a + b for a, b in zip(mat_vec(R1, t2), t1)]


IDENT = ([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [0.0, 0.0, 0.0])


def apply(T, pts):
    R, t = T
    return [(R[0][0] * p[0] + R[0][1] * p[1] + R[0][2] * p[2] + t[0],
             R[1][0] * p[0] + R[1][1] * p[1] + R[1][2] * p[2] + t[1],
             R[2][0] * p[0] + R[2][1] * p[1] + R[2][2] * p[2] + t[2]) for p in pts]


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def neg(a):
    return (-a[0], -a[1], -a[2])


# ---------------------------------------------------------------------------------------
# GJK (boolean, with a margin: A grown by a ball of radius `margin`)
# ---------------------------------------------------------------------------------------


def _support(pts, d):
    best, bv = None, -1e300
    dx, dy, dz = d
    for p in pts:
        v = p[0] * dx + p[1] * dy + p[2] * dz
        if v > bv:
            bv, best = v, p
    return best


def _mink(A, B, d, margin):
    a = _support(A, d)
    b = _support(B, neg(d))
    n = math.sqrt(dot(d, d)) or 1.0
    return (a[0] - b[0] + margin * d[0] / n, a[1] - b[1] + margin * d[1] / n,
            a[2] - b[2] + margin * d[2] / n)


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


def gjk(A, B, margin=0.0):
    """True when the convex hulls of point sets A and B come closer than `margin`
    (touching or degenerate cases count as intersecting: conservative)."""
    d = (1.0, 0.0, 0.0)
    s = [_mink(A, B, d, margin)]
    d = neg(s[0])
    for _ in range(64):
        if dot(d, d) < 1e-24:
            return True
        p = _mink(A, B, d, margin)
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


def clearance(A, B, hi=0.3):
    """Distance between convex hulls of A and B, to 1 mm (0 when they intersect)."""
    if gjk(A, B, 0.0):
        return 0.0
    if not gjk(A, B, hi):
        return hi
    lo = 0.0
    while hi - lo > 0.001:
        mid = 0.5 * (lo + hi)
        if gjk(A, B, mid):
            hi = mid
        else:
            lo = mid
    return lo


def aabb(pts):
    return ([min(p[i] for p in pts) for i in range(3)], [max(p[i] for p in pts) for i in range(3)])


def aabb_overlap(a, b, margin=0.0):
    return all(a[0][i] - margin < b[1][i] and b[0][i] - margin < a[1][i] for i in range(3))


# ---------------------------------------------------------------------------------------
# Meshes
# ---------------------------------------------------------------------------------------


def read_stl(path):
    with open(path, "rb") as f:
        data = f.read()
    n = struct.unpack("<I", data[80:84])[0]
    assert len(data) == 84 + 50 * n, path + ": not a binary STL of %d triangles" % n
    tris = []
    for i in range(n):
        v = struct.unpack("<12f", data[84 + 50 * i: 84 + 50 * i + 48])
        tris.append((v[3:6], v[6:9], v[9:12]))
    return tris


def weld(tris):
    index, verts, faces = {}, [], []
    for t in tris:
        f = []
        for p in t:
            key = tuple(round(c, 6) for c in p)
            if key not in index:
                index[key] = len(verts)
                verts.append(tuple(float(c) for c in p))
            f.append(index[key])
        faces.append(tuple(f))
    return verts, faces


def validate_mesh(name, verts, faces):
    """Closed, consistently outward, no degenerate triangles, no NaN; returns the convex
    pieces (connected components) as vertex lists."""
    for v in verts:
        assert all(math.isfinite(c) for c in v), name + ": NaN/inf vertex"
    edges = {}
    for f in faces:
        a, b, c = (verts[i] for i in f)
        n = cross(sub(b, a), sub(c, a))
        assert math.sqrt(dot(n, n)) > 1e-12, name + ": degenerate triangle"
        for i in range(3):
            e = (f[i], f[(i + 1) % 3])
            assert e not in edges, name + ": edge used twice in one direction"
            edges[e] = True
    for (a, b) in edges:
        assert (b, a) in edges, name + ": open edge"
    # components
    parent = list(range(len(verts)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for f in faces:
        for i in (1, 2):
            ra, rb = find(f[0]), find(f[i])
            if ra != rb:
                parent[ra] = rb
    comps = {}
    for fi, f in enumerate(faces):
        comps.setdefault(find(f[0]), []).append(f)
    pieces = []
    for fs in comps.values():
        vol = 0.0
        for f in fs:
            a, b, c = (verts[i] for i in f)
            vol += dot(a, cross(b, c)) / 6.0
        assert vol > 0, name + ": a piece is inside out (volume %g)" % vol
        ids = sorted({i for f in fs for i in f})
        pieces.append([verts[i] for i in ids])
    return pieces


def box_points(size, xyz=(0, 0, 0)):
    return [(xyz[0] + sx * size[0] / 2, xyz[1] + sy * size[1] / 2, xyz[2] + sz * size[2] / 2)
            for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]


# ---------------------------------------------------------------------------------------
# URDF model
# ---------------------------------------------------------------------------------------


class Robot:
    def __init__(self, urdf_path):
        root = ET.parse(urdf_path).getroot()
        self.links, self.joints, self.children = {}, {}, {}
        self.triangles = 0
        cache = {}
        for l in root.findall("link"):
            pieces = []
            for c in l.findall("collision"):
                o = c.find("origin")
                xyz = [float(x) for x in o.get("xyz", "0 0 0").split()] if o is not None else [0] * 3
                rpy = [float(x) for x in o.get("rpy", "0 0 0").split()] if o is not None else [0] * 3
                g = c.find("geometry")[0]
                T = (rpy_matrix(*rpy), xyz)
                if g.tag == "mesh":
                    fn = g.get("filename")
                    assert fn.startswith("package://gplanner_robots/"), fn
                    path = os.path.join(ROOT, "robots", fn[len("package://gplanner_robots/"):])
                    if path not in cache:
                        tris = read_stl(path)
                        verts, faces = weld(tris)
                        cache[path] = (validate_mesh(fn, verts, faces), len(tris))
                    ps, nt = cache[path]
                    self.triangles += nt
                    pieces += [apply(T, p) for p in ps]
                elif g.tag == "box":
                    size = [float(x) for x in g.get("size").split()]
                    pieces.append(apply(T, box_points(size)))
                    self.triangles += 12
                else:
                    raise AssertionError("unexpected geometry " + g.tag)
            self.links[l.get("name")] = pieces
        for j in root.findall("joint"):
            o = j.find("origin")
            a = j.find("axis")
            lim = j.find("limit")
            m = j.find("mimic")
            jd = {
                "name": j.get("name"), "type": j.get("type"),
                "parent": j.find("parent").get("link"), "child": j.find("child").get("link"),
                "T": (rpy_matrix(*[float(x) for x in o.get("rpy", "0 0 0").split()]),
                      [float(x) for x in o.get("xyz", "0 0 0").split()]),
                "axis": [float(x) for x in a.get("xyz").split()] if a is not None else [1, 0, 0],
                "lower": float(lim.get("lower")) if lim is not None and lim.get("lower") else None,
                "upper": float(lim.get("upper")) if lim is not None and lim.get("upper") else None,
                "mimic": (m.get("joint"), float(m.get("multiplier", 1)), float(m.get("offset", 0)))
                if m is not None else None,
            }
            self.joints[jd["name"]] = jd
            self.children.setdefault(jd["parent"], []).append(jd)
        childs = {j["child"] for j in self.joints.values()}
        roots = [l for l in self.links if l not in childs]
        assert len(roots) == 1, roots
        self.root = roots[0]
        self.parent_of = {j["child"]: j["parent"] for j in self.joints.values()}
        # local piece AABBs for quick culling
        self.local = {n: [(p, aabb(p)) for p in ps] for n, ps in self.links.items()}

    def movable(self):
        return [j for j in self.joints.values() if j["type"] != "fixed" and j["mimic"] is None]

    def fk(self, q, base=IDENT):
        """Link name -> world transform; q: joint name -> value (missing: 0, or the nearest
        limit when 0 is outside the range)."""
        out = {self.root: base}

        def value(j):
            if j["mimic"] is not None:
                mj, mul, off = j["mimic"]
                return mul * value(self.joints[mj]) + off
            if j["name"] in q:
                return q[j["name"]]
            lo, hi = j["lower"], j["upper"]
            if lo is not None and j["type"] != "continuous":
                return min(max(0.0, lo), hi)
            return 0.0

        stack = [self.root]
        while stack:
            l = stack.pop()
            for j in self.children.get(l, []):
                T = compose(out[l], j["T"])
                if j["type"] in ("revolute", "continuous"):
                    T = compose(T, (axis_angle(j["axis"], value(j)), [0, 0, 0]))
                elif j["type"] == "prismatic":
                    v = value(j)
                    T = compose(T, (IDENT[0], [a * v for a in j["axis"]]))
                out[j["child"]] = T
                stack.append(j["child"])
        return out

    def world_pieces(self, Ts):
        """Link -> list of (points, aabb) in the world."""
        res = {}
        for n, ps in self.links.items():
            if ps:
                res[n] = [(pts, aabb(pts)) for pts in (apply(Ts[n], p) for p in ps)]
        return res


def link_aabb(pieces):
    lo = [min(b[0][i] for _, b in pieces) for i in range(3)]
    hi = [max(b[1][i] for _, b in pieces) for i in range(3)]
    return lo, hi


def pieces_collide(PA, PB, margin):
    for pa, ba in PA:
        for pb, bb in PB:
            if aabb_overlap(ba, bb, margin) and gjk(pa, pb, margin):
                return True
    return False


def pieces_clearance(PA, PB, cap=0.3):
    best = cap
    for pa, ba in PA:
        for pb, bb in PB:
            if aabb_overlap(ba, bb, best):
                best = min(best, clearance(pa, pb, best))
    return best


# ---------------------------------------------------------------------------------------
# SRDF, environment, scenes
# ---------------------------------------------------------------------------------------


def read_srdf(path):
    root = ET.parse(path).getroot()
    dis = {}
    for e in root.findall("disable_collisions"):
        dis[tuple(sorted((e.get("link1"), e.get("link2"))))] = e.get("reason")
    groups = {g.get("name") for g in root.findall("group")}
    return dis, groups


def read_obj(path, validate=False):
    """Parts of an OBJ (`o name` groups): name -> (vertices, aabb); and triangle counts.
    validate: also checks each part is closed, outward and free of degenerate triangles."""
    parts, faces, cur, verts, counts = {}, {}, None, [], {}
    with open(path) as f:
        for line in f:
            if line.startswith("o "):
                cur = line.split()[1]
                parts[cur], faces[cur], counts[cur] = [], [], 0
            elif line.startswith("v "):
                v = tuple(float(x) for x in line.split()[1:4])
                verts.append(v)
                parts[cur].append(v)
            elif line.startswith("f "):
                counts[cur] += 1
                faces[cur].append(tuple(int(x.split("/")[0]) - 1 for x in line.split()[1:4]))
    if validate:
        for name, fs in faces.items():  # welded by position, as meshlib's boxes repeat vertices
            validate_mesh(name, *weld([tuple(verts[i] for i in f) for f in fs]))
    return {n: (p, aabb(p)) for n, p in parts.items()}, counts


def env_boxes():
    """Obstacle parts that are exact boxes (for 'vertex strictly inside'): name -> (lo, hi).
    The table top is a rounded rectangle; its inner box (corners cut) is used."""
    boxes = {}
    for name, kind, data, _ in generate.env_parts():
        if kind == "box":
            boxes[name] = data
    x0, x1 = generate.TABLE_X
    y0, y1 = generate.TABLE_Y
    boxes["table_top"] = ((x0 + 0.03, y0 + 0.03, generate.TABLE_TOP[0]),
                          (x1 - 0.03, y1 - 0.03, generate.TABLE_TOP[1]))
    return boxes


def scene_config(sc, which):
    q = dict(sc["fixed"])
    q.update(sc[which])
    x, y, th = sc[which + "_base"]
    base = ([[math.cos(th), -math.sin(th), 0], [math.sin(th), math.cos(th), 0], [0, 0, 1]], [x, y, 0.0])
    return q, base


def interpolate(sc, t):
    q = dict(sc["fixed"])
    for j in sc["planned"]:
        q[j] = (1 - t) * sc["start"][j] + t * sc["goal"][j]
    b0, b1 = sc["start_base"], sc["goal_base"]
    x, y, th = [(1 - t) * a + t * b for a, b in zip(b0, b1)]
    base = ([[math.cos(th), -math.sin(th), 0], [math.sin(th), math.cos(th), 0], [0, 0, 1]], [x, y, 0.0])
    return q, base


def env_report(robot, env, W, margin):
    """Returns (ok, min clearance (capped at 0.3 m), closest (link, part), number of
    link/part AABB overlaps (within the margin), each resolved by GJK)."""
    ok, best, where, n_aabb = True, 0.3, None, 0
    for ln, P in W.items():
        la = link_aabb(P)
        for pn, (pts, pa) in env.items():
            if not aabb_overlap(la, pa, 0.3):
                continue
            n_aabb += aabb_overlap(la, pa, margin)
            c = pieces_clearance(P, [(pts, pa)], cap=0.3)
            if c < best:
                best, where = c, (ln, pn)
            if c < margin:
                ok = False
    return ok, best, where, n_aabb


def self_report(W, pairs, margin=None):
    """margin None: pair_margin() per pair. Returns (ok, clearance of the pair with the
    least slack over its margin, that pair, [pairs below their margin])."""
    ok, slack, best, where, bad = True, 1.0, 0.3, None, []
    for a, b in pairs:
        if a not in W or b not in W:
            continue
        m = pair_margin(a, b) if margin is None else margin
        if not aabb_overlap(link_aabb(W[a]), link_aabb(W[b]), max(m, 0.05)):
            continue
        c = pieces_clearance(W[a], W[b], cap=0.3)
        if c - m < slack:
            slack, best, where = c - m, c, (a, b)
        if c < m:
            ok = False
            bad.append((a, b, c))
    return ok, best, where, bad


def inside_box(p, lo, hi, eps=1e-4):
    return all(lo[i] + eps < p[i] < hi[i] - eps for i in range(3))


# ---------------------------------------------------------------------------------------


def main():
    args = sys.argv[1:]
    failures = []

    def check(cond, msg):
        print(("  ok    " if cond else "  FAIL  ") + msg)
        if not cond:
            failures.append(msg)

    generate.build_tree()
    print("model")
    robot = Robot(os.path.join(HERE, "pr2.urdf"))
    npieces = sum(len(p) for p in robot.links.values())
    check(27000 <= robot.triangles <= 33000,
          "robot collision triangles %d (target about 30,000), %d convex pieces; every STL "
          "closed, outward, no degenerate triangles" % (robot.triangles, npieces))
    names = set(robot.links)
    dis, groups = read_srdf(os.path.join(HERE, "pr2.srdf"))
    check(all(a in names and b in names for a, b in dis), "SRDF pairs name URDF links")
    check({"left_arm", "right_arm", "torso", "arms"} <= groups, "SRDF groups " + ", ".join(sorted(groups)))
    coll = [l for l in robot.links if robot.links[l]]
    adjacent = {tuple(sorted((j["parent"], j["child"]))) for j in robot.joints.values()}
    checked = [tuple(sorted((a, b))) for i, a in enumerate(coll) for b in coll[i + 1:]
               if tuple(sorted((a, b))) not in dis and tuple(sorted((a, b))) not in adjacent]
    print("  %d collision links, %d disabled pairs, %d checked pairs" % (len(coll), len(dis), len(checked)))
    cont = [j["name"] for j in robot.joints.values() if j["type"] == "continuous"]
    check(len(cont) == 4 and all(robot.joints[j]["lower"] is None for j in cont),
          "continuous joints without limits: " + ", ".join(sorted(cont)))
    mim = [j["name"] for j in robot.joints.values() if j["mimic"]]
    check(len(mim) == 6, "mimic joints: " + ", ".join(sorted(mim)))

    ref = os.path.join(ROOT, "..", "shared", "data", "pr2_moveit_config", "config", "pr2.srdf")
    if os.path.exists(ref):
        rdis, _ = read_srdf(ref)
        ref_checked = [p for p in checked_all(coll) if p not in rdis]
        missing = [p for p in ref_checked if p in dis]
        check(not missing, "every pair the reference PR2 SRDF checks is checked here (%d of them), "
              "every pair disabled here is disabled there" % len(ref_checked)
              + ("; missing: %s" % missing[:5] if missing else ""))

    env, counts = read_obj(os.path.join(ROOT, "scenes", "environments", "pr2_table_shelf.obj"), True)
    ntri = sum(counts.values())
    check(2000 <= ntri <= 4000, "environment triangles %d (target 2,000-4,000), %d parts, each "
          "closed and outward" % (ntri, len(env)))
    lo = [min(b[0][i] for _, b in env.values()) for i in range(3)]
    hi = [max(b[1][i] for _, b in env.values()) for i in range(3)]
    print("  environment bounds: [%.2f, %.2f, %.2f] .. [%.2f, %.2f, %.2f]" % (*lo, *hi))
    boxes = env_boxes()

    # zero configuration: self-collision
    print("all-zero configuration")
    W = robot.world_pieces(robot.fk({}))
    ok, best, where, bad = self_report(W, checked, 0.0)
    check(ok, "checked pairs free (closest %s: %.3f m)%s" % (where, best, bad[:3] if bad else ""))
    contacts = [p for p in dis if dis[p] == "Default"]
    touching = [p for p in contacts if pieces_collide(W[p[0]], W[p[1]], 0.0)]
    check(len(touching) == len(contacts), "SRDF Default pairs in contact at zero: %d of %d"
          % (len(touching), len(contacts)))

    for name, sc in generate.SCENES.items():
        print("scene " + name)
        for which in ("start", "goal"):
            q, base = scene_config(sc, which)
            for j, v in q.items():
                jd = robot.joints[j]
                if jd["lower"] is not None:
                    assert jd["lower"] <= v <= jd["upper"], (j, v)
            W = robot.world_pieces(robot.fk(q, base))
            ok, best, where, n = env_report(robot, env, W, MARGIN_ENV)
            check(ok, "%s: environment clearance %.3f m >= %.2f (closest %s; %d link/part AABB "
                  "overlaps resolved by GJK)" % (which, best, MARGIN_ENV, where, n))
            ok, best, where, bad = self_report(W, checked)
            check(ok, "%s: self clearance >= %.3f m over checked pairs (%.3f at the joints' "
                  "own clevis gaps); tightest: %s at %.3f m%s"
                  % (which, MARGIN_SELF, MARGIN_JOINT, where, best, bad[:3] if bad else ""))
            if "bounds" in sc:
                (a, b), (c, d) = sc["bounds"]
                x, y = base[1][0], base[1][1]
                check(a + 0.5 < x < c - 0.5 and b + 0.5 < y < d - 0.5, "%s base inside bounds" % which)
        # straight line
        hit = None
        for k in range(1, 100):
            t = k / 100.0
            q, base = interpolate(sc, t)
            Ts = robot.fk(q, base)
            for ln, ps in robot.links.items():
                if not ps:
                    continue
                for p in ps:
                    for v in apply(Ts[ln], p):
                        for bn, (lo, hi) in boxes.items():
                            if inside_box(v, lo, hi):
                                hit = (t, ln, bn, v)
                                break
                        if hit:
                            break
                    if hit:
                        break
                if hit:
                    break
            if hit:
                break
        check(hit is not None, "straight line: %s" % (
            "at t=%.2f a vertex of %s is strictly inside %s at (%.3f, %.3f, %.3f)"
            % (hit[0], hit[1], hit[2], *hit[3]) if hit else "no vertex inside an obstacle box"))
        if hit:
            q, base = interpolate(sc, hit[0])
            W = robot.world_pieces(robot.fk(q, base))
            check(pieces_collide(W[hit[1]], [env[hit[2]]], 0.0), "  GJK agrees: %s intersects %s"
                  % (hit[1], hit[2]))

    if "--pairs" in args:
        n = int(args[args.index("--pairs") + 1])
        sample_pairs(robot, dis, n)
    if "--witness" in args:
        witness(robot, env, checked, failures)

    gplan = os.path.join(ROOT, "build", "apps", "gplan")
    if os.path.exists(gplan):
        for name in generate.SCENES:
            r = subprocess.run([gplan, "check", "scenes/%s.yaml" % name, "--n", "2000"], cwd=ROOT,
                               capture_output=True, text=True)
            print("gplan check %s: rc=%d\n%s%s" % (name, r.returncode, r.stdout, r.stderr))
            if r.returncode != 0:
                failures.append("gplan check " + name)
    else:
        print("(build/apps/gplan not built: skipped the C++ check)")
    print("\n%s" % ("all checks passed" if not failures else "%d FAILED" % len(failures)))
    return 1 if failures else 0


def checked_all(coll):
    return [tuple(sorted((a, b))) for i, a in enumerate(coll) for b in coll[i + 1:]]


def sample_pairs(robot, dis, n):
    """Random configurations over all joint ranges; reports disabled (non-adjacent) pairs
    that come into contact."""
    rng = random.Random(12345)
    mov = robot.movable()
    hits = {}
    pairs = [p for p, r in dis.items() if r != "Adjacent"]
    for k in range(n):
        q = {}
        for j in mov:
            lo, hi = (j["lower"], j["upper"]) if j["lower"] is not None else (-math.pi, math.pi)
            q[j["name"]] = rng.uniform(lo, hi)
        W = robot.world_pieces(robot.fk(q))
        for a, b in pairs:
            if aabb_overlap(link_aabb(W[a]), link_aabb(W[b])) and pieces_collide(W[a], W[b], 0.0):
                hits[(a, b)] = hits.get((a, b), 0) + 1
        if (k + 1) % 500 == 0:
            print("  %d samples, %d disabled pairs in contact so far" % (k + 1, len(hits)), flush=True)
    print("disabled pairs in contact (count of %d samples):" % n)
    for p, c in sorted(hits.items(), key=lambda x: -x[1]):
        print("  %4d  %s %s  (%s)" % (c, p[0], p[1], dis[p]))


# ---------------------------------------------------------------------------------------
# Witness paths: a small RRT-Connect on this file's own collision test (contact, no
# margin), to show each scene has a solution.
# ---------------------------------------------------------------------------------------


class Checker:
    def __init__(self, robot, env, pairs):
        self.robot = robot
        self.pairs = pairs
        self.env = []
        for name, (pts, bb) in env.items():
            self.env.append((name, pts, bb))
        self.local = {}
        for ln, ps in robot.links.items():
            if ps:
                self.local[ln] = [(p, [(x, y, z) for x in (b[0][0], b[1][0]) for y in (b[0][1], b[1][1])
                                       for z in (b[0][2], b[1][2])]) for p, b in
                                  ((p, aabb(p)) for p in ps)]
        self.calls = 0

    def collides(self, q, base):
        self.calls += 1
        Ts = self.robot.fk(q, base)
        boxes, cache = {}, {}
        for ln, ps in self.local.items():
            pb = [aabb(apply(Ts[ln], corners)) for _, corners in ps]
            boxes[ln] = (pb, ([min(b[0][i] for b in pb) for i in range(3)],
                              [max(b[1][i] for b in pb) for i in range(3)]))

        def pts(ln, k):
            key = (ln, k)
            if key not in cache:
                cache[key] = apply(Ts[ln], self.local[ln][k][0])
            return cache[key]

        for ln, (pb, lb) in boxes.items():
            for name, epts, eb in self.env:
                if not aabb_overlap(lb, eb):
                    continue
                for k, b in enumerate(pb):
                    if aabb_overlap(b, eb) and gjk(pts(ln, k), epts):
                        return True
        for a, b in self.pairs:
            pa, la = boxes[a]
            pb2, lb = boxes[b]
            if not aabb_overlap(la, lb):
                continue
            for i, ba in enumerate(pa):
                if not aabb_overlap(ba, lb):
                    continue
                for k, bb in enumerate(pb2):
                    if aabb_overlap(ba, bb) and gjk(pts(a, i), pts(b, k)):
                        return True
        return False


class Space:
    """A scene's configuration space: base (planar: x y theta) then planned joints."""

    def __init__(self, robot, sc, active=None):
        self.sc = sc
        self.planar = sc["base"] == "planar"
        self.names = active or sc["planned"]
        self.lo, self.hi = [], []
        if self.planar:
            (a, b), (c, d) = sc["bounds"]
            self.lo += [a, b, -math.pi]
            self.hi += [c, d, math.pi]
        for j in self.names:
            jd = robot.joints[j]
            lo, hi = (jd["lower"], jd["upper"]) if jd["lower"] is not None else (-math.pi, math.pi)
            self.lo.append(lo)
            self.hi.append(hi)

    def config(self, which):
        v = list(self.sc[which + "_base"]) if self.planar else []
        return tuple(v + [self.sc[which][j] for j in self.names])

    def of(self, q, base=None):
        return tuple((list(base) if self.planar else []) + [q[j] for j in self.names])

    def split(self, v):
        q = dict(self.sc["fixed"])
        k = 3 if self.planar else 0
        for j, x in zip(self.names, v[k:]):
            q[j] = x
        x, y, th = v[:3] if self.planar else (0.0, 0.0, 0.0)
        base = ([[math.cos(th), -math.sin(th), 0], [math.sin(th), math.cos(th), 0], [0, 0, 1]], [x, y, 0.0])
        return q, base

    def dist(self, a, b):
        return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))

    def sample(self, rng):
        return tuple(rng.uniform(l, h) for l, h in zip(self.lo, self.hi))


def edge_free(ck, sp, a, b, res):
    n = max(1, int(math.ceil(max(abs(x - y) for x, y in zip(a, b)) / res)))
    for k in range(1, n + 1):
        t = k / n
        if ck.collides(*sp.split(tuple(x + t * (y - x) for x, y in zip(a, b)))):
            return False
    return True


def rrt_connect(ck, sp, qs, qg, rng, step=0.25, res=0.02, max_nodes=20000):
    trees = [([qs], [-1]), ([qg], [-1])]

    def nearest(tree, q):
        return min(range(len(tree[0])), key=lambda i: sp.dist(tree[0][i], q))

    def steer(a, b):
        d = sp.dist(a, b)
        if d <= step:
            return b
        return tuple(x + (y - x) * step / d for x, y in zip(a, b))

    def extend(tree, q):
        i = nearest(tree, q)
        new = steer(tree[0][i], q)
        if edge_free(ck, sp, tree[0][i], new, res):
            tree[0].append(new)
            tree[1].append(i)
            return "reached" if new == q else "advanced"
        return "trapped"

    def connect(tree, q):
        while True:
            r = extend(tree, q)
            if r != "advanced":
                return r

    def path(tree, i):
        out = []
        while i >= 0:
            out.append(tree[0][i])
            i = tree[1][i]
        return out

    for it in range(max_nodes):
        q = sp.sample(rng) if rng.random() > 0.1 else trees[1][0][0]
        a, b = trees
        if extend(a, q) != "trapped":
            if connect(b, a[0][-1]) == "reached":
                pa, pb = path(a, len(a[0]) - 1), path(b, len(b[0]) - 1)
                p = list(reversed(pa)) + pb[1:]
                if p[0] != qs:
                    p.reverse()
                return p, it
        trees.reverse()
    return None, max_nodes


def shortcut(ck, sp, p, rng, tries=200, res=0.01):
    p = list(p)
    for _ in range(tries):
        if len(p) < 3:
            break
        i = rng.randrange(0, len(p) - 2)
        j = rng.randrange(i + 2, len(p))
        if edge_free(ck, sp, p[i], p[j], res):
            p = p[:i + 1] + p[j:]
    return p


def repair(ck, sp, p, rng, res=0.01):
    """Re-plans (at `res` steps) each segment that touches at `res` steps."""
    out = [p[0]]
    for a, b in zip(p, p[1:]):
        if not edge_free(ck, sp, a, b, res):
            sub_path, _ = rrt_connect(ck, sp, a, b, rng, res=res, max_nodes=5000)
            if sub_path is None:
                return None
            out += sub_path[1:-1]
        out.append(b)
    return out


def witness(robot, env, checked, failures):
    """RRT-Connect from start to goal of each scene, in stages where the scene says so
    (generate.WITNESS_VIA: intermediate configurations and the joints that move to reach
    each); the stages joined are a path in the full configuration space."""
    import time
    for name, sc in generate.SCENES.items():
        ck = Checker(robot, env, checked)
        rng = random.Random(7)
        t0 = time.time()
        stages = generate.WITNESS_VIA.get(name, []) + [(sc["planned"], sc["goal"])]
        cur = dict(sc["start"])
        full = Space(robot, sc)
        base0, base1 = sc["start_base"], sc["goal_base"]
        waypoints, its, ok = [full.of(cur, base0)], 0, True
        for k, (active, target) in enumerate(stages):
            stage_sc = dict(sc, fixed=dict(sc["fixed"], **{j: v for j, v in cur.items() if j not in active}),
                            start=dict(cur), goal=dict(cur, **target))
            last = k == len(stages) - 1
            stage_sc["goal_base"] = base1 if last else base0
            sp = Space(robot, stage_sc, active)
            p, it = rrt_connect(ck, sp, sp.config("start"), sp.config("goal"), rng, max_nodes=30000)
            its += it
            if p is None:
                ok = False
                break
            p = shortcut(ck, sp, p, rng)
            p = repair(ck, sp, p, rng)
            if p is None:
                ok = False
                break
            for v in p[1:]:
                q, base = sp.split(v)
                b = tuple(v[:3]) if sp.planar else None
                cur = {j: q[j] for j in sc["planned"]}
                waypoints.append(full.of(cur, b))
        if ok:
            bad = [k for k, (a, b) in enumerate(zip(waypoints, waypoints[1:]))
                   if not edge_free(ck, full, a, b, 0.01)]
            ok = not bad
            if bad:
                print("  segments in contact at 0.01 steps: %s" % bad)
        length = sum(full.dist(a, b) for a, b in zip(waypoints, waypoints[1:]))
        print("  %s  %s: witness path in %d stage(s), %d waypoints, length %.2f, rechecked at "
              "0.01 steps (%d iterations, %d collision checks, %.0f s)"
              % ("ok  " if ok else "FAIL", name, len(stages), len(waypoints), length, its, ck.calls,
                 time.time() - t0))
        for v in waypoints:
            print("      " + " ".join("%.3f" % x for x in v))
        if not ok:
            failures.append("witness " + name)


if __name__ == "__main__":
    sys.exit(main())
