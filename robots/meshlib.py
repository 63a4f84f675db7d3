"""The helpers that the robots' generators and check scripts share.

Python 3 standard library only, deterministic output. A Mesh is a list of vertices
(x, y, z) and a list of triangles (i, j, k) with counter-clockwise winding seen from
outside. Builders return closed meshes; combine them with Mesh.add() or merge().

Sections: meshes and their builders; mesh files (STL, OBJ, COLLADA) written and read
back; mesh checks (closed, outward, not degenerate); small linear algebra (vectors,
rotation matrices, quaternions, poses (R, p)); URDF kinematics and SRDF pairs; the
scene files (folded text, the subset of YAML they use).

The planner itself (collision, kinematics, planning) is C++; what is here serves
authoring: building the files, and checking what the C++ tests do not (see each
robot's check.py).
"""

import math
import os
import re
import struct
import xml.etree.ElementTree as ET


# ---------------------------------------------------------------- meshes


class Mesh:
    def __init__(self, vertices=None, triangles=None):
        self.vertices = list(vertices or [])
        self.triangles = list(triangles or [])

    def add(self, other):
        """Appends another mesh (in place); returns self."""
        base = len(self.vertices)
        self.vertices.extend(other.vertices)
        self.triangles.extend((a + base, b + base, c + base) for a, b, c in other.triangles)
        return self

    def transformed(self, xyz=(0, 0, 0), rpy=(0, 0, 0), scale=(1, 1, 1)):
        """A copy scaled, then rotated by roll-pitch-yaw (URDF order), then moved."""
        R = rpy_matrix(*rpy)
        out = []
        for v in self.vertices:
            s = (v[0] * scale[0], v[1] * scale[1], v[2] * scale[2])
            out.append(tuple(sum(R[r][c] * s[c] for c in range(3)) + xyz[r] for r in range(3)))
        tris = self.triangles
        if scale[0] * scale[1] * scale[2] < 0:
            tris = [(a, c, b) for a, b, c in tris]
        return Mesh(out, tris)

    def bounds(self):
        return point_bounds(self.vertices)

    def __len__(self):
        return len(self.triangles)


def box(size, center=(0, 0, 0), divisions=(1, 1, 1)):
    """Axis-aligned box with full side lengths `size`; each face split into a grid of
    divisions (so 2 * (dx*dy + dy*dz + dz*dx) * 2 triangles)."""
    sx, sy, sz = (s / 2.0 for s in size)
    cx, cy, cz = center
    mesh = Mesh()
    nx, ny, nz = divisions
    # each face: origin corner, two edge vectors (u, v) with u x v pointing outward
    faces = [
        ((cx + sx, cy - sy, cz - sz), (0, 2 * sy, 0), (0, 0, 2 * sz), ny, nz),  # +x
        ((cx - sx, cy - sy, cz - sz), (0, 0, 2 * sz), (0, 2 * sy, 0), nz, ny),  # -x
        ((cx - sx, cy + sy, cz - sz), (0, 0, 2 * sz), (2 * sx, 0, 0), nz, nx),  # +y
        ((cx - sx, cy - sy, cz - sz), (2 * sx, 0, 0), (0, 0, 2 * sz), nx, nz),  # -y
        ((cx - sx, cy - sy, cz + sz), (2 * sx, 0, 0), (0, 2 * sy, 0), nx, ny),  # +z
        ((cx - sx, cy - sy, cz - sz), (0, 2 * sy, 0), (2 * sx, 0, 0), ny, nx),  # -z
    ]
    for origin, u, v, nu, nv in faces:
        mesh.add(grid(origin, u, v, nu, nv))
    return mesh


def grid(origin, u, v, nu, nv):
    """A flat rectangle origin + a*u + b*v, split into nu x nv cells; normal u x v."""
    m = Mesh()
    for i in range(nu + 1):
        for j in range(nv + 1):
            a, b = i / nu, j / nv
            m.vertices.append(tuple(origin[k] + a * u[k] + b * v[k] for k in range(3)))
    for i in range(nu):
        for j in range(nv):
            p = i * (nv + 1) + j
            q = (i + 1) * (nv + 1) + j
            m.triangles.append((p, q, q + 1))
            m.triangles.append((p, q + 1, p + 1))
    return m


