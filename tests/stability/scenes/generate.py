#!/usr/bin/env python3
"""Generates the narrow-passage fixtures of the stability suite (standard library only).

    python3 tests/stability/scenes/generate.py      (from anywhere; paths follow this file)

Writes, beside this file,
    piano_doorway.yaml   the real piano (robots/piano/piano.obj) through a doorway
                         4.0 mm wider than the piano's least width
    peg.obj              a 24-sided peg, 20 mm across its corners, 80 mm long
    peg_in_hole.yaml     the peg into a square hole 0.6 mm wider than the peg

Both obstacles are a plate with a rectangular hole, made of four boxes. Every figure
stated in the scenes is computed here from the meshes (the piano's least width over all
of its vertices, at the orientation exactly as the scene writes it), and asserted: the
clearances, start and goal clear of the plate, and the straight line from start to goal
through it. These are stability fixtures, not shipped scenes (scenes/*.yaml): the
shipped-scene suites ask for large meshes and plan every scene there.
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
sys.path.insert(0, os.path.join(ROOT, "robots", "piano"))

import geom  # noqa: E402
import passage as ps  # noqa: E402

DOOR_SPARE = 0.004       # doorway width over the piano's least width (total, m)
WALL_T = 0.15            # wall thickness
PEG_R, PEG_L, PEG_SIDES = 0.010, 0.080, 24
HOLE_SPARE = 0.0006      # hole side over the peg's diameter (total, m)
PLATE_T = 0.030


def read_vertices(path):
    out = []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                out.append(tuple(float(x) for x in line.split()[1:4]))
    return out


def num(x, digits=7):
    s = ("%.*f" % (digits, x)).rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def vec(v, digits=7):
    return "[%s]" % ", ".join(num(x, digits) for x in v)


def rounded_quat(q):
    q = geom.quat_normalize(q)
    return tuple(float("%.7f" % x) for x in q)


def frame_boxes(hole_w, hole_h, thick, outer_w, outer_h):
    """A plate in the plane y = 0 (x across, z up), `thick` along y, with a centred
    hole_w x hole_h hole: four boxes as (size, centre)."""
    side_w = (outer_w - hole_w) / 2
    cap_h = (outer_h - hole_h) / 2
    sx = hole_w / 2 + side_w / 2
    cz = hole_h / 2 + cap_h / 2
    return [((side_w, thick, outer_h), (-sx, 0, 0)), ((side_w, thick, outer_h), (sx, 0, 0)),
            ((hole_w, thick, cap_h), (0, 0, cz)), ((hole_w, thick, cap_h), (0, 0, -cz))]


def inside_a_box(p, boxes):
    """Whether point p lies strictly inside one of the boxes (a vertex-inside test:
    enough to show that the straight line collides)."""
    return any(all(abs(p[i] - c[i]) < size[i] / 2 for i in range(3)) for size, c in boxes)


def any_vertex_inside(points, boxes):
    return any(inside_a_box(p, boxes) for p in points)


def aabb(points):
    return ([min(p[i] for p in points) for i in range(3)],
            [max(p[i] for p in points) for i in range(3)])


def clear_of_boxes(points, boxes, margin):
    """Bounding box of the points at least `margin` from every box along some axis."""
    lo, hi = aabb(points)
    for size, c in boxes:
        gap = max(max(c[i] - size[i] / 2 - hi[i], lo[i] - (c[i] + size[i] / 2)) for i in range(3))
        if gap < margin:
            return False
    return True


def straight_line_hits(points, start, goal, boxes, n=400):
    for k in range(1, n):
        t = k / n
        p = tuple(start[0][i] + t * (goal[0][i] - start[0][i]) for i in range(3))
        q = geom.slerp(start[1], goal[1], t)
        if any_vertex_inside(geom.transform_points(points, p, q), boxes):
            return t
    raise AssertionError("the straight line from start to goal is free")


def obstacles_yaml(boxes):
    return "".join("  - box: %s\n    pose: {xyz: %s}\n" % (vec(s), vec(c)) for s, c in boxes)


def write(name, text):
    with open(os.path.join(HERE, name), "w") as f:
        f.write(text)


def piano_doorway():
    V = read_vertices(os.path.join(ROOT, "robots", "piano", "piano.obj"))
    w, a = ps.min_width_direction(ps.support_points(V))
    a, b, c = ps.passage_frame(a)
    q = rounded_quat(ps.frame_quat(a, b, c))
    # Everything below from the orientation as written: world x across the doorway.
    P = geom.transform_points(V, (0, 0, 0), q)
    lo, hi = aabb(P)
    width, height = hi[0] - lo[0], hi[2] - lo[2]
    assert abs(width - ps.width(V, a)) < 1e-6, (width, ps.width(V, a))
    door_w = round(width + DOOR_SPARE, 6)
    door_h = round(height + 0.20, 2)
    spare_w = door_w - width
    # Centred in the doorway at the origin: base position -(centre of the extents).
    cx, cz = (lo[0] + hi[0]) / 2, (lo[2] + hi[2]) / 2
    reach = max(math.sqrt(sum(x * x for x in v)) for v in V)
    off = 0.05     # start and goal this far to either side of the doorway's centre
    gap = 0.05     # start and goal this far in front of / behind the wall
    start = ((round(-cx - off, 4), round(-WALL_T / 2 - gap - hi[1], 4), round(-cz, 4)), q)
    goal = ((round(-cx + off, 4), round(WALL_T / 2 + gap - lo[1], 4), round(-cz, 4)), q)
    bmin = (round(-cx - 0.25, 3), round(start[0][1] - 0.3, 3), round(-cz - 0.15, 3))
    bmax = (round(-cx + 0.25, 3), round(goal[0][1] + 0.3, 3), round(-cz + 0.15, 3))
    # The wall reaches past anything the piano can touch, so the doorway is the only way.
    outer_w = math.ceil(20 * (max(-bmin[0], bmax[0]) + reach + 0.05)) / 10
    outer_h = math.ceil(20 * (max(-bmin[2], bmax[2]) + reach + 0.05)) / 10
    boxes = frame_boxes(door_w, door_h, WALL_T, outer_w, outer_h)
    for pose in (start, goal):
        assert clear_of_boxes(geom.transform_points(V, pose[0], pose[1]), boxes, gap - 1e-4)
    t = straight_line_hits(V, start, goal, boxes)
    corners = [(x, z) for x in (bmin[0], bmax[0]) for z in (bmin[2], bmax[2])]
    assert all(abs(x) + reach < outer_w / 2 and abs(z) + reach < outer_h / 2 for x, z in corners)
    diag = math.sqrt(outer_w ** 2 + (bmax[1] - bmin[1]) ** 2 + outer_h ** 2)
    delta = 1e-5 * diag
    narrow = (
        "The doorway is %.4f m wide (x) and %.2f m high (z) in a %.2f m wall. Lying on its side "
        "in its least-width orientation (the scene's start and goal orientation; least-width "
        "direction (%.4f, %.4f, %.4f) in the piano's frame, along world x) the piano is "
        "%.4f m wide and %.3f m high: %.1f mm of width to spare (%.1f mm a side when "
        "centred) and %.0f mm of height. The tolerance band delta (1e-5 of the %.2f m scene "
        "diagonal) is %.0f um, %.0f times less than the clearance a side."
        % (door_w, door_h, WALL_T, a[0], a[1], a[2], width, height, 1000 * spare_w,
           500 * spare_w, 1000 * (door_h - height), diag, 1e6 * delta,
           0.5 * spare_w / delta))
    text = (
        "# Written by tests/stability/scenes/generate.py; do not edit.\n"
        "name: piano_doorway\ndescription: >\n%s\nnarrowest_passage: >\n%s\n\n"
        "robot:\n  mesh: ../../../robots/piano/piano.obj\n\nobstacles:\n%s\n"
        "bounds:\n  min: %s\n  max: %s\n\n"
        "start:\n  base: {xyz: %s, quat_wxyz: %s}\n"
        "goal:\n  base: {xyz: %s, quat_wxyz: %s}\n\n"
        "# Edges sampled so that no piano point moves more than 2 mm between samples (the\n"
        "# clearance a side; the path's final check, at a tenth of that, catches what they\n"
        "# miss); rotations drawn within about 0.15 deg of the start's and goal's (the\n"
        "# least-width orientation: only rotations within a fraction of a degree of it fit\n"
        "# the doorway, which uniform rotations almost never are); a fifth of the attempts\n"
        "# by the bridge test;\n"
        "# little shortcutting (each shortcut through the doorway costs thousands of checks).\n"
        "planner:\n  max_displacement: 0.002\n  shortcut: {rounds: 2, candidates: 64}\n  distance_weights: {rotation: %.2f}\n"
        "  sampler: {rotation_spread: 0.002, bridge_fraction: 0.2, bridge_sigma: 0.02}\n"
        % (ps_wrap("The real piano (robots/piano/piano.obj), lying on its side in its "
                   "least-width orientation, through a doorway in a wall that only just "
                   "takes it. Start and goal stand %.0f cm in front of and behind the wall, "
                   "%.0f cm to either side of the doorway's centre, so the straight line "
                   "between them runs into the door jambs (first at %.0f%% of the way)."
                   % (100 * gap, 100 * off, 100 * t)),
           ps_wrap(narrow), obstacles_yaml(boxes), vec(bmin, 4), vec(bmax, 4),
           vec(start[0], 4), vec(q), vec(goal[0], 4), vec(q), reach))
    write("piano_doorway.yaml", text)
    print("piano_doorway: least width %.6f m, doorway %.6f m: %.3f mm total clearance; "
          "height %.4f m in %.2f m; delta %.1f um; straight line collides at t = %.3f"
          % (width, door_w, 1000 * spare_w, height, door_h, 1e6 * delta, t))


def peg_in_hole():
    # The peg: a 24-sided prism along z, centred, its corners on a circle of radius PEG_R
    # (one on the x axis), so its extent along any horizontal direction is at most PEG_R.
    n = PEG_SIDES
    ring = [(PEG_R * math.cos(2 * math.pi * k / n), PEG_R * math.sin(2 * math.pi * k / n))
            for k in range(n)]
    verts = [(x, y, -PEG_L / 2) for x, y in ring] + [(x, y, PEG_L / 2) for x, y in ring]
    faces = []
    for k in range(n):
        k1 = (k + 1) % n
        faces += [(k, k1, n + k1), (k, n + k1, n + k)]
    for k in range(1, n - 1):
        faces += [(0, k + 1, k), (n, n + k, n + k + 1)]
    lines = ["# peg.obj: a %d-sided prism peg, %.0f mm across its corners, %.0f mm long along z,"
             % (n, 2000 * PEG_R, 1000 * PEG_L),
             "# centred at the origin; written by tests/stability/scenes/generate.py."]
    lines += ["v %s %s %s" % tuple(num(x, 9) for x in v) for v in verts]
    lines += ["f %d %d %d" % (f[0] + 1, f[1] + 1, f[2] + 1) for f in faces]
    write("peg.obj", "\n".join(lines) + "\n")

    hole = round(2 * PEG_R + HOLE_SPARE, 6)
    spare = hole - 2 * PEG_R
    # The plate lies in z (the peg goes down), so boxes are turned: x across, y across.
    reach = math.sqrt(PEG_R ** 2 + (PEG_L / 2) ** 2)
    bmin, bmax = (-0.015, -0.015, -0.01), (0.015, 0.015, 0.1)
    outer = math.ceil(2 * (0.015 + reach + 0.01) * 100) / 100
    boxes = [((s[0], s[2], s[1]), (c[0], c[2], c[1]))
             for s, c in frame_boxes(hole, hole, PLATE_T, outer, outer)]
    start = ((0.012, 0.0, 0.085), (1.0, 0.0, 0.0, 0.0))
    goal = ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0))
    for pose in (start, goal):
        pts = geom.transform_points(verts, pose[0], pose[1])
        if pose is start:
            assert clear_of_boxes(pts, boxes, 0.005)
        else:
            # In the hole: clear of the four boxes by the spare a side, across x and y.
            lo, hi = aabb(pts)
            assert hi[0] <= hole / 2 and lo[0] >= -hole / 2 and hi[1] <= hole / 2
    t = straight_line_hits(verts, start, goal, boxes)
    diag = math.sqrt((outer) ** 2 * 2 + (bmax[2] - min(bmin[2], -PLATE_T / 2)) ** 2)
    delta = 1e-5 * diag
    tol = spare / PLATE_T
    narrow = (
        "The hole is %.4f m square through a %.3f m plate; the peg is %.4f m across its "
        "corners (at most that wide in any direction across its axis): %.2f mm to spare "
        "(%.2f mm a side when centred), and upright it may lean at most about %.1f deg in the "
        "hole. The tolerance band delta (1e-5 of the %.3f m scene diagonal) is %.1f um, %.0f "
        "times less than the clearance a side."
        % (hole, PLATE_T, 2 * PEG_R, 1000 * spare, 500 * spare, math.degrees(tol), diag,
           1e6 * delta, 0.5 * spare / delta))
    text = (
        "# Written by tests/stability/scenes/generate.py; do not edit.\n"
        "name: peg_in_hole\ndescription: >\n%s\nnarrowest_passage: >\n%s\n\n"
        "robot:\n  mesh: peg.obj\n\nobstacles:\n%s\n"
        "bounds:\n  min: %s\n  max: %s\n\n"
        "start:\n  base: {xyz: %s, quat_wxyz: %s}\n"
        "goal:\n  base: {xyz: %s, quat_wxyz: %s}\n\n"
        "# Edges sampled so that no peg point moves more than 0.15 mm between samples (half\n"
        "# the clearance a side); rotations drawn within about 0.25 deg of the start's and\n"
        "# goal's, and nine in ten attempts by the bridge test, which finds the hole.\n"
        "planner:\n  max_displacement: 0.00015\n  distance_weights: {rotation: 0.3}\n"
        "  sampler: {rotation_spread: 0.003, bridge_fraction: 0.9, bridge_sigma: 0.002}\n"
        % (ps_wrap("A 24-sided peg (a rigid robot, %d triangles) is put into a square hole "
                   "through a plate, from %.0f mm to the side above it, to its goal half way "
                   "through the plate, both upright; the straight line between "
                   "them runs into the plate (first at %.0f%% of the way)."
                   % (len(faces), 1000 * start[0][0], 100 * t)),
           ps_wrap(narrow), obstacles_yaml(boxes), vec(bmin), vec(bmax), vec(start[0]),
           vec(start[1]), vec(goal[0]), vec(goal[1])))
    write("peg_in_hole.yaml", text)
    print("peg_in_hole: peg %.4f m, hole %.4f m: %.3f mm total clearance; plate %.3f m; "
          "delta %.2f um; straight line collides at t = %.3f"
          % (2 * PEG_R, hole, 1000 * spare, PLATE_T, 1e6 * delta, t))


def ps_wrap(text, width=88, indent="  "):
    words, lines, line = text.split(), [], indent
    for w in words:
        if len(line) + len(w) + 1 > width and line.strip():
            lines.append(line.rstrip())
            line = indent
        line += w + " "
    lines.append(line.rstrip())
    return "\n".join(lines)


if __name__ == "__main__":
    piano_doorway()
    peg_in_hole()
