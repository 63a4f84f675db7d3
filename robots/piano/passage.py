"""Cross-sections of a rigid body for doorway design, and witness-path certification.

A body passes a doorway of width W and height H in a thin wall by a pure translation
across the wall exactly when its extent along the doorway's width direction is at most
W and along its height direction at most H. min_width_direction() finds the
orientation of least width; certify_path() checks a piecewise path
(linear in position, slerp in rotation) against box obstacles with a clearance margin.
"""

import math

import geom
import meshlib as ml


def extent(points, d):
    p = [v[0] * d[0] + v[1] * d[1] + v[2] * d[2] for v in points]
    return min(p), max(p)


def width(points, d):
    lo, hi = extent(points, d)
    return hi - lo


def support_points(points, ndir=1000):
    """The vertices extreme in one of ndir directions: a subset of the convex hull's
    vertices on which widths are (nearly) those of the whole body."""
    keep = set()
    for d in ml.fibonacci_directions(ndir):
        keep.add(max(range(len(points)),
                     key=lambda i: points[i][0] * d[0] + points[i][1] * d[1] + points[i][2] * d[2]))
    return [points[i] for i in sorted(keep)]


def tangents(a):
    """Two unit vectors perpendicular to the unit vector a and to each other."""
    t = (1.0, 0.0, 0.0) if abs(a[0]) < 0.9 else (0.0, 1.0, 0.0)
    u = ml.normalize(ml.cross(a, t))
    return u, ml.cross(a, u)


def min_width_direction(points):
    """Direction of least width (grid over the sphere, then a pattern search)."""
    best = min((width(points, d), d) for d in ml.fibonacci_directions(6000))
    w, a = best
    step = 0.02
    while step > 1e-6:
        improved = False
        u, v = tangents(a)
        for du, dv in ((1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1)):
            cand = ml.normalize(tuple(a[i] + step * (du * u[i] + dv * v[i]) for i in range(3)))
            wc = width(points, cand)
            if wc < w - 1e-12:
                w, a, improved = wc, cand, True
                break
        if not improved:
            step *= 0.5
    return w, a


def passage_frame(a, along=(0.0, 1.0, 0.0), up=(1.0, 0.0, 0.0)):
    """Doorway frame for a body of least width along a: width direction a, height
    direction c perpendicular to a and to the body axis `along` (so that the body
    travels along that axis) and signed to point along `up`, travel direction
    b = c x a. Returns (a, b, c) in body coordinates."""
    c = ml.normalize(ml.cross(a, along))
    if sum(c[i] * up[i] for i in range(3)) < 0:
        c = tuple(-x for x in c)
    return a, ml.cross(c, a), c


def frame_quat(a, b, c):
    """Quaternion (w, x, y, z) of the rotation taking body vectors a, b, c to world x, y, z."""
    m = [list(a), list(b), list(c)]   # rows: world axes in body coordinates
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = (0.25 * s, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s)
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2
        q = ((m[2][1] - m[1][2]) / s, 0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s)
    elif m[1][1] > m[2][2]:
        s = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2
        q = ((m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s)
    else:
        s = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2
        q = ((m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s)
    q = ml.quat_normalize(q)
    return q if q[0] >= 0 else tuple(-x for x in q)


def world_extents(points, pos, q):
    return ml.point_bounds(ml.transform(ml.pose(pos, q), points))


# ---------------------------------------------------------------- certification


class Robot:
    """Parts as (name, vertices, triangles) with the radius bounding point motion."""

    def __init__(self, parts):
        self.parts = [(nm, list(m.vertices), list(m.triangles)) for nm, m in parts]
        self.radius = max(ml.norm(v) for _, vs, _ in self.parts for v in vs)

    def collides(self, pos, q, boxes, margin=0.0, first=True):
        """Boxes [(name, lo, hi)], grown by margin on every side. Returns the names of
        the boxes hit (robot triangle overlapping the grown box)."""
        hits = []
        T = ml.pose(pos, q)
        grown = [(nm, [lo[i] - margin for i in range(3)], [hi[i] + margin for i in range(3)])
                 for nm, lo, hi in boxes]
        for _, vs, tris in self.parts:
            pts = ml.transform(T, vs)
            plo, phi = ml.point_bounds(pts)
            for nm, lo, hi in grown:
                if any(plo[i] > hi[i] or phi[i] < lo[i] for i in range(3)):
                    continue
                if nm in hits:
                    continue
                center = [(lo[i] + hi[i]) / 2 for i in range(3)]
                half = [(hi[i] - lo[i]) / 2 for i in range(3)]
                for a, b, c in tris:
                    pa, pb, pc = pts[a], pts[b], pts[c]
                    if (max(pa[0], pb[0], pc[0]) < lo[0] or min(pa[0], pb[0], pc[0]) > hi[0] or
                            max(pa[1], pb[1], pc[1]) < lo[1] or min(pa[1], pb[1], pc[1]) > hi[1] or
                            max(pa[2], pb[2], pc[2]) < lo[2] or min(pa[2], pb[2], pc[2]) > hi[2]):
                        continue
                    if geom.tri_box_overlap(center, half, (pa, pb, pc)):
                        hits.append(nm)
                        if first:
                            return hits
                        break
        return hits

    def vertex_inside(self, pos, q, boxes, depth=0.0):
        """Names of boxes that contain a robot vertex at least `depth` inside."""
        hits = set()
        for _, vs, _ in self.parts:
            pts = ml.transform(ml.pose(pos, q), vs)
            plo, phi = ml.point_bounds(pts)
            for nm, lo, hi in boxes:
                if nm in hits or any(plo[i] > hi[i] - depth or phi[i] < lo[i] + depth
                                     for i in range(3)):
                    continue
                if any(all(lo[i] + depth < p[i] < hi[i] - depth for i in range(3))
                       for p in pts):
                    hits.add(nm)
        return sorted(hits)


def path_samples(waypoints, radius, step):
    """Samples along the path through waypoints [(pos, quat)], linear in position and
    slerp in rotation per segment, so that no robot point (within `radius` of the
    origin) moves more than `step` between consecutive samples."""
    out = [waypoints[0]]
    for (p0, q0), (p1, q1) in zip(waypoints, waypoints[1:]):
        dist = math.sqrt(sum((p1[i] - p0[i]) ** 2 for i in range(3)))
        ang = ml.quat_angle(q0, q1)
        n = max(1, int(math.ceil((dist + radius * ang) / step)))
        for k in range(1, n + 1):
            t = k / n
            out.append((tuple(p0[i] + t * (p1[i] - p0[i]) for i in range(3)), ml.slerp(q0, q1, t)))
    return out


def certify_path(robot, waypoints, boxes, clearance=0.01, log=None):
    """True when every sample (point motion between samples at most 2 * clearance)
    keeps `clearance` from every box, so the continuous path is collision-free."""
    samples = path_samples(waypoints, robot.radius, 2 * clearance)
    for k, (p, q) in enumerate(samples):
        hit = robot.collides(p, q, boxes, clearance)
        if hit:
            if log:
                log("  path sample %d/%d at %s collides with %s" % (
                    k, len(samples), tuple(round(x, 3) for x in p), hit))
            return False, len(samples)
    return True, len(samples)