def box_between(lo, hi, divisions=(1, 1, 1)):
    """The axis-aligned box from corner lo to corner hi (see box())."""
    size = [hi[i] - lo[i] for i in range(3)]
    center = [(hi[i] + lo[i]) / 2 for i in range(3)]
    return box(size, center, divisions)


def merge(*meshes):
    """One mesh holding all the given ones."""
    out = Mesh()
    for m in meshes:
        out.add(m)
    return out


def cylinder(radius, length, segments=24, center=(0, 0, 0), axis="z", radius_top=None):
    """Closed cylinder (a cone frustum when radius_top differs) along an axis."""
    rt = radius if radius_top is None else radius_top
    h = length / 2.0
    m = Mesh()
    for z, r in ((-h, radius), (h, rt)):
        for s in range(segments):
            t = 2 * math.pi * s / segments
            m.vertices.append((r * math.cos(t), r * math.sin(t), z))
    m.vertices.append((0, 0, -h))
    m.vertices.append((0, 0, h))
    bottom, top = 2 * segments, 2 * segments + 1
    for s in range(segments):
        n = (s + 1) % segments
        m.triangles.append((s, n, segments + n))
        m.triangles.append((s, segments + n, segments + s))
        m.triangles.append((bottom, n, s))
        m.triangles.append((top, segments + s, segments + n))
    return orient(m, axis, center)


def sphere(radius, center=(0, 0, 0), rings=12, segments=24, scale=(1, 1, 1)):
    """UV sphere (an ellipsoid with `scale`)."""
    m = Mesh()
    m.vertices.append((0, 0, -radius))
    for i in range(1, rings):
        phi = -math.pi / 2 + math.pi * i / rings
        for s in range(segments):
            t = 2 * math.pi * s / segments
            m.vertices.append((radius * math.cos(phi) * math.cos(t),
                               radius * math.cos(phi) * math.sin(t), radius * math.sin(phi)))
    m.vertices.append((0, 0, radius))
    top = len(m.vertices) - 1
    for s in range(segments):
        n = (s + 1) % segments
        m.triangles.append((0, 1 + n, 1 + s))
        last = 1 + (rings - 2) * segments
        m.triangles.append((top, last + s, last + n))
    for i in range(rings - 2):
        for s in range(segments):
            n = (s + 1) % segments
            a, b = 1 + i * segments + s, 1 + i * segments + n
            c, d = a + segments, b + segments
            m.triangles.append((a, b, d))
            m.triangles.append((a, d, c))
    return m.transformed(xyz=center, scale=scale)


def extrude(polygon, height, z0=0.0):
    """Prism from a simple counter-clockwise polygon [(x, y), ...] in the xy-plane,
    from z0 to z0 + height. Caps are ear-clipped, so the polygon may be non-convex."""
    n = len(polygon)
    m = Mesh()
    for z in (z0, z0 + height):
        for x, y in polygon:
            m.vertices.append((x, y, z))
    for i in range(n):
        j = (i + 1) % n
        m.triangles.append((i, j, n + j))
        m.triangles.append((i, n + j, n + i))
    for a, b, c in ear_clip(polygon):
        m.triangles.append((a, c, b))
        m.triangles.append((n + a, n + b, n + c))
    return m


def ear_clip(polygon):
    """Triangulates a simple counter-clockwise polygon; returns index triples."""
    idx = list(range(len(polygon)))
    tris = []

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    def inside(p, a, b, c):
        return cross(a, b, p) >= 0 and cross(b, c, p) >= 0 and cross(c, a, p) >= 0

    guard = 0
    while len(idx) > 3 and guard < 10000:
        guard += 1
        for k in range(len(idx)):
            i0, i1, i2 = idx[k - 1], idx[k], idx[(k + 1) % len(idx)]
            a, b, c = polygon[i0], polygon[i1], polygon[i2]
            if cross(a, b, c) <= 0:
                continue
            if any(inside(polygon[j], a, b, c) for j in idx if j not in (i0, i1, i2)):
                continue
            tris.append((i0, i1, i2))
            idx.pop(k)
            break
    tris.append(tuple(idx))
    return tris


def orient(m, axis, center=(0, 0, 0)):
    """A mesh built along z turned to lie along `axis` ("x", "y" or "z"), then moved."""
    rpy = {"z": (0, 0, 0), "x": (0, math.pi / 2, 0), "y": (-math.pi / 2, 0, 0)}[axis]
    return m.transformed(xyz=center, rpy=rpy)


# ---------------------------------------------------------------- mesh files


