#!/usr/bin/env python3
"""Generates the helicopter robot and its city scene (deterministic, standard library).

Writes (paths relative to the repository root):
  robots/helicopter/helicopter.dae          the robot, COLLADA, one node per part
  scenes/environments/helicopter_city.obj   the city, one object per part
  scenes/helicopter.yaml                    the planning problem

Run `python3 robots/helicopter/generate.py` from anywhere; then
`python3 robots/helicopter/check.py` validates the result.

Robot frame: x forward (nose), y left, z up; origin at the centre of the mesh's
bounding box.
"""

import math
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))

import meshlib  # noqa: E402
from meshlib import Mesh  # noqa: E402

DAE_PATH = os.path.join(HERE, "helicopter.dae")
OBJ_PATH = os.path.join(ROOT, "scenes", "environments", "helicopter_city.obj")
YAML_PATH = os.path.join(ROOT, "scenes", "helicopter.yaml")


# --------------------------------------------------------------------------- helpers

def mat_apply(mesh, R, t=(0, 0, 0)):
    """A copy of mesh with vertices v -> R v + t (R a proper rotation)."""
    out = [tuple(sum(R[r][c] * v[c] for c in range(3)) + t[r] for r in range(3))
           for v in mesh.vertices]
    return Mesh(out, mesh.triangles)


def frame_z_to(d):
    """A rotation matrix whose third column is the unit vector d."""
    d = meshlib.normalize(d)
    helper = [1.0, 0.0, 0.0] if abs(d[0]) < 0.9 else [0.0, 1.0, 0.0]
    u = meshlib.normalize(meshlib.cross(helper, d))
    w = meshlib.cross(d, u)
    return [[u[0], w[0], d[0]], [u[1], w[1], d[1]], [u[2], w[2], d[2]]]


def tube(p0, p1, radius, segments=10, radius1=None):
    """Closed cylinder (frustum) from point p0 to point p1."""
    d = [p1[i] - p0[i] for i in range(3)]
    length = math.sqrt(sum(x * x for x in d))
    c = meshlib.cylinder(radius, length, segments=segments, radius_top=radius1)
    mid = [(p0[i] + p1[i]) / 2 for i in range(3)]
    return mat_apply(c, frame_z_to(d), mid)


def loft(stations, segments, exponent=2.0, axis_frame=None):
    """Closed body swept along local x through cross-sections.

    stations: [(x, half_width_y, half_height_z, z_centre), ...] with x increasing; the
    first and last may have zero size (a pointed end), otherwise that end is capped
    flat. Cross-sections are super-ellipses |y/a|^e + |z/b|^e = 1."""
    m = Mesh()
    rings = []
    for x, a, b, zc in stations:
        if a == 0 and b == 0:
            rings.append(len(m.vertices))
            m.vertices.append((x, 0.0, zc))
            continue
        start = len(m.vertices)
        for s in range(segments):
            t = 2 * math.pi * s / segments
            c, sn = math.cos(t), math.sin(t)
            y = a * math.copysign(abs(c) ** (2.0 / exponent), c)
            z = b * math.copysign(abs(sn) ** (2.0 / exponent), sn)
            m.vertices.append((x, y, zc + z))
        rings.append((start,))
    n = segments

    def ring_is_point(r):
        return not isinstance(r, tuple)

    # end caps for flat ends
    if not ring_is_point(rings[0]):
        c = len(m.vertices)
        x, _, _, zc = stations[0]
        m.vertices.append((x, 0.0, zc))
        s0 = rings[0][0]
        for s in range(n):
            m.triangles.append((c, s0 + (s + 1) % n, s0 + s))
    if not ring_is_point(rings[-1]):
        c = len(m.vertices)
        x, _, _, zc = stations[-1]
        m.vertices.append((x, 0.0, zc))
        s0 = rings[-1][0]
        for s in range(n):
            m.triangles.append((c, s0 + s, s0 + (s + 1) % n))
    for k in range(len(rings) - 1):
        r0, r1 = rings[k], rings[k + 1]
        for s in range(n):
            t = (s + 1) % n
            if ring_is_point(r0):
                m.triangles.append((r0, r1[0] + t, r1[0] + s))
            elif ring_is_point(r1):
                m.triangles.append((r0[0] + s, r0[0] + t, r1))
            else:
                a, b = r0[0] + s, r0[0] + t
                c, d = r1[0] + s, r1[0] + t
                m.triangles.append((a, b, d))
                m.triangles.append((a, d, c))
    if axis_frame is not None:
        m = mat_apply(m, axis_frame)
    return m


