"""The grand piano, as named closed parts (see generate.py).

Model frame while building: x across the keyboard (bass at -x), y along the piano
(keyboard at the front, -y; tail at +y), z up, floor at z = 0. build_piano() returns
the parts moved so that the origin is the centre of the bounding box.
"""

import math

import geom
import meshlib as ml
from meshlib import Mesh, box_between as box

HALF_W = 0.775          # half width of the case (1.55 m)
Z_CASE = 0.62           # underside of the case
Z_RIM = 0.99            # top of the rim (lid hinge height)
Y_FRONT = 0.0           # front face of the case; keyboard in front of it (-y)
LID_T = 0.025           # lid thickness

# The bent side (treble, +x) and the tail, from the end of the straight front-right
# edge round to the start of the straight bass side; first and last points only set
# the end tangents. Concave (S-shaped) between y = 0.62 and y = 1.44.
BENT_SIDE = [
    (0.775, -0.10), (0.775, 0.22), (0.765, 0.38), (0.715, 0.50), (0.610, 0.62),
    (0.470, 0.76), (0.350, 0.92), (0.255, 1.10), (0.185, 1.28), (0.130, 1.44),
    (0.060, 1.56), (-0.060, 1.645), (-0.230, 1.68), (-0.430, 1.675), (-0.610, 1.625),
    (-0.725, 1.535), (-0.768, 1.43), (-0.775, 1.34), (-0.775, 1.00),
]


def outline(n_curve):
    """Top view of the case: counter-clockwise polygon, front edge at Y_FRONT."""
    pts = [(-HALF_W, Y_FRONT), (HALF_W, Y_FRONT)] + geom.spline(BENT_SIDE, n_curve)
    pts = geom.clean_polygon(pts)
    assert ml.polygon_area(pts) > 0 and geom.polygon_is_simple(pts)
    return pts


def outline_x_at(poly, y):
    """Largest x of the outline at height y (the bent side)."""
    best = -1e9
    for i in range(len(poly)):
        a, b = poly[i - 1], poly[i]
        if (a[1] - y) * (b[1] - y) <= 0 and a[1] != b[1]:
            t = (y - a[1]) / (b[1] - a[1])
            best = max(best, a[0] + t * (b[0] - a[0]))
    return best


def rot_y(angle):
    c, s = math.cos(angle), math.sin(angle)
    return [[c, 0, s], [0, 1, 0], [-s, 0, c]]


def rot_x(angle):
    c, s = math.cos(angle), math.sin(angle)
    return [[1, 0, 0], [0, c, -s], [0, s, c]]


# ---------------------------------------------------------------- keyboard


