#!/usr/bin/env python3
"""Authoring checks of the helicopter robot and scenes/helicopter.yaml (standard
library only). Reads the shipped files (helicopter.dae, helicopter_city.obj,
helicopter.yaml) and asserts:
  * triangle counts near the targets, closed outward meshes, the robot's bounding box;
    the city's objects are the generator's solids;
  * start and goal at least 1 m inside the bounds;
  * the narrowest passage's figures (level widths, yaw window, fraction of rotations
    that fit the slot's cross-section) are those the scene states, and they make a
    narrow passage; the ceiling keeps the helicopter from flying over the skybridge,
    and the wall's alleys are narrower than the helicopter's smallest width, so the
    slot is the only way through;
  * the planner section's rotation weight is the helicopter's radius.

Start and goal free, the straight line colliding and a path existing are the C++
tests' (tests/planner/shipped_scenes_test.cpp, tests/apps/gplan_plan_test.cpp).

Usage: python3 robots/helicopter/check.py   (from anywhere)
"""

import math
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.dirname(HERE)]

import generate as gen  # noqa: E402
import meshlib as ml  # noqa: E402


def main():
    heli = ml.read_dae(gen.DAE_PATH)
    city = ml.read_obj(gen.OBJ_PATH)
    scene = ml.read_yaml(gen.YAML_PATH)
    b_min, b_max = scene["bounds"]["min"], scene["bounds"]["max"]
    passage = scene["narrowest_passage"]
    world = gen.city_parts()
    solids = world.boxes + world.others   # (name, lo, hi)

    # ---- meshes
    n_heli = sum(len(m) for _, m in heli)
    n_city = sum(len(m) for _, m in city)
    print("helicopter.dae: %d triangles, %d nodes" % (n_heli, len(heli)))
    print("helicopter_city.obj: %d triangles, %d objects" % (n_city, len(city)))
    assert abs(n_heli - 3600) <= 360, n_heli
    assert abs(n_city - 2800) <= 280, n_city
    for name, m in heli + city:
        ml.check_closed(m, name, min_area=1e-7)
    V = [v for _, m in heli for v in m.vertices]
    lo, hi = ml.point_bounds(V)
    size = [hi[i] - lo[i] for i in range(3)]
    print("helicopter bbox size %.3f x %.3f x %.3f m, centre %s; meshes closed and outward"
          % (size[0], size[1], size[2], ["%.4f" % ((lo[i] + hi[i]) / 2) for i in range(3)]))
    assert all(abs(lo[i] + hi[i]) < 1e-4 for i in range(3)), "origin not at bbox centre"
    assert 11.5 < size[0] < 13.5 and 3.5 < size[2] < 5.5
    rmax = max(ml.norm(v) for v in V)
    print("helicopter radius (max |v|): %.3f m" % rmax)
    # the city's objects are the solids the figures below are computed on
    names = [n for n, _ in city]
    assert len(set(names)) == len(names)
    for name, m in city:
        mlo, mhi = ml.point_bounds(m.vertices)
        plo = [min(s[1][i] for s in solids if s[0] == name) for i in range(3)]
        phi = [max(s[2][i] for s in solids if s[0] == name) for i in range(3)]
        assert all(abs(mlo[i] - plo[i]) < 1e-4 and abs(mhi[i] - phi[i]) < 1e-4
                   for i in range(3)), name

    # ---- bounds
    for label in ("start", "goal"):
        p = scene[label]["base"]["xyz"]
        assert all(b_min[i] + 1.0 <= p[i] <= b_max[i] - 1.0 for i in range(3)), label
    print("start and goal at least 1 m inside the bounds")

    # ---- the passage figures
    width = gen.GAP_Y1 - gen.GAP_Y0
    wmin, window = gen.level_yaw_window(V, width)
    wmax = gen.level_width_max(V)
    print("slot %.2f m wide x %.2f m high; level width %.3f..%.3f m; yaw window +-%.1f deg"
          % (width, gen.SKY_Z0, wmin, wmax, window))
    assert "%.2f m wide" % width in passage and "%.2f m high" % gen.SKY_Z0 in passage
    assert "%.2f to %.2f m wide" % (wmin, wmax) in passage
    assert "+-%.0f deg of yaw" % window in passage
    # narrow: the level helicopter fits the slot only over a range of yaws (not
    # sideways), the helicopter on its side is taller than the slot; but the level
    # helicopter fits with room to spare in both directions (a passage PRM can find)
    assert wmin + 2.0 < width < wmax - 1.0, "the slot's width is not a narrow passage"
    assert 20.0 < window < 60.0, window
    assert size[2] + 2.0 < gen.SKY_Z0 < size[1], "the slot's height is not a narrow passage"
    # support function over directions (Lipschitz in the direction with constant rmax,
    # so a grid of spacing ~delta errs by at most rmax * delta)
    U = list({tuple(round(x, 4) for x in v) for v in V})
    dirs = ml.fibonacci_directions(12000)
    delta = math.sqrt(4 * math.pi / len(dirs))
    supp = [max(ml.dot(d, v) for v in U) for d in dirs]
    err = rmax * delta
    h_min = min(supp) - err
    widths = [supp[k] + max(-ml.dot(d, v) for v in U)
              for k, d in enumerate(dirs[:len(dirs) // 2 + 1])]
    w_min_any = min(widths) - 2 * err
    print("smallest reach from the centre in any direction >= %.3f m; smallest width "
          "in any orientation >= %.3f m" % (h_min, w_min_any))
    # over the skybridge: the lowest point is at most b_max.z - h_min
    assert b_max[2] - h_min < gen.SKY_Z1 - 0.3, "the helicopter could fly over the bridge"
    # the wall: spans the bounds in y beyond the helicopter's reach, and its alleys
    # (at heights the helicopter can reach) are narrower than the helicopter
    reach_top = b_max[2] + rmax
    wall = [s for s in world.boxes if s[0].startswith("wall_tower")]
    assert min(s[1][1] for s in wall) < b_min[1] - rmax - 1
    assert max(s[2][1] for s in wall) > b_max[1] + rmax + 1
    towers = sorted({s[0] for s in wall}, key=lambda n: min(s[1][1] for s in wall
                                                           if s[0] == n))
    for tname in towers:
        base = [s for s in wall if s[0] == tname and s[1][2] <= 0.0]
        assert len(base) == 1, tname
        blo, bhi = base[0][1], base[0][2]
        # the ground tier spans the wall's whole depth and is higher than the
        # helicopter's lowest point can ever be
        assert blo[0] <= gen.WALL_X0 and bhi[0] >= gen.WALL_X1, tname
        assert bhi[2] > b_max[2] - h_min + 1.0, tname
    widest = 0.0
    for a, b in zip(towers, towers[1:]):
        if (a, b) == ("wall_tower_s4", "wall_tower_n1"):
            continue  # the slot itself
        for zc in [0.5 * k for k in range(int(reach_top * 2) + 1)]:
            ya = max(s[2][1] for s in wall if s[0] == a and s[1][2] <= zc <= s[2][2])
            yb = min(s[1][1] for s in wall if s[0] == b and s[1][2] <= zc <= s[2][2])
            widest = max(widest, yb - ya)
    print("widest other opening in the wall below %.1f m: %.2f m" % (reach_top, widest))
    assert widest < w_min_any - 0.5
    # roughly how much of SO(3) fits the slot's cross-section (sampled here
    # independently of the generator's figure, on a subset of the vertices)
    rng = random.Random(11)
    U2 = U[::3]
    fit = 0
    N = 3000
    for _ in range(N):
        u1, u2, u3 = rng.random(), rng.random(), rng.random()
        q = (math.sqrt(1 - u1) * math.sin(2 * math.pi * u2),
             math.sqrt(1 - u1) * math.cos(2 * math.pi * u2),
             math.sqrt(u1) * math.sin(2 * math.pi * u3),
             math.sqrt(u1) * math.cos(2 * math.pi * u3))
        R = ml.quat_matrix(q)
        ys = [ml.dot(R[1], v) for v in U2]
        zs = [ml.dot(R[2], v) for v in U2]
        if max(ys) - min(ys) < width and max(zs) - min(zs) < gen.SKY_Z0:
            fit += 1
    stated = float(passage.split("only about ")[1].split("%")[0])
    print("rotations whose y/z extents fit the slot: %.1f%% (%d samples; the scene "
          "states about %.0f%%)" % (100.0 * fit / N, N, stated))
    # a narrow passage (most rotations do not fit), several times less narrow than
    # the 8.8 x 7.0 m slot the planner could not find (2%)
    assert 0.06 < fit / N < 0.15, fit / N
    assert abs(100.0 * fit / N - stated) < 2.0, "the scene's fraction is off"
    # the metric weighs rotation by the helicopter's radius
    w_rot = scene["planner"]["distance_weights"]["rotation"]
    print("planner: rotation weight %.1f (helicopter radius %.3f m)" % (w_rot, rmax))
    assert rmax <= w_rot < rmax + 0.1, w_rot
    print("all checks passed")


if __name__ == "__main__":
    main()