# --------------------------------------------------------------------------- helicopter

ROTOR_RADIUS = 5.5          # main rotor: 11.0 m diameter, 4 blades in an X
ROTOR_BLADE_CHORD = 0.40
ROTOR_Z = 1.95              # rotor plane height in the raw frame
TAIL_ROTOR_RADIUS = 0.95


def blade(root, tip, chord, thick, stations=10, segments=8):
    """A rotor blade along local +x from r=root to r=tip, flat (in the xy-plane),
    slightly tapered at the tip; elliptic cross-section."""
    st = []
    for k in range(stations):
        x = root + (tip - root) * k / (stations - 1)
        f = 1.0 if k < stations - 2 else (0.85 if k == stations - 2 else 0.6)
        st.append((x, chord / 2 * f, thick / 2 * f, 0.0))
    return loft(st, segments, exponent=2.0)


def helicopter_parts():
    parts = []
    # Fuselage: super-elliptic loft, pointed nose (+x) and a tapering rear.
    fus = [
        (-2.75, 0.0, 0.0, 0.62),
        (-2.6, 0.36, 0.40, 0.60),
        (-2.2, 0.62, 0.62, 0.52),
        (-1.6, 0.86, 0.82, 0.44),
        (-0.9, 1.00, 0.98, 0.38),
        (-0.2, 1.06, 1.04, 0.34),
        (0.5, 1.06, 1.04, 0.32),
        (1.2, 1.02, 0.98, 0.28),
        (1.9, 0.92, 0.86, 0.22),
        (2.5, 0.74, 0.68, 0.16),
        (2.95, 0.50, 0.46, 0.10),
        (3.2, 0.24, 0.22, 0.06),
        (3.3, 0.0, 0.0, 0.05),
    ]
    parts.append(("fuselage", loft(fus, 40, exponent=2.6)))
    # Cockpit canopy: an ellipsoid bulging out of the upper front of the fuselage.
    parts.append(("canopy", meshlib.sphere(1.0, center=(1.55, 0.0, 0.78), rings=12,
                                           segments=28, scale=(1.25, 0.88, 0.62))))
    # Engine cowling behind the mast, with two exhaust stubs.
    eng = [
        (-2.0, 0.0, 0.0, 1.25),
        (-1.9, 0.30, 0.18, 1.25),
        (-1.5, 0.52, 0.32, 1.25),
        (-0.6, 0.60, 0.38, 1.25),
        (0.3, 0.58, 0.36, 1.24),
        (0.8, 0.40, 0.24, 1.22),
        (0.95, 0.0, 0.0, 1.2),
    ]
    parts.append(("engine_cowling", loft(eng, 16, exponent=2.4)))
    parts.append(("exhaust_left", tube((-1.4, 0.4, 1.35), (-2.1, 0.75, 1.45), 0.13, 12)))
    parts.append(("exhaust_right", tube((-1.4, -0.4, 1.35), (-2.1, -0.75, 1.45), 0.13, 12)))
    # Mast and rotor hub.
    parts.append(("rotor_mast", meshlib.cylinder(0.13, 0.75, segments=12,
                                                 center=(0.0, 0.0, ROTOR_Z - 0.3))))
    parts.append(("rotor_hub", meshlib.cylinder(0.42, 0.30, segments=20,
                                                center=(0.0, 0.0, ROTOR_Z))))
    parts.append(("rotor_cap", meshlib.sphere(0.22, center=(0.0, 0.0, ROTOR_Z + 0.15),
                                              rings=6, segments=12, scale=(1, 1, 0.8))))
    # Main rotor: 4 blades at 45, 135, 225, 315 degrees (fixed, not spinning).
    for k in range(4):
        yaw = math.radians(45 + 90 * k)
        b = blade(0.30, ROTOR_RADIUS, ROTOR_BLADE_CHORD, 0.09, stations=14, segments=8)
        parts.append(("main_blade_%d" % (k + 1), b.transformed(xyz=(0, 0, ROTOR_Z),
                                                               rpy=(0, 0, yaw))))
    # Tail boom: a frustum from inside the fuselage rear to the tail.
    parts.append(("tail_boom", tube((-2.3, 0.0, 0.62), (-8.3, 0.0, 0.95), 0.36, 20, 0.16)))
    # Vertical fin (swept), extruded in y, from the boom end upwards and downwards.
    fin_poly = [(-8.75, -0.35), (-8.15, -0.30), (-7.55, 0.85), (-7.35, 1.55), (-7.65, 2.15),
                (-8.05, 2.30), (-8.45, 2.20), (-8.75, 1.20)]
    fin = meshlib.extrude(fin_poly, 0.12, z0=-0.06)
    parts.append(("tail_fin", fin.transformed(rpy=(math.pi / 2, 0, 0))))
    # Horizontal stabilizer (flat, tapered planform), extruded in z.
    stab_poly = [(-6.55, -1.25), (-6.15, -1.25), (-5.85, -0.2), (-5.85, 0.2), (-6.15, 1.25),
                 (-6.55, 1.25), (-6.6, 0.0)]
    parts.append(("stabilizer", meshlib.extrude(stab_poly, 0.08, z0=0.74)))
    # Tail rotor on the left side of the fin: a hub along y (touching the fin) and 2
    # blades in the xz-plane (the flat blade is rolled so its chord lies in that plane,
    # then swung about y).
    tr_c = (-8.2, 0.22, 1.75)
    parts.append(("tail_rotor_hub", meshlib.cylinder(0.14, 0.34, segments=12, center=tr_c,
                                                     axis="y")))
    for k in range(2):
        tb = blade(0.08, TAIL_ROTOR_RADIUS, 0.20, 0.05, stations=6, segments=8)
        ang = math.radians(60 + 180 * k)
        parts.append(("tail_rotor_blade_%d" % (k + 1),
                      tb.transformed(rpy=(math.pi / 2, 0, 0)).transformed(
                          rpy=(0, ang, 0)).transformed(xyz=(tr_c[0], tr_c[1] + 0.12, tr_c[2]))))
    # Landing skids: two tubes with an upturned front, four struts.
    skid_z = -1.90
    for side, sy in (("left", 1.15), ("right", -1.15)):
        parts.append(("skid_%s" % side, tube((-1.9, sy, skid_z), (1.7, sy, skid_z), 0.07, 12)))
        parts.append(("skid_%s_toe" % side, tube((1.62, sy, skid_z - 0.01),
                                                  (2.25, sy, skid_z + 0.38), 0.07, 12)))
        for sx in (-1.1, 1.0):
            parts.append(("strut_%s_%s" % (side, "rear" if sx < 0 else "front"),
                          tube((sx, 0.55 * (1 if sy > 0 else -1), -0.45),
                               (sx, sy, skid_z + 0.02), 0.06, 10)))
    # Centre the whole robot on its bounding-box centre.
    lo = [min(min(v[i] for v in m.vertices) for _, m in parts) for i in range(3)]
    hi = [max(max(v[i] for v in m.vertices) for _, m in parts) for i in range(3)]
    c = [(lo[i] + hi[i]) / 2 for i in range(3)]
    return [(n, m.transformed(xyz=(-c[0], -c[1], -c[2]))) for n, m in parts], c


