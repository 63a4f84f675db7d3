#!/usr/bin/env python3
"""Generates gplanner's own PR2 model and its two scenes.

Writes (paths relative to the repository root):
  robots/pr2/pr2.urdf, robots/pr2/pr2.srdf, robots/pr2/meshes/*.stl
  scenes/environments/pr2_table_shelf.obj
  scenes/pr2_reach.yaml, scenes/pr2_base_arm.yaml

The kinematics (joint names, link names, joint origins, axes, limits, mimic joints) are
the Willow Garage PR2's published figures, read off the expanded PR2 URDF
(moveit_resources_pr2_description/urdf/robot.xml). The collision meshes are our own,
built here from boxes, rounded prisms, cylinders and ellipsoids sized like the PR2's
parts; every mesh is a union of closed convex pieces. Simplifications against the real
robot: the casters are fixed links (wheels folded into the caster mesh), the gripper
motor slider/screw, the r/l_gripper_joint and the sensor frames are left out; the
gripper is driven by *_gripper_l_finger_joint, the other three finger joints mimic it
as on the real PR2.

Python 3 standard library only; deterministic. Run from anywhere:
    python3 robots/pr2/generate.py
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "robots"))

import meshlib  # noqa: E402
from meshlib import Mesh  # noqa: E402

PI = math.pi
MESH_DIR = os.path.join(HERE, "meshes")
PACKAGE = "package://gplanner_robots/pr2/meshes/"

# ---------------------------------------------------------------------------------------
# Shape helpers (each returns one closed convex piece)
# ---------------------------------------------------------------------------------------


def _ccw(poly):
    return list(poly) if meshlib.polygon_area(poly) > 0 else list(reversed(poly))


def rrect(x0, x1, y0, y1, r, seg=6):
    """Rectangle [x0,x1]x[y0,y1] with rounded corners; r is one radius or four
    (corners +x+y, -x+y, -x-y, +x-y). CCW polygon."""
    rs = r if isinstance(r, (list, tuple)) else (r, r, r, r)
    corners = [(x1 - rs[0], y1 - rs[0], 0.0), (x0 + rs[1], y1 - rs[1], 0.5 * PI),
               (x0 + rs[2], y0 + rs[2], PI), (x1 - rs[3], y0 + rs[3], 1.5 * PI)]
    pts = []
    for (cx, cy, a0), rad in zip(corners, rs):
        for k in range(seg + 1):
            a = a0 + 0.5 * PI * k / seg
            pts.append((cx + rad * math.cos(a), cy + rad * math.sin(a)))
    return pts


def arc(cx, cy, r, a0, a1, seg):
    return [(cx + r * math.cos(a0 + (a1 - a0) * k / seg), cy + r * math.sin(a0 + (a1 - a0) * k / seg))
            for k in range(seg + 1)]


def prism(poly, axis, lo, hi):
    """Extrudes a convex polygon along `axis` from lo to hi. The polygon's two
    coordinates are (x, y) for axis z, (y, z) for axis x and (x, z) for axis y."""
    if axis == "y":
        poly = [(p[1], p[0]) for p in poly]  # (z, x): cyclic with y
    m = meshlib.extrude(_ccw(poly), hi - lo, z0=lo)
    if axis == "z":
        return m
    if axis == "x":  # (a, b, h) -> (h, a, b)
        return Mesh([(v[2], v[0], v[1]) for v in m.vertices], m.triangles)
    return Mesh([(v[1], v[2], v[0]) for v in m.vertices], m.triangles)  # (z, x, y) -> ...


def cyl(radius, lo, hi, axis="z", at=(0.0, 0.0), seg=24, radius_top=None):
    """Cylinder (frustum) along an axis from lo to hi; `at` is the position in the two
    other coordinates ((x, y) for z, (y, z) for x, (x, z) for y)."""
    c = 0.5 * (lo + hi)
    center = {"z": (at[0], at[1], c), "x": (c, at[0], at[1]), "y": (at[0], c, at[1])}[axis]
    return meshlib.cylinder(radius, hi - lo, segments=seg, center=center, axis=axis,
                            radius_top=radius_top)


def cyl_y(radius, lo, hi, at=(0.0, 0.0), seg=24):
    """Cylinder along y; meshlib's 'y' orientation points the radius_top end to -y,
    which does not matter for a straight cylinder."""
    return cyl(radius, lo, hi, axis="y", at=at, seg=seg)


def segment_box(p0, p1, width, zlo, zhi):
    """A bar in the xy-plane from p0 to p1, `width` wide, z from zlo to zhi."""
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    ln = math.hypot(dx, dy)
    nx, ny = -dy / ln * width / 2, dx / ln * width / 2
    poly = [(p0[0] - nx, p0[1] - ny), (p1[0] - nx, p1[1] - ny),
            (p1[0] + nx, p1[1] + ny), (p0[0] + nx, p0[1] + ny)]
    return prism(poly, "z", zlo, zhi)


# ---------------------------------------------------------------------------------------
# Link meshes (in the link frames of the PR2 URDF)
# ---------------------------------------------------------------------------------------


def base_mesh():
    return meshlib.merge(
        # chassis block and the bumper band around it (z = 0 is the chassis bottom,
        # 0.051 m above the floor)
        prism(rrect(-0.32, 0.32, -0.32, 0.32, 0.06, 24), "z", 0.0, 0.225),
        prism(rrect(-0.334, 0.334, -0.334, 0.334, 0.075, 24), "z", 0.025, 0.105),
        # top deck
        prism(rrect(-0.30, 0.30, -0.30, 0.30, 0.05, 16), "z", 0.225, 0.235),
        # base laser (Hokuyo) housing at the front, base_laser_link at (0.275, 0, 0.252)
        prism(rrect(0.16, 0.26, -0.046, 0.046, 0.012, 6), "z", 0.235, 0.29),
        cyl(0.03, 0.235, 0.29, "z", (0.275, 0.0), seg=48),
        # spine housing at the back (the torso column slides in it)
        prism(rrect(-0.33, -0.19, -0.24, 0.24, 0.03, 16), "z", 0.235, 0.37),
        prism(rrect(-0.33, -0.255, -0.21, 0.21, 0.025, 16), "z", 0.37, 0.656),
    )


def caster_mesh():
    # caster_rotation_link frame: the wheel axle (wheels 0.0748 m radius)
    return meshlib.merge(
        prism(rrect(-0.10, 0.10, -0.085, 0.085, 0.04, 10), "z", 0.128, 0.168),
        prism(rrect(-0.03, 0.03, -0.085, 0.085, 0.01, 4), "z", 0.09, 0.13),
        # fork plates outside the wheels and the axle
        prism(rrect(-0.028, 0.028, -0.02, 0.10, 0.012, 4), "y", 0.068, 0.082),
        prism(rrect(-0.028, 0.028, -0.02, 0.10, 0.012, 4), "y", -0.082, -0.068),
        cyl_y(0.014, -0.082, 0.082, seg=16),
        # the two wheels (fl_caster_l/r_wheel_link of the real PR2: y = +-0.049)
        cyl_y(0.0748, 0.032, 0.066, seg=96),
        cyl_y(0.0748, -0.066, -0.032, seg=96),
    )


def torso_mesh():
    return meshlib.merge(
        # column that slides in the base's spine housing
        prism(rrect(-0.285, -0.19, -0.17, 0.17, 0.02, 12), "z", -0.50, 0.16),
        # upper back block
        prism(rrect(-0.285, -0.20, -0.205, 0.205, 0.025, 12), "z", -0.045, 0.16),
        # shoulder cover above the shoulders, head on top of it
        prism(rrect(-0.285, 0.03, -0.26, 0.26, (0.12, 0.03, 0.03, 0.12), 32), "z", 0.16, 0.30),
    )


def head_pan_mesh():
    bracket = []
    for s in (1, -1):
        ylo, yhi = sorted((s * 0.13, s * 0.158))
        bracket.append(prism(rrect(0.02, 0.116, -0.05, 0.0, 0.008, 4), "y", ylo, yhi))
        bracket.append(cyl_y(0.048, ylo, yhi, at=(0.068, 0.0), seg=48))
    return meshlib.merge(
        cyl(0.11, -0.066, -0.036, "z", seg=96),
        cyl(0.06, -0.08, -0.066, "z", seg=48),
        *bracket)


def head_tilt_mesh():
    lenses = [cyl(0.013, 0.075, 0.092, "x", (y, 0.115), seg=32) for y in (0.06, 0.03, -0.03, -0.06)]
    return meshlib.merge(
        prism(rrect(-0.18, 0.045, -0.124, 0.124, 0.02, 16), "z", 0.06, 0.155),
        prism(rrect(-0.124, 0.124, 0.05, 0.15, 0.01, 4), "x", 0.04, 0.075),   # sensor plate
        *lenses,
        cyl(0.018, 0.075, 0.095, "x", (-0.105, 0.119), seg=40),              # prosilica
        prism(rrect(0.095, 0.123, 0.10, 0.138, 0.004, 2), "x", 0.075, 0.09),  # projector
        cyl(0.012, 0.15, 0.275, "z", (-0.147, 0.0), seg=16),                # kinect post
        prism(rrect(-0.18, -0.115, -0.14, 0.14, 0.012, 6), "z", 0.27, 0.31),  # kinect
    )


def laser_tilt_mesh():
    return meshlib.merge(
        prism(rrect(-0.045, 0.03, 0.06, 0.078, 0.004, 2), "z", -0.055, 0.02),
        prism(rrect(-0.045, 0.03, -0.078, -0.06, 0.004, 2), "z", -0.055, 0.02),
        prism(rrect(-0.045, -0.02, -0.06, 0.06, 0.004, 2), "z", -0.055, -0.036),
        prism(rrect(-0.025, 0.025, -0.025, 0.025, 0.006, 4), "z", -0.035, 0.018),  # Hokuyo
        cyl(0.021, 0.018, 0.06, "z", seg=32),                                 # scan window
    )


def shoulder_pan_mesh():
    # the pan drum around the pan axis, the counterbalance housing hanging below and
    # behind it (leaving room below the lift axis for the upper arm when it points down),
    # and the clevis plates carrying the shoulder lift axis at x = 0.1
    plates = [cyl_y(0.125, lo, hi, at=(0.1, 0.0), seg=64) for lo, hi in ((0.08, 0.115), (-0.115, -0.08))]
    return meshlib.merge(
        cyl(0.125, -0.10, 0.13, "z", seg=128),
        cyl(0.10, -0.36, -0.10, "z", (-0.065, 0.0), seg=96),
        *plates)


def shoulder_lift_mesh():
    return meshlib.sphere(0.12, rings=28, segments=56, scale=(1.0, 0.6, 1.0))


def upper_arm_roll_mesh():
    return cyl(0.072, 0.119, 0.14, "x", seg=64)


def upper_arm_mesh():
    # clevis plates around the elbow flex axis at x = 0.4
    prof = arc(0.40, 0.0, 0.08, -0.5 * PI, 0.5 * PI, 32) + [(0.31, 0.07), (0.31, -0.07)]
    plates = [prism(prof, "y", lo, hi) for lo, hi in ((0.024, 0.066), (-0.066, -0.024))]
    return meshlib.merge(
        cyl(0.078, 0.138, 0.32, "x", seg=128, radius_top=0.062),
        prism(rrect(-0.066, 0.066, -0.07, 0.07, 0.02, 12), "x", 0.30, 0.335),
        *plates)


def elbow_flex_mesh():
    return meshlib.merge(
        cyl_y(0.078, -0.018, 0.018, seg=64),
        cyl(0.045, 0.04, 0.092, "x", seg=48),
    )


def forearm_roll_mesh():
    return cyl(0.041, 0.092, 0.107, "x", seg=64)


def forearm_mesh():
    # body, then a lower section in front of the wrist (room for the hand folded back),
    # and the clevis plates around the wrist flex axis at x = 0.321
    prof = arc(0.321, 0.0, 0.036, -0.5 * PI, 0.5 * PI, 16) + [(0.295, 0.036), (0.295, -0.036)]
    plates = [prism(prof, "y", lo, hi) for lo, hi in ((0.03, 0.056), (-0.056, -0.03))]
    return meshlib.merge(
        prism(rrect(-0.06, 0.06, -0.05, 0.05, 0.025, 16), "x", 0.10, 0.245),
        prism(rrect(-0.058, 0.058, -0.05, 0.01, (0.008, 0.008, 0.025, 0.025), 16), "x", 0.235, 0.30),
        prism(rrect(-0.026, 0.026, 0.045, 0.064, 0.006, 4), "x", 0.12, 0.16),  # forearm camera
        *plates)


def wrist_flex_mesh():
    return cyl_y(0.036, -0.024, 0.024, seg=64)


def wrist_roll_mesh():
    return cyl(0.019, 0.024, 0.042, "x", seg=48)


def palm_mesh():
    return meshlib.merge(
        cyl(0.019, 0.028, 0.052, "x", seg=48),
        prism(rrect(0.05, 0.116, -0.05, 0.05, 0.014, 12), "z", -0.024, 0.024),
        prism(rrect(-0.034, 0.034, -0.02, 0.02, 0.008, 6), "x", 0.112, 0.126),
    )


def finger_mesh():
    """Left finger in r/l_gripper_l_finger_link; the right finger uses it turned by pi
    about x (as the real PR2 does)."""
    knee = (0.045, 0.036)
    tip = (0.09137, 0.00495)  # the finger tip joint
    return meshlib.merge(
        cyl(0.011, -0.026, 0.026, "z", seg=48),
        segment_box((0.0, 0.0), knee, 0.016, -0.024, 0.024),
        cyl(0.009, -0.02, 0.02, "z", knee, seg=48),
        segment_box(knee, tip, 0.014, -0.014, 0.014),
        cyl(0.008, -0.013, 0.013, "z", tip, seg=48),
    )


def finger_tip_mesh():
    pad = [(-0.014, 0.002), (0.004, -0.0135), (0.032, -0.0135), (0.032, 0.004),
           (0.012, 0.018), (-0.014, 0.018)]
    return meshlib.merge(
        prism(pad, "z", -0.011, 0.011),
        cyl(0.008, -0.011, 0.011, "z", seg=48),
    )


MESHES = {
    "base.stl": base_mesh,
    "caster.stl": caster_mesh,
    "torso_lift.stl": torso_mesh,
    "head_pan.stl": head_pan_mesh,
    "head_tilt.stl": head_tilt_mesh,
    "tilting_laser.stl": laser_tilt_mesh,
    "shoulder_pan.stl": shoulder_pan_mesh,
    "shoulder_lift.stl": shoulder_lift_mesh,
    "upper_arm_roll.stl": upper_arm_roll_mesh,
    "upper_arm.stl": upper_arm_mesh,
    "elbow_flex.stl": elbow_flex_mesh,
    "forearm_roll.stl": forearm_roll_mesh,
    "forearm.stl": forearm_mesh,
    "wrist_flex.stl": wrist_flex_mesh,
    "wrist_roll.stl": wrist_roll_mesh,
    "gripper_palm.stl": palm_mesh,
    "finger.stl": finger_mesh,
    "finger_tip.stl": finger_tip_mesh,
}

# ---------------------------------------------------------------------------------------
# Kinematic tree: the PR2's joints (names, origins, axes, limits: the real figures)
# ---------------------------------------------------------------------------------------

# link -> (collision, mass). collision: ("mesh", file, rpy) or ("box", size, xyz) or None
LINKS = {}
# (name, type, parent, child, xyz, rpy, axis, limit, mimic)
JOINTS = []


def link(name, collision, mass):
    LINKS[name] = (collision, mass)


def joint(name, jtype, parent, child, xyz, rpy=(0, 0, 0), axis=None, limit=None, mimic=None):
    JOINTS.append((name, jtype, parent, child, xyz, rpy, axis, limit, mimic))


def build_tree():
    link("base_footprint", None, 1.0)
    link("base_link", ("mesh", "base.stl", (0, 0, 0)), 116.0)
    joint("base_footprint_joint", "fixed", "base_footprint", "base_link", (0, 0, 0.051))
    link("base_bellow_link", ("box", (0.05, 0.37, 0.3), (0, 0, 0)), 1.0)
    joint("base_bellow_joint", "fixed", "base_link", "base_bellow_link", (-0.29, 0, 0.8))
    for c, x, y in (("fl", 1, 1), ("fr", 1, -1), ("bl", -1, 1), ("br", -1, -1)):
        link(c + "_caster_rotation_link", ("mesh", "caster.stl", (0, 0, 0)), 3.473082 + 2 * 0.44036)
        joint(c + "_caster_rotation_joint", "fixed", "base_link", c + "_caster_rotation_link",
              (0.2246 * x, 0.2246 * y, 0.0282))
    link("torso_lift_link", ("mesh", "torso_lift.stl", (0, 0, 0)), 36.248046)
    joint("torso_lift_joint", "prismatic", "base_link", "torso_lift_link", (-0.05, 0, 0.739675),
          axis=(0, 0, 1), limit=(0.0, 0.33, 10000, 0.013))
    link("head_pan_link", ("mesh", "head_pan.stl", (0, 0, 0)), 6.339)
    joint("head_pan_joint", "revolute", "torso_lift_link", "head_pan_link", (-0.01707, 0, 0.38145),
          axis=(0, 0, 1), limit=(-3.007, 3.007, 2.645, 6))
    link("head_tilt_link", ("mesh", "head_tilt.stl", (0, 0, 0)), 4.479)
    joint("head_tilt_joint", "revolute", "head_pan_link", "head_tilt_link", (0.068, 0, 0),
          axis=(0, 1, 0), limit=(-0.471238, 1.39626, 18, 5))
    link("laser_tilt_mount_link", ("mesh", "tilting_laser.stl", (0, 0, 0)), 0.591)
    joint("laser_tilt_mount_joint", "revolute", "torso_lift_link", "laser_tilt_mount_link",
          (0.09893, 0, 0.227), axis=(0, 1, 0), limit=(-0.7854, 1.48353, 0.65, 10.0))
    for s, sign in (("r", -1), ("l", 1)):
        arm(s, sign)


def arm(s, sign):
    p = s + "_"
    pan = (-2.2853981634, 0.714601836603) if s == "r" else (-0.714601836603, 2.2853981634)
    roll = (-3.9, 0.8) if s == "r" else (-0.8, 3.9)
    link(p + "shoulder_pan_link", ("mesh", "shoulder_pan.stl", (0, 0, 0)), 25.799322)
    joint(p + "shoulder_pan_joint", "revolute", "torso_lift_link", p + "shoulder_pan_link",
          (0, 0.188 * sign, 0), axis=(0, 0, 1), limit=pan + (30, 2.088))
    link(p + "shoulder_lift_link", ("mesh", "shoulder_lift.stl", (0, 0, 0)), 2.74988)
    joint(p + "shoulder_lift_joint", "revolute", p + "shoulder_pan_link", p + "shoulder_lift_link",
          (0.1, 0, 0), axis=(0, 1, 0), limit=(-0.5236, 1.3963, 30, 2.082))
    link(p + "upper_arm_roll_link", ("mesh", "upper_arm_roll.stl", (0, 0, 0)), 0.1)
    joint(p + "upper_arm_roll_joint", "revolute", p + "shoulder_lift_link", p + "upper_arm_roll_link",
          (0, 0, 0), axis=(1, 0, 0), limit=roll + (30, 3.27))
    link(p + "upper_arm_link", ("mesh", "upper_arm.stl", (0, 0, 0)), 6.01769)
    joint(p + "upper_arm_joint", "fixed", p + "upper_arm_roll_link", p + "upper_arm_link", (0, 0, 0))
    link(p + "elbow_flex_link", ("mesh", "elbow_flex.stl", (0, 0, 0)), 1.90327)
    joint(p + "elbow_flex_joint", "revolute", p + "upper_arm_link", p + "elbow_flex_link",
          (0.4, 0, 0), axis=(0, 1, 0), limit=(-2.3213, 0.0, 30, 3.3))
    link(p + "forearm_roll_link", ("mesh", "forearm_roll.stl", (0, 0, 0)), 0.1)
    joint(p + "forearm_roll_joint", "continuous", p + "elbow_flex_link", p + "forearm_roll_link",
          (0, 0, 0), axis=(1, 0, 0), limit=(None, None, 30, 3.6))
    link(p + "forearm_link", ("mesh", "forearm.stl", (0, 0, 0)), 2.57968)
    joint(p + "forearm_joint", "fixed", p + "forearm_roll_link", p + "forearm_link", (0, 0, 0))
    link(p + "wrist_flex_link", ("mesh", "wrist_flex.stl", (0, 0, 0)), 0.61402)
    joint(p + "wrist_flex_joint", "revolute", p + "forearm_link", p + "wrist_flex_link",
          (0.321, 0, 0), axis=(0, 1, 0), limit=(-2.18, 0.0, 10, 3.078))
    link(p + "wrist_roll_link", ("mesh", "wrist_roll.stl", (0, 0, 0)), 0.1)
    joint(p + "wrist_roll_joint", "continuous", p + "wrist_flex_link", p + "wrist_roll_link",
          (0, 0, 0), axis=(1, 0, 0), limit=(None, None, 10, 3.6))
    g = p + "gripper_"
    link(g + "palm_link", ("mesh", "gripper_palm.stl", (0, 0, 0)), 0.58007)
    joint(g + "palm_joint", "fixed", p + "wrist_roll_link", g + "palm_link", (0, 0, 0))
    link(g + "tool_frame", None, 0.0)
    joint(g + "tool_joint", "fixed", g + "palm_link", g + "tool_frame", (0.18, 0, 0))
    lim = (0.0, 0.548, 1000.0, 0.5)
    master = g + "l_finger_joint"
    link(g + "l_finger_link", ("mesh", "finger.stl", (0, 0, 0)), 0.17126)
    joint(master, "revolute", g + "palm_link", g + "l_finger_link", (0.07691, 0.01, 0),
          axis=(0, 0, 1), limit=lim)
    link(g + "r_finger_link", ("mesh", "finger.stl", (PI, 0, 0)), 0.17389)
    joint(g + "r_finger_joint", "revolute", g + "palm_link", g + "r_finger_link", (0.07691, -0.01, 0),
          axis=(0, 0, -1), limit=lim, mimic=master)
    link(g + "l_finger_tip_link", ("mesh", "finger_tip.stl", (0, 0, 0)), 0.04419)
    joint(g + "l_finger_tip_joint", "revolute", g + "l_finger_link", g + "l_finger_tip_link",
          (0.09137, 0.00495, 0), axis=(0, 0, -1), limit=lim, mimic=master)
    link(g + "r_finger_tip_link", ("mesh", "finger_tip.stl", (PI, 0, 0)), 0.04419)
    joint(g + "r_finger_tip_joint", "revolute", g + "r_finger_link", g + "r_finger_tip_link",
          (0.09137, -0.00495, 0), axis=(0, 0, 1), limit=lim, mimic=master)


# ---------------------------------------------------------------------------------------
# URDF
# ---------------------------------------------------------------------------------------


def fmt(v):
    s = "%.6f" % v
    s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def vec(v):
    return " ".join(fmt(x) for x in v)


def inertial(mass, lo, hi):
    c = [(a + b) / 2 for a, b in zip(lo, hi)]
    d = [b - a for a, b in zip(lo, hi)]
    ixx = mass * (d[1] ** 2 + d[2] ** 2) / 12
    iyy = mass * (d[0] ** 2 + d[2] ** 2) / 12
    izz = mass * (d[0] ** 2 + d[1] ** 2) / 12
    return ('    <inertial>\n      <origin xyz="%s" rpy="0 0 0"/>\n      <mass value="%s"/>\n'
            '      <inertia ixx="%s" ixy="0" ixz="0" iyy="%s" iyz="0" izz="%s"/>\n    </inertial>\n'
            % (vec(c), fmt(mass), "%.6g" % ixx, "%.6g" % iyy, "%.6g" % izz))


def write_urdf(path, mesh_bounds):
    out = ['<?xml version="1.0"?>\n',
           "<!-- Generated by robots/pr2/generate.py; do not edit. gplanner's own PR2 model:\n"
           "     the Willow Garage PR2's joint names, link names, joint origins and limits,\n"
           "     with our own collision meshes (unions of convex pieces). -->\n",
           '<robot name="pr2">\n']
    for name, (col, mass) in LINKS.items():
        out.append('  <link name="%s">\n' % name)
        if col is not None:
            if col[0] == "mesh":
                lo, hi = mesh_bounds[col[1]]
                if col[2][0]:  # turned by pi about x: y and z flip
                    lo, hi = (lo[0], -hi[1], -hi[2]), (hi[0], -lo[1], -lo[2])
                out.append(inertial(mass, lo, hi))
                geom = '<mesh filename="%s%s"/>' % (PACKAGE, col[1])
                org = '<origin xyz="0 0 0" rpy="%s"/>' % vec(col[2])
            else:
                size, xyz = col[1], col[2]
                out.append(inertial(mass, [c - s / 2 for c, s in zip(xyz, size)],
                                    [c + s / 2 for c, s in zip(xyz, size)]))
                geom = '<box size="%s"/>' % vec(size)
                org = '<origin xyz="%s" rpy="0 0 0"/>' % vec(xyz)
            for tag in ("visual", "collision"):
                out.append("    <%s>\n      %s\n      <geometry>\n        %s\n      </geometry>\n"
                           "    </%s>\n" % (tag, org, geom, tag))
        elif mass > 0:
            out.append(inertial(mass, (-0.05, -0.05, -0.05), (0.05, 0.05, 0.05)))
        out.append("  </link>\n")
    for name, jtype, parent, child, xyz, rpy, axis, limit, mimic in JOINTS:
        out.append('  <joint name="%s" type="%s">\n' % (name, jtype))
        out.append('    <parent link="%s"/>\n    <child link="%s"/>\n' % (parent, child))
        out.append('    <origin xyz="%s" rpy="%s"/>\n' % (vec(xyz), vec(rpy)))
        if axis is not None:
            out.append('    <axis xyz="%s"/>\n' % vec(axis))
        if limit is not None:
            lo, hi, effort, vel = limit
            if lo is None:
                out.append('    <limit effort="%s" velocity="%s"/>\n' % (fmt(effort), fmt(vel)))
            else:
                out.append('    <limit lower="%s" upper="%s" effort="%s" velocity="%s"/>\n'
                           % (fmt(lo), fmt(hi), fmt(effort), fmt(vel)))
        if mimic is not None:
            out.append('    <mimic joint="%s" multiplier="1" offset="0"/>\n' % mimic)
        out.append("  </joint>\n")
    out.append("</robot>\n")
    with open(path, "w") as f:
        f.write("".join(out))


# ---------------------------------------------------------------------------------------
# SRDF
# ---------------------------------------------------------------------------------------

ARM_LINKS = ["shoulder_pan_link", "shoulder_lift_link", "upper_arm_roll_link", "upper_arm_link",
             "elbow_flex_link", "forearm_roll_link", "forearm_link", "wrist_flex_link",
             "wrist_roll_link", "gripper_palm_link", "gripper_l_finger_link",
             "gripper_r_finger_link", "gripper_l_finger_tip_link", "gripper_r_finger_tip_link"]
ARM_JOINTS = ["shoulder_pan_joint", "shoulder_lift_joint", "upper_arm_roll_joint",
              "elbow_flex_joint", "forearm_roll_joint", "wrist_flex_joint", "wrist_roll_joint"]
BODY_LINKS = ["base_link", "base_bellow_link", "fl_caster_rotation_link", "fr_caster_rotation_link",
              "bl_caster_rotation_link", "br_caster_rotation_link", "torso_lift_link",
              "head_pan_link", "head_tilt_link", "laser_tilt_mount_link"]


def collision_links():
    return BODY_LINKS + ["r_" + a for a in ARM_LINKS] + ["l_" + a for a in ARM_LINKS]


# The pairs that stay checked; every other pair of collision links is disabled in the
# SRDF. Modelled on the PR2 MoveIt configuration (pr2_moveit_config/config/pr2.srdf):
# its checked pairs, mapped onto our link set, are a subset of these (robots/pr2/check.py
# verifies that when the reference is at hand), made symmetric and widened:
#   - every body link (base, bellow, casters, torso, head, tilting laser) against each
#     arm's elbow, forearm, wrist and gripper links;
#   - each shoulder pan link against its own arm's forearm, wrist and gripper links;
#   - every left-arm link against every right-arm link;
#   - within each arm, the pairs our geometry brings into contact within the joint
#     limits although the reference disables them (found by check.py --pairs, random
#     sampling, then made symmetric): the shoulder against the elbow and everything
#     beyond it, the upper arm against the forearm and everything beyond it, and the
#     forearm against the wrist roll link and the gripper (wrist flexed fully back).
# Reasons for the disabled pairs: "Adjacent" (parent/child), "Default" (in contact at
# the all-zero configuration: DEFAULT_PAIRS, mechanically touching at every pose),
# "Never" (no contact in 6,000 random configurations: check.py --pairs 6000).
S_FAR = ["forearm_link", "wrist_flex_link", "wrist_roll_link", "gripper_palm_link",
         "gripper_l_finger_link", "gripper_r_finger_link", "gripper_l_finger_tip_link",
         "gripper_r_finger_tip_link"]
G_ALL = ["gripper_palm_link", "gripper_l_finger_link", "gripper_r_finger_link",
         "gripper_l_finger_tip_link", "gripper_r_finger_tip_link"]


def checked_pairs():
    pairs = set()

    def add(a, b):
        pairs.add(tuple(sorted((a, b))))

    for s in "rl":
        for body in BODY_LINKS:
            for a in ["elbow_flex_link", "forearm_roll_link"] + S_FAR:
                add(body, s + "_" + a)
        for a in ["elbow_flex_link", "forearm_roll_link"] + S_FAR:
            add(s + "_shoulder_pan_link", s + "_" + a)
        for a in S_FAR:
            for b in ("shoulder_lift_link", "upper_arm_roll_link", "upper_arm_link"):
                add(s + "_" + b, s + "_" + a)
        add(s + "_upper_arm_link", s + "_forearm_roll_link")
        for a in ["wrist_roll_link"] + G_ALL:
            add(s + "_forearm_link", s + "_" + a)
    for a in ARM_LINKS:
        for b in ARM_LINKS:
            add("r_" + a, "l_" + b)
    return pairs


def disabled_pairs():
    """(link1, link2, reason) for every collision-link pair that is not checked."""
    links = collision_links()
    parent = {}
    for name, jtype, par, child, *_ in JOINTS:
        parent[child] = par
    checked = checked_pairs()
    out = []
    for i, a in enumerate(links):
        for b in links[i + 1:]:
            key = tuple(sorted((a, b)))
            if key in checked:
                continue
            if parent.get(a) == b or parent.get(b) == a:
                reason = "Adjacent"
            elif key in DEFAULT_PAIRS:
                reason = "Default"
            else:
                reason = "Never"
            out.append((a, b, reason))
    return out


DEFAULT_PAIRS = {("base_bellow_link", "torso_lift_link")} | {tuple(sorted(p)) for s in "rl" for p in (
    (s + "_gripper_l_finger_link", s + "_gripper_r_finger_link"),
    (s + "_gripper_palm_link", s + "_wrist_flex_link"))}


def write_srdf(path):
    out = ['<?xml version="1.0"?>\n',
           "<!-- Generated by robots/pr2/generate.py; do not edit. Groups as in the PR2 MoveIt\n"
           "     configuration. The disabled pairs are a subset of those the PR2 MoveIt\n"
           "     configuration disables (mapped onto our link set): less the pairs our geometry\n"
           "     can bring into contact (robots/pr2/check.py samples them) and a few more kept\n"
           "     checked for left/right symmetry. -->\n",
           '<robot name="pr2">\n']
    for s, side in (("l", "left"), ("r", "right")):
        out.append('  <group name="%s_arm">\n' % side)
        for j in ARM_JOINTS:
            out.append('    <joint name="%s_%s"/>\n' % (s, j))
        out.append("  </group>\n")
    out.append('  <group name="arms">\n    <group name="left_arm"/>\n    <group name="right_arm"/>\n'
               '  </group>\n')
    out.append('  <group name="torso">\n    <joint name="torso_lift_joint"/>\n  </group>\n')
    out.append('  <group name="head">\n    <joint name="head_pan_joint"/>\n'
               '    <joint name="head_tilt_joint"/>\n  </group>\n')
    out.append('  <group name="arms_and_torso">\n    <group name="arms"/>\n    <group name="torso"/>\n'
               '  </group>\n')
    for s, side in (("l", "left"), ("r", "right")):
        out.append('  <group name="%s_gripper">\n' % side)
        for a in G_ALL:
            out.append('    <link name="%s_%s"/>\n' % (s, a))
        out.append("  </group>\n")
    for s, side in (("l", "left"), ("r", "right")):
        out.append('  <group_state name="tuck_%s_arm" group="%s_arm">\n' % (side, side))
        for j, v in zip(ARM_JOINTS, TUCK[s]):
            out.append('    <joint name="%s_%s" value="%s"/>\n' % (s, j, fmt(v)))
        out.append("  </group_state>\n")
    for s, side in (("l", "left"), ("r", "right")):
        out.append('  <end_effector name="%s_eef" parent_link="%s_wrist_roll_link" group="%s_gripper"/>\n'
                   % (side, s, side))
    out.append('  <virtual_joint name="world_joint" type="planar" parent_frame="odom_combined" '
               'child_link="base_footprint"/>\n')
    for a, b, reason in disabled_pairs():
        out.append('  <disable_collisions link1="%s" link2="%s" reason="%s"/>\n' % (a, b, reason))
    out.append("</robot>\n")
    with open(path, "w") as f:
        f.write("".join(out))


# Arm tuck postures (pan, lift, upper arm roll, elbow, forearm roll, wrist flex, wrist
# roll): upper arms hanging down, forearms folded across the front of the body at two
# heights, everything inside the base's footprint. (The real PR2's tuck postures would
# put our thicker forearms into each other.)
TUCK = {
    "r": (-0.3, 1.35, -1.57, -1.75, 0.0, -1.6, 0.0),
    "l": (0.3, 1.35, 1.57, -1.0, 0.0, -1.0, 0.0),
}

# ---------------------------------------------------------------------------------------
# Environment: a table in front of the robot's start and a bookshelf to its right
# ---------------------------------------------------------------------------------------

TABLE_TOP = (0.71, 0.75)                   # z of the table top's underside and top
TABLE_X, TABLE_Y = (0.40, 1.20), (-0.80, 0.75)
LEGS = [(0.45, -0.75), (0.45, 0.70), (1.15, -0.75), (1.15, 0.70)]
SHELF_X, SHELF_Y = (-0.40, 0.36), (-1.32, -0.85)   # outer; the open side faces +y
SHELF_BOARDS = [(0.285, 0.31), (0.55, 0.575), (0.815, 0.84), (1.08, 1.105)]
SHELF_TOP = (1.345, 1.37)
WALL = 0.02


def env_parts():
    """[(name, Mesh)], each part convex."""
    parts = []

    def box(name, lo, hi, div=(1, 1, 1)):
        parts.append((name, meshlib.box_between(lo, hi, div)))

    top = prism(rrect(TABLE_X[0], TABLE_X[1], TABLE_Y[0], TABLE_Y[1], 0.03, 8), "z", *TABLE_TOP)
    parts.append(("table_top", top))
    for k, (x, y) in enumerate(LEGS):
        parts.append(("table_leg_%d" % k, cyl(0.03, 0.0, TABLE_TOP[0], "z", (x, y), seg=48)))
    box("table_apron_far", (1.14, -0.75, 0.63), (1.16, 0.70, TABLE_TOP[0]), (1, 12, 1))
    box("table_apron_right", (0.45, -0.76, 0.63), (1.15, -0.74, TABLE_TOP[0]), (6, 1, 1))
    box("table_apron_left", (0.45, 0.69, 0.63), (1.15, 0.71, TABLE_TOP[0]), (6, 1, 1))
    x0, x1 = SHELF_X
    y0, y1 = SHELF_Y
    box("shelf_side_left", (x1 - WALL, y0, 0.0), (x1, y1, SHELF_TOP[1]), (1, 4, 14))
    box("shelf_side_right", (x0, y0, 0.0), (x0 + WALL, y1, SHELF_TOP[1]), (1, 4, 14))
    box("shelf_back", (x0 + WALL, y0, 0.0), (x1 - WALL, y0 + WALL, SHELF_TOP[1]), (8, 1, 14))
    box("shelf_plinth", (x0 + WALL, y0 + WALL, 0.0), (x1 - WALL, y1, 0.10), (8, 4, 1))
    for k, (lo, hi) in enumerate(SHELF_BOARDS):
        box("shelf_board_%d" % (k + 1), (x0 + WALL, y0 + WALL, lo), (x1 - WALL, y1, hi), (8, 4, 1))
    box("shelf_top", (x0, y0, SHELF_TOP[0]), (x1, y1, SHELF_TOP[1]), (8, 4, 1))
    return parts


# ---------------------------------------------------------------------------------------
# Scenes
# ---------------------------------------------------------------------------------------

R_ARM = ["r_" + j for j in ARM_JOINTS]
L_ARM = ["l_" + j for j in ARM_JOINTS]


def arm_dict(side, values):
    return dict(zip(R_ARM if side == "r" else L_ARM, values))


# Arms stretched forward under the table top (forearm level, 0.52 m below the shoulders'
# height minus the upper arm's drop), the right hand in the shelf's fourth compartment,
# the left hand above the table.
UNDER_TABLE = (0.0, 0.75, 0.0, -0.75, 0.0, 0.0, 0.0)
R_IN_SHELF = (-1.5708, 0.2, 0.0, -0.2, 0.0, 0.0, 0.0)
L_OVER_TABLE = (0.25, 0.45, 0.0, -0.45, 0.0, 0.0, 0.0)
GOAL_TORSO = 0.25
HEAD = {"head_pan_joint": 0.0, "head_tilt_joint": 0.3, "laser_tilt_mount_joint": 0.0,
        "r_gripper_l_finger_joint": 0.0, "l_gripper_l_finger_joint": 0.0}

NARROW_SHELF = (
    "The shelf compartment the right hand reaches into: 0.24 m high (boards at z 0.84 and "
    "1.08), 0.72 m wide, 0.45 m deep, its front 0.52 m to the right of the robot's side. "
    "The forearm is 0.12 m wide and 0.114 m high (0.10 m body plus the camera bump), the "
    "palm 0.10 x 0.048 m, and 0.52 m of forearm and gripper go into the compartment: level "
    "at the goal they clear the boards by 7 cm below and 5.5 cm above.")

SCENES = {
    "pr2_reach": {
        "description": (
            "The PR2 (our own model, 15 planned DOF: torso lift and both 7-DOF arms) stands "
            "at a table with both arms stretched forward under the table top (forearms 0.13 m "
            "below its underside, between the legs). The right hand must come out from under "
            "the table and reach into a compartment of the bookshelf to the robot's right, the "
            "left hand must come out and up above the table top, and the torso rises by 0.25 m. "
            "The straight line in joint space drives both forearms up through the table top."),
        "narrowest": (
            "Getting the arms out from under the table: the table's near edge is 0.35 m in "
            "front of the shoulder lift axes and its underside 0.71 m above the floor, below "
            "the shoulders (0.79 m at torso 0), while forearm plus gripper are 0.52 m long: "
            "each arm must pull its hand back under the table top (upper arm down, elbow and "
            "wrist folded, or the forearm swung sideways) before it can rise. " + NARROW_SHELF),
        "base": "fixed",
        "planned": ["torso_lift_joint"] + R_ARM + L_ARM,
        "fixed": dict(HEAD),
        "start": {"torso_lift_joint": 0.0, **arm_dict("r", UNDER_TABLE), **arm_dict("l", UNDER_TABLE)},
        "goal": {"torso_lift_joint": GOAL_TORSO, **arm_dict("r", R_IN_SHELF),
                 **arm_dict("l", L_OVER_TABLE)},
        "start_base": (0.0, 0.0, 0.0),
        "goal_base": (0.0, 0.0, 0.0),
        # Uniform milestones with k = 15 rarely connect the arms' way out from under the
        # table (lazy PRM on the GPU solved 5 of 10 seeds in 60 s): bridge-test milestones
        # fill that slot and k = 30 joins them (10 of 10 seeds, median 4 s; bench/history/issue4_planning.md).
        "planner": ["  roadmap: {neighbors: 30}",
                    "  sampler: {bridge_fraction: 0.5, bridge_sigma: 0.2}"],
    },
    "pr2_base_arm": {
        "description": (
            "The PR2 (our own model on a planar base, x y theta, plus the 7 right-arm joints: "
            "10 DOF; torso at 0.25 m, left arm tucked) starts on the far side of the table "
            "facing it, right arm tucked. It must drive around the table to the bookshelf's "
            "corner and reach its right hand into a shelf compartment. The straight line "
            "drives the robot through the table (its top is at shoulder and torso height)."),
        "narrowest": (
            "The goal pose stands the robot in the corner between the table (near edge 0.07 m "
            "in front of the base) and the bookshelf (0.52 m to its right), reachable only "
            "from behind; there the arm must unfold from the tuck into the compartment. "
            + NARROW_SHELF),
        "base": "planar",
        "planned": list(R_ARM),
        "fixed": {"torso_lift_joint": GOAL_TORSO, **arm_dict("l", TUCK["l"]), **HEAD},
        "start": arm_dict("r", TUCK["r"]),
        "goal": arm_dict("r", R_IN_SHELF),
        "start_base": (1.90, 0.25, 3.14159),
        "goal_base": (0.0, 0.0, 0.0),
        "bounds": ((-1.5, -1.7), (3.0, 2.2)),
    },
}


def write_scene(path, name, sc):
    def num(v):
        return fmt(v)

    def jdict(d, indent):
        out = []
        for k, v in d.items():
            out.append("%s%s: %s" % (indent, k, num(v)))
        return "\n".join(out)

    y = ["# Generated by robots/pr2/generate.py; do not edit.",
         "name: %s" % name,
         "description: >", meshlib.wrap_text(sc["description"]),
         "narrowest_passage: >", meshlib.wrap_text(sc["narrowest"]),
         "",
         "robot:",
         "  urdf: ../robots/pr2/pr2.urdf",
         "  srdf: ../robots/pr2/pr2.srdf",
         "  packages: {gplanner_robots: ../robots}",
         "  base: %s" % sc["base"]]
    if sc["base"] == "fixed":
        y.append("  base_pose: {xyz: [0, 0, 0], quat_wxyz: [1, 0, 0, 0]}")
    y.append("  planned_joints:")
    y += ["    - %s" % j for j in sc["planned"]]
    y.append("  fixed_joints:")
    y.append(jdict(sc["fixed"], "    "))
    y += ["", "obstacles:", "  - mesh: environments/pr2_table_shelf.obj", ""]
    if "bounds" in sc:
        (a, b), (c, d) = sc["bounds"]
        y += ["bounds:", "  min: [%s, %s]" % (num(a), num(b)), "  max: [%s, %s]" % (num(c), num(d)), ""]
    for key in ("start", "goal"):
        y.append("%s:" % key)
        if sc["base"] == "planar":
            bx, by, bt = sc[key + "_base"]
            y.append("  base: {xy: [%s, %s], theta: %s}" % (num(bx), num(by), num(bt)))
        y.append("  joints:")
        y.append(jdict(sc[key], "    "))
    if "planner" in sc:
        y += ["planner:"] + sc["planner"]
    with open(path, "w") as f:
        f.write("\n".join(y) + "\n")


# ---------------------------------------------------------------------------------------


def main():
    os.makedirs(MESH_DIR, exist_ok=True)
    build_tree()
    bounds, total = {}, 0
    print("link meshes (triangles):")
    for fname, fn in MESHES.items():
        m = fn()
        meshlib.write_stl(os.path.join(MESH_DIR, fname), m, name="gplanner pr2 " + fname)
        bounds[fname] = m.bounds()
        uses = sum(1 for col, _ in LINKS.values() if col and col[0] == "mesh" and col[1] == fname)
        total += uses * len(m)
        print("  %-20s %6d  x%d" % (fname, len(m), uses))
    print("robot collision triangles: %d (+ the bellow box)" % total)
    write_urdf(os.path.join(HERE, "pr2.urdf"), bounds)
    write_srdf(os.path.join(HERE, "pr2.srdf"))
    print("srdf: %d disabled pairs, %d checked pairs"
          % (len(disabled_pairs()), len(checked_pairs())))
    parts = env_parts()
    env_path = os.path.join(ROOT, "scenes", "environments", "pr2_table_shelf.obj")
    os.makedirs(os.path.dirname(env_path), exist_ok=True)
    meshlib.write_obj(env_path, parts,
                      comment="Generated by robots/pr2/generate.py: a table and a bookshelf "
                              "for the PR2 scenes.")
    print("environment triangles: %d (%d parts)" % (sum(len(m) for _, m in parts), len(parts)))
    for name, sc in SCENES.items():
        write_scene(os.path.join(ROOT, "scenes", name + ".yaml"), name, sc)
    print("scenes: " + ", ".join(SCENES))


if __name__ == "__main__":
    main()