def keyboard(x0, x1, large):
    """88 keys (52 white, 36 black) between x0 and x1; white keys are extruded outlines
    with the notches the black keys sit in."""
    n_white = 52
    pitch = (x1 - x0) / n_white
    gap = 0.0012
    bw = pitch * 0.58                     # black key width
    notch = bw / 2 + 0.0008
    y_front, y_notch, y_back = -0.300, -0.200, -0.100
    z_lo, z_top = 0.680, 0.710
    # white key names from A0: A B C D E F G ...; a black key follows C D F G A
    names = "ABCDEFG"
    white = []
    has_black_after = []
    for i in range(n_white):
        nm = names[i % 7]
        white.append(nm)
        has_black_after.append(nm in "CDFGA" and i < n_white - 1)
    whites, blacks = Mesh(), Mesh()
    for i in range(n_white):
        xa, xb = x0 + i * pitch + gap / 2, x0 + (i + 1) * pitch - gap / 2
        cut_l = notch - gap / 2 if i > 0 and has_black_after[i - 1] else 0.0
        cut_r = notch - gap / 2 if has_black_after[i] else 0.0
        poly = [(xa, y_front), (xb, y_front)]
        if cut_r:
            poly += [(xb, y_notch), (xb - cut_r, y_notch), (xb - cut_r, y_back)]
        else:
            poly += [(xb, y_back)]
        if cut_l:
            poly += [(xa + cut_l, y_back), (xa + cut_l, y_notch), (xa, y_notch)]
        else:
            poly += [(xa, y_back)]
        if large:
            # key top (ivory) over a slightly narrower key stick, with a bevelled front
            top = geom.offset_polygon(poly, 0.0008)
            whites.add(geom.extrude_between(poly, top, z_top - 0.010, z_top))
            stick = [(xa + 0.001, y_front + 0.004), (xb - 0.001, y_front + 0.004),
                     (xb - 0.001, y_back + 0.08), (xa + 0.001, y_back + 0.08)]
            whites.add(ml.extrude(stick, z_top - 0.010 - z_lo + 0.001, z_lo))
        else:
            whites.add(ml.extrude(poly, z_top - z_lo, z_lo))
        if has_black_after[i]:
            xc = x0 + (i + 1) * pitch
            if large:
                # tapered black key: trapezoid section extruded along y, with a sloped front
                side = [(-0.200, 0.700), (-0.100, 0.700), (-0.100, 0.722), (-0.185, 0.722),
                        (-0.200, 0.712)]
                prism = ml.extrude(side, bw, 0.0)       # in (y, z), extruded along +x'
                # map (u=y, v=z, w) -> (x = xc - bw/2 + w, y = u, z = v)
                m = Mesh([(xc - bw / 2 + w, u, v) for u, v, w in prism.vertices],
                         prism.triangles)
                # taper: pull the top vertices in by 1.5 mm on both sides
                verts = []
                for x, y, z in m.vertices:
                    if z > 0.721:
                        x = xc + (x - xc) * (bw / 2 - 0.0015) / (bw / 2)
                    verts.append((x, y, z))
                blacks.add(Mesh(verts, m.triangles))
            else:
                blacks.add(box((xc - bw / 2, -0.200, 0.700), (xc + bw / 2, -0.100, 0.722)))
    return whites, blacks


# ---------------------------------------------------------------- legs and lyre


def leg(cx, cy, large):
    parts = Mesh()
    if large:
        # turned leg on a caster: block, bead, tapered fluted shaft, collar, caster
        parts.add(box((cx - 0.085, cy - 0.085, 0.54), (cx + 0.085, cy + 0.085, Z_CASE + 0.002)))
        prof = [(0, 0.085), (0.048, 0.085), (0.056, 0.100), (0.050, 0.118), (0.044, 0.15)]
        for k in range(1, 9):
            z = 0.15 + k * 0.045
            prof.append((0.044 + 0.0032 * k, z))
        prof += [(0.074, 0.51), (0.082, 0.52), (0.082, 0.535), (0.070, 0.545), (0, 0.545)]
        parts.add(geom.lathe(prof, 32, center=(cx, cy, 0)))
        # caster: fork plate, two cheeks, wheel
        parts.add(box((cx - 0.035, cy - 0.035, 0.075), (cx + 0.035, cy + 0.035, 0.088)))
        for sx in (-1, 1):
            parts.add(box((cx + sx * 0.022 - 0.004, cy - 0.025, 0.030),
                          (cx + sx * 0.022 + 0.004, cy + 0.025, 0.078)))
        parts.add(ml.cylinder(0.035, 0.034, segments=24, center=(cx, cy, 0.035), axis="x"))
    else:
        parts.add(box((cx - 0.08, cy - 0.08, 0.54), (cx + 0.08, cy + 0.08, Z_CASE + 0.002)))
        parts.add(ml.cylinder(0.045, 0.545, segments=16, center=(cx, cy, 0.2725),
                              radius_top=0.062))
        parts.add(ml.cylinder(0.054, 0.04, segments=16, center=(cx, cy, 0.02)))
    return parts


