"""Environment authoring for the piano scenes: named parts (closed meshes) plus, for
each part, the axis-aligned boxes that bound it for the pure-Python checks (exact for
walls, conservative for furniture)."""

import math

import meshlib as ml
from meshlib import Mesh


def box_mesh(lo, hi, cell=None):
    """Box from lo to hi; with cell (metres), faces are split into a grid of about
    cell-sized squares (a finely tessellated wall)."""
    size = [hi[i] - lo[i] for i in range(3)]
    div = (1, 1, 1) if cell is None else tuple(max(1, int(round(s / cell))) for s in size)
    return ml.box_between(lo, hi, div)


class Env:
    def __init__(self, cell=None):
        self.parts = []      # (name, Mesh)
        self.boxes = []      # (name, lo, hi) for checks
        self.cell = cell     # tessellation of walls (None: plain boxes)
        self._names = {}

    def _name(self, name):
        k = self._names.get(name, 0)
        self._names[name] = k + 1
        return name if k == 0 else "%s_%d" % (name, k + 1)

    def box(self, name, lo, hi, tessellate=True):
        assert all(hi[i] > lo[i] for i in range(3)), name
        name = self._name(name)
        self.parts.append((name, box_mesh(lo, hi, self.cell if tessellate else None)))
        self.boxes.append((name, tuple(lo), tuple(hi)))
        return name

    def item(self, name, meshes_and_boxes):
        """A furniture item: [(Mesh, bound)], bound being (lo, hi), a list of such boxes
        that together enclose the mesh, or None: the mesh's own bounding box."""
        name = self._name(name)
        m = Mesh()
        for mesh, bb in meshes_and_boxes:
            m.add(mesh)
            bbs = bb if isinstance(bb, list) else [bb if bb else mesh.bounds()]
            for lo, hi in bbs:
                self.boxes.append((name, tuple(lo), tuple(hi)))
        self.parts.append((name, m))
        return name

    def wall_x(self, name, x0, x1, y0, y1, height, doors=(), z0=0.0):
        """Wall along x (x0..x1, thickness y0..y1) with doorways [(xa, xb, door_height)]:
        wall segments between the doorways and a lintel over each."""
        cuts = sorted(doors)
        x = x0
        for k, (xa, xb, dh) in enumerate(cuts):
            if xa > x:
                self.box(name, (x, y0, z0), (xa, y1, z0 + height))
            self.box(name + "_lintel", (xa, y0, z0 + dh), (xb, y1, z0 + height))
            x = xb
        if x1 > x:
            self.box(name, (x, y0, z0), (x1, y1, z0 + height))

    def wall_y(self, name, y0, y1, x0, x1, height, doors=(), z0=0.0):
        cuts = sorted(doors)
        y = y0
        for ya, yb, dh in cuts:
            if ya > y:
                self.box(name, (x0, y, z0), (x1, ya, z0 + height))
            self.box(name + "_lintel", (x0, ya, z0 + dh), (x1, yb, z0 + height))
            y = yb
        if y1 > y:
            self.box(name, (x0, y, z0), (x1, y1, z0 + height))

    def triangles(self):
        return sum(len(m.triangles) for _, m in self.parts)


# ---------------------------------------------------------------- furniture


def _b(lo, hi):
    return box_mesh(lo, hi), (tuple(lo), tuple(hi))


def _rot_boxes(pieces, origin, yaw_quarter):
    """Rotates furniture pieces built at the origin facing +y by a multiple of 90 deg
    about z and moves them to origin (exact for boxes)."""
    out = []
    ang = math.pi / 2 * yaw_quarter
    for mesh, (lo, hi) in pieces:
        m = mesh.transformed(xyz=origin, rpy=(0, 0, ang))
        out.append((m, None))
    return out


def table(x, y, w, d, h=0.75, top=0.04, leg=0.06, yaw=0):
    p = [_b((-w / 2, -d / 2, h - top), (w / 2, d / 2, h))]
    for sx in (-1, 1):
        for sy in (-1, 1):
            cx, cy = sx * (w / 2 - leg), sy * (d / 2 - leg)
            p.append(_b((cx - leg / 2, cy - leg / 2, 0), (cx + leg / 2, cy + leg / 2, h - top)))
    # apron
    p.append(_b((-w / 2 + leg, -d / 2 + leg / 2, h - top - 0.08), (w / 2 - leg, -d / 2 + leg, h - top)))
    p.append(_b((-w / 2 + leg, d / 2 - leg, h - top - 0.08), (w / 2 - leg, d / 2 - leg / 2, h - top)))
    return _rot_boxes(p, (x, y, 0), yaw)


def chair(x, y, yaw=0):
    """Chair facing +y before the yaw (its back at -y)."""
    s, leg = 0.45, 0.04
    p = [_b((-s / 2, -s / 2, 0.42), (s / 2, s / 2, 0.46))]
    for sx in (-1, 1):
        for sy in (-1, 1):
            cx, cy = sx * (s / 2 - leg / 2), sy * (s / 2 - leg / 2)
            top = 0.95 if sy < 0 else 0.42
            p.append(_b((cx - leg / 2, cy - leg / 2, 0), (cx + leg / 2, cy + leg / 2, top)))
    p.append(_b((-s / 2 + leg, -s / 2, 0.70), (s / 2 - leg, -s / 2 + 0.025, 0.92)))
    return _rot_boxes(p, (x, y, 0), yaw)


