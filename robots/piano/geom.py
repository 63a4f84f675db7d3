"""Geometry of the piano family's meshes (pure Python, deterministic): 2D curves and
polygon offsets, sweeps and lathes, and the triangle / box overlap test (separating
axes) with which check.py certifies the witness paths. The helpers every robot uses
(meshes, rotations, mesh checks) are in robots/meshlib.py.
"""

import math

import meshlib as ml
from meshlib import Mesh


# ---------------------------------------------------------------- 2D curves


def _cr_point(p0, p1, p2, p3, t, alpha=0.5):
    """Centripetal Catmull-Rom point on the segment p1 -> p2 (t in [0, 1])."""

    def tj(ti, a, b):
        d = math.hypot(b[0] - a[0], b[1] - a[1])
        return ti + max(d, 1e-12) ** alpha

    t0 = 0.0
    t1 = tj(t0, p0, p1)
    t2 = tj(t1, p1, p2)
    t3 = tj(t2, p2, p3)
    u = t1 + (t2 - t1) * t

    def lerp(a, b, ta, tb):
        wa, wb = (tb - u) / (tb - ta), (u - ta) / (tb - ta)
        return (wa * a[0] + wb * b[0], wa * a[1] + wb * b[1])

    a1 = lerp(p0, p1, t0, t1)
    a2 = lerp(p1, p2, t1, t2)
    a3 = lerp(p2, p3, t2, t3)
    b1 = lerp(a1, a2, t0, t2)
    b2 = lerp(a2, a3, t1, t3)
    return lerp(b1, b2, t1, t2)


def spline(ctrl, n):
    """n points along a centripetal Catmull-Rom curve through ctrl[1:-1] (ctrl[0] and
    ctrl[-1] only shape the end tangents), spread by segment length, ends included."""
    segs = [(ctrl[i - 1], ctrl[i], ctrl[i + 1], ctrl[i + 2]) for i in range(1, len(ctrl) - 2)]
    lens = [math.hypot(s[2][0] - s[1][0], s[2][1] - s[1][1]) for s in segs]
    total = sum(lens)
    out = []
    for k in range(n):
        s = total * k / (n - 1)
        i = 0
        while i < len(segs) - 1 and s > lens[i]:
            s -= lens[i]
            i += 1
        out.append(_cr_point(*segs[i], t=min(1.0, s / lens[i])))
    return out


def clean_polygon(poly, min_sin=2e-3, min_len=1e-4):
    """Drops vertices where the outline goes (almost) straight on, and near-duplicates."""
    pts = list(poly)
    changed = True
    while changed and len(pts) > 3:
        changed = False
        for i in range(len(pts)):
            a, b, c = pts[i - 1], pts[i], pts[(i + 1) % len(pts)]
            u = (b[0] - a[0], b[1] - a[1])
            v = (c[0] - b[0], c[1] - b[1])
            lu, lv = math.hypot(*u), math.hypot(*v)
            if lu < min_len or lv < min_len or abs(u[0] * v[1] - u[1] * v[0]) < min_sin * lu * lv:
                pts.pop(i)
                changed = True
                break
    return pts


def offset_polygon(poly, d):
    """Offsets a counter-clockwise polygon inward by d (outward for d < 0), mitred."""
    n = len(poly)
    normals = []
    for i in range(n):
        a, b = poly[i], poly[(i + 1) % n]
        ln = math.hypot(b[0] - a[0], b[1] - a[1])
        normals.append((-(b[1] - a[1]) / ln, (b[0] - a[0]) / ln))  # left = inward
    out = []
    for i in range(n):
        n1, n2 = normals[i - 1], normals[i]
        k = d / (1.0 + n1[0] * n2[0] + n1[1] * n2[1])
        out.append((poly[i][0] + k * (n1[0] + n2[0]), poly[i][1] + k * (n1[1] + n2[1])))
    return out


def clip_polygon(poly, axis, value, keep_above=True):
    """Sutherland-Hodgman clip of a polygon against coordinate[axis] >= value (or <=)."""
    sign = 1.0 if keep_above else -1.0
    out = []
    for i in range(len(poly)):
        a, b = poly[i - 1], poly[i]
        da, db = sign * (a[axis] - value), sign * (b[axis] - value)
        if db >= 0:
            if da < 0:
                t = da / (da - db)
                out.append((a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])))
            out.append(b)
        elif da >= 0:
            t = da / (da - db)
            out.append((a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])))
    return out


def polygon_is_simple(poly):
    n = len(poly)

    def orient(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])

    for i in range(n):
        a, b = poly[i], poly[(i + 1) % n]
        for j in range(i + 2, n):
            if i == 0 and j == n - 1:
                continue
            c, d = poly[j], poly[(j + 1) % n]
            if (orient(a, b, c) > 0) != (orient(a, b, d) > 0) and \
                    (orient(c, d, a) > 0) != (orient(c, d, b) > 0):
                return False
    return True


# ---------------------------------------------------------------- solids


def sweep(rings):
    """Closed tube through a cyclic list of rings (each a closed loop of 3D points, all
    of the same length). With rings going up the outside of a counter-clockwise
    outline, across the top, down the inside and back across the bottom (a profile
    counter-clockwise in the (outward, z) plane), faces point outward."""
    m = Mesh()
    n = len(rings[0])
    for r in rings:
        m.vertices.extend(r)
    k = len(rings)
    for a in range(k):
        b = (a + 1) % k
        for i in range(n):
            j = (i + 1) % n
            m.triangles.append((a * n + i, a * n + j, b * n + j))
            m.triangles.append((a * n + i, b * n + j, b * n + i))
    return m


