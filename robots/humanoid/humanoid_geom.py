"""Pure-Python geometry for the humanoid's generator and check script: URDF forward
kinematics, mesh loading (binary STL, OBJ parts) and conservative proximity tests.

Proximity is tested on axis-aligned boxes: two meshes are `apart by margin m` when every
pair of their triangles has bounding boxes separated by at least m along some axis
(so their Euclidean distance is at least m). This is conservative: it may call close
meshes that are a little farther apart than m, never the reverse.
"""

import math
import os
import re
import struct
import xml.etree.ElementTree as ET


# ---------------------------------------------------------------- small linear algebra

def mat_mul(A, B):
    return [[sum(A[r][k] * B[k][c] for k in range(3)) for c in range(3)] for r in range(3)]


def mat_vec(A, v):
    return tuple(A[r][0] * v[0] + A[r][1] * v[1] + A[r][2] * v[2] for r in range(3))


def rpy_matrix(roll, pitch, yaw):
    """R = Rz(yaw) * Ry(pitch) * Rx(roll), as URDF defines rpy."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]


def axis_angle_matrix(axis, angle):
    n = math.sqrt(sum(a * a for a in axis))
    x, y, z = (a / n for a in axis)
    c, s = math.cos(angle), math.sin(angle)
    C = 1 - c
    return [
        [c + x * x * C, x * y * C - z * s, x * z * C + y * s],
        [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
        [z * x * C - y * s, z * y * C + x * s, c + z * z * C],
    ]


def quat_matrix(q):
    w, x, y, z = q
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ]


def slerp(q0, q1, t):
    d = sum(a * b for a, b in zip(q0, q1))
    if d < 0:
        q1, d = [-a for a in q1], -d
    if d > 0.9995:
        q = [a + t * (b - a) for a, b in zip(q0, q1)]
    else:
        th = math.acos(d)
        s0, s1 = math.sin((1 - t) * th) / math.sin(th), math.sin(t * th) / math.sin(th)
        q = [s0 * a + s1 * b for a, b in zip(q0, q1)]
    n = math.sqrt(sum(a * a for a in q))
    return [a / n for a in q]


def compose(T1, T2):
    """Poses as (R, p): T1 * T2."""
    R1, p1 = T1
    R2, p2 = T2
    q = mat_vec(R1, p2)
    return mat_mul(R1, R2), (q[0] + p1[0], q[1] + p1[1], q[2] + p1[2])


IDENTITY = ([[1, 0, 0], [0, 1, 0], [0, 0, 1]], (0.0, 0.0, 0.0))


# ---------------------------------------------------------------- URDF

class Joint:
    def __init__(self, el):
        self.name = el.get("name")
        self.type = el.get("type")
        self.parent = el.find("parent").get("link")
        self.child = el.find("child").get("link")
        o = el.find("origin")
        xyz = [float(v) for v in (o.get("xyz", "0 0 0") if o is not None else "0 0 0").split()]
        rpy = [float(v) for v in (o.get("rpy", "0 0 0") if o is not None else "0 0 0").split()]
        self.origin = (rpy_matrix(*rpy), tuple(xyz))
        a = el.find("axis")
        self.axis = [float(v) for v in a.get("xyz").split()] if a is not None else [1, 0, 0]
        lim = el.find("limit")
        self.lower = float(lim.get("lower")) if lim is not None and lim.get("lower") else None
        self.upper = float(lim.get("upper")) if lim is not None and lim.get("upper") else None
        self.limit = lim


class Urdf:
    def __init__(self, path):
        self.path = path
        self.root_el = ET.parse(path).getroot()
        self.name = self.root_el.get("name")
        self.links = [l.get("name") for l in self.root_el.findall("link")]
        self.link_el = {l.get("name"): l for l in self.root_el.findall("link")}
        self.joints = [Joint(j) for j in self.root_el.findall("joint")]
        children = {j.child for j in self.joints}
        roots = [l for l in self.links if l not in children]
        assert len(roots) == 1, roots
        self.root = roots[0]
        # topological order of joints
        by_parent = {}
        for j in self.joints:
            by_parent.setdefault(j.parent, []).append(j)
        self.order = []
        stack = [self.root]
        while stack:
            l = stack.pop(0)
            for j in by_parent.get(l, []):
                self.order.append(j)
                stack.append(j.child)
        assert len(self.order) == len(self.joints)
        self.parent_of = {j.child: j.parent for j in self.joints}

    def actuated(self):
        return [j for j in self.joints if j.type != "fixed"]

    def fk(self, base_pose, q):
        """World pose of every link. base_pose (R, p) of the root; q: {joint: value}."""
        poses = {self.root: base_pose}
        for j in self.order:
            T = compose(poses[j.parent], j.origin)
            if j.type in ("revolute", "continuous"):
                T = compose(T, (axis_angle_matrix(j.axis, q.get(j.name, 0.0)), (0, 0, 0)))
            elif j.type == "prismatic":
                d = q.get(j.name, 0.0)
                n = math.sqrt(sum(a * a for a in j.axis))
                T = compose(T, (IDENTITY[0], tuple(a / n * d for a in j.axis)))
            poses[j.child] = T
        return poses

    def collision_meshes(self, packages):
        """{link: [(origin pose, vertices, triangles)]} for mesh collision elements."""
        out = {}
        for name, el in self.link_el.items():
            for c in el.findall("collision"):
                g = c.find("geometry")
                m = g.find("mesh")
                assert m is not None, "humanoid uses mesh collision geometry only"
                path = resolve_uri(m.get("filename"), packages, os.path.dirname(self.path))
                o = c.find("origin")
                xyz = [float(v) for v in (o.get("xyz", "0 0 0") if o is not None else "0 0 0").split()]
                rpy = [float(v) for v in (o.get("rpy", "0 0 0") if o is not None else "0 0 0").split()]
                verts, tris = read_stl(path)
                out.setdefault(name, []).append(((rpy_matrix(*rpy), tuple(xyz)), verts, tris))
        return out


def resolve_uri(uri, packages, base_dir):
    if uri.startswith("package://"):
        rest = uri[len("package://"):]
        pkg, _, sub = rest.partition("/")
        return os.path.join(packages[pkg], sub)
    if uri.startswith("file://"):
        return uri[len("file://"):]
    return os.path.join(base_dir, uri)


# ---------------------------------------------------------------- mesh files

def read_stl(path):
    with open(path, "rb") as f:
        data = f.read()
    n = struct.unpack_from("<I", data, 80)[0]
    assert len(data) == 84 + 50 * n, "%s: not a binary STL of %d triangles" % (path, n)
    verts, tris, index = [], [], {}
    for i in range(n):
        vals = struct.unpack_from("<12f", data, 84 + 50 * i)
        tri = []
        for k in range(3):
            p = vals[3 + 3 * k: 6 + 3 * k]
            if p not in index:
                index[p] = len(verts)
                verts.append(p)
            tri.append(index[p])
        tris.append(tuple(tri))
    return verts, tris


def read_obj_parts(path):
    """[(name, vertices, triangles)] with triangle indices local to each part."""
    parts, allv = [], []
    name, faces = None, []
    with open(path) as f:
        for line in f:
            t = line.split()
            if not t or t[0].startswith("#"):
                continue
            if t[0] == "o":
                if name is not None:
                    parts.append((name, faces))
                name, faces = t[1], []
            elif t[0] == "v":
                allv.append(tuple(float(x) for x in t[1:4]))
            elif t[0] == "f":
                faces.append(tuple(int(x.split("/")[0]) - 1 for x in t[1:4]))
    if name is not None:
        parts.append((name, faces))
    out = []
    for name, faces in parts:
        # weld coincident vertices (builders repeat them along face seams)
        verts, index, remap = [], {}, {}
        for i in sorted({i for f in faces for i in f}):
            p = allv[i]
            if p not in index:
                index[p] = len(verts)
                verts.append(p)
            remap[i] = index[p]
        out.append((name, verts, [tuple(remap[i] for i in f) for f in faces]))
    return out


def mesh_problems(verts, tris):
    """Checks closedness and orientation; returns a list of complaints (empty if fine)."""
    problems = []
    for v in verts:
        if any(math.isnan(c) or math.isinf(c) for c in v):
            problems.append("NaN/inf vertex")
            break
    directed = {}
    for t in tris:
        a, b, c = (verts[i] for i in t)
        u = [b[i] - a[i] for i in range(3)]
        w = [c[i] - a[i] for i in range(3)]
        n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
        if math.sqrt(sum(x * x for x in n)) < 1e-12:
            problems.append("degenerate triangle %s" % (t,))
        for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            directed[e] = directed.get(e, 0) + 1
    bad = [e for e, k in directed.items() if k != 1 or directed.get((e[1], e[0]), 0) != 1]
    if bad:
        problems.append("%d edges not shared by exactly two opposite triangles" % len(bad))
    # signed volume per connected shell must be positive (outward winding)
    parent = list(range(len(verts)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b, c in tris:
        parent[find(b)] = find(a)
        parent[find(c)] = find(a)
    vol = {}
    for t in tris:
        a, b, c = (verts[i] for i in t)
        v6 = (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
              + a[2] * (b[0] * c[1] - b[1] * c[0]))
        r = find(t[0])
        vol[r] = vol.get(r, 0.0) + v6 / 6.0
    neg = [v for v in vol.values() if v <= 0]
    if neg:
        problems.append("%d shells with non-positive volume (inward winding)" % len(neg))
    return problems


# ---------------------------------------------------------------- proximity

def transform_points(T, pts):
    R, p = T
    return [(R[0][0] * v[0] + R[0][1] * v[1] + R[0][2] * v[2] + p[0],
             R[1][0] * v[0] + R[1][1] * v[1] + R[1][2] * v[2] + p[1],
             R[2][0] * v[0] + R[2][1] * v[1] + R[2][2] * v[2] + p[2]) for v in pts]


def tri_boxes(verts, tris):
    out = []
    for a, b, c in tris:
        pa, pb, pc = verts[a], verts[b], verts[c]
        out.append((min(pa[0], pb[0], pc[0]), min(pa[1], pb[1], pc[1]), min(pa[2], pb[2], pc[2]),
                    max(pa[0], pb[0], pc[0]), max(pa[1], pb[1], pc[1]), max(pa[2], pb[2], pc[2])))
    return out


def box_of(points):
    xs, ys, zs = zip(*points)
    return (min(xs), min(ys), min(zs), max(xs), max(ys), max(zs))


def merge_boxes(boxes):
    return (min(b[0] for b in boxes), min(b[1] for b in boxes), min(b[2] for b in boxes),
            max(b[3] for b in boxes), max(b[4] for b in boxes), max(b[5] for b in boxes))


def boxes_close(a, b, margin):
    """True when the boxes are nearer than margin along every axis (i.e. not certified
    apart by margin)."""
    return (a[0] < b[3] + margin and b[0] < a[3] + margin and a[1] < b[4] + margin
            and b[1] < a[4] + margin and a[2] < b[5] + margin and b[2] < a[5] + margin)


def box_gap(a, b):
    """Largest axis separation between two boxes (negative: overlapping on all axes)."""
    return max(b[0] - a[3], a[0] - b[3], b[1] - a[4], a[1] - b[4], b[2] - a[5], a[2] - b[5])


def sets_close(A, B, margin, cell=0.04):
    """Triangle-box lists A and B: the smallest axis gap found among close pairs, or None
    when every pair is certified apart by margin."""
    if not A or not B:
        return None
    bA, bB = merge_boxes(A), merge_boxes(B)
    if not boxes_close(bA, bB, margin):
        return None
    A = [a for a in A if boxes_close(a, bB, margin)]
    B = [b for b in B if boxes_close(b, bA, margin)]
    if not A or not B:
        return None
    grid = {}
    for k, b in enumerate(B):
        for i in range(int(math.floor(b[0] / cell)), int(math.floor(b[3] / cell)) + 1):
            for j in range(int(math.floor(b[1] / cell)), int(math.floor(b[4] / cell)) + 1):
                for l in range(int(math.floor(b[2] / cell)), int(math.floor(b[5] / cell)) + 1):
                    grid.setdefault((i, j, l), []).append(k)
    worst = None
    for a in A:
        seen = set()
        for i in range(int(math.floor((a[0] - margin) / cell)), int(math.floor((a[3] + margin) / cell)) + 1):
            for j in range(int(math.floor((a[1] - margin) / cell)), int(math.floor((a[4] + margin) / cell)) + 1):
                for l in range(int(math.floor((a[2] - margin) / cell)), int(math.floor((a[5] + margin) / cell)) + 1):
                    for k in grid.get((i, j, l), ()):
                        if k in seen:
                            continue
                        seen.add(k)
                        if boxes_close(a, B[k], margin):
                            g = box_gap(a, B[k])
                            if worst is None or g < worst:
                                worst = g
    return worst


class PosedRobot:
    """World-frame vertices and triangle boxes of every link at one configuration.

    Self-collision pairs are culled with world boxes, then refined in the frame of the
    first link of the pair, so the verdict depends only on the links' relative pose
    (boxes of triangles are tight in a link's own frame, loose when rotated)."""

    def __init__(self, urdf, meshes, base_pose, q):
        self.poses = urdf.fk(base_pose, q)
        self.local, self.verts, self.boxes, self.link_box = {}, {}, {}, {}
        for link, items in meshes.items():
            lv, lt = [], []
            for origin, verts, tris in items:
                base = len(lv)
                lv.extend(transform_points(origin, verts))
                lt.extend((a + base, b + base, c + base) for a, b, c in tris)
            self.local[link] = (lv, lt)
            w = transform_points(self.poses[link], lv)
            self.verts[link], self.boxes[link] = w, tri_boxes(w, lt)
            self.link_box[link] = box_of(w)

    def relative(self, a, b):
        """Pose of link b in the frame of link a."""
        Ra, pa = self.poses[a]
        Rt = [[Ra[c][r] for c in range(3)] for r in range(3)]
        p = mat_vec(Rt, pa)
        return compose((Rt, (-p[0], -p[1], -p[2])), self.poses[b])

    def self_close_pairs(self, pairs, margin):
        out = []
        for a, b in pairs:
            if a not in self.boxes or b not in self.boxes:
                continue
            if not boxes_close(self.link_box[a], self.link_box[b], margin):
                continue
            la, ta = self.local[a]
            lb, tb = self.local[b]
            g = sets_close(tri_boxes(la, ta), tri_boxes(transform_points(self.relative(a, b), lb), tb),
                           margin)
            if g is not None:
                out.append((a, b, g))
        return out

    def env_close(self, parts, margin):
        """parts: [(name, box)] obstacle boxes; returns [(link, part, gap)]."""
        out = []
        for link, bs in self.boxes.items():
            lb = self.link_box[link]
            for name, pb in parts:
                if not boxes_close(lb, pb, margin):
                    continue
                g = sets_close(bs, [pb], margin)
                if g is not None:
                    out.append((link, name, g))
        return out


def base_pose_from(xyz, quat_wxyz):
    return (quat_matrix(quat_wxyz), tuple(xyz))


# ---------------------------------------------------------------- scene YAML subset

def read_scene_yaml(path):
    """Reads the subset of YAML the scene files use: block mappings by indentation,
    `>` folded text, one-line flow collections and scalars. Returns (dict, line map)."""

    def scalar(s):
        s = s.strip()
        if s.startswith("{") or s.startswith("["):
            value, rest = flow(s)
            assert not rest.strip(), "trailing text after a flow collection: %r" % rest
            return value
        if re.fullmatch(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?", s):
            return float(s) if any(c in s for c in ".eE") else int(s)
        if s in ("true", "false"):
            return s == "true"
        if len(s) >= 2 and s[0] == s[-1] and s[0] in "'\"":
            return s[1:-1]
        return s

    def flow(s):
        """Parses one flow value at the start of s; returns (value, rest)."""
        s = s.lstrip()
        if s[0] in "{[":
            close = "}" if s[0] == "{" else "]"
            out = {} if s[0] == "{" else []
            s = s[1:].lstrip()
            while s[0] != close:
                if isinstance(out, dict):
                    k, _, s = s.partition(":")
                    v, s = flow(s)
                    out[k.strip()] = v
                else:
                    v, s = flow(s)
                    out.append(v)
                s = s.lstrip()
                if s[0] == ",":
                    s = s[1:].lstrip()
            return out, s[1:]
        m = re.match(r"[^,\]}]*", s)
        return scalar(m.group(0)), s[m.end():]

    lines = []
    with open(path) as f:
        for raw in f:
            if not raw.strip() or raw.lstrip().startswith("#"):
                lines.append(None)
                continue
            lines.append(raw.rstrip("\n"))
    root = {}
    stack = [(-1, root)]
    i = 0
    while i < len(lines):
        line = lines[i]
        i += 1
        if line is None:
            continue
        ind = len(line) - len(line.lstrip())
        text = line.strip()
        while stack[-1][0] >= ind:
            stack.pop()
        cont = stack[-1][1]
        if text.startswith("- "):
            item_text = text[2:]
            if ":" in item_text and not item_text.startswith(("{", "[")):
                k, _, v = item_text.partition(":")
                d = {k.strip(): scalar(v)} if v.strip() else {k.strip(): {}}
                cont.append(d)
                stack.append((ind + 1, d))
            else:
                cont.append(scalar(item_text))
            continue
        k, _, v = text.partition(":")
        k, v = k.strip(), v.strip()
        if v == ">":
            buf = []
            while i < len(lines) and (lines[i] is None or len(lines[i]) - len(lines[i].lstrip()) > ind):
                if lines[i] is not None:
                    buf.append(lines[i].strip())
                i += 1
            cont[k] = " ".join(buf)
        elif v == "":
            nxt = next((l for l in lines[i:] if l is not None), "")
            child = [] if nxt.strip().startswith("- ") else {}
            cont[k] = child
            stack.append((ind, child))
        else:
            cont[k] = scalar(v)
    return root
