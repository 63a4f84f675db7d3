#!/usr/bin/env python3
"""Generates the humanoid robot and its scene.

Writes robots/humanoid/humanoid.urdf, humanoid.srdf, meshes/*.stl,
scenes/environments/humanoid_room.obj and scenes/humanoid.yaml, then runs check.py.

The humanoid: about 1.73 m tall, root link `pelvis` (a floating base in the scene), 32
revolute joints: legs 6 each (hip yaw/roll/pitch, knee, ankle pitch/roll), torso yaw and
pitch, neck yaw and pitch, arms 7 each (shoulder pitch/roll/yaw, elbow, wrist
yaw/pitch/roll) and one finger-curl joint per hand. Frames: x forward, y left, z up;
at the zero configuration it stands straight with the arms hanging at its sides.
Deterministic; Python 3 standard library only.
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "robots"))
sys.path.insert(0, HERE)

import meshlib  # noqa: E402
from meshlib import Mesh  # noqa: E402
import humanoid_geom as hg  # noqa: E402

MESH_DIR = os.path.join(HERE, "meshes")
URDF_PATH = os.path.join(HERE, "humanoid.urdf")
SRDF_PATH = os.path.join(HERE, "humanoid.srdf")
ENV_PATH = os.path.join(ROOT, "scenes", "environments", "humanoid_room.obj")
SCENE_PATH = os.path.join(ROOT, "scenes", "humanoid.yaml")
PACKAGE_URI = "package://gplanner_robots/humanoid/meshes/"

# margins (m): pairs nearer than DEFAULT_MARGIN at the zero pose are disabled in the SRDF
DEFAULT_MARGIN = 0.01
FOOT_CLEARANCE = 0.03


# ================================================================ mesh builders

def loft(rings):
    """Closed tube through rings of equal length (each counter-clockwise about the
    direction of travel), capped at both ends by fans to the ring centroids."""
    m = Mesh()
    n = len(rings[0])
    for ring in rings:
        assert len(ring) == n
        m.vertices.extend(tuple(p) for p in ring)
    for i in range(len(rings) - 1):
        for s in range(n):
            t = (s + 1) % n
            a, b = i * n + s, i * n + t
            c, d = (i + 1) * n + t, (i + 1) * n + s
            m.triangles.append((a, b, c))
            m.triangles.append((a, c, d))
    for k, ring in ((0, rings[0]), (len(rings) - 1, rings[-1])):
        cen = tuple(sum(p[i] for p in ring) / n for i in range(3))
        m.vertices.append(cen)
        ci = len(m.vertices) - 1
        for s in range(n):
            t = (s + 1) % n
            if k == 0:
                m.triangles.append((ci, t, s))
            else:
                m.triangles.append((ci, k * n + s, k * n + t))
    return m


def se_ring(a, b, z, segs, n=2.0, cx=0.0, cy=0.0):
    """Superellipse x = a*cos^(2/n), y = b*sin^(2/n) at height z, counter-clockwise."""
    pts = []
    e = 2.0 / n
    for s in range(segs):
        t = 2 * math.pi * s / segs
        c, si = math.cos(t), math.sin(t)
        x = a * math.copysign(abs(c) ** e, c)
        y = b * math.copysign(abs(si) ** e, si)
        pts.append((cx + x, cy + y, z))
    return pts


def limb(profile, segs, n=2.0):
    """Lofted body along +z: profile rows (z, half-depth x, half-width y, x offset,
    y offset), z ascending."""
    return loft([se_ring(a, b, z, segs, n, cx, cy) for z, a, b, cx, cy in profile])


def tube(points, radii, segs):
    """Round tube along a polyline (points ordered base to tip) with a radius per point."""
    rings = []
    for i, p in enumerate(points):
        q0 = points[max(i - 1, 0)]
        q1 = points[min(i + 1, len(points) - 1)]
        t = meshlib.normalize(meshlib.sub(q1, q0))
        ref = (1.0, 0.0, 0.0) if abs(t[0]) < 0.9 else (0.0, 1.0, 0.0)
        u = meshlib.normalize(meshlib.cross(ref, t))
        v = meshlib.cross(t, u)
        ring = []
        for s in range(segs):
            th = 2 * math.pi * s / segs
            c, sn = math.cos(th), math.sin(th)
            ring.append(tuple(p[k] + radii[i] * (c * u[k] + sn * v[k]) for k in range(3)))
        rings.append(ring)
    return loft(rings)


def sector(rx_out, ry_out, rx_in, ry_in, a0, a1, n, z0, height, cx=0.0, cy=0.0):
    """An elliptical annulus sector from angle a0 to a1 (counter-clockwise), extruded."""
    outer = [(cx + rx_out * math.cos(a0 + (a1 - a0) * i / n),
              cy + ry_out * math.sin(a0 + (a1 - a0) * i / n)) for i in range(n + 1)]
    inner = [(cx + rx_in * math.cos(a1 - (a1 - a0) * i / n),
              cy + ry_in * math.sin(a1 - (a1 - a0) * i / n)) for i in range(n + 1)]
    return meshlib.extrude(outer + inner, height, z0)


def housing(radius, length, segs, axis="z", center=(0, 0, 0), step=0.025):
    """A joint housing: a cylinder split along its axis every `step` metres, so that no
    triangle is long and thin."""
    n = max(1, int(math.ceil(length / step - 1e-9)))
    m = limb([(-length / 2 + length * i / n, radius, radius, 0.0, 0.0) for i in range(n + 1)], segs)
    return meshlib.orient(m, axis, center)


def mirror_y(m):
    return m.transformed(scale=(1, -1, 1))


# ================================================================ link shapes (left side)

def pelvis_mesh():
    body = limb([(-0.115, 0.065, 0.090, 0.0, 0.0), (-0.095, 0.085, 0.120, 0.0, 0.0),
                 (-0.065, 0.098, 0.135, 0.0, 0.0), (-0.030, 0.106, 0.140, 0.0, 0.0),
                 (0.000, 0.110, 0.140, 0.0, 0.0), (0.030, 0.108, 0.136, 0.0, 0.0),
                 (0.055, 0.102, 0.128, 0.0, 0.0), (0.075, 0.094, 0.118, 0.0, 0.0),
                 (0.090, 0.082, 0.106, 0.0, 0.0)], 40, n=2.6)
    # a belt ridge around the waist: a slightly larger thin band (non-convex outline)
    belt = limb([(0.036, 0.112, 0.141, 0.0, 0.0), (0.044, 0.116, 0.145, 0.0, 0.0),
                 (0.052, 0.112, 0.141, 0.0, 0.0)], 40, n=2.6)
    # buttocks behind (towards -x), two rounded lobes
    lobes = [meshlib.sphere(0.055, center=(-0.06, y, -0.06), rings=10, segments=20,
                            scale=(0.9, 1.1, 1.0)) for y in (-0.055, 0.055)]
    return meshlib.merge(body, belt, *lobes)


def hip_yaw_mesh():
    return housing(0.042, 0.05, 28, center=(0, 0, -0.012))


def hip_roll_mesh():
    return housing(0.044, 0.105, 28, axis="x")


def thigh_mesh():
    prof = [(0.030, 0.032, 0.030, 0.0, 0.0), (0.020, 0.052, 0.048, 0.0, 0.0),
            (0.000, 0.064, 0.060, 0.004, 0.0), (-0.030, 0.070, 0.064, 0.008, 0.0),
            (-0.070, 0.073, 0.066, 0.011, 0.0), (-0.110, 0.072, 0.065, 0.012, 0.0),
            (-0.150, 0.068, 0.062, 0.011, 0.0), (-0.190, 0.063, 0.058, 0.009, 0.0),
            (-0.230, 0.058, 0.054, 0.006, 0.0), (-0.270, 0.053, 0.050, 0.004, 0.0),
            (-0.305, 0.049, 0.047, 0.003, 0.0), (-0.335, 0.048, 0.046, 0.004, 0.0),
            (-0.360, 0.052, 0.049, 0.008, 0.0), (-0.380, 0.053, 0.050, 0.010, 0.0),
            (-0.398, 0.048, 0.046, 0.006, 0.0), (-0.412, 0.034, 0.032, 0.0, 0.0)]
    rings = []
    # refine the profile: linear interpolation between rows for a smooth tessellation
    for k in range(len(prof) - 1):
        r0, r1 = prof[k], prof[k + 1]
        for s in range(2):
            f = s / 2.0
            rings.append(tuple(r0[i] + f * (r1[i] - r0[i]) for i in range(5)))
    rings.append(prof[-1])
    rings.sort(key=lambda r: r[0])
    body = limb(rings, 32, n=2.2)
    # knee cap in front of the knee joint (z = -0.38)
    cap = meshlib.sphere(0.03, center=(0.048, 0, -0.372), rings=8, segments=16,
                         scale=(0.7, 1.0, 1.2))
    return meshlib.merge(body, cap)


def shin_mesh():
    prof = [(-0.374, 0.028, 0.026, 0.0, 0.0), (-0.362, 0.036, 0.033, 0.0, 0.0),
            (-0.340, 0.038, 0.035, -0.002, 0.0), (-0.300, 0.041, 0.038, -0.004, 0.0),
            (-0.260, 0.045, 0.041, -0.007, 0.0), (-0.220, 0.050, 0.045, -0.010, 0.0),
            (-0.180, 0.055, 0.049, -0.013, 0.0), (-0.140, 0.059, 0.052, -0.016, 0.0),
            (-0.100, 0.060, 0.053, -0.016, 0.0), (-0.065, 0.057, 0.051, -0.013, 0.0),
            (-0.035, 0.052, 0.049, -0.008, 0.0), (-0.010, 0.050, 0.048, -0.004, 0.0),
            (0.010, 0.046, 0.045, 0.0, 0.0), (0.024, 0.032, 0.032, 0.0, 0.0)]
    rings = []
    for k in range(len(prof) - 1):
        r0, r1 = prof[k], prof[k + 1]
        for s in range(2):
            f = s / 2.0
            rings.append(tuple(r0[i] + f * (r1[i] - r0[i]) for i in range(5)))
    rings.append(prof[-1])
    return limb(rings, 32, n=2.2)


def ankle_mesh():
    return housing(0.03, 0.075, 24, axis="y")


def foot_outline():
    """Left foot outline (counter-clockwise, seen from above) in the ankle frame; the
    medial side (towards the body) is -y, with an arch cut into it."""
    pts = []
    # heel: half circle behind x = -0.03
    for i in range(9):
        t = math.pi / 2 + math.pi * i / 8          # from +y round the back to -y
        pts.append((-0.03 + 0.035 * math.cos(t), 0.035 * math.sin(t)))
    # medial side from heel to ball with an arch (concave)
    for i in range(1, 10):
        f = i / 10.0
        x = -0.03 + f * 0.15
        arch = 0.014 * math.sin(math.pi * f)
        y = -0.035 - 0.015 * f + arch
        pts.append((x, y))
    # toe front: an arc from medial ball (0.12, -0.05) to lateral (0.10, 0.045)
    for i in range(0, 13):
        t = -math.pi / 2 + math.pi * i / 12
        pts.append((0.12 + 0.05 * math.cos(t) * (1.0 - 0.25 * (i / 12.0)),
                    -0.0025 + 0.0475 * math.sin(t)))
    # lateral side back to the heel
    for i in range(1, 8):
        f = i / 8.0
        x = 0.10 - f * 0.13
        y = 0.045 - f * 0.010
        pts.append((x, y))
    return pts


def foot_mesh():
    sole = meshlib.extrude(foot_outline(), 0.028, z0=-0.075)
    instep = limb([(-0.048, 0.088, 0.040, 0.032, -0.002), (-0.036, 0.078, 0.039, 0.026, -0.002),
                   (-0.024, 0.064, 0.037, 0.018, -0.001), (-0.014, 0.050, 0.034, 0.010, 0.0),
                   (-0.006, 0.038, 0.031, 0.004, 0.0), (0.000, 0.028, 0.026, 0.0, 0.0)], 32, n=2.3)
    toes = []
    for k, (x, y, r) in enumerate([(0.165, -0.030, 0.013), (0.163, -0.008, 0.011),
                                   (0.156, 0.010, 0.010), (0.146, 0.025, 0.0095),
                                   (0.133, 0.038, 0.009)]):
        toes.append(meshlib.sphere(r, center=(x, y, -0.062), rings=6, segments=12,
                                   scale=(1.3, 1.0, 0.9)))
    return meshlib.merge(sole, instep, *toes)


def abdomen_mesh():
    return limb([(-0.045, 0.084, 0.112, 0.0, 0.0), (-0.020, 0.082, 0.110, 0.0, 0.0),
                 (0.010, 0.077, 0.104, 0.0, 0.0), (0.040, 0.074, 0.100, 0.002, 0.0),
                 (0.070, 0.078, 0.104, 0.004, 0.0), (0.095, 0.084, 0.110, 0.004, 0.0),
                 (0.115, 0.088, 0.112, 0.002, 0.0), (0.128, 0.080, 0.104, 0.0, 0.0)], 40, n=2.6)


def chest_mesh():
    prof = [(-0.030, 0.086, 0.108, 0.000), (-0.005, 0.095, 0.113, 0.004),
            (0.030, 0.105, 0.118, 0.008), (0.070, 0.116, 0.122, 0.012),
            (0.110, 0.124, 0.125, 0.014), (0.150, 0.126, 0.126, 0.014),
            (0.185, 0.122, 0.126, 0.012), (0.215, 0.114, 0.128, 0.008),
            (0.240, 0.104, 0.134, 0.004), (0.262, 0.092, 0.140, 0.000),
            (0.280, 0.076, 0.136, -0.004), (0.293, 0.058, 0.110, -0.006),
            (0.302, 0.038, 0.066, -0.006)]
    body = limb([(z, a, b, cx, 0.0) for z, a, b, cx in prof], 56, n=3.0)
    # back pack (battery box), rounded, behind the chest
    pack = limb([(0.030, 0.035, 0.090, -0.100, 0.0), (0.045, 0.045, 0.100, -0.105, 0.0),
                 (0.200, 0.045, 0.100, -0.105, 0.0), (0.215, 0.035, 0.090, -0.100, 0.0)],
                40, n=4.0)
    # pectoral plates: two flat lobes on the front
    pecs = [limb([(0.125, 0.012, 0.045, 0.125, y), (0.140, 0.022, 0.055, 0.128, y),
                  (0.185, 0.020, 0.052, 0.124, y), (0.200, 0.010, 0.040, 0.118, y)], 24, n=2.5)
            for y in (-0.055, 0.055)]
    return meshlib.merge(body, pack, *pecs)


def neck_mesh():
    col = limb([(-0.045, 0.046, 0.046, 0.0, 0.0), (-0.010, 0.041, 0.041, 0.0, 0.0),
                (0.030, 0.037, 0.037, 0.0, 0.0), (0.055, 0.038, 0.038, 0.0, 0.0)], 28)
    pin = housing(0.026, 0.075, 24, axis="y", center=(0, 0, 0.06))
    return meshlib.merge(col, pin)


def head_mesh():
    skull = meshlib.sphere(1.0, center=(0.01, 0, 0.09), rings=22, segments=36,
                           scale=(0.100, 0.085, 0.112))
    visor = sector(0.113, 0.097, 0.080, 0.066, -1.25, 1.25, 24, 0.075, 0.045, cx=0.012)
    ears = [meshlib.cylinder(0.026, 0.03, segments=24, center=(-0.005, y, 0.085), axis="y")
            for y in (-0.085, 0.085)]
    jaw = limb([(-0.015, 0.050, 0.050, 0.030, 0.0), (0.000, 0.060, 0.058, 0.028, 0.0),
                (0.030, 0.066, 0.062, 0.022, 0.0)], 28, n=2.5)
    return meshlib.merge(skull, visor, jaw, *ears)


def shoulder_pitch_mesh():
    return meshlib.sphere(0.054, rings=12, segments=24)


def shoulder_roll_mesh():
    return housing(0.044, 0.10, 28, axis="x")


def upper_arm_mesh():
    prof = [(-0.236, 0.026, 0.026, 0.0, 0.0), (-0.226, 0.036, 0.034, 0.0, 0.0),
            (-0.212, 0.040, 0.037, 0.0, 0.0), (-0.195, 0.038, 0.036, 0.002, 0.0),
            (-0.170, 0.038, 0.036, 0.004, 0.0), (-0.140, 0.041, 0.038, 0.006, 0.0),
            (-0.110, 0.044, 0.040, 0.008, 0.0), (-0.080, 0.046, 0.042, 0.009, 0.0),
            (-0.050, 0.046, 0.043, 0.007, 0.0), (-0.025, 0.044, 0.043, 0.004, 0.0),
            (-0.010, 0.040, 0.040, 0.0, 0.0), (0.000, 0.030, 0.030, 0.0, 0.0)]
    rings = []
    for k in range(len(prof) - 1):
        r0, r1 = prof[k], prof[k + 1]
        for s in range(2):
            f = s / 2.0
            rings.append(tuple(r0[i] + f * (r1[i] - r0[i]) for i in range(5)))
    rings.append(prof[-1])
    return limb(rings, 32, n=2.0)


def forearm_mesh():
    prof = [(-0.250, 0.018, 0.018, 0.0, 0.0), (-0.244, 0.024, 0.022, 0.0, 0.0),
            (-0.232, 0.027, 0.024, 0.0, 0.0), (-0.210, 0.028, 0.025, 0.0, 0.0),
            (-0.180, 0.030, 0.027, 0.001, 0.0), (-0.150, 0.033, 0.029, 0.002, 0.0),
            (-0.120, 0.036, 0.031, 0.004, 0.0), (-0.090, 0.039, 0.033, 0.005, 0.0),
            (-0.060, 0.041, 0.035, 0.005, 0.0), (-0.035, 0.041, 0.036, 0.003, 0.0),
            (-0.012, 0.039, 0.037, 0.0, 0.0), (0.006, 0.036, 0.035, -0.002, 0.0),
            (0.020, 0.030, 0.030, -0.003, 0.0), (0.030, 0.020, 0.020, -0.003, 0.0)]
    return limb(prof, 32, n=2.0)


def wrist_yaw_mesh():
    return meshlib.cylinder(0.025, 0.026, segments=20)


def wrist_pitch_mesh():
    return housing(0.021, 0.046, 20, axis="y")


def hand_mesh():
    """Palm in the sagittal plane (palm facing -y for the left hand), thumb in front."""
    palm = limb([(-0.098, 0.036, 0.012, 0.0, 0.0), (-0.092, 0.042, 0.016, 0.0, -0.001),
                 (-0.070, 0.044, 0.017, 0.0, -0.002), (-0.040, 0.042, 0.017, 0.0, -0.002),
                 (-0.020, 0.036, 0.016, 0.0, -0.001), (-0.008, 0.026, 0.015, 0.0, 0.0),
                 (0.000, 0.018, 0.014, 0.0, 0.0)], 32, n=3.5)
    thumb = tube([(0.026, -0.006, -0.030), (0.045, -0.014, -0.042), (0.058, -0.022, -0.058),
                  (0.066, -0.028, -0.074), (0.070, -0.031, -0.086)],
                 [0.013, 0.012, 0.0105, 0.0095, 0.0075], 16)
    return meshlib.merge(palm, thumb)


def fingers_mesh():
    """Four fingers hanging from the knuckle line (this link's origin), curled slightly
    towards the palm (-y)."""
    out = Mesh()
    for x, length in ((0.030, 0.074), (0.010, 0.082), (-0.010, 0.078), (-0.029, 0.064)):
        pts, radii = [], []
        for i, (f, r) in enumerate([(-0.12, 0.0085), (0.0, 0.0092), (0.18, 0.0084),
                                    (0.36, 0.0088), (0.52, 0.0080), (0.68, 0.0082),
                                    (0.84, 0.0074), (0.95, 0.0066), (1.0, 0.0048)]):
            z = -f * length
            y = -0.012 * f * f
            pts.append((x, y, z))
            radii.append(r * (1.0 if x > -0.02 else 0.92))
        out.add(tube(pts, radii, 14))
    return out


# ================================================================ kinematics

# (joint, parent, child, xyz, axis, lower, upper, effort, velocity)
def joint_table():
    J = []

    def side(s, sign):
        def m(lo, hi, flip):
            return (-hi, -lo) if (flip and sign < 0) else (lo, hi)
        J.extend([
            (s + "hip_yaw_joint", "pelvis", s + "hip_yaw_link", (0, sign * 0.10, -0.06),
             (0, 0, 1), *m(-0.5, 0.9, True), 120, 8),
            (s + "hip_roll_joint", s + "hip_yaw_link", s + "hip_roll_link", (0, 0, -0.05),
             (1, 0, 0), *m(-0.4, 0.8, True), 150, 8),
            (s + "hip_pitch_joint", s + "hip_roll_link", s + "thigh", (0, 0, 0),
             (0, 1, 0), -2.2, 0.6, 200, 8),
            (s + "knee_joint", s + "thigh", s + "shin", (0, 0, -0.38),
             (0, 1, 0), 0.0, 2.4, 250, 10),
            (s + "ankle_pitch_joint", s + "shin", s + "ankle_link", (0, 0, -0.38),
             (0, 1, 0), -0.9, 0.6, 100, 8),
            (s + "ankle_roll_joint", s + "ankle_link", s + "foot", (0, 0, 0),
             (1, 0, 0), *m(-0.4, 0.4, True), 60, 8),
        ])

    def arm(s, sign):
        def m(lo, hi, flip):
            return (-hi, -lo) if (flip and sign < 0) else (lo, hi)
        J.extend([
            (s + "shoulder_pitch_joint", "chest", s + "shoulder_pitch_link",
             (0, sign * 0.22, 0.24), (0, 1, 0), -3.1, 1.0, 80, 6),
            (s + "shoulder_roll_joint", s + "shoulder_pitch_link", s + "shoulder_roll_link",
             (0, 0, 0), (1, 0, 0), *m(-0.25, 2.9, True), 80, 6),
            (s + "shoulder_yaw_joint", s + "shoulder_roll_link", s + "upper_arm",
             (0, 0, -0.06), (0, 0, 1), *m(-2.0, 2.0, True), 40, 6),
            (s + "elbow_joint", s + "upper_arm", s + "forearm", (0, 0, -0.22),
             (0, 1, 0), -2.5, 0.0, 60, 6),
            (s + "wrist_yaw_joint", s + "forearm", s + "wrist_yaw_link", (0, 0, -0.24),
             (0, 0, 1), *m(-1.8, 1.8, True), 15, 5),
            (s + "wrist_pitch_joint", s + "wrist_yaw_link", s + "wrist_pitch_link", (0, 0, 0),
             (0, 1, 0), -1.2, 1.2, 15, 5),
            (s + "wrist_roll_joint", s + "wrist_pitch_link", s + "hand", (0, 0, 0),
             (1, 0, 0), *m(-0.8, 0.8, True), 15, 5),
        ])

    side("l_", 1)
    side("r_", -1)
    J.extend([
        ("torso_yaw_joint", "pelvis", "abdomen", (0, 0, 0.10), (0, 0, 1), -1.0, 1.0, 150, 6),
        ("torso_pitch_joint", "abdomen", "chest", (0, 0, 0.10), (0, 1, 0), -0.35, 0.9, 200, 6),
        ("neck_yaw_joint", "chest", "neck_link", (0, 0, 0.32), (0, 0, 1), -1.3, 1.3, 20, 4),
        ("neck_pitch_joint", "neck_link", "head", (0, 0, 0.06), (0, 1, 0), -0.6, 0.7, 20, 4),
    ])
    arm("l_", 1)
    arm("r_", -1)
    # finger curl: positive angles close the fingers towards the palm (-y left, +y right)
    J.append(("l_hand_joint", "l_hand", "l_fingers", (0, 0, -0.098), (-1, 0, 0), 0.0, 1.6, 5, 3))
    J.append(("r_hand_joint", "r_hand", "r_fingers", (0, 0, -0.098), (1, 0, 0), 0.0, 1.6, 5, 3))
    return J


LINK_SHAPES = {
    "pelvis": (pelvis_mesh, 8.0), "abdomen": (abdomen_mesh, 4.0), "chest": (chest_mesh, 14.0),
    "neck_link": (neck_mesh, 0.6), "head": (head_mesh, 4.0),
    "hip_yaw_link": (hip_yaw_mesh, 1.0), "hip_roll_link": (hip_roll_mesh, 1.2),
    "thigh": (thigh_mesh, 6.0), "shin": (shin_mesh, 3.5), "ankle_link": (ankle_mesh, 0.5),
    "foot": (foot_mesh, 1.2), "shoulder_pitch_link": (shoulder_pitch_mesh, 1.0),
    "shoulder_roll_link": (shoulder_roll_mesh, 0.9), "upper_arm": (upper_arm_mesh, 2.2),
    "forearm": (forearm_mesh, 1.4), "wrist_yaw_link": (wrist_yaw_mesh, 0.25),
    "wrist_pitch_link": (wrist_pitch_mesh, 0.25), "hand": (hand_mesh, 0.45),
    "fingers": (fingers_mesh, 0.15),
}


def link_meshes():
    """{link name: Mesh} for all 33 links (right side mirrored from the left)."""
    out = {}
    for name, (fn, _) in LINK_SHAPES.items():
        m = fn()
        if name in ("pelvis", "abdomen", "chest", "neck_link", "head"):
            out[name] = m
        else:
            out["l_" + name] = m
            out["r_" + name] = mirror_y(m)
    return out


def link_mass(link):
    base = link[2:] if link[:2] in ("l_", "r_") else link
    return LINK_SHAPES[base][1]


# ================================================================ writers

def fmt(x):
    s = "%.6g" % x
    return "0" if s in ("-0", "0") else s


def vec(v):
    return " ".join(fmt(x) for x in v)


def write_urdf(meshes, joints):
    lines = ['<?xml version="1.0"?>',
             "<!-- Generated by robots/humanoid/generate.py; do not edit by hand. -->",
             '<robot name="humanoid">']
    order = ["pelvis"] + [j[2] for j in joints]
    for link in order:
        m = meshes[link]
        lo, hi = m.bounds()
        c = [(lo[i] + hi[i]) / 2 for i in range(3)]
        d = [hi[i] - lo[i] for i in range(3)]
        mass = link_mass(link)
        ixx = mass * (d[1] ** 2 + d[2] ** 2) / 12
        iyy = mass * (d[0] ** 2 + d[2] ** 2) / 12
        izz = mass * (d[0] ** 2 + d[1] ** 2) / 12
        uri = PACKAGE_URI + link + ".stl"
        lines += [
            '  <link name="%s">' % link,
            "    <inertial>",
            '      <origin xyz="%s" rpy="0 0 0"/>' % vec(c),
            '      <mass value="%s"/>' % fmt(mass),
            '      <inertia ixx="%s" ixy="0" ixz="0" iyy="%s" iyz="0" izz="%s"/>'
            % (fmt(ixx), fmt(iyy), fmt(izz)),
            "    </inertial>",
            "    <visual>",
            '      <origin xyz="0 0 0" rpy="0 0 0"/>',
            '      <geometry><mesh filename="%s"/></geometry>' % uri,
            "    </visual>",
            "    <collision>",
            '      <origin xyz="0 0 0" rpy="0 0 0"/>',
            '      <geometry><mesh filename="%s"/></geometry>' % uri,
            "    </collision>",
            "  </link>",
        ]
    for name, parent, child, xyz, axis, lo, hi, eff, vel in joints:
        lines += [
            '  <joint name="%s" type="revolute">' % name,
            '    <parent link="%s"/>' % parent,
            '    <child link="%s"/>' % child,
            '    <origin xyz="%s" rpy="0 0 0"/>' % vec(xyz),
            '    <axis xyz="%s"/>' % vec(axis),
            '    <limit lower="%s" upper="%s" effort="%s" velocity="%s"/>'
            % (fmt(lo), fmt(hi), fmt(eff), fmt(vel)),
            "  </joint>",
        ]
    lines.append("</robot>")
    with open(URDF_PATH, "w") as f:
        f.write("\n".join(lines) + "\n")


def never_pairs():
    """Pairs that cannot collide anywhere in the joint ranges: the hip housings sit on
    the hip yaw axes below the pelvis (they only spin in place, at least 6 cm apart),
    out of reach of the torso, neck and head, whose lowest point is 6 cm above the pelvis."""
    hips = ["l_hip_yaw_link", "l_hip_roll_link", "r_hip_yaw_link", "r_hip_roll_link"]
    out = []
    for a in ("abdomen", "chest", "neck_link", "head"):
        for h in hips:
            out.append((a, h))
    for a in hips[:2]:
        for b in hips[2:]:
            out.append((a, b))
    return out


def write_srdf(joints, adjacent, default, never):
    lines = ['<?xml version="1.0"?>',
             "<!-- Generated by robots/humanoid/generate.py; do not edit by hand. -->",
             '<robot name="humanoid">',
             '  <group name="whole_body">']
    for j in joints:
        lines.append('    <joint name="%s"/>' % j[0])
    lines.append("  </group>")
    for reason, pairs in (("Adjacent", adjacent), ("Default", default), ("Never", never)):
        for a, b in pairs:
            lines.append('  <disable_collisions link1="%s" link2="%s" reason="%s"/>' % (a, b, reason))
    lines.append("</robot>")
    with open(SRDF_PATH, "w") as f:
        f.write("\n".join(lines) + "\n")


# ================================================================ environment

WALL_T = 0.15            # wall thickness, wall centred on x = 0
DOOR_W, DOOR_H = 0.90, 2.00   # clear opening between the jambs / under the head jamb
JAMB_T = 0.04
WALL_H = 2.60
ROOM_X1 = 4.50           # back wall inner face
ROOM_Y = 2.60            # side walls' inner faces at y = +-ROOM_Y
FLOOR = (-3.0, 4.65, -2.75, 2.75)
TABLE = (2.8, -1.6, 1.40, 0.80, 0.75)   # centre x, y, length (x), depth (y), height


def bx(x0, x1, y0, y1, z0, z1, cell=1.0):
    """Box from (x0, y0, z0) to (x1, y1, z1), faces split into cells of at most `cell`."""
    size = (x1 - x0, y1 - y0, z1 - z0)
    div = tuple(max(1, int(math.ceil(s / cell - 1e-9))) for s in size)
    return meshlib.box_between((x0, y0, z0), (x1, y1, z1), div)


def chair(cx, cy, yaw):
    """A chair whose front faces direction yaw; parts relative to its centre."""
    parts = Mesh()
    seat_h, s = 0.45, 0.44
    parts.add(bx(-s / 2, s / 2, -s / 2, s / 2, seat_h - 0.045, seat_h, cell=0.15))
    for x in (-0.18, 0.18):
        for y in (-0.18, 0.18):
            parts.add(meshlib.cylinder(0.018, seat_h - 0.04, segments=10,
                                       center=(x, y, (seat_h - 0.04) / 2), radius_top=0.022))
    # back at -x side: two posts and three slats
    for y in (-0.18, 0.18):
        parts.add(meshlib.cylinder(0.018, 0.48, segments=10, center=(-0.195, y, seat_h + 0.24)))
    for z in (0.62, 0.74, 0.86):
        parts.add(bx(-0.21, -0.18, -0.17, 0.17, z - 0.03, z + 0.03, cell=0.2))
    return parts.transformed(xyz=(cx, cy, 0), rpy=(0, 0, yaw))


def environment_parts():
    P = []
    x0, x1, y0, y1 = FLOOR
    P.append(("floor", bx(x0, x1, y0, y1, -0.05, 0.0, cell=2.0)))
    hw, wt = WALL_T / 2, WALL_T
    ow = DOOR_W / 2 + JAMB_T          # rough opening half-width in the wall
    oh = DOOR_H + JAMB_T              # rough opening height
    P.append(("wall_south", bx(-hw, hw, y0, -ow, 0.0, WALL_H)))
    P.append(("wall_north", bx(-hw, hw, ow, y1, 0.0, WALL_H)))
    P.append(("wall_lintel", bx(-hw, hw, -ow, ow, oh, WALL_H, cell=0.6)))
    # door frame: jambs lining the opening and architraves on both faces
    P.append(("jamb_south", bx(-hw, hw, -ow, -DOOR_W / 2, 0.0, oh, cell=0.6)))
    P.append(("jamb_north", bx(-hw, hw, DOOR_W / 2, ow, 0.0, oh, cell=0.6)))
    P.append(("jamb_head", bx(-hw, hw, -DOOR_W / 2, DOOR_W / 2, DOOR_H, oh, cell=0.6)))
    for face, xa, xb in (("hall", -hw - 0.02, -hw), ("room", hw, hw + 0.02)):
        P.append(("architrave_%s_south" % face, bx(xa, xb, -DOOR_W / 2 - 0.07, -DOOR_W / 2, 0.0, DOOR_H + 0.07, cell=0.6)))
        P.append(("architrave_%s_north" % face, bx(xa, xb, DOOR_W / 2, DOOR_W / 2 + 0.07, 0.0, DOOR_H + 0.07, cell=0.6)))
        P.append(("architrave_%s_head" % face, bx(xa, xb, -DOOR_W / 2 - 0.07, DOOR_W / 2 + 0.07, DOOR_H, DOOR_H + 0.07, cell=0.6)))
    # door leaf: hinged at the north jamb on the room side, open 90 degrees into the room
    lx0, lx1, ly0, ly1 = hw + 0.025, hw + 0.025 + 0.86, DOOR_W / 2 + 0.005, DOOR_W / 2 + 0.045
    leaf = bx(lx0, lx1, ly0, ly1, 0.01, 1.99, cell=0.6)
    # recessed-panel look: four raised panels on each face
    for yy in (ly0 - 0.008, ly1):
        for xa, xb, za, zb in ((0.12, 0.42, 0.15, 0.90), (0.50, 0.80, 0.15, 0.90),
                               (0.12, 0.42, 1.05, 1.85), (0.50, 0.80, 1.05, 1.85)):
            leaf.add(bx(lx0 + xa, lx0 + xb, yy - 0.001, yy + 0.009, za, zb, cell=0.4))
    P.append(("door_leaf", leaf))
    handle = Mesh()
    for yy, d in ((ly0, -1), (ly1, 1)):
        handle.add(meshlib.cylinder(0.025, 0.012, segments=12, axis="y",
                                    center=(lx1 - 0.07, yy + d * 0.006, 1.0)))
        handle.add(meshlib.cylinder(0.009, 0.05, segments=8, axis="y",
                                    center=(lx1 - 0.07, yy + d * 0.03, 1.0)))
        handle.add(meshlib.cylinder(0.01, 0.12, segments=8, axis="x",
                                    center=(lx1 - 0.12, yy + d * 0.055, 1.0)))
    P.append(("door_handle", handle))
    # room walls
    P.append(("wall_room_south", bx(hw, ROOM_X1, y0, -ROOM_Y, 0.0, WALL_H)))
    P.append(("wall_room_north", bx(hw, ROOM_X1, ROOM_Y, y1, 0.0, WALL_H)))
    P.append(("wall_room_back", bx(ROOM_X1, x1, y0, y1, 0.0, WALL_H)))
    # table: rounded top and four tapered legs
    tx, ty, tl, td, th = TABLE
    r = 0.06
    outline = []
    for cxs, cys, a0 in ((1, 1, 0.0), (-1, 1, 0.5), (-1, -1, 1.0), (1, -1, 1.5)):
        for i in range(7):
            a = math.pi * (a0 + 0.5 * i / 6)
            outline.append((cxs * (tl / 2 - r) + r * math.cos(a), cys * (td / 2 - r) + r * math.sin(a)))
    top = meshlib.extrude(outline, 0.04, z0=th - 0.04).transformed(xyz=(tx, ty, 0))
    P.append(("table_top", top))
    apron = Mesh()
    apron.add(bx(tx - tl / 2 + 0.06, tx + tl / 2 - 0.06, ty - td / 2 + 0.06, ty - td / 2 + 0.08, th - 0.14, th - 0.04, cell=0.4))
    apron.add(bx(tx - tl / 2 + 0.06, tx + tl / 2 - 0.06, ty + td / 2 - 0.08, ty + td / 2 - 0.06, th - 0.14, th - 0.04, cell=0.4))
    P.append(("table_apron", apron))
    k = 0
    for sx in (-1, 1):
        for sy in (-1, 1):
            k += 1
            P.append(("table_leg_%d" % k, meshlib.cylinder(
                0.022, th - 0.04, segments=16,
                center=(tx + sx * (tl / 2 - 0.09), ty + sy * (td / 2 - 0.09), (th - 0.04) / 2),
                radius_top=0.032)))
    # chairs: one on the open (+y) side of the table, one at its far end
    P.append(("chair_1", chair(2.55, -0.82, -math.pi / 2)))
    P.append(("chair_2", chair(3.95, -1.60, math.pi)))
    # cabinet against the north wall
    cab = Mesh()
    cx0, cx1, cy0, cy1 = 2.30, 3.40, ROOM_Y - 0.48, ROOM_Y - 0.02
    cab.add(bx(cx0, cx1, cy0, cy1, 0.08, 1.85, cell=0.6))
    cab.add(bx(cx0 + 0.03, cx1 - 0.03, cy0 + 0.03, cy1 - 0.002, 0.0, 0.085, cell=0.6))
    for xa, xb in ((cx0 + 0.02, (cx0 + cx1) / 2 - 0.005), ((cx0 + cx1) / 2 + 0.005, cx1 - 0.02)):
        cab.add(bx(xa, xb, cy0 - 0.02, cy0 + 0.002, 0.10, 1.83, cell=0.6))
    for hx in ((cx0 + cx1) / 2 - 0.06, (cx0 + cx1) / 2 + 0.06):
        cab.add(meshlib.cylinder(0.012, 0.30, segments=12, center=(hx, cy0 - 0.045, 1.0)))
        for hz in (0.87, 1.13):
            cab.add(meshlib.cylinder(0.008, 0.03, segments=8, axis="y", center=(hx, cy0 - 0.025, hz)))
    cab.add(bx(cx0 - 0.02, cx1 + 0.02, cy0 - 0.03, cy1, 1.845, 1.89, cell=0.6))
    P.append(("cabinet", cab))
    # floor lamp in the south-west corner of the room
    lamp = Mesh()
    lx, ly = 0.75, -2.25
    lamp.add(meshlib.cylinder(0.16, 0.03, segments=24, center=(lx, ly, 0.015), radius_top=0.14))
    lamp.add(meshlib.cylinder(0.06, 0.042, segments=24, center=(lx, ly, 0.049), radius_top=0.03))
    lamp.add(meshlib.cylinder(0.012, 1.40, segments=12, center=(lx, ly, 0.75)))
    lamp.add(meshlib.sphere(0.03, center=(lx, ly, 1.45), rings=6, segments=12))
    lamp.add(meshlib.cylinder(0.22, 0.30, segments=32, center=(lx, ly, 1.60), radius_top=0.13))
    lamp.add(meshlib.sphere(0.02, center=(lx, ly, 1.77), rings=4, segments=8))
    P.append(("floor_lamp", lamp))
    # book shelf against the back wall, with books
    shelf = Mesh()
    bx0, bx1, by0, by1 = ROOM_X1 - 0.32, ROOM_X1 - 0.02, 0.30, 1.50
    shelf.add(bx(bx0, bx1, by0, by0 + 0.03, 0.0, 1.60, cell=0.4))
    shelf.add(bx(bx0, bx1, by1 - 0.03, by1, 0.0, 1.60, cell=0.4))
    # back panel and shelves overlap the sides by a few mm (no shared edges)
    shelf.add(bx(bx1 - 0.02, bx1, by0 + 0.027, by1 - 0.027, 0.001, 1.599, cell=0.4))
    for z in (0.0, 0.40, 0.80, 1.20, 1.565):
        shelf.add(bx(bx0 + 0.002, bx1 - 0.018, by0 + 0.027, by1 - 0.027, z + 0.002, z + 0.03, cell=0.4))
    for level, z in enumerate((0.43,)):
        y = by0 + 0.05
        k = 0
        while True:
            w = 0.03 + 0.012 * ((k * 7 + level * 3) % 5)
            h = 0.22 + 0.025 * ((k * 5 + level) % 4)
            if y + w > by0 + 0.65:
                break
            shelf.add(bx(bx0 + 0.04, bx1 - 0.04, y, y + w - 0.004, z - 0.002, z + h, cell=0.4))
            y += w
            k += 1
    P.append(("bookshelf", shelf))
    return P


# ================================================================ scene

LEG_JOINTS = ["hip_yaw_joint", "hip_roll_joint", "hip_pitch_joint", "knee_joint",
              "ankle_pitch_joint", "ankle_roll_joint"]
ARM_JOINTS = ["shoulder_pitch_joint", "shoulder_roll_joint", "shoulder_yaw_joint",
              "elbow_joint", "wrist_yaw_joint", "wrist_pitch_joint", "wrist_roll_joint"]


def planned_joints():
    return (["l_" + j for j in LEG_JOINTS] + ["r_" + j for j in LEG_JOINTS]
            + ["torso_yaw_joint", "torso_pitch_joint", "neck_yaw_joint", "neck_pitch_joint"]
            + ["l_" + j for j in ARM_JOINTS] + ["r_" + j for j in ARM_JOINTS]
            + ["l_hand_joint", "r_hand_joint"])


def leg(s, bend, roll=0.0, yaw=0.0):
    """Leg angles with the foot kept flat: hip -bend, knee 2*bend, ankle -bend."""
    return {s + "hip_yaw_joint": yaw, s + "hip_roll_joint": roll, s + "hip_pitch_joint": -bend,
            s + "knee_joint": 2 * bend, s + "ankle_pitch_joint": -bend,
            s + "ankle_roll_joint": -roll}


def start_goal_joints():
    start = {j: 0.0 for j in planned_joints()}
    start.update(leg("l_", 0.08, 0.03))
    start.update(leg("r_", 0.08, -0.03))
    start.update({"l_shoulder_pitch_joint": 0.05, "l_shoulder_roll_joint": 0.12,
                  "l_elbow_joint": -0.30, "r_shoulder_pitch_joint": 0.05,
                  "r_shoulder_roll_joint": -0.12, "r_elbow_joint": -0.30,
                  "l_hand_joint": 0.2, "r_hand_joint": 0.2})
    goal = {j: 0.0 for j in planned_joints()}
    goal.update(leg("l_", 0.15, 0.07, 0.10))
    goal.update(leg("r_", 0.15, -0.07, -0.10))
    goal.update({"torso_yaw_joint": 0.15, "torso_pitch_joint": 0.05,
                 "neck_yaw_joint": -0.30, "neck_pitch_joint": -0.25,
                 # right arm raised overhead
                 "r_shoulder_pitch_joint": -2.75, "r_shoulder_roll_joint": -0.20,
                 "r_shoulder_yaw_joint": 0.30, "r_elbow_joint": -0.35,
                 "r_wrist_yaw_joint": 0.40, "r_wrist_pitch_joint": 0.30, "r_wrist_roll_joint": -0.20,
                 "r_hand_joint": 0.9,
                 # left forearm forward
                 "l_shoulder_pitch_joint": -0.35, "l_shoulder_roll_joint": 0.20,
                 "l_shoulder_yaw_joint": -0.20, "l_elbow_joint": -1.10,
                 "l_wrist_pitch_joint": -0.20, "l_hand_joint": 0.4})
    return start, goal


START_XY, START_QUAT = (-1.10, 0.0), (1.0, 0.0, 0.0, 0.0)
GOAL_XY, GOAL_QUAT = (1.70, -1.60), (0.7071068, 0.0, 0.0, 0.7071068)
BOUNDS = ((-2.5, -2.3, 0.85), (4.1, 2.3, 1.20))


def standing_height(urdf, meshes, q, xy, quat):
    """Pelvis z that leaves the lowest robot vertex FOOT_CLEARANCE above the floor."""
    pose = meshlib.pose((xy[0], xy[1], 0.0), quat)
    posed = hg.PosedRobot(urdf, meshes, pose, q)
    low = min(b[2] for b in posed.link_box.values())
    return round(FOOT_CLEARANCE - low, 4)


def write_scene(start_q, goal_q, start_z, goal_z, shoulder_w, height):
    pj = planned_joints()

    def cfg(xy, z, quat, q):
        joints = ", ".join("%s: %s" % (j, fmt(q[j])) for j in pj)
        return ("  base: {xyz: [%s, %s, %s], quat_wxyz: [%s]}\n  joints: {%s}\n"
                % (fmt(xy[0]), fmt(xy[1]), fmt(z), ", ".join(fmt(c) for c in quat), joints))

    text = (
        "# Generated by robots/humanoid/generate.py; do not edit by hand.\n"
        "name: humanoid\n"
        "description: >\n"
        "  A %.2f m humanoid (floating base + 32 revolute joints = 38 DOF) standing in a\n"
        "  hall in front of a doorway walks through it into a furnished room (table, two\n"
        "  chairs, cabinet, floor lamp, book shelf, the door leaf open 90 degrees into the\n"
        "  room) and ends beside the table, turned 90 degrees, with its right arm raised\n"
        "  overhead. The straight line from start to goal runs through the wall south of\n"
        "  the doorway.\n"
        "narrowest_passage: >\n"
        "  The doorway: %.2f m clear between the jambs x %.2f m high in a %.2f m thick wall\n"
        "  with 2 cm architraves; the humanoid is %.2f m across the shoulders with the arms\n"
        "  at its sides and %.2f m tall standing, so it has about %.2f m each side and\n"
        "  %.2f m overhead when it walks upright through the middle (arms raised sideways it\n"
        "  spans over 1.4 m and must not).\n"
        "\n"
        "robot:\n"
        "  urdf: ../robots/humanoid/humanoid.urdf\n"
        "  srdf: ../robots/humanoid/humanoid.srdf\n"
        "  packages: {gplanner_robots: ../robots}\n"
        "  base: floating\n"
        "  planned_joints: [%s]\n"
        "\n"
        "obstacles:\n"
        "  - mesh: environments/humanoid_room.obj\n"
        "\n"
        "bounds:\n"
        "  min: [%s]\n"
        "  max: [%s]\n"
        "\n"
        "start:\n%s"
        "goal:\n%s"
        "\n"
        "planner:\n"
        "  # 20 neighbours, not 15: in 38 dimensions the lazy search then finds a valid path\n"
        "  # in fewer checker calls (bench/history/issue4_planning.md, plan times at 2d05991)\n"
        "  roadmap: {neighbors: 20}\n"
    ) % (height, DOOR_W, DOOR_H, WALL_T, shoulder_w, height, (DOOR_W - shoulder_w) / 2,
         DOOR_H - height - FOOT_CLEARANCE, ", ".join(pj),
         ", ".join(fmt(v) for v in BOUNDS[0]), ", ".join(fmt(v) for v in BOUNDS[1]),
         cfg(START_XY, start_z, START_QUAT, start_q), cfg(GOAL_XY, goal_z, GOAL_QUAT, goal_q))
    with open(SCENE_PATH, "w") as f:
        f.write(text)


# ================================================================ main

def main():
    os.makedirs(MESH_DIR, exist_ok=True)
    os.makedirs(os.path.dirname(ENV_PATH), exist_ok=True)
    meshes = link_meshes()
    joints = joint_table()
    assert len(joints) == 32 and len(meshes) == 33
    for name in sorted(os.listdir(MESH_DIR)):
        if name.endswith(".stl") and name[:-4] not in meshes:
            os.remove(os.path.join(MESH_DIR, name))
    total = 0
    for link in ["pelvis"] + [j[2] for j in joints]:
        meshlib.write_stl(os.path.join(MESH_DIR, link + ".stl"), meshes[link], name=link)
        total += len(meshes[link])
    write_urdf(meshes, joints)

    urdf = meshlib.Urdf(URDF_PATH)
    lm = urdf.collision_geometry({"gplanner_robots": os.path.join(ROOT, "robots")})

    # SRDF: adjacent pairs, pairs touching (within DEFAULT_MARGIN) at the zero pose, never
    adjacent = [(j[1], j[2]) for j in joints]
    adj_set = {frozenset(p) for p in adjacent}
    never = never_pairs()
    never_set = {frozenset(p) for p in never}
    zero = hg.PosedRobot(urdf, lm, meshlib.IDENTITY, {})
    links = urdf.links
    cand = [(a, b) for i, a in enumerate(links) for b in links[i + 1:]
            if frozenset((a, b)) not in adj_set]
    default = [(a, b) for a, b, g in zero.self_close_pairs(cand, DEFAULT_MARGIN)]
    never = [p for p in never if frozenset(p) not in {frozenset(d) for d in default}]
    write_srdf(joints, adjacent, default, never)

    # environment
    parts = environment_parts()
    env_tris = sum(len(m) for _, m in parts)
    meshlib.write_obj(ENV_PATH, parts,
                      comment="humanoid_room: hall, wall with a 0.90 x 2.00 m doorway, furnished room\n"
                              "Generated by robots/humanoid/generate.py; do not edit by hand.")

    # scene
    start_q, goal_q = start_goal_joints()
    start_z = standing_height(urdf, lm, start_q, START_XY, START_QUAT)
    goal_z = standing_height(urdf, lm, goal_q, GOAL_XY, GOAL_QUAT)
    lo, hi = [min(b[i] for b in zero.link_box.values()) for i in range(3)], \
             [max(b[i + 3] for b in zero.link_box.values()) for i in range(3)]
    shoulder_w = round(hi[1] - lo[1], 2)
    height = round(hi[2] - lo[2], 2)
    write_scene(start_q, goal_q, start_z, goal_z, shoulder_w, height)

    print("humanoid: %d links, %d joints, %d collision triangles" % (len(meshes), len(joints), total))
    for link in ["pelvis"] + [j[2] for j in joints]:
        print("  %-22s %5d" % (link, len(meshes[link])))
    print("zero pose: %.3f m wide (y), %.3f m deep (x), %.3f m tall" % (hi[1] - lo[1], hi[0] - lo[0], hi[2] - lo[2]))
    print("srdf: %d adjacent, %d default, %d never" % (len(adjacent), len(default), len(never)))
    print("environment: %d parts, %d triangles" % (len(parts), env_tris))
    print("start pelvis z %.4f, goal pelvis z %.4f" % (start_z, goal_z))


if __name__ == "__main__":
    main()
    import check
    sys.exit(check.main())