def write_stl(path, mesh, name="gplanner"):
    """Binary STL."""
    with open(path, "wb") as f:
        f.write(name.encode().ljust(80, b"\0")[:80])
        f.write(struct.pack("<I", len(mesh.triangles)))
        for a, b, c in mesh.triangles:
            pa, pb, pc = mesh.vertices[a], mesh.vertices[b], mesh.vertices[c]
            u = [pb[i] - pa[i] for i in range(3)]
            v = [pc[i] - pa[i] for i in range(3)]
            n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
            ln = math.sqrt(sum(x * x for x in n)) or 1.0
            f.write(struct.pack("<3f", *(x / ln for x in n)))
            for p in (pa, pb, pc):
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


def write_obj(path, parts, comment=""):
    """Wavefront OBJ with one named group per part: parts is [(name, Mesh), ...]."""
    with open(path, "w") as f:
        if comment:
            for line in comment.splitlines():
                f.write("# %s\n" % line)
        base = 1
        for name, mesh in parts:
            f.write("o %s\n" % name)
            for v in mesh.vertices:
                f.write("v %.6f %.6f %.6f\n" % v)
            for a, b, c in mesh.triangles:
                f.write("f %d %d %d\n" % (a + base, b + base, c + base))
            base += len(mesh.vertices)


def write_dae(path, parts):
    """Minimal COLLADA 1.4 file, one geometry and node per part."""
    geoms, nodes = [], []
    for k, (name, mesh) in enumerate(parts):
        pos = " ".join("%.6f %.6f %.6f" % v for v in mesh.vertices)
        idx = " ".join("%d %d %d" % t for t in mesh.triangles)
        geoms.append(
            '<geometry id="g%d" name="%s"><mesh>'
            '<source id="g%d-pos"><float_array id="g%d-arr" count="%d">%s</float_array>'
            '<technique_common><accessor source="#g%d-arr" count="%d" stride="3">'
            '<param name="X" type="float"/><param name="Y" type="float"/>'
            '<param name="Z" type="float"/></accessor></technique_common></source>'
            '<vertices id="g%d-vtx"><input semantic="POSITION" source="#g%d-pos"/></vertices>'
            '<triangles count="%d"><input semantic="VERTEX" source="#g%d-vtx" offset="0"/>'
            "<p>%s</p></triangles></mesh></geometry>"
            % (k, name, k, k, 3 * len(mesh.vertices), pos, k, len(mesh.vertices), k, k,
               len(mesh.triangles), k, idx))
        nodes.append('<node id="n%d" name="%s"><instance_geometry url="#g%d"/></node>'
                     % (k, name, k))
    with open(path, "w") as f:
        f.write('<?xml version="1.0" encoding="utf-8"?>\n'
                '<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">'
                "<asset><unit name=\"meter\" meter=\"1\"/><up_axis>Z_UP</up_axis></asset>"
                "<library_geometries>%s</library_geometries>"
                '<library_visual_scenes><visual_scene id="scene">%s</visual_scene>'
                "</library_visual_scenes>"
                '<scene><instance_visual_scene url="#scene"/></scene></COLLADA>\n'
                % ("".join(geoms), "".join(nodes)))


def read_stl(path):
    """A binary STL as a Mesh, exactly coincident vertices merged (the file repeats
    each vertex in every triangle that uses it)."""
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
    return Mesh(verts, tris)


def read_obj(path):
    """[(name, Mesh)] of an OBJ of triangles in `o` objects (as write_obj writes them),
    each object's vertex indices made its own."""
    verts, parts = [], []
    with open(path) as f:
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == "o":
                parts.append((t[1], []))
            elif t[0] == "v":
                verts.append(tuple(float(x) for x in t[1:4]))
            elif t[0] == "f":
                assert len(t) == 4, "%s: a face that is not a triangle" % path
                parts[-1][1].append(tuple(int(x.split("/")[0]) - 1 for x in t[1:]))
    out = []
    for name, tris in parts:
        used = sorted({i for t in tris for i in t})
        local = {i: k for k, i in enumerate(used)}
        out.append((name, Mesh([verts[i] for i in used],
                               [tuple(local[i] for i in t) for t in tris])))
    return out