# --------------------------------------------------------------------------- city

# Ground top at z = 0. The helicopter flies west (-x) -> east (+x). A continuous wall
# of high-rises (WALL_X0..WALL_X1) crosses the whole city (and the bounds in y by more
# than the helicopter's radius); the only opening is a slot between two towers,
# GAP_Y0..GAP_Y1, crossed by a low skybridge whose underside is SKY_Z0 above the
# ground. The bounds cap the helicopter's centre at BOUNDS_MAX[2], less than SKY_Z1 plus
# the helicopter's smallest reach from its centre in any direction (~1.8 m, see
# check.py), so flying over the skybridge is impossible: it has to pass under it.
# The slot is narrower than the level helicopter at some yaws (13.4 m at most) and
# lower than the helicopter on its side (7.95 m): about a tenth of all rotations fit
# its cross-section (slot_rotation_fraction), few enough that the passage is narrow,
# enough that lazy PRM with uniform sampling finds it within a few rounds.

WALL_X0, WALL_X1 = -9.0, 9.0
GAP_Y0, GAP_Y1 = 14.0, 26.0            # 12.0 m wide slot
SKY_X0, SKY_X1 = -3.0, 3.0             # skybridge, 6 m long in x
SKY_Z0, SKY_Z1 = 7.5, 11.0             # underside 7.5 m above the ground
BOUNDS_MIN = [-62.0, -44.0, 1.0]
BOUNDS_MAX = [62.0, 44.0, 12.0]
START = ((-50.0, -22.0, 6.0), (1.0, 0.0, 0.0, 0.0))
GOAL_YAW = math.radians(90.0)
GOAL = ((49.0, -24.0, 7.0), (math.cos(GOAL_YAW / 2), 0.0, 0.0, math.sin(GOAL_YAW / 2)))


