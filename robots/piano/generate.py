#!/usr/bin/env python3
"""Generates the piano family: the robots, their environments and scenes.

    python3 robots/piano/generate.py        (from anywhere; paths follow this file)

Writes
    robots/piano/piano.obj                          grand piano, ~6,500 triangles
    robots/piano/large_piano.obj                    detailed grand piano, ~35,000
    robots/piano/witness_paths.yaml                 a collision-free path per scene
    scenes/environments/piano_rooms.obj             rooms, ~650 triangles
    scenes/environments/piano_rooms_detailed.obj    the same, tessellated and furnished
    scenes/environments/large_piano_house.obj       house with a staircase, ~14,000
    scenes/piano.yaml, scenes/piano_detailed.yaml, scenes/large_piano.yaml

and asserts on the way: closed outward meshes, triangle counts, doorways sized from
the piano's least width, furniture clear of walls and of other furniture, start and
goal clear of every obstacle box, the straight line from start to goal through an
obstacle. check.py then certifies the witness paths from the written files.
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path[:0] = [HERE, os.path.dirname(HERE)]

import layouts as L  # noqa: E402
import meshlib as ml  # noqa: E402
import passage as ps  # noqa: E402
import piano_model as pm  # noqa: E402

ENVS = os.path.join(ROOT, "scenes", "environments")
SCENES = os.path.join(ROOT, "scenes")

LID_ANGLE_DEG = 15.0    # lid propped on the short stick
CLEAR = 0.03            # start and goal hover this far above the floor
# spare width of the doorways over the piano's least width
D1_SPARE, D2_SPARE = 0.07, 0.10       # piano_rooms
A_SPARE, B_SPARE = 0.06, 0.09         # large_piano_house

TARGETS = {"piano": 6540, "large_piano": 34880, "piano_rooms": 648,
           "large_piano_house": 13824}


def log(msg):
    print(msg, flush=True)


def near_target(name, count, tol=0.10):
    t = TARGETS[name]
    assert abs(count - t) <= tol * t, "%s: %d triangles, target %d" % (name, count, t)


def check_parts(parts, label):
    total = 0
    for nm, m in parts:
        ml.check_closed(m, "%s/%s" % (label, nm), min_area=1e-9)
        total += len(m.triangles)
    return total


# ---------------------------------------------------------------- analysis


def analyse(parts):
    """Least width of the piano and the doorway orientation (see passage.py)."""
    V = [v for _, m in parts for v in m.vertices]
    S = ps.support_points(V)
    w, a = ps.min_width_direction(S)
    w = ps.width(V, a)
    a, b, c = ps.passage_frame(a)
    q = ps.frame_quat(a, b, c)
    ext = ps.world_extents(V, (0, 0, 0), q)
    az = abs(a[2])
    u, v = ps.tangents(a)
    d1 = math.radians(1.0)
    w_1deg = max(ps.width(S, [a[i] * math.cos(d1) + math.sin(d1) * (
        math.cos(t) * u[i] + math.sin(t) * v[i]) for i in range(3)])
        for t in [2 * math.pi * k / 72 for k in range(72)])
    return {
        "w_1deg": w_1deg,
        "w": w, "a": a, "b": b, "c": c, "q": q, "ext": ext,
        "h": ext[1][2] - ext[0][2], "len": ext[1][1] - ext[0][1],
        "upright_w": ps.width(V, (1, 0, 0)), "side_t": ps.width(V, (0, 0, 1)),
        "length": ps.width(V, (0, 1, 0)),
        "tilt_x": math.degrees(math.atan2(abs(a[0]), az)),
        "tilt_y": math.degrees(math.atan2(abs(a[1]), az)),
    }


# ---------------------------------------------------------------- environment checks


def overlap_check(env, joined=("stair_",), tol=1e-3):
    """No two parts overlap by more than tol (touching is fine); parts whose names
    start with one of `joined` are allowed to meet each other (stair, rail, posts)."""
    B = env.boxes
    for i in range(len(B)):
        for j in range(i + 1, len(B)):
            n1, l1, h1 = B[i]
            n2, l2, h2 = B[j]
            if n1 == n2 or (n1.startswith(joined) and n2.startswith(joined)):
                continue
            if all(min(h1[k], h2[k]) - max(l1[k], l2[k]) > tol for k in range(3)):
                raise AssertionError("%s overlaps %s" % (n1, n2))


def clear_of(parts, pose, boxes, margin):
    """Per-part bounding boxes of the transformed piano against obstacle boxes; returns
    the smallest gap (negative: overlap) and the pair."""
    best = (1e9, None)
    for nm, m in parts:
        lo, hi = ml.point_bounds(ml.transform(ml.pose(*pose), m.vertices))
        for bn, bl, bh in boxes:
            gap = max(max(bl[i] - hi[i], lo[i] - bh[i]) for i in range(3))
            if gap < best[0]:
                best = (gap, (nm, bn))
    assert best[0] >= margin, "pose %s: %s within %.3f m of %s" % (pose, best[1][0], best[0],
                                                                   best[1][1])
    return best


def straight_line_hit(robot, start, goal, boxes, depth=0.05, n=100):
    """A sample of the straight line start -> goal with a piano vertex at least
    `depth` inside an obstacle box: (t, boxes)."""
    for k in range(1, n):
        t = k / n
        p = tuple(start[0][i] + t * (goal[0][i] - start[0][i]) for i in range(3))
        q = ml.slerp(start[1], goal[1], t)
        hits = robot.vertex_inside(p, q, boxes, depth)
        if hits:
            return t, hits
    raise AssertionError("the straight line from start to goal is free")


# ---------------------------------------------------------------- writers


def f3(v):
    return "[%s]" % ", ".join(("%.4f" % x).rstrip("0").rstrip(".") if abs(x) > 5e-5 else "0"
                              for x in v)


def fq(q):
    q = ml.quat_normalize(q)
    return "[%s]" % ", ".join(("%.7f" % x).rstrip("0").rstrip(".") if abs(x) > 5e-8 else "0"
                              for x in q)


def write_scene(name, description, narrow, robot, env_obj, bounds, start, goal):
    path = os.path.join(SCENES, name + ".yaml")
    text = ("name: %s\ndescription: >\n%s\nnarrowest_passage: >\n%s\n\n"
            "robot:\n  mesh: ../robots/piano/%s\n\n"
            "obstacles:\n  - mesh: environments/%s\n\n"
            "bounds:\n  min: %s\n  max: %s\n\n"
            "start:\n  base: {xyz: %s, quat_wxyz: %s}\n"
            "goal:\n  base: {xyz: %s, quat_wxyz: %s}\n"
            % (name, ml.wrap_text(description), ml.wrap_text(narrow), robot, env_obj,
               f3(bounds[0]), f3(bounds[1]), f3(start[0]), fq(start[1]), f3(goal[0]),
               fq(goal[1])))
    with open(path, "w") as f:
        f.write(text)
    return path


def rounded_pose(pose):
    return (tuple(float(("%.4f" % x)) for x in pose[0]),
            tuple(float("%.7f" % x) for x in ml.quat_normalize(pose[1])))


# ---------------------------------------------------------------- main


def main():
    os.makedirs(ENVS, exist_ok=True)
    witness = []

    # ---- robots
    pianos = {}
    for name, large in (("piano", False), ("large_piano", True)):
        parts, info = pm.build_piano(large, LID_ANGLE_DEG)
        n = check_parts(parts, name)
        near_target(name, n)
        A = analyse(parts)
        info.update(A)
        sz = info["size"]
        log("%-12s %6d triangles, %2d parts, %.3f x %.3f x %.3f m (lid open %g deg); floor "
            "%.4f m below the origin" % (name, n, len(parts), sz[0], sz[1], sz[2],
                                         LID_ANGLE_DEG, -info["floor_z"]))
        log("             upright %.3f m wide, %.3f m thick on its side; least width %.4f m "
            "(tilted %.1f deg across, %.1f deg along), %.3f m high travelling lengthwise"
            % (A["upright_w"], A["side_t"], A["w"], A["tilt_x"], A["tilt_y"], A["h"]))
        comment = ("%s: grand piano of the gplanner piano family (rigid robot), written by "
                   "robots/piano/generate.py.\nUnits: metres. Origin: centre of the bounding "
                   "box. x across the keyboard (bass at -x), y along the piano (keyboard at "
                   "-y, tail at +y), z up.\nSize %.3f x %.3f x %.3f m with the lid propped "
                   "open at %g deg; the leg bottoms (floor) at z = %.4f. %d triangles, %d "
                   "parts (one object each), every part a union of closed outward meshes."
                   % (name, sz[0], sz[1], sz[2], LID_ANGLE_DEG, info["floor_z"], n,
                      len(parts)))
        ml.write_obj(os.path.join(HERE, name + ".obj"), parts, comment)
        pianos[name] = (parts, info, n)
        assert sz[0] < 1.60 and 1.95 < sz[1] < 2.05, sz

    # ---- piano_rooms and piano_rooms_detailed
    parts, info, n_piano = pianos["piano"]
    A = info
    w1, w2 = round(A["w"] + D1_SPARE, 2), round(A["w"] + D2_SPARE, 2)
    assert A["w"] + 0.04 < w1 < w2 < A["side_t"] < A["upright_w"]
    assert A["h"] + 0.10 < L.DOOR_H
    plan = L.RoomsPlan(w1, w2)
    robot = ps.Robot(parts)
    start, goal, path = L.rooms_scene(plan, A["q"], A["ext"], -info["floor_z"], CLEAR)
    start, goal = rounded_pose(start), rounded_pose(goal)
    path = [start] + path[1:-1] + [goal]
    bounds = ((0.0, 0.0, 0.3), (plan.X1, plan.Y_HALL, 2.3))
    n_rooms = {}
    for detailed, env_name in ((False, "piano_rooms"), (True, "piano_rooms_detailed")):
        env = L.piano_rooms(plan, detailed)
        n_env = n_rooms[detailed] = check_parts(env.parts, env_name)
        if detailed:
            assert 10000 <= n_env <= 20000, n_env
        else:
            near_target(env_name, n_env)
        overlap_check(env)
        for pose in (start, goal):
            clear_of(parts, pose, env.boxes, 0.02)
        t, hit = straight_line_hit(robot, start, goal, env.boxes)
        log("%-21s %6d triangles, %3d parts; start/goal clear; straight line hits %s at "
            "t = %.2f" % (env_name, n_env, len(env.parts), hit[0], t))
        ml.write_obj(os.path.join(ENVS, env_name + ".obj"), env.parts,
                     "%s: environment of scenes/%s.yaml, written by robots/piano/generate.py."
                     "\nUnits: metres, z up, floor top at z = 0; walls 0.15 m thick, 2.6 m "
                     "high. %d triangles, one object per part." % (
                         env_name, "piano" if not detailed else "piano_detailed", n_env))
    sz = info["size"]
    common = (
        "Doorway D1 (living room to hall) is %.2f m wide x %.2f m high in a %.2f m wall; "
        "D2 (hall to music room) is %.2f m wide. Upright the piano is %.3f m wide, and "
        "lying on its straight side it is %.3f m thick, so it passes neither way. Its "
        "least width is %.3f m: lying on its side, tilted %.0f deg across and %.0f deg "
        "along its length (least-width direction (%.3f, %.3f, %.3f) in the piano's frame), "
        "where it is %.3f m high when it travels lengthwise. D1 leaves %.1f cm of width to "
        "spare (%.1f cm a side) and %.0f cm of height; tilting the least-width direction by "
        "one degree costs up to %.1f cm of width. The 3.0 m deep hall then takes the %.2f m long piano on its "
        "side." % (w1, L.DOOR_H, L.T, w2, A["upright_w"], A["side_t"], A["w"], A["tilt_x"],
                   A["tilt_y"], A["a"][0], A["a"][1], A["a"][2], A["h"],
                   100 * (w1 - A["w"]), 50 * (w1 - A["w"]), 100 * (L.DOOR_H - A["h"]),
                   100 * (A["w_1deg"] - A["w"]), A["len"]))
    desc = (
        "A grand piano (rigid, %.2f m wide x %.2f m long x %.2f m high with its lid propped "
        "open at %g deg, %d triangles) is moved from the living room of a flat into the "
        "music room next door. The two rooms share a solid wall, which the straight line "
        "runs through; the way round is through doorway D1 into the hall, along the hall "
        "and through doorway D2 into the music room, both doorways narrower than the "
        "piano in any upright or plain side-lying pose. Start and goal hover %d cm above "
        "the floor." % (sz[0], sz[1], sz[2], LID_ANGLE_DEG, n_piano, round(100 * CLEAR)))
    write_scene("piano", desc + " Walls, fittings and built-in furniture only (%d "
                "triangles)." % n_rooms[False], common, "piano.obj", "piano_rooms.obj",
                bounds, start, goal)
    write_scene("piano_detailed", desc + " The detailed version (%d triangles): walls finely "
                "tessellated and the rooms furnished (sofas, tables, chairs, bookshelves, "
                "lamps, beds)." % n_rooms[True], common, "piano.obj",
                "piano_rooms_detailed.obj", bounds, start, goal)
    witness.append(("piano", path))
    witness.append(("piano_detailed", path))

    # ---- large_piano_house
    parts, info, n_piano = pianos["large_piano"]
    A = info
    wa, wb = round(A["w"] + A_SPARE, 2), round(A["w"] + B_SPARE, 2)
    assert A["w"] + 0.04 < wa < wb < A["upright_w"] and wa < A["side_t"] + 0.02
    plan = L.HousePlan(wa, wb)
    robot = ps.Robot(parts)
    start, goal, path = L.house_scene(plan, A["q"], A["ext"], -info["floor_z"], CLEAR)
    start, goal = rounded_pose(start), rounded_pose(goal)
    path = [start] + path[1:-1] + [goal]
    env = L.house(plan)
    n_env = check_parts(env.parts, "large_piano_house")
    near_target("large_piano_house", n_env)
    overlap_check(env)
    for pose in (start, goal):
        clear_of(parts, pose, env.boxes, 0.02)
    t, hit = straight_line_hit(robot, start, goal, env.boxes)
    log("%-21s %6d triangles, %3d parts; start/goal clear; straight line hits %s at t = %.2f"
        % ("large_piano_house", n_env, len(env.parts), hit[0], t))
    ml.write_obj(os.path.join(ENVS, "large_piano_house.obj"), env.parts,
                 "large_piano_house: environment of scenes/large_piano.yaml, written by "
                 "robots/piano/generate.py.\nUnits: metres, z up, floor top at z = 0; walls "
                 "0.15 m thick, 2.6 m high; stairwell opening in the ceiling over the stairs. "
                 "%d triangles, one object per part." % n_env)
    hall_free = plan.STAIR_Y[0] - (plan.Y_S + L.T)
    sz = info["size"]
    write_scene(
        "large_piano",
        "A detailed grand piano (rigid, %.2f m wide x %.2f m long x %.2f m high with its lid "
        "open at %g deg and the music desk up, on casters; %d triangles) is moved through a "
        "furnished house (%d triangles) from the living room to the music room. Living "
        "room, dining room and music room lie side by side; the ways between them (a %.1f m "
        "opening and a %.1f m door) are far too narrow, and the straight line runs through "
        "their walls. The piano must go through doorway A into the hall, past the "
        "staircase, and through doorway B into the music room. Start and goal hover %d cm "
        "above the floor." % (sz[0], sz[1], sz[2], LID_ANGLE_DEG, n_piano, n_env, 1.2,
                               L.SMALL_DOOR, round(100 * CLEAR)),
        "Doorway A (living room to hall) is %.2f m wide x %.2f m high in a %.2f m wall; "
        "doorway B (hall to music room) is %.2f m wide. Upright the piano is %.3f m wide, "
        "and lying on its side %.3f m thick; its least width is %.3f m, lying on its side "
        "tilted %.0f deg across and %.0f deg along its length, where it is %.3f m high "
        "travelling lengthwise: A leaves %.1f cm of width to spare (%.1f cm a side). Beside "
        "the staircase the hall is %.2f m deep for the %.2f m long piano on its side."
        % (wa, L.DOOR_H, L.T, wb, A["upright_w"], A["side_t"], A["w"], A["tilt_x"],
           A["tilt_y"], A["h"], 100 * (wa - A["w"]), 50 * (wa - A["w"]), hall_free,
           A["len"]),
        "large_piano.obj", "large_piano_house.obj",
        ((0.0, 0.0, 0.3), (plan.X1, plan.Y_N, 2.3)), start, goal)
    witness.append(("large_piano", path))

    # ---- witness paths
    with open(os.path.join(HERE, "witness_paths.yaml"), "w") as f:
        f.write("# A collision-free path for each piano scene, written by generate.py and\n"
                "# certified by check.py (clearance >= 1 cm at samples no robot point moves\n"
                "# more than 2 cm between). Waypoints [x, y, z, qw, qx, qy, qz]; between\n"
                "# waypoints the pose moves linearly in position and by slerp in rotation.\n")
        for name, pth in witness:
            f.write("%s:\n" % name)
            for p, q in pth:
                q = ml.quat_normalize(q)
                f.write("  - [%s]\n" % ", ".join("%.7f" % x for x in tuple(p) + tuple(q)))
    log("wrote robots/piano/{piano,large_piano}.obj, witness_paths.yaml, scenes/{piano,"
        "piano_detailed,large_piano}.yaml and their environments")


if __name__ == "__main__":
    main()