def read_dae(path):
    """[(node name, Mesh)] of a COLLADA file as write_dae writes it."""
    ns = {"c": "http://www.collada.org/2005/11/COLLADASchema"}
    root = ET.parse(path).getroot()
    geoms = {}
    for g in root.iter("{%s}geometry" % ns["c"]):
        arr = [float(x) for x in g.find(".//c:float_array", ns).text.split()]
        idx = [int(x) for x in g.find(".//c:triangles/c:p", ns).text.split()]
        assert len(idx) == 3 * int(g.find(".//c:triangles", ns).get("count")), path
        geoms[g.get("id")] = Mesh([tuple(arr[i:i + 3]) for i in range(0, len(arr), 3)],
                                  [tuple(idx[i:i + 3]) for i in range(0, len(idx), 3)])
    return [(n.get("name"), geoms[n.find("c:instance_geometry", ns).get("url").lstrip("#")])
            for n in root.iter("{%s}node" % ns["c"])]


# ---------------------------------------------------------------- mesh checks


def _weld_map(vertices, eps):
    """Merged vertices (the first of each group within eps) and every vertex's index
    among them."""
    index, verts, remap = {}, [], []
    for v in vertices:
        key = tuple(int(round(x / eps)) for x in v)
        if key not in index:
            index[key] = len(verts)
            verts.append(v)
        remap.append(index[key])
    return verts, remap


def weld(mesh, eps=1e-6):
    """A copy with coincident vertices merged (box() repeats corners per face);
    triangles that collapse are dropped."""
    verts, remap = _weld_map(mesh.vertices, eps)
    tris = []
    for a, b, c in mesh.triangles:
        a, b, c = remap[a], remap[b], remap[c]
        if len({a, b, c}) == 3:
            tris.append((a, b, c))
    return Mesh(verts, tris)