def sofa(x, y, w=2.1, d=0.9, yaw=0, seats=3):
    """Sofa facing +y before the yaw (backrest at -y)."""
    p = [_b((-w / 2, -d / 2, 0.08), (w / 2, d / 2, 0.40)),                     # base
         _b((-w / 2, -d / 2, 0.40), (w / 2, -d / 2 + 0.22, 0.85)),             # back
         _b((-w / 2, -d / 2 + 0.22, 0.40), (-w / 2 + 0.18, d / 2, 0.62)),      # arms
         _b((w / 2 - 0.18, -d / 2 + 0.22, 0.40), (w / 2, d / 2, 0.62))]
    cw = (w - 0.36) / seats
    for k in range(seats):                                                     # cushions
        x0 = -w / 2 + 0.18 + k * cw
        p.append(_b((x0 + 0.01, -d / 2 + 0.23, 0.40), (x0 + cw - 0.01, d / 2 - 0.02, 0.52)))
        p.append(_b((x0 + 0.01, -d / 2 + 0.22, 0.52), (x0 + cw - 0.01, -d / 2 + 0.36, 0.80)))
    for sx in (-1, 1):                                                         # feet
        for sy in (-1, 1):
            cx, cy = sx * (w / 2 - 0.06), sy * (d / 2 - 0.06)
            p.append(_b((cx - 0.03, cy - 0.03, 0), (cx + 0.03, cy + 0.03, 0.08)))
    return _rot_boxes(p, (x, y, 0), yaw)


def bookshelf(x, y, w=1.0, d=0.35, h=2.0, shelves=5, yaw=0, books=True):
    """Bookshelf with its back at -y before the yaw; books on every shelf."""
    t = 0.02
    p = [_b((-w / 2, -d / 2, 0), (-w / 2 + t, d / 2, h)),
         _b((w / 2 - t, -d / 2, 0), (w / 2, d / 2, h)),
         _b((-w / 2 + t, -d / 2, 0), (w / 2 - t, -d / 2 + t, h))]
    for k in range(shelves + 1):
        z = k * (h - t) / shelves
        p.append(_b((-w / 2 + t, -d / 2 + t, z), (w / 2 - t, d / 2, z + t)))
        if books and k < shelves:
            n = 9
            bw = (w - 2 * t) / n
            for j in range(n):
                hb = 0.18 + 0.06 * ((j * 7 + k * 3) % 5) / 4.0
                hb = min(hb, (h - t) / shelves - t - 0.02)
                p.append(_b((-w / 2 + t + j * bw + 0.003, -d / 2 + t + 0.02, z + t),
                            (-w / 2 + t + (j + 1) * bw - 0.003, d / 2 - 0.03, z + t + hb)))
    return _rot_boxes(p, (x, y, 0), yaw)


def bed(x, y, w=1.6, l=2.1, yaw=0):
    """Bed with its headboard at -y before the yaw."""
    p = [_b((-w / 2, -l / 2, 0.10), (w / 2, l / 2, 0.35)),
         _b((-w / 2 + 0.02, -l / 2 + 0.02, 0.35), (w / 2 - 0.02, l / 2 - 0.02, 0.55)),
         _b((-w / 2, -l / 2 - 0.06, 0), (w / 2, -l / 2, 1.05)),
         _b((-w / 2, l / 2, 0), (w / 2, l / 2 + 0.05, 0.55))]
    for sx in (-1, 1):
        p.append(_b((sx * w / 4 - 0.3, -l / 2 + 0.08, 0.55), (sx * w / 4 + 0.3, -l / 2 + 0.48, 0.67)))
    for sx in (-1, 1):
        for sy in (-1, 1):
            cx, cy = sx * (w / 2 - 0.05), sy * (l / 2 - 0.05)
            p.append(_b((cx - 0.04, cy - 0.04, 0), (cx + 0.04, cy + 0.04, 0.10)))
    return _rot_boxes(p, (x, y, 0), yaw)


def cabinet(x, y, w, d, h, yaw=0, doors=2):
    p = [_b((-w / 2, -d / 2, 0.08), (w / 2, d / 2, h)), _b((-w / 2 + 0.03, -d / 2 + 0.03, 0),
                                                           (w / 2 - 0.03, d / 2 - 0.05, 0.08))]
    for k in range(doors):
        x0 = -w / 2 + k * w / doors
        p.append(_b((x0 + 0.01, d / 2, 0.10), (x0 + w / doors - 0.01, d / 2 + 0.02, h - 0.02)))
        p.append(_b((x0 + w / doors / 2 - 0.06, d / 2 + 0.02, h - 0.15),
                    (x0 + w / doors / 2 + 0.06, d / 2 + 0.04, h - 0.13)))
    return _rot_boxes(p, (x, y, 0), yaw)


def round_table(x, y, r=0.5, h=0.74, segments=32):
    top = ml.cylinder(r, 0.04, segments=segments, center=(x, y, h - 0.02))
    col = ml.cylinder(0.05, h - 0.06, segments=16, center=(x, y, 0.02 + (h - 0.06) / 2))
    foot = ml.cylinder(0.28, 0.03, segments=segments, center=(x, y, 0.015))
    return [(top, None), (col, None), (foot, None)]


def floor_lamp(x, y, h=1.6, segments=24):
    base = ml.cylinder(0.16, 0.03, segments=segments, center=(x, y, 0.015))
    pole = ml.cylinder(0.015, h - 0.25, segments=12, center=(x, y, 0.03 + (h - 0.25) / 2))
    shade = ml.cylinder(0.22, 0.28, segments=segments, center=(x, y, h - 0.14), radius_top=0.14)
    return [(base, None), (pole, None), (shade, None)]


def plant(x, y, segments=16):
    pot = ml.cylinder(0.16, 0.35, segments=segments, center=(x, y, 0.175), radius_top=0.2)
    leaves = ml.sphere(0.35, center=(x, y, 0.75), rings=10, segments=segments, scale=(1, 1, 1.2))
    return [(pot, None), (leaves, None)]