class City:
    def __init__(self):
        self.parts = []      # (name, Mesh) for the OBJ
        self.boxes = []      # (name, lo, hi): solid axis-aligned boxes (exact geometry)
        self.others = []     # (name, lo, hi): AABBs of non-box solids

    def building(self, name, pieces, extras=()):
        """pieces: [(x0, y0, z0, x1, y1, z1), ...] solid boxes of one building."""
        m = Mesh()
        for p in pieces:
            x0, y0, z0, x1, y1, z1 = p
            m.add(meshlib.box((x1 - x0, y1 - y0, z1 - z0),
                              center=((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2)))
            self.boxes.append((name, (x0, y0, z0), (x1, y1, z1)))
        for e in extras:
            m.add(e)
            lo, hi = e.bounds()
            self.others.append((name, tuple(lo), tuple(hi)))
        self.parts.append((name, m))


def antenna(x, y, z, height, r=0.35):
    """A mast with a thinner whip on top."""
    m = meshlib.cylinder(r, height * 0.6, segments=8, center=(x, y, z + height * 0.3))
    m.add(meshlib.cylinder(r * 0.4, height * 0.4 + 0.02, segments=6,
                           center=(x, y, z + height * 0.8 - 0.01)))
    return m


def tower_block(x0, y0, x1, y1, h, setbacks=2, step=1.5, frac=0.55):
    """Pieces of a high-rise: a box with `setbacks` set-back tiers; each tier is inset
    by `step` on every side and starts at `frac` of the height still left above the
    tier below (tiers overlap by 1 cm)."""
    pieces = []
    za = 0.0
    for k in range(setbacks + 1):
        zb = h if k == setbacks else za + (h - za) * frac
        inset = step * k
        pieces.append((x0 + inset, y0 + inset, za - (0.0 if k == 0 else 0.01),
                       x1 - inset, y1 - inset, zb))
        za = zb
    return pieces


def rooftop_tank(x, y, z, r=1.2, h=2.0):
    return meshlib.cylinder(r, h, segments=12, center=(x, y, z + h / 2))


def city_parts():
    c = City()
    # Ground slab.
    c.building("ground", [(-80.0, -68.0, -1.0, 80.0, 68.0, 0.0)])

    # ---- the wall of high-rises (x in [WALL_X0, WALL_X1]) ---------------------------
    X0, X1 = WALL_X0, WALL_X1
    # South of the slot: y from -66 to GAP_Y0, split by 1.0 m service alleys (far narrower
    # than the helicopter's smallest width). Set-backs start above 16 m, higher than
    # the bounds' ceiling.
    wall_south = [(-66.0, -41.0, 42.0, 2), (-40.0, -19.0, 30.0, 1), (-18.0, -2.0, 54.0, 2),
                  (-1.0, GAP_Y0, 38.0, 1)]
    for k, (ya, yb, h, sb) in enumerate(wall_south):
        pieces = tower_block(X0, ya, X1, yb, h, setbacks=sb, step=1.5)
        extras = []
        top = pieces[-1]
        if k in (0, 2):
            extras.append(antenna((top[0] + top[3]) / 2, (top[1] + top[4]) / 2, top[5],
                                  14.0 if k == 2 else 9.0))
        else:
            extras.append(rooftop_tank(top[0] + 3.0, top[1] + 3.0, top[5]))
        c.building("wall_tower_s%d" % (k + 1), pieces, extras)
    # North of the slot.
    wall_north = [(GAP_Y1, 41.0, 46.0, 1), (42.0, 66.0, 34.0, 2)]
    for k, (ya, yb, h, sb) in enumerate(wall_north):
        pieces = tower_block(X0, ya, X1, yb, h, setbacks=sb, step=1.5)
        top = pieces[-1]
        extras = [antenna((top[0] + top[3]) / 2, (top[1] + top[4]) / 2, top[5], 11.0)] \
            if k == 0 else [rooftop_tank(top[3] - 3.0, top[4] - 3.0, top[5], 1.5, 2.5)]
        c.building("wall_tower_n%d" % (k + 1), pieces, extras)
    # The slot's walls are the lowest tiers of wall_tower_s4 and wall_tower_n1 (their
    # first set-backs are at 20.9 m and 25.3 m). Skybridge across the slot, embedded
    # 1 m into both towers, with a glazed roof box.
    c.building("skybridge", [(SKY_X0, GAP_Y0 - 1.0, SKY_Z0, SKY_X1, GAP_Y1 + 1.0, SKY_Z1),
                             (SKY_X0 + 0.8, GAP_Y0 - 0.5, SKY_Z1 - 0.01,
                              SKY_X1 - 0.8, GAP_Y1 + 0.5, SKY_Z1 + 1.2)])
    # An upper skybridge between the set-back tiers (far above the ceiling).
    c.building("skybridge_upper", [(-2.0, GAP_Y0 - 3.0, 30.0, 2.0, GAP_Y1 + 3.0, 33.0)])

    # ---- west side (start) ----------------------------------------------------------
    # streets at least ~14 m wide; open plaza around the start (-50, -22)
    west = [
        ("west_office_1", -70.0, -64.0, -56.0, -46.0, 36.0, 2, True),
        ("west_office_2", -44.0, -62.0, -28.0, -46.0, 28.0, 1, False),
        ("west_block_3", -70.0, -6.0, -58.0, 10.0, 22.0, 1, False),
        ("west_tower_4", -40.0, -4.0, -26.0, 8.0, 48.0, 2, True),
        ("west_block_5", -68.0, 26.0, -50.0, 40.0, 18.0, 1, False),
        ("west_block_6", -36.0, 32.0, -22.0, 48.0, 26.0, 2, False),
        ("west_block_7", -76.0, 50.0, -58.0, 64.0, 30.0, 1, True),
        ("west_block_8", -24.0, -40.0, -16.0, -30.0, 20.0, 1, False),
    ]
    # ---- east side (goal) -----------------------------------------------------------
    east = [
        ("east_tower_1", 24.0, -64.0, 40.0, -48.0, 50.0, 2, True),
        ("east_block_2", 58.0, -62.0, 74.0, -46.0, 24.0, 1, False),
        ("east_block_3", 20.0, -28.0, 32.0, -8.0, 32.0, 2, False),
        ("east_tower_4", 30.0, 6.0, 44.0, 18.0, 44.0, 2, True),
        ("east_block_5", 58.0, 2.0, 74.0, 16.0, 20.0, 1, False),
        ("east_block_6", 22.0, 34.0, 38.0, 50.0, 28.0, 1, False),
        ("east_block_7", 54.0, 30.0, 72.0, 46.0, 36.0, 2, True),
        ("east_block_8", 50.0, 54.0, 76.0, 64.0, 16.0, 1, False),
    ]
    for name, x0, y0, x1, y1, h, sb, ant in west + east:
        pieces = tower_block(x0, y0, x1, y1, h, setbacks=sb, step=1.5)
        top = pieces[-1]
        extras = []
        if ant:
            extras.append(antenna((top[0] + top[3]) / 2, (top[1] + top[4]) / 2, top[5],
                                  8.0 + 0.1 * h))
        else:
            extras.append(rooftop_tank(top[0] + 2.5, top[1] + 2.5, top[5]))
        c.building(name, pieces, extras)
    # Round towers (cylinders) and street-level details.
    rounds = [("west_round_tower", -50.0, 14.0, 5.0, 40.0),
              ("east_round_tower", 48.0, 12.0, 4.5, 34.0)]
    for name, x, y, r, h in rounds:
        m = meshlib.cylinder(r, h, segments=24, center=(x, y, h / 2))
        m.add(meshlib.cylinder(r * 0.7, 4.0, segments=24, center=(x, y, h + 2.0 - 0.01)))
        m.add(antenna(x, y, h + 4.0 - 0.02, 10.0, r=0.3))
        c.parts.append((name, m))
        lo, hi = m.bounds()
        c.others.append((name, tuple(lo), tuple(hi)))
    # Trees in the streets (small obstacles along the way).
    trees = ((-30.0, -20.0), (-16.0, -12.0), (-16.0, 34.0), (15.0, 36.0), (18.0, -36.0),
             (40.0, -36.0))
    for k, (x, y) in enumerate(trees):
        tree = meshlib.cylinder(0.25, 3.0, segments=6, center=(x, y, 1.5))
        tree.add(meshlib.sphere(2.0, center=(x, y, 4.5), rings=5, segments=8))
        c.parts.append(("tree_%d" % k, tree))
        lo, hi = tree.bounds()
        c.others.append(("tree_%d" % k, tuple(lo), tuple(hi)))
    return c


# --------------------------------------------------------------------------- main

def main():
    heli, _ = helicopter_parts()
    # merge the corners that box() repeats per face
    heli = [(n, meshlib.weld(m)) for n, m in heli]
    for name, m in heli:
        meshlib.check_closed(m, name, min_area=1e-7)
    n_heli = sum(len(m) for _, m in heli)
    lo = [min(min(v[i] for v in m.vertices) for _, m in heli) for i in range(3)]
    hi = [max(max(v[i] for v in m.vertices) for _, m in heli) for i in range(3)]
    print("helicopter: %d triangles in %d parts" % (n_heli, len(heli)))
    print("helicopter bbox: %s .. %s (size %s)" % (
        ["%.3f" % x for x in lo], ["%.3f" % x for x in hi],
        ["%.3f" % (hi[i] - lo[i]) for i in range(3)]))
    meshlib.write_dae(DAE_PATH, heli)

    city = city_parts()
    city.parts = [(n, meshlib.weld(m)) for n, m in city.parts]
    for name, m in city.parts:
        meshlib.check_closed(m, name, min_area=1e-7)
    n_city = sum(len(m) for _, m in city.parts)
    print("city: %d triangles in %d objects" % (n_city, len(city.parts)))
    os.makedirs(os.path.dirname(OBJ_PATH), exist_ok=True)
    meshlib.write_obj(OBJ_PATH, city.parts,
                      comment="helicopter_city: generated by robots/helicopter/generate.py")
    write_yaml(lo, hi, [v for _, m in heli for v in m.vertices])
    return heli, city


def fmt(v):
    return "[%s]" % ", ".join(("%.7f" % x).rstrip("0").rstrip(".") if x != 0 else "0"
                               for x in v)


def level_width(vertices, yaw):
    """Extent in y of the helicopter rotated by yaw about z (level flight)."""
    c, s = math.cos(yaw), math.sin(yaw)
    ys = [s * v[0] + c * v[1] for v in vertices]
    return max(ys) - min(ys)


def level_yaw_window(vertices, width, step_deg=0.1):
    """(Minimum level width, largest yaw offset from heading +x such that the level
    helicopter stays narrower than `width` for every yaw within it, in degrees; 180
    when it fits at every yaw)."""
    wmin = min(level_width(vertices, math.radians(d * step_deg))
               for d in range(int(round(90 / step_deg)) + 1))
    k = 0
    while k * step_deg < 180 and all(
            level_width(vertices, sgn * math.radians((k + 1) * step_deg)) < width
            for sgn in (1, -1)):
        k += 1
    return wmin, k * step_deg


def level_width_max(vertices, step_deg=0.1):
    """Largest extent in y of the level helicopter over all yaws."""
    return max(level_width(vertices, math.radians(d * step_deg))
               for d in range(int(round(180 / step_deg))))


def slot_rotation_fraction(vertices, width, height, samples=3000, seed=7):
    """Fraction of uniformly random rotations (Shoemake's method, a fixed seed) under
    which the helicopter's extents in y and z are less than width and height: how much
    of SO(3) fits the slot's cross-section."""
    rng = random.Random(seed)
    U = sorted({tuple(round(x, 4) for x in v) for v in vertices})
    fit = 0
    for _ in range(samples):
        u1, u2, u3 = rng.random(), rng.random(), rng.random()
        x = math.sqrt(1 - u1) * math.sin(2 * math.pi * u2)
        y = math.sqrt(1 - u1) * math.cos(2 * math.pi * u2)
        z = math.sqrt(u1) * math.sin(2 * math.pi * u3)
        w = math.sqrt(u1) * math.cos(2 * math.pi * u3)
        r1 = (2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x))
        r2 = (2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y))
        ys = [r1[0] * v[0] + r1[1] * v[1] + r1[2] * v[2] for v in U]
        if max(ys) - min(ys) >= width:
            continue
        zs = [r2[0] * v[0] + r2[1] * v[1] + r2[2] * v[2] for v in U]
        if max(zs) - min(zs) < height:
            fit += 1
    return fit / samples