def components(mesh, eps=1e-6):
    """The connected pieces of a mesh (joined through coincident positions), each a
    Mesh over the welded vertices it uses; collapsed triangles are kept, so that
    check_closed() sees them."""
    verts, remap = _weld_map(mesh.vertices, eps)
    parent = list(range(len(verts)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    tris = [(remap[a], remap[b], remap[c]) for a, b, c in mesh.triangles]
    for a, b, c in tris:
        r = find(a)
        parent[find(b)] = r
        parent[find(c)] = r
    groups = {}
    for t in tris:
        groups.setdefault(find(t[0]), []).append(t)
    out = []
    for group in groups.values():
        used = sorted({i for t in group for i in t})
        local = {i: k for k, i in enumerate(used)}
        out.append(Mesh([verts[i] for i in used], [tuple(local[i] for i in t) for t in group]))
    return out


def check_closed(mesh, name="mesh", min_area=1e-12):
    """Asserts a union of closed solids: finite vertices and, with coincident positions
    merged, no triangle of area min_area (m2) or less, every edge met as often in one
    direction as in the other (closed and consistently wound; solids may touch along an
    edge), and each connected piece of positive volume (outward). Returns the number of
    pieces."""
    for v in mesh.vertices:
        assert all(math.isfinite(c) for c in v), "%s: NaN or infinite vertex" % name
    pieces = components(mesh)
    for piece in pieces:
        V = piece.vertices
        edges = {}
        vol = 0.0
        for a, b, c in piece.triangles:
            assert len({a, b, c}) == 3, "%s: degenerate triangle" % name
            area = 0.5 * norm(cross(sub(V[b], V[a]), sub(V[c], V[a])))
            assert area > min_area, "%s: sliver triangle (area %.3g)" % (name, area)
            vol += dot(V[a], cross(V[b], V[c])) / 6.0
            for e in ((a, b), (b, c), (c, a)):
                edges[e] = edges.get(e, 0) + 1
        for (i, j), k in edges.items():
            assert edges.get((j, i), 0) == k, "%s: open or inconsistently wound edge" % name
        assert vol > 0, "%s: a piece faces inward (volume %.3g)" % (name, vol)
    return len(pieces)


# ---------------------------------------------------------------- linear algebra


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(v):
    return math.sqrt(sum(x * x for x in v))


def normalize(v):
    n = math.sqrt(sum(x * x for x in v))
    return tuple(x / n for x in v)


def point_bounds(points):
    """([min x, y, z], [max x, y, z]) of a list of points."""
    lo = [min(v[i] for v in points) for i in range(3)]
    hi = [max(v[i] for v in points) for i in range(3)]
    return lo, hi


def fibonacci_directions(n):
    """n unit vectors spread evenly over the sphere (a Fibonacci lattice)."""
    g = math.pi * (3 - math.sqrt(5))
    out = []
    for i in range(n):
        z = 1 - 2 * (i + 0.5) / n
        r = math.sqrt(1 - z * z)
        out.append((r * math.cos(g * i), r * math.sin(g * i), z))
    return out


def polygon_area(poly):
    """Signed area of a 2D polygon: positive when counter-clockwise."""
    return 0.5 * sum(poly[i - 1][0] * poly[i][1] - poly[i][0] * poly[i - 1][1]
                     for i in range(len(poly)))


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


def mat_mul(A, B):
    return [[sum(A[r][k] * B[k][c] for k in range(3)) for c in range(3)] for r in range(3)]


def mat_vec(A, v):
    return tuple(A[r][0] * v[0] + A[r][1] * v[1] + A[r][2] * v[2] for r in range(3))


# Poses are (R, p): x -> R x + p.
IDENTITY = ([[1, 0, 0], [0, 1, 0], [0, 0, 1]], (0.0, 0.0, 0.0))


def compose(T1, T2):
    """T1 * T2."""
    R1, p1 = T1
    R2, p2 = T2
    q = mat_vec(R1, p2)
    return mat_mul(R1, R2), (q[0] + p1[0], q[1] + p1[1], q[2] + p1[2])


def inverse(T):
    R, p = T
    Rt = [[R[c][r] for c in range(3)] for r in range(3)]
    q = mat_vec(Rt, p)
    return Rt, (-q[0], -q[1], -q[2])


def transform(T, points):
    """The points moved by the pose T = (R, p)."""
    R, p = T
    r0, r1, r2 = R
    return [(r0[0] * x + r0[1] * y + r0[2] * z + p[0],
             r1[0] * x + r1[1] * y + r1[2] * z + p[1],
             r2[0] * x + r2[1] * y + r2[2] * z + p[2]) for x, y, z in points]


def pose(xyz, quat_wxyz):
    return quat_matrix(quat_wxyz), tuple(xyz)


def quat_normalize(q):
    n = math.sqrt(sum(x * x for x in q))
    return tuple(x / n for x in q)


def quat_matrix(q):
    """Rotation matrix of a quaternion (w, x, y, z), normalized first."""
    w, x, y, z = quat_normalize(q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def quat_mul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return (w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)


def quat_axis(axis, angle):
    s = math.sin(angle / 2)
    n = math.sqrt(sum(a * a for a in axis))
    return (math.cos(angle / 2), axis[0] / n * s, axis[1] / n * s, axis[2] / n * s)


def slerp(a, b, t):
    """The rotation a fraction t of the short way from a to b."""
    dot_ab = sum(x * y for x, y in zip(a, b))
    if dot_ab < 0:
        b = tuple(-x for x in b)
        dot_ab = -dot_ab
    if dot_ab > 0.9999995:
        return quat_normalize(tuple(x + t * (y - x) for x, y in zip(a, b)))
    th = math.acos(dot_ab)
    sa, sb = math.sin((1 - t) * th) / math.sin(th), math.sin(t * th) / math.sin(th)
    return tuple(sa * x + sb * y for x, y in zip(a, b))


def quat_angle(a, b):
    """The angle of the rotation between two unit quaternions."""
    dot_ab = abs(sum(x * y for x, y in zip(a, b)))
    return 2 * math.acos(min(1.0, dot_ab))


# ---------------------------------------------------------------- URDF and SRDF


def _origin(el):
    """The pose an element's <origin> gives (identity when it has none)."""
    o = el.find("origin")
    xyz = [float(v) for v in (o.get("xyz", "0 0 0") if o is not None else "0 0 0").split()]
    rpy = [float(v) for v in (o.get("rpy", "0 0 0") if o is not None else "0 0 0").split()]
    return rpy_matrix(*rpy), tuple(xyz)


class Joint:
    def __init__(self, el):
        self.name = el.get("name")
        self.type = el.get("type")
        self.parent = el.find("parent").get("link")
        self.child = el.find("child").get("link")
        self.origin = _origin(el)
        a = el.find("axis")
        self.axis = [float(v) for v in a.get("xyz").split()] if a is not None else [1, 0, 0]
        lim = el.find("limit")
        self.limit = lim
        self.lower = float(lim.get("lower")) if lim is not None and lim.get("lower") else None
        self.upper = float(lim.get("upper")) if lim is not None and lim.get("upper") else None
        m = el.find("mimic")
        self.mimic = None if m is None else (m.get("joint"), float(m.get("multiplier", 1)),
                                             float(m.get("offset", 0)))


class Urdf:
    """A URDF's kinematic tree: links, joints (parents before children) and forward
    kinematics, as the generators need them (the planner's own is C++)."""

    def __init__(self, path):
        self.path = path
        root = ET.parse(path).getroot()
        self.name = root.get("name")
        self.links = [l.get("name") for l in root.findall("link")]
        self.link_el = {l.get("name"): l for l in root.findall("link")}
        self.joints = [Joint(j) for j in root.findall("joint")]
        self.joint = {j.name: j for j in self.joints}
        children = {j.child for j in self.joints}
        roots = [l for l in self.links if l not in children]
        assert len(roots) == 1, roots
        self.root = roots[0]
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

    def actuated(self):
        """The joints a configuration sets: neither fixed nor mimicking another."""
        return [j for j in self.joints if j.type != "fixed" and j.mimic is None]

    def position(self, j, q):
        """Joint j's value in q ({name: value}); a mimic joint follows its master; a
        missing joint is at 0, or at its nearest limit when 0 is out of range."""
        if j.mimic is not None:
            master, multiplier, offset = j.mimic
            return multiplier * self.position(self.joint[master], q) + offset
        if j.name in q:
            return q[j.name]
        if j.lower is not None and j.type != "continuous":
            return min(max(0.0, j.lower), j.upper)
        return 0.0

    def fk(self, base_pose, q):
        """{link: world pose} with the root at base_pose."""
        poses = {self.root: base_pose}
        for j in self.order:
            T = compose(poses[j.parent], j.origin)
            if j.type in ("revolute", "continuous"):
                T = compose(T, (axis_angle_matrix(j.axis, self.position(j, q)), (0, 0, 0)))
            elif j.type == "prismatic":
                d = self.position(j, q)
                n = math.sqrt(sum(a * a for a in j.axis))
                T = compose(T, (IDENTITY[0], tuple(a / n * d for a in j.axis)))
            poses[j.child] = T
        return poses

    def collision_geometry(self, packages):
        """{link: [(origin pose, Mesh)]} of the links' <collision> meshes and boxes;
        packages maps package:// names to folders."""
        out, cache = {}, {}
        for name, el in self.link_el.items():
            for c in el.findall("collision"):
                g = c.find("geometry")[0]
                if g.tag == "mesh":
                    path = resolve_uri(g.get("filename"), packages, os.path.dirname(self.path))
                    if path not in cache:
                        cache[path] = read_stl(path)
                    mesh = cache[path]
                elif g.tag == "box":
                    mesh = box([float(x) for x in g.get("size").split()])
                else:
                    raise AssertionError("%s: unexpected collision geometry %s" % (name, g.tag))
                out.setdefault(name, []).append((_origin(c), mesh))
        return out


def resolve_uri(uri, packages, base_dir):
    if uri.startswith("package://"):
        pkg, _, rest = uri[len("package://"):].partition("/")
        return os.path.join(packages[pkg], rest)
    if uri.startswith("file://"):
        return uri[len("file://"):]
    return os.path.join(base_dir, uri)


def read_srdf(path):
    """({(link, link) sorted: reason} of the disabled pairs, {group: [joint names]})."""
    root = ET.parse(path).getroot()
    disabled = {tuple(sorted((d.get("link1"), d.get("link2")))): d.get("reason")
                for d in root.findall("disable_collisions")}
    groups = {g.get("name"): [j.get("name") for j in g.findall("joint")]
              for g in root.findall("group")}
    return disabled, groups


# ---------------------------------------------------------------- scene files


def wrap_text(text, width=88, indent="  "):
    """Words filled into lines of at most `width` characters, each starting with indent
    (a folded YAML block)."""
    words, lines, line = text.split(), [], indent
    for w in words:
        if len(line) + len(w) + 1 > width and line.strip():
            lines.append(line.rstrip())
            line = indent
        line += w + " "
    lines.append(line.rstrip())
    return "\n".join(lines)


def read_yaml(path):
    """Reads the subset of YAML the scene files use: block mappings and lists by
    indentation, `>` folded text, one-line flow collections and scalars."""

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
            while i < len(lines) and (lines[i] is None or
                                      len(lines[i]) - len(lines[i].lstrip()) > ind):
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