def lyre(large):
    m = Mesh()
    yc = 0.08
    m.add(box((-0.15, yc - 0.06, 0.04), (0.15, yc + 0.06, 0.13)))           # pedal box
    m.add(box((-0.16, yc - 0.05, 0.575), (0.16, yc + 0.05, Z_CASE + 0.002)))  # top block
    for px in (-0.07, 0.0, 0.07):                                               # pedals
        if large:
            # pedal: a flat foot plate with a rounded toe, on a rod into the pedal box
            plate = [(px + 0.018, 0.0), (px - 0.018, 0.0), (px - 0.018, -0.045)]
            for k in range(1, 10):
                t = math.pi + math.pi * k / 10
                plate.append((px + 0.018 * math.cos(t), -0.045 + 0.018 * math.sin(t)))
            plate.append((px + 0.018, -0.045))
            assert ml.polygon_area(plate) > 0
            m.add(ml.extrude(geom.clean_polygon(plate), 0.012, 0.070))
            m.add(ml.cylinder(0.008, 0.12, segments=12, center=(px, 0.0, 0.076), axis="y"))
        else:
            m.add(box((px - 0.016, -0.07, 0.070), (px + 0.016, yc - 0.05, 0.085)))
    if large:
        # lyre arms: two S-curved bands (in the x-z plane) each side of the centre
        for sx in (-1, 1):
            pts = []
            for k in range(25):
                t = k / 24.0
                z = 0.13 + t * (0.575 - 0.13)
                x = sx * (0.09 + 0.05 * math.sin(math.pi * t) + 0.01 * math.sin(3 * math.pi * t))
                pts.append((x, z))
            band = [(x - 0.017, z) for x, z in pts] + [(x + 0.017, z) for x, z in reversed(pts)]
            if ml.polygon_area(band) < 0:
                band = list(reversed(band))
            arm = ml.extrude(geom.clean_polygon(band), 0.03, -0.015)
            # (x, y=z_lyre, z=depth) -> (x, yc - depth, z_lyre): rotate about x by +90 deg
            arm = geom.rotate_about(arm, (0, 0, 0), rot_x(math.pi / 2))
            m.add(geom.translate(arm, (0, yc, 0)))
        # strings of the lyre (the decorative rods between the arms)
        for px in (-0.03, 0.0, 0.03):
            m.add(ml.cylinder(0.006, 0.44, segments=10, center=(px, yc, 0.353)))
    else:
        for px in (-0.10, 0.10):
            m.add(geom.segment_cylinder((px, yc, 0.125), (px, yc, 0.58), 0.022, 12))
    seg = 12 if large else 8
    for px in (-1, 1):                                                          # braces
        m.add(geom.segment_cylinder((px * 0.12, yc + 0.05, 0.10), (px * 0.22, 0.50, Z_CASE + 0.01),
                                    0.012, seg))
    return m


# ---------------------------------------------------------------- the piano