def rotation_weight(vertices):
    """The metric's weight per radian of rotation: the helicopter's radius (the largest
    distance of a vertex from the origin, rounded up to 0.1 m), the farthest any of its
    points moves per radian."""
    rmax = max(math.sqrt(sum(x * x for x in v)) for v in vertices)
    return math.ceil(rmax * 10 - 1e-9) / 10


def write_yaml(lo, hi, heli_vertices):
    size = [hi[i] - lo[i] for i in range(3)]
    width = GAP_Y1 - GAP_Y0
    wmin, window = level_yaw_window(heli_vertices, width)
    wmax = level_width_max(heli_vertices)
    frac = slot_rotation_fraction(heli_vertices, width, SKY_Z0)
    rot_w = rotation_weight(heli_vertices)
    print("level: width %.3f..%.3f m; yaw window +-%.1f deg for the %.2f m slot; "
          "%.1f%% of rotations fit the %.2f x %.2f m cross-section; rotation weight %.1f"
          % (wmin, wmax, window, width, 100 * frac, width, SKY_Z0, rot_w))
    text = """name: helicopter
description: >
  A helicopter (rigid, 11.0 m four-blade main rotor, %.2f x %.2f x %.2f m overall,
  COLLADA mesh) crosses a city from a plaza on the west side to a plaza on the east
  side. A continuous wall of high-rises runs north-south through the whole city; the
  straight line runs into a tower of that wall. The only way through is a slot
  between two towers, crossed by a skybridge; the flight ceiling (the bounds) keeps
  the helicopter below the skybridge's roof, so it must fly under it.
narrowest_passage: >
  The slot under the skybridge: %.2f m wide (y %.1f..%.1f) and %.2f m high (ground to
  the skybridge underside), %.1f m long (the skybridge; the slot itself is %.1f m long).
  Level, the helicopter's four-blade rotor (11.0 m diameter) and tail make it %.2f to
  %.2f m wide depending on yaw, so it passes level only within about +-%.0f deg of yaw
  around heading east (or west); banking narrows it but makes it taller (%.2f m level,
  %.2f m on its side, more than the slot is high), so only about %.0f%% of all rotations
  fit the slot's %.1f x %.1f m cross-section.

robot:
  mesh: ../robots/helicopter/helicopter.dae

obstacles:
  - mesh: environments/helicopter_city.obj

bounds:
  min: %s
  max: %s

start:
  base: {xyz: %s, quat_wxyz: %s}
goal:
  base: {xyz: %s, quat_wxyz: %s}

planner:
  # per radian of rotation: the helicopter's radius, the farthest its points move
  distance_weights: {rotation: %.1f}
""" % (size[0], size[1], size[2], width, GAP_Y0, GAP_Y1, SKY_Z0, SKY_X1 - SKY_X0,
       WALL_X1 - WALL_X0, wmin, wmax, window, size[2], size[1], 100 * frac, width, SKY_Z0,
       fmt(BOUNDS_MIN), fmt(BOUNDS_MAX),
       fmt(START[0]), fmt(START[1]), fmt(GOAL[0]), fmt(GOAL[1]), rot_w)
    with open(YAML_PATH, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
