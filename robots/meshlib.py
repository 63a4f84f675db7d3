"""Small mesh-authoring library for the project's robots and environments.

Python 3 standard library only, deterministic output. A Mesh is a list of vertices
(x, y, z) and a list of triangles (i, j, k) with counter-clockwise winding seen from
outside. Builders return closed meshes; combine them with Mesh.add().
"""

import math
import struct


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
        lo = [min(v[i] for v in self.vertices) for i in range(3)]
        hi = [max(v[i] for v in self.vertices) for i in range(3)]
        return lo, hi

    def __len__(self):
        return len(self.triangles)


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
    return _orient(m, axis, center)


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


def _orient(m, axis, center):
    rpy = {"z": (0, 0, 0), "x": (0, math.pi / 2, 0), "y": (-math.pi / 2, 0, 0)}[axis]
    return m.transformed(xyz=center, rpy=rpy)


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