def profile_sweep(outline, profile):
    """A ring solid along a closed counter-clockwise outline: profile is a list of
    (inward_offset, z) points, counter-clockwise in the (outward, z) plane."""
    rings = [[(x, y, z) for x, y in offset_polygon(outline, d)] for d, z in profile]
    return sweep(rings)


def extrude_between(bottom, top, z0, z1):
    """Prism-like solid: bottom polygon at z0, top polygon (same count, CCW) at z1;
    side quads join corresponding vertices (a chamfer when top is an inset)."""
    n = len(bottom)
    m = Mesh()
    m.vertices.extend((x, y, z0) for x, y in bottom)
    m.vertices.extend((x, y, z1) for x, y in top)
    for i in range(n):
        j = (i + 1) % n
        m.triangles.append((i, j, n + j))
        m.triangles.append((i, n + j, n + i))
    for a, b, c in ml.ear_clip(bottom):
        m.triangles.append((a, c, b))
    for a, b, c in ml.ear_clip(top):
        m.triangles.append((n + a, n + b, n + c))
    return m


def lathe(profile, segments, center=(0, 0, 0)):
    """Solid of revolution about the z axis: profile is [(r, z), ...] from the bottom
    centre outward, up and back to the axis at the top: r > 0 except at both ends, where
    r == 0 (those become single pole vertices)."""
    assert profile[0][0] == 0 and profile[-1][0] == 0
    m = Mesh()
    m.vertices.append((center[0], center[1], center[2] + profile[0][1]))
    inner = profile[1:-1]
    for r, z in inner:
        for s in range(segments):
            t = 2 * math.pi * s / segments
            m.vertices.append((center[0] + r * math.cos(t), center[1] + r * math.sin(t),
                               center[2] + z))
    m.vertices.append((center[0], center[1], center[2] + profile[-1][1]))
    top = len(m.vertices) - 1
    for s in range(segments):
        n = (s + 1) % segments
        m.triangles.append((0, 1 + n, 1 + s))
        last = 1 + (len(inner) - 1) * segments
        m.triangles.append((top, last + s, last + n))
    for i in range(len(inner) - 1):
        for s in range(segments):
            n = (s + 1) % segments
            a, b = 1 + i * segments + s, 1 + i * segments + n
            c, d = a + segments, b + segments
            m.triangles.append((a, b, d))
            m.triangles.append((a, d, c))
    return m


def segment_cylinder(p, q, radius, segments=8):
    """Cylinder from point p to point q."""
    d = [q[i] - p[i] for i in range(3)]
    length = math.sqrt(sum(x * x for x in d))
    yaw = math.atan2(d[1], d[0])
    pitch = math.atan2(math.hypot(d[0], d[1]), d[2])
    mid = [(p[i] + q[i]) / 2 for i in range(3)]
    c = ml.cylinder(radius, length, segments=segments)
    # Rz(yaw) * Ry(pitch) takes +z to d
    return c.transformed(xyz=mid, rpy=(0, pitch, yaw))


def translate(mesh, t):
    return Mesh([(v[0] + t[0], v[1] + t[1], v[2] + t[2]) for v in mesh.vertices],
                mesh.triangles)


def rotate_about(mesh, axis_point, R):
    ax, ay, az = axis_point
    out = []
    for x, y, z in mesh.vertices:
        p = (x - ax, y - ay, z - az)
        out.append(tuple(R[r][0] * p[0] + R[r][1] * p[1] + R[r][2] * p[2] + axis_point[r]
                         for r in range(3)))
    return Mesh(out, mesh.triangles)


# ---------------------------------------------------------------- triangle vs box


def tri_box_overlap(center, half, tri):
    """Separating-axis test (Akenine-Moeller) of a triangle against an axis-aligned box."""
    v0 = [tri[0][i] - center[i] for i in range(3)]
    v1 = [tri[1][i] - center[i] for i in range(3)]
    v2 = [tri[2][i] - center[i] for i in range(3)]
    for i in range(3):
        if min(v0[i], v1[i], v2[i]) > half[i] or max(v0[i], v1[i], v2[i]) < -half[i]:
            return False
    e0 = [v1[i] - v0[i] for i in range(3)]
    e1 = [v2[i] - v1[i] for i in range(3)]
    e2 = [v0[i] - v2[i] for i in range(3)]
    for e in (e0, e1, e2):
        # axes: unit_x cross e, unit_y cross e, unit_z cross e
        for ax in ((0, -e[2], e[1]), (e[2], 0, -e[0]), (-e[1], e[0], 0)):
            p0 = v0[0] * ax[0] + v0[1] * ax[1] + v0[2] * ax[2]
            p1 = v1[0] * ax[0] + v1[1] * ax[1] + v1[2] * ax[2]
            p2 = v2[0] * ax[0] + v2[1] * ax[1] + v2[2] * ax[2]
            r = half[0] * abs(ax[0]) + half[1] * abs(ax[1]) + half[2] * abs(ax[2])
            if min(p0, p1, p2) > r or max(p0, p1, p2) < -r:
                return False
    n = (e0[1] * e1[2] - e0[2] * e1[1], e0[2] * e1[0] - e0[0] * e1[2],
         e0[0] * e1[1] - e0[1] * e1[0])
    d = n[0] * v0[0] + n[1] * v0[1] + n[2] * v0[2]
    r = half[0] * abs(n[0]) + half[1] * abs(n[1]) + half[2] * abs(n[2])
    return abs(d) <= r