def build_piano(large=False, lid_angle_deg=15.0):
    n_curve = 520 if large else 196
    outer = outline(n_curve)
    parts = []

    # case: rim (a ring, moulded on the large piano), soundboard, iron plate
    if large:
        profile = [(0.004, Z_CASE), (0.0, Z_CASE + 0.012), (0.0, 0.80), (-0.004, 0.81),
                   (0.0, 0.82), (0.0, 0.955), (-0.008, 0.962), (-0.008, 0.975), (-0.002, 0.984),
                   (0.006, Z_RIM), (0.050, Z_RIM), (0.055, Z_RIM - 0.006),
                   (0.055, Z_CASE + 0.001)]
    else:
        profile = [(0.0, Z_CASE), (0.0, Z_RIM - 0.012), (0.006, Z_RIM), (0.055, Z_RIM),
                   (0.055, Z_CASE)]
    parts.append(("rim", geom.profile_sweep(outer, profile)))
    inner = geom.offset_polygon(outer, 0.050)
    assert geom.polygon_is_simple(inner)
    parts.append(("soundboard", ml.extrude(inner, 0.76 - Z_CASE, Z_CASE)))
    plate_outer = geom.clean_polygon(geom.offset_polygon(outer, 0.11), min_sin=5e-3)
    assert geom.polygon_is_simple(plate_outer)
    if large:
        # cast-iron plate: a frame with struts, tuning pins, strings
        assert geom.polygon_is_simple(geom.offset_polygon(plate_outer, 0.05))
        parts.append(("plate", geom.profile_sweep(plate_outer, [
            (0.0, 0.76), (0.0, 0.80), (0.01, 0.81), (0.05, 0.81), (0.05, 0.76)])))
        struts = Mesh()
        for x_tail, y_tail in ((-0.55, 1.50), (-0.25, 1.55), (0.02, 1.42)):
            xa, ya = x_tail * 0.6, 0.22
            d = math.hypot(x_tail - xa, y_tail - ya)
            strut = box((-0.02, 0, 0.76), (0.02, d, 0.815), divisions=(1, 8, 1))
            ang = math.atan2(-(x_tail - xa), y_tail - ya)
            struts.add(strut.transformed(xyz=(xa, ya, 0), rpy=(0, 0, ang)))
        struts.add(box((-0.62, 0.10, 0.76), (0.62, 0.24, 0.83), divisions=(12, 2, 1)))
        parts.append(("plate_struts", struts))
        pins = Mesh()
        strings = Mesh()
        n_str = 176                  # two strings a note (the treble has three in life)
        for k in range(n_str):
            t = k / (n_str - 1)
            x = -0.60 + 1.20 * t
            # string from the pin block (front) to the hitch near the rim
            y_end = 1.45 - 1.05 * t ** 1.3
            x_end = x - 0.10 * (1 - t)
            pins.add(ml.cylinder(0.0035, 0.05, segments=6, center=(x, 0.15 + 0.04 * (k % 2), 0.855)))
            ln = math.hypot(x_end - x, y_end - 0.20)
            s = box((-0.0012, 0, -0.0012), (0.0012, ln, 0.0012))
            ang = math.atan2(-(x_end - x), y_end - 0.20)
            strings.add(s.transformed(xyz=(x, 0.20, 0.845), rpy=(0, 0, ang)))
        parts.append(("tuning_pins", pins))
        parts.append(("strings", strings))
    else:
        parts.append(("plate", ml.extrude(plate_outer, 0.04, 0.76)))

    # keyboard: keybed, cheek blocks, key slip, fallboard, keys
    kx = 0.645
    parts.append(("keybed", box((-HALF_W, -0.30, Z_CASE), (HALF_W, Y_FRONT + 0.01, 0.68),
                                divisions=(6, 2, 1) if large else (1, 1, 1))))
    for sx, nm in ((-1, "cheek_left"), (1, "cheek_right")):
        if large:
            # side profile with a rounded top front (in the y-z plane), extruded along x
            prof = [(-0.32, Z_CASE), (Y_FRONT + 0.01, Z_CASE), (Y_FRONT + 0.01, 0.80),
                    (-0.22, 0.80)]
            for k in range(1, 12):
                t = (math.pi / 2) * k / 12
                prof.append((-0.22 - 0.10 * math.sin(t), 0.70 + 0.10 * math.cos(t)))
            prof.append((-0.32, 0.70))
            prism = ml.extrude(geom.clean_polygon(prof), HALF_W - kx, 0)
            x_lo = kx if sx > 0 else -HALF_W
            m = Mesh([(x_lo + w, u, v) for u, v, w in prism.vertices],
                     prism.triangles)
        else:
            lo = (kx, -0.32, Z_CASE) if sx > 0 else (-HALF_W, -0.32, Z_CASE)
            hi = (HALF_W, Y_FRONT + 0.01, 0.79) if sx > 0 else (-kx, Y_FRONT + 0.01, 0.79)
            m = box(lo, hi)
        parts.append((nm, m))
    parts.append(("key_slip", box((-kx, -0.32, 0.635), (kx, -0.30, 0.70))))
    if large:
        # fallboard with a rounded front, nameboard behind it
        prof = [(-0.15, 0.700), (Y_FRONT + 0.01, 0.700), (Y_FRONT + 0.01, 0.800), (-0.12, 0.800)]
        for k in range(1, 10):
            t = (math.pi / 2) * k / 10
            prof.append((-0.12 - 0.03 * math.sin(t), 0.77 + 0.03 * math.cos(t)))
        prism = ml.extrude(geom.clean_polygon(prof), 2 * kx, 0)
        parts.append(("fallboard", Mesh([(-kx + w, u, v) for u, v, w in prism.vertices],
                                        prism.triangles)))
    else:
        parts.append(("fallboard", box((-kx, -0.15, 0.70), (kx, Y_FRONT + 0.01, 0.80))))
    whites, blacks = keyboard(-kx, kx, large)
    parts.append(("white_keys", whites))
    parts.append(("black_keys", blacks))

    # lid: main lid (outline behind y = 0.32) with the front flap folded back on top,
    # hinged along the straight bass side, propped open on its stick at the bent side
    alpha = math.radians(lid_angle_deg)
    lid_poly = geom.clean_polygon(geom.clip_polygon(outer, 1, 0.32))
    if large:
        lid = geom.extrude_between(lid_poly, geom.offset_polygon(lid_poly, 0.006),
                                   Z_RIM, Z_RIM + LID_T)
    else:
        lid = ml.extrude(lid_poly, LID_T, Z_RIM)
    flap_x1 = outline_x_at(outer, 0.32) - 0.003
    flap = box((-HALF_W, 0.32, Z_RIM + LID_T), (flap_x1, 0.60, Z_RIM + 2 * LID_T),
               divisions=(8, 2, 1) if large else (1, 1, 1))
    hinge = (-HALF_W, 0.0, Z_RIM)
    R = rot_y(-alpha)
    parts.append(("lid", geom.rotate_about(lid, hinge, R)))
    parts.append(("lid_flap", geom.rotate_about(flap, hinge, R)))
    if large:
        hinges = Mesh()
        for hy in (0.45, 0.95, 1.30):
            hinges.add(ml.cylinder(0.008, 0.06, segments=12, center=(-HALF_W - 0.004, hy, Z_RIM),
                                   axis="y"))
            hinges.add(box((-HALF_W - 0.002, hy - 0.03, Z_RIM - 0.03), (-HALF_W + 0.002, hy + 0.03,
                                                                            Z_RIM)))
        parts.append(("lid_hinges", hinges))
    y_s = 0.78
    x_s = outline_x_at(outer, y_s) - 0.03
    z_top = Z_RIM + (x_s + HALF_W) * math.tan(alpha) + 0.005
    if large:
        stick = geom.segment_cylinder((x_s, y_s, Z_RIM - 0.005), (x_s, y_s, z_top), 0.011, 16)
    else:
        stick = box((x_s - 0.012, y_s - 0.012, Z_RIM - 0.005), (x_s + 0.012, y_s + 0.012, z_top))
    parts.append(("lid_stick", stick))

    if large:
        # music desk: a slanted board with a ledge, on two supports
        desk = Mesh()
        board = box((-0.40, -0.011, 0.0), (0.40, 0.011, 0.30), divisions=(16, 1, 6))
        ledge = box((-0.40, -0.045, -0.005), (0.40, 0.011, 0.018), divisions=(16, 1, 1))
        for k in range(9):
            xs = -0.32 + 0.08 * k
            desk.add(box((xs - 0.012, -0.018, 0.06), (xs + 0.012, -0.010, 0.27)))
        desk.add(board)
        desk.add(ledge)
        desk = desk.transformed(xyz=(0, 0.16, Z_RIM + 0.005), rpy=(-math.radians(14), 0, 0))
        for sx in (-0.30, 0.30):
            desk.add(box((sx - 0.02, 0.06, Z_RIM - 0.01), (sx + 0.02, 0.26, Z_RIM + 0.02)))
        parts.append(("music_desk", desk))

    # three legs and the pedal lyre
    legs = Mesh()
    for cx, cy in ((-0.680, -0.13), (0.680, -0.13), (-0.30, 1.45)):
        legs.add(leg(cx, cy, large))
    parts.append(("legs", legs))
    parts.append(("pedal_lyre", lyre(large)))

    # centre the bounding box on the origin
    lo = [min(min(v[i] for v in m.vertices) for _, m in parts) for i in range(3)]
    hi = [max(max(v[i] for v in m.vertices) for _, m in parts) for i in range(3)]
    c = [(lo[i] + hi[i]) / 2 for i in range(3)]
    parts = [(nm, geom.translate(m, (-c[0], -c[1], -c[2]))) for nm, m in parts]
    info = {"model_center": c, "size": [hi[i] - lo[i] for i in range(3)],
            "floor_z": -c[2], "lid_angle_deg": lid_angle_deg}
    return parts, info
