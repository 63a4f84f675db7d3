#!/usr/bin/env python3
"""Checks the humanoid and its scene in pure Python (run from any directory):

- URDF: root `pelvis`, 32 revolute joints with limits, every link with mesh collision;
- meshes: closed, outward winding, no degenerate triangles, triangle totals in range;
- SRDF: the group holds the 32 planned joints; disabled pairs name real links;
- scene: keys, planned joints, every joint given at start and goal within its limits,
  the pelvis inside the bounds;
- start and goal: every link's triangles (forward kinematics of the URDF) keep
  ENV_MARGIN from every obstacle part's box, and every checked link pair keeps
  SELF_MARGIN (box tests, conservative); the zero pose is self-collision free;
- the straight line start -> goal puts robot vertices deep inside the wall;
- then `build/apps/gplan check` when that tool has been built.
"""

import os
import subprocess
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)

import humanoid_geom as hg  # noqa: E402

SCENE = os.path.join(ROOT, "scenes", "humanoid.yaml")
ENV_MARGIN = 0.02
SELF_MARGIN = 0.02
ROBOT_TRIS = (25200, 30800)
ENV_TRIS = (3150, 3850)
WALL_PARTS = ("wall_south", "wall_north", "wall_lintel", "jamb_south", "jamb_north", "jamb_head")
DEPTH = 0.05
WITNESS_STEP = 0.08


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def main():
    scene = hg.read_scene_yaml(SCENE)
    sdir = os.path.dirname(SCENE)
    rob = scene["robot"]
    for key in ("name", "description", "narrowest_passage", "robot", "obstacles", "bounds",
                "start", "goal"):
        if key not in scene:
            fail("scene lacks %s" % key)
    if rob.get("base") != "floating":
        fail("base must be floating")
    packages = {k: os.path.normpath(os.path.join(sdir, v)) for k, v in rob["packages"].items()}
    urdf = hg.Urdf(os.path.normpath(os.path.join(sdir, rob["urdf"])))
    if urdf.root != "pelvis":
        fail("root link is %s" % urdf.root)
    act = urdf.actuated()
    if len(act) != 32 or any(j.type != "revolute" for j in act):
        fail("expected 32 revolute joints, got %d" % len(act))
    limits = {}
    for j in act:
        lim = j.limit
        if lim is None or any(lim.get(k) is None for k in ("lower", "upper", "effort", "velocity")):
            fail("%s: incomplete <limit>" % j.name)
        if not j.lower < j.upper:
            fail("%s: empty range" % j.name)
        limits[j.name] = (j.lower, j.upper)
    for name, el in urdf.link_el.items():
        if el.find("collision") is None or el.find("inertial") is None:
            fail("link %s lacks collision or inertial" % name)

    meshes = urdf.collision_meshes(packages)
    total = 0
    for link, items in sorted(meshes.items()):
        for _, verts, tris in items:
            probs = hg.mesh_problems(verts, tris)
            if probs:
                fail("%s mesh: %s" % (link, "; ".join(probs)))
            total += len(tris)
    if not ROBOT_TRIS[0] <= total <= ROBOT_TRIS[1]:
        fail("robot has %d triangles, want %s" % (total, ROBOT_TRIS))
    print("robot: %d links, %d revolute joints, %d triangles, meshes closed and outward"
          % (len(urdf.links), len(act), total))

    # SRDF
    srdf = ET.parse(os.path.normpath(os.path.join(sdir, rob["srdf"]))).getroot()
    group = [j.get("name") for g in srdf.findall("group") for j in g.findall("joint")]
    planned = rob["planned_joints"]
    if sorted(group) != sorted(limits) or sorted(planned) != sorted(limits) or len(planned) != 32:
        fail("SRDF group / planned_joints do not match the 32 URDF joints")
    disabled = set()
    for d in srdf.findall("disable_collisions"):
        a, b = d.get("link1"), d.get("link2")
        if a not in urdf.link_el or b not in urdf.link_el:
            fail("disable_collisions names unknown link %s/%s" % (a, b))
        disabled.add(frozenset((a, b)))
    adjacent = {frozenset((j.parent, j.child)) for j in urdf.joints}
    links = urdf.links
    checked = [(a, b) for i, a in enumerate(links) for b in links[i + 1:]
               if frozenset((a, b)) not in disabled and frozenset((a, b)) not in adjacent]
    print("srdf: %d disabled pairs, %d checked link pairs" % (len(disabled), len(checked)))

    # environment
    obs = scene["obstacles"]
    if len(obs) != 1 or "mesh" not in obs[0]:
        fail("expected one mesh obstacle")
    env = hg.read_obj_parts(os.path.normpath(os.path.join(sdir, obs[0]["mesh"])))
    env_tris = 0
    parts = []
    for name, verts, tris in env:
        probs = hg.mesh_problems(verts, tris)
        if probs:
            fail("obstacle %s: %s" % (name, "; ".join(probs)))
        env_tris += len(tris)
        parts.append((name, hg.box_of(verts)))
    if not ENV_TRIS[0] <= env_tris <= ENV_TRIS[1]:
        fail("environment has %d triangles, want %s" % (env_tris, ENV_TRIS))
    print("environment: %d parts, %d triangles, all closed and outward" % (len(parts), env_tris))
    part_box = dict(parts)

    # start / goal
    lo, hi = scene["bounds"]["min"], scene["bounds"]["max"]
    configs = {}
    for key in ("start", "goal"):
        c = scene[key]
        xyz, quat, q = c["base"]["xyz"], c["base"]["quat_wxyz"], c["joints"]
        if sorted(q) != sorted(planned):
            fail("%s does not list every planned joint exactly once" % key)
        for j, v in q.items():
            a, b = limits[j]
            if not a <= v <= b:
                fail("%s: %s = %g outside [%g, %g]" % (key, j, v, a, b))
        for i in range(3):
            if not lo[i] + 0.1 <= xyz[i] <= hi[i] - 0.1:
                fail("%s pelvis %s not well inside the bounds" % (key, xyz))
        configs[key] = (xyz, quat, q)
        posed = hg.PosedRobot(urdf, meshes, hg.base_pose_from(xyz, quat), q)
        hits = posed.env_close(parts, ENV_MARGIN)
        if hits:
            fail("%s: near obstacles: %s" % (key, hits[:8]))
        selfhits = posed.self_close_pairs(checked, SELF_MARGIN)
        if selfhits:
            fail("%s: self-collision pairs within %g m: %s" % (key, SELF_MARGIN, selfhits[:8]))
        # report the clearance to the nearest obstacle part (box distance)
        near = min((hg.box_gap(posed.link_box[l], pb), l, n) for l in posed.link_box for n, pb in parts)
        low = min(b[2] for b in posed.link_box.values())
        print("%s: free (env >= %g m, %d checked pairs >= %g m); lowest point z = %.3f; "
              "nearest part box: %s-%s %.3f m" % (key, ENV_MARGIN, len(checked), SELF_MARGIN,
                                                  low, near[1], near[2], near[0]))
    zero = hg.PosedRobot(urdf, meshes, hg.IDENTITY, {})
    zh = zero.self_close_pairs(checked, 0.0)
    if zh:
        fail("zero pose: checked pairs touching: %s" % zh[:8])
    print("zero pose: checked pairs free")

    # straight line
    (x0, q0, j0), (x1, q1, j1) = configs["start"], configs["goal"]
    deepest = (0.0, None, None)
    for k in range(1, 40):
        t = k / 40.0
        xyz = [a + t * (b - a) for a, b in zip(x0, x1)]
        quat = hg.slerp(q0, q1, t)
        q = {j: j0[j] + t * (j1[j] - j0[j]) for j in j0}
        posed = hg.PosedRobot(urdf, meshes, hg.base_pose_from(xyz, quat), q)
        for name in WALL_PARTS:
            b = part_box[name]
            for link, vs in posed.verts.items():
                for v in vs:
                    d = min(v[0] - b[0], b[3] - v[0], v[1] - b[1], b[4] - v[1], v[2] - b[2], b[5] - v[2])
                    if d > deepest[0]:
                        deepest = (d, t, "%s vertex in %s" % (link, name))
    if deepest[0] < DEPTH:
        fail("straight line: no robot vertex deeper than %g m in the wall" % DEPTH)
    print("straight line: blocked: at t = %.3f a %s, %.3f m deep" % (deepest[1], deepest[2], deepest[0]))

    # a witness path shows the problem is solvable: walk upright in the start posture
    # through the middle of the doorway, turn, then take the goal posture beside the table
    stand_q = j0
    waypoints = [(x0, q0, j0), ([-0.5, 0.0, x0[2]], q0, stand_q), ([0.7, 0.0, x0[2]], q0, stand_q),
                 ([1.3, -1.1, x0[2]], q1, stand_q), (x1, q1, j1)]
    n_checked, worst = 0, None
    for (pa, ra, ja), (pb, rb, jb) in zip(waypoints, waypoints[1:]):
        dist = max(sum((a - b) ** 2 for a, b in zip(pa, pb)) ** 0.5,
                   max(abs(ja[j] - jb[j]) for j in ja) * 0.3)
        steps = max(2, int(dist / WITNESS_STEP) + 1)
        for k in range(steps + 1):
            t = k / float(steps)
            xyz = [a + t * (b - a) for a, b in zip(pa, pb)]
            q = {j: ja[j] + t * (jb[j] - ja[j]) for j in ja}
            posed = hg.PosedRobot(urdf, meshes, hg.base_pose_from(xyz, hg.slerp(ra, rb, t)), q)
            hits = posed.env_close(parts, 0.0) + posed.self_close_pairs(checked, 0.0)
            if hits:
                fail("witness path collides at %s: %s" % ([round(c, 3) for c in xyz], hits[:4]))
            n_checked += 1
            in_door = min(min(abs(b[1] - part_box["jamb_south"][4]), abs(b[4] - part_box["jamb_north"][1]))
                          for l, b in posed.link_box.items()
                          if b[0] < part_box["jamb_south"][3] and b[3] > part_box["jamb_south"][0])  \
                if any(b[0] < part_box["jamb_south"][3] and b[3] > part_box["jamb_south"][0]
                       for b in posed.link_box.values()) else None
            if in_door is not None and (worst is None or in_door < worst):
                worst = in_door
    print("witness path: %d configurations free (box test); side clearance to the jambs "
          "in the doorway >= %.3f m" % (n_checked, worst))

    gplan = os.path.join(ROOT, "build", "apps", "gplan")
    if os.path.exists(gplan):
        print("running %s check scenes/humanoid.yaml --n 2000" % gplan)
        r = subprocess.run([gplan, "check", "scenes/humanoid.yaml", "--n", "2000"], cwd=ROOT)
        if r.returncode != 0:
            fail("gplan check exited with %d" % r.returncode)
    else:
        print("(build/apps/gplan not built: FCL check skipped)")
    print("OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
