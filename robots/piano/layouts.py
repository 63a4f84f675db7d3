"""Floor plans of the piano scenes, start and goal poses, and witness paths.

World frame: z up, floor top at z = 0, walls 0.15 m thick and 2.6 m high, a floor slab
below and a ceiling slab above. Doorway sizes come from the piano's smallest
cross-section (passage.py), so the narrow passages are a few cm wider than the piano
in its best orientation.
"""

import math

import envlib as E
import meshlib as ml

T = 0.15            # wall thickness
WALL_H = 2.6        # wall height (floor to ceiling)
DOOR_H = 2.0        # height of the piano doorways
SMALL_DOOR = 0.9    # ordinary doors (too narrow for the piano)
SMALL_DOOR_H = 2.1


def yaw_quat(deg):
    return ml.quat_axis((0, 0, 1), math.radians(deg))


def upright_near(q):
    """The upright heading (0 or 180 deg) from which q is the smaller turn: the piano
    turns to it on the floor, then rolls over onto its side about its long axis."""
    return min((ml.quat_angle(yaw_quat(d), q), d) for d in (0, 180))[1]


def turn(pos, yaw_from, yaw_to, step=90):
    """Waypoints turning an upright piano in place, at most `step` deg at a time."""
    n = max(1, int(math.ceil(abs(yaw_to - yaw_from) / step - 1e-9)))
    return [(pos, yaw_quat(yaw_from + (yaw_to - yaw_from) * k / n)) for k in range(1, n + 1)]


# ---------------------------------------------------------------- piano_rooms


class RoomsPlan:
    """Living room (start), hall, music room (goal); three small rooms north of the
    hall behind ordinary doors."""
    X1 = 12.15                  # interior x: 0 .. X1
    Y_MID = 5.0                 # wall between the rooms and the hall: Y_MID .. Y_MID + T
    Y_HALL = 8.15               # hall: Y_MID + T .. Y_HALL
    Y1 = 11.30                  # north rooms: Y_HALL + T .. Y1
    X_LM = 6.0                  # wall between living room and music room
    D1_X = 3.0                  # centre of doorway D1 (living room -> hall)
    D2_X = 9.2                  # centre of doorway D2 (hall -> music room)

    def __init__(self, w1, w2):
        self.w1, self.w2 = w1, w2
        self.d1 = (self.D1_X - w1 / 2, self.D1_X + w1 / 2)
        self.d2 = (self.D2_X - w2 / 2, self.D2_X + w2 / 2)


def piano_rooms(plan, detailed=False, cell=0.35):
    P = plan
    env = E.Env(cell=cell if detailed else None)
    X1, Y1, H = P.X1, P.Y1, WALL_H
    slab = dict(tessellate=False)
    env.box("floor", (-T, -T, -0.10), (X1 + T, Y1 + T, 0.0), **slab)
    env.box("ceiling", (-T, -T, H), (X1 + T, Y1 + T, H + 0.10), **slab)
    env.box("wall_south", (-T, -T, 0), (X1 + T, 0, H))
    env.box("wall_north", (-T, Y1, 0), (X1 + T, Y1 + T, H))
    env.box("wall_west", (-T, 0, 0), (0, Y1, H))
    env.box("wall_east", (X1, 0, 0), (X1 + T, Y1, H))
    env.box("wall_living_music", (P.X_LM, 0, 0), (P.X_LM + T, P.Y_MID, H))
    env.wall_x("wall_hall_south", 0, X1, P.Y_MID, P.Y_MID + T, H,
               doors=[(P.d1[0], P.d1[1], DOOR_H), (P.d2[0], P.d2[1], DOOR_H)])
    # north rooms: bedroom (x 0..4.5), bathroom (4.65..8.0), kitchen (8.15..X1)
    yh = P.Y_HALL
    doors_n = [(2.2, "bedroom"), (6.3, "bathroom"), (10.0, "kitchen")]
    env.wall_x("wall_hall_north", 0, X1, yh, yh + T, H,
               doors=[(x - SMALL_DOOR / 2, x + SMALL_DOOR / 2, SMALL_DOOR_H) for x, _ in doors_n])
    env.box("wall_bedroom_bathroom", (4.5, yh + T, 0), (4.5 + T, Y1, H))
    env.box("wall_bathroom_kitchen", (8.0, yh + T, 0), (8.0 + T, Y1, H))
    for x, room in doors_n:          # door leaves, opened 90 deg into the rooms
        xa = x + SMALL_DOOR / 2
        env.box("door_" + room, (xa - 0.04, yh + T, 0.01), (xa, yh + T + SMALL_DOOR - 0.04, 2.08))
    # living room: fireplace (chimney breast, hearth, mantel), radiator, built-in cabinet
    env.box("chimney_breast", (0, 1.7, 0), (0.45, 3.3, H))
    env.box("hearth", (0.45, 1.8, 0), (0.95, 3.2, 0.04))
    env.box("mantel", (0.45, 1.6, 1.15), (0.62, 3.4, 1.25))
    env.box("radiator_living", (1.6, 0, 0.15), (3.2, 0.10, 0.75))
    env.box("cabinet_living", (5.55, 0.4, 0), (6.0, 1.9, 0.9))
    # music room: bookshelves along the east wall, radiator
    env.box("shelves_music", (11.75, 0.6, 0), (X1, 4.3, 2.3))
    env.box("radiator_music", (7.6, 0, 0.15), (9.2, 0.10, 0.75))
    # hall: coat cupboard by the west wall, console by the north wall
    env.box("coat_cupboard", (0, 7.45, 0), (0.9, yh, 2.2))
    env.box("console_hall", (3.6, yh - 0.4, 0), (4.8, yh, 0.85))
    # north rooms: wardrobe, bathtub, basin, kitchen counters and wall cupboards
    env.box("wardrobe", (0, 9.2, 0), (0.62, 11.0, 2.2))
    env.box("bathtub", (4.65, Y1 - 0.75, 0), (6.4, Y1, 0.55))
    env.box("basin", (7.4, Y1 - 0.5, 0), (8.0, Y1, 0.85))
    env.box("counter_north", (8.15, Y1 - 0.6, 0), (X1, Y1, 0.9))
    env.box("counter_east", (X1 - 0.6, yh + T + 0.9, 0), (X1, Y1 - 0.6, 0.9))
    env.box("cupboards_north", (8.15, Y1 - 0.35, 1.5), (X1, Y1, 2.2))
    # window sills, a hall radiator, bathroom and kitchen fittings
    env.box("sill_living", (1.5, 0, 0.85), (3.3, 0.2, 0.89))
    env.box("sill_music", (7.5, 0, 0.85), (9.3, 0.2, 0.89))
    env.box("sill_bedroom", (0.8, Y1 - 0.2, 0.85), (2.6, Y1, 0.89))
    env.box("radiator_hall", (5.0, yh - 0.10, 0.15), (5.8, yh, 0.75))
    env.box("toilet", (7.45, yh + T + 1.0, 0), (8.0, yh + T + 1.45, 0.42))
    env.box("shower_tray", (4.65, yh + T, 0), (5.55, yh + T + 0.9, 0.08))
    env.box("fridge", (X1 - 0.65, yh + T, 0), (X1, yh + T + 0.7, 1.85))
    env.box("cooker_hood", (9.8, Y1 - 0.5, 1.7), (10.4, Y1 - 0.35, 2.0))
    # skirting boards in the hall, the living room and the music room
    sk = 0.10
    hall_s = [(0, P.d1[0]), (P.d1[1], P.d2[0]), (P.d2[1], X1)]
    for xa, xb in hall_s:
        env.box("skirting_hall", (xa, P.Y_MID + T, 0), (xb, P.Y_MID + T + 0.02, sk))
    env.box("skirting_living", (0.9, 0, 0), (1.6, 0.02, sk))
    env.box("skirting_living", (P.X_LM - 0.02, 1.9, 0), (P.X_LM, P.Y_MID, sk))
    env.box("skirting_music", (P.X_LM + T, 0, 0), (P.X_LM + T + 0.02, P.Y_MID, sk))
    env.box("skirting_music", (9.2, 0, 0), (X1, 0.02, sk))
    if detailed:
        furnish_rooms(env, P)
    return env


def furnish_rooms(env, P):
    """Furniture of the detailed version, kept off the witness path."""
    yh = P.Y_HALL
    # living room (the piano turns in the middle and leaves through D1 at x 2.3..3.7)
    env.item("sofa", E.sofa(0.5, 4.2, w=1.4, seats=2, yaw=-1))
    env.item("armchair", E.sofa(5.0, 4.25, w=0.95, seats=1, yaw=2))
    env.item("coffee_table", E.table(4.95, 3.3, 0.9, 0.5, h=0.42))
    env.item("floor_lamp", E.floor_lamp(0.3, 1.2))
    env.item("plant", E.plant(4.7, 0.4))
    env.item("bookshelf", E.bookshelf(0.95, 0.2, w=1.1, d=0.3, h=1.9))
    # music room (the piano comes in through D2 at x 8.5..9.9 and turns at 9.1, 2.4)
    env.item("piano_bench", E.table(10.6, 4.45, 0.8, 0.35, h=0.5))
    env.item("desk", E.table(7.0, 4.45, 1.4, 0.7))
    env.item("desk_chair", E.chair(7.0, 3.8, yaw=2))
    env.item("armchair", E.sofa(11.3, 0.75, w=0.95, seats=1, yaw=1))
    env.item("floor_lamp", E.floor_lamp(11.4, 4.6))
    env.item("side_table", E.round_table(6.8, 0.75, r=0.45))
    env.item("chair", E.chair(7.5, 0.55, yaw=1))
    env.item("plant", E.plant(10.2, 0.45))
    # hall: the piano crosses it between x 2.3 and 9.9
    env.item("plant", E.plant(11.7, 5.6))
    env.item("bench_hall", E.table(11.2, yh - 0.2, 1.2, 0.36, h=0.45))
    env.item("console_hall", E.table(1.6, yh - 0.2, 1.1, 0.36, h=0.8))
    # bedroom, bathroom, kitchen
    env.item("bed", E.bed(3.6, 10.1, yaw=2))
    env.item("bedside_table", E.cabinet(2.45, 10.95, 0.45, 0.4, 0.55, yaw=2, doors=1))
    env.item("bath_cabinet", E.cabinet(4.87, 9.9, 0.9, 0.4, 0.8, yaw=-1))
    env.item("dining_table", E.table(9.9, 9.8, 1.6, 0.9))
    for cx, cy, yaw in ((9.5, 10.45, 2), (10.3, 10.45, 2), (8.85, 9.8, -1), (10.95, 9.8, 1)):
        env.item("kitchen_chair", E.chair(cx, cy, yaw=yaw))


def rooms_scene(plan, q_pass, extents_pass, center_height, clear=0.03):
    """Start, goal and witness path of piano_rooms. extents_pass: (lo, hi) of the
    piano's vertices at q_pass relative to its centre."""
    P = plan
    lo, hi = extents_pass
    z_pass = DOOR_H / 2 - (lo[2] + hi[2]) / 2
    x1 = P.D1_X - (lo[0] + hi[0]) / 2
    x2 = P.D2_X - (lo[0] + hi[0]) / 2
    y_hall = (P.Y_MID + T + P.Y_HALL) / 2 - (lo[1] + hi[1]) / 2
    z_floor = center_height + clear
    start = ((2.9, 2.3, z_floor), yaw_quat(90))
    goal = ((9.1, 2.4, z_floor), yaw_quat(180))
    up = upright_near(q_pass)
    path = ([start] + turn((2.9, 2.5, 1.30), 90, up) +
            [((2.9, 2.5, 1.30), q_pass),
             ((x1, 2.5, z_pass), q_pass),
             ((x1, y_hall, z_pass), q_pass),
             ((x2, y_hall, z_pass), q_pass),
             ((x2, 2.5, z_pass), q_pass),
             ((9.1, 2.5, 1.30), q_pass),
             ((9.1, 2.5, 1.30), yaw_quat(up))] +
            turn((9.1, 2.45, 1.0), up, 180)[:-1] + [goal])
    return start, goal, path


# ---------------------------------------------------------------- large_piano_house


class HousePlan:
    """Ground floor of a house: living room (start), dining room and music room (goal)
    along the south side, a hall with the staircase, kitchen, WC, study and utility
    room along the north side."""
    X1, Y1 = 16.0, 12.0          # interior
    Y_S = 6.0                    # hall south wall: Y_S .. Y_S + T
    Y_N = 9.75                   # hall north wall: Y_N .. Y_N + T
    X_LD, X_DM = 7.0, 10.5       # living | dining | music walls
    A_X, B_X = 3.0, 13.3         # centres of the piano doorways A (living) and B (music)
    STAIR_X = (8.3, 12.5)        # staircase along the hall's north wall, rising east
    STAIR_Y = (8.75, 9.75)
    WELL_X0 = 9.2                # stairwell opening in the ceiling: WELL_X0 .. STAIR_X[1]

    def __init__(self, wa, wb):
        self.wa, self.wb = wa, wb
        self.da = (self.A_X - wa / 2, self.A_X + wa / 2)
        self.db = (self.B_X - wb / 2, self.B_X + wb / 2)


def _strip_bounds(mesh, xa, xb):
    """Bounding box of the part of a convex mesh with xa <= x <= xb (from its corners
    in the strip and its edges crossing the strip's sides)."""
    pts = [v for v in mesh.vertices if xa <= v[0] <= xb]
    for a, b, c in mesh.triangles:
        for i, j in ((a, b), (b, c), (c, a)):
            p, q = mesh.vertices[i], mesh.vertices[j]
            for x in (xa, xb):
                if (p[0] - x) * (q[0] - x) < 0:
                    t = (x - p[0]) / (q[0] - p[0])
                    pts.append(tuple(p[k] + t * (q[k] - p[k]) for k in range(3)))
    lo = tuple(min(p[k] for p in pts) - 1e-4 for k in range(3))
    hi = tuple(max(p[k] for p in pts) + 1e-4 for k in range(3))
    return lo, hi


def staircase(env, P, steps=14):
    x0, x1 = P.STAIR_X
    y0, y1 = P.STAIR_Y
    run = (x1 - x0) / steps
    rise = WALL_H / steps
    for k in range(steps):
        env.box("stair_step", (x0 + k * run, y0, 0), (x0 + (k + 1) * run, y1, (k + 1) * rise))
        # nosing: a thin tread lip over the riser
        env.box("stair_nosing", (x0 + k * run - 0.03, y0, (k + 1) * rise - 0.025),
                (x0 + k * run, y1, (k + 1) * rise))
        # baluster on each tread, along the open (south) side
        bx = x0 + (k + 0.5) * run
        env.box("stair_baluster", (bx - 0.02, y0 + 0.02, (k + 1) * rise),
                (bx + 0.02, y0 + 0.06, (k + 1) * rise + 0.88))
    env.box("stair_newel", (x0 - 0.145, y0, 0), (x0 - 0.035, y0 + 0.11, 1.1))
    # handrail: a sloped bar over the balusters, from the newel to the upper floor
    length = math.hypot(x1 - x0, WALL_H)
    pitch = math.atan2(WALL_H, x1 - x0)
    rail = ml.box((length, 0.06, 0.05), (0, 0, 0)).transformed(
        xyz=((x0 + x1) / 2 - 0.06, y0 + 0.04, WALL_H / 2 + 0.92), rpy=(0, -pitch, 0))
    lo, hi = rail.bounds()
    boxes = [_strip_bounds(rail, lo[0] + k * (hi[0] - lo[0]) / steps,
                           lo[0] + (k + 1) * (hi[0] - lo[0]) / steps) for k in range(steps)]
    env.item("stair_handrail", [(rail, boxes)])
    # the upper floor's balustrade round the stairwell (above the ceiling)
    zt = WALL_H + 0.10
    env.box("balustrade_rail", (P.WELL_X0, y0 - 0.05, zt + 0.85), (x1, y0, zt + 0.90))
    env.box("balustrade_post", (P.WELL_X0, y0 - 0.05, zt), (P.WELL_X0 + 0.08, y0, zt + 0.85))
    env.box("balustrade_post", (P.WELL_X0 - 0.05, y0, zt), (P.WELL_X0, y1, zt + 0.90))


def house(plan, cell=0.5):
    P = plan
    env = E.Env(cell=cell)
    X1, Y1, H = P.X1, P.Y1, WALL_H
    slab = dict(tessellate=False)
    env.box("floor", (-T, -T, -0.10), (X1 + T, Y1 + T, 0.0), **slab)
    sx0, sx1 = P.WELL_X0, P.STAIR_X[1]
    sy0, sy1 = P.STAIR_Y
    env.box("ceiling", (-T, -T, H), (X1 + T, sy0, H + 0.10), **slab)
    env.box("ceiling", (-T, sy1, H), (X1 + T, Y1 + T, H + 0.10), **slab)
    env.box("ceiling", (-T, sy0, H), (sx0, sy1, H + 0.10), **slab)
    env.box("ceiling", (sx1, sy0, H), (X1 + T, sy1, H + 0.10), **slab)
    env.box("wall_south", (-T, -T, 0), (X1 + T, 0, H))
    env.box("wall_north", (-T, Y1, 0), (X1 + T, Y1 + T, H))
    env.box("wall_west", (-T, 0, 0), (0, Y1, H))
    env.box("wall_east", (X1, 0, 0), (X1 + T, Y1, H))
    env.wall_y("wall_living_dining", 0, P.Y_S, P.X_LD, P.X_LD + T, H,
               doors=[(2.4, 3.6, SMALL_DOOR_H)])          # 1.2 m opening: too narrow
    env.wall_y("wall_dining_music", 0, P.Y_S, P.X_DM, P.X_DM + T, H,
               doors=[(1.05, 1.95, SMALL_DOOR_H)])
    env.wall_x("wall_hall_south", 0, X1, P.Y_S, P.Y_S + T, H,
               doors=[(P.da[0], P.da[1], DOOR_H), (P.db[0], P.db[1], DOOR_H),
                      (9.4, 10.3, SMALL_DOOR_H)])
    yn = P.Y_N
    north_doors = [(2.0, "kitchen"), (5.8, "wc"), (7.7, "study"), (13.6, "utility")]
    env.wall_x("wall_hall_north", 0, X1, yn, yn + T, H,
               doors=[(x - SMALL_DOOR / 2, x + SMALL_DOOR / 2, SMALL_DOOR_H)
                      for x, _ in north_doors])
    for x0 in (4.5, 7.0, 11.0):
        env.box("wall_north_rooms", (x0, yn + T, 0), (x0 + T, Y1, H))
    for x, room in north_doors:           # door leaves, opened into the rooms
        xa = x + SMALL_DOOR / 2
        env.box("door_" + room, (xa - 0.04, yn + T, 0.01), (xa, yn + T + SMALL_DOOR - 0.04, 2.08))
    env.box("door_dining", (10.3 - 0.04, P.Y_S - SMALL_DOOR + 0.04, 0.01), (10.3, P.Y_S, 2.08))
    staircase(env, P)
    # fixtures
    env.box("chimney_breast", (0, 1.5, 0), (0.45, 3.0, H))
    env.box("hearth", (0.45, 1.6, 0), (0.95, 2.9, 0.04))
    env.box("mantel", (0.45, 1.4, 1.15), (0.62, 3.1, 1.25))
    for name, xa, xb in (("living", 4.0, 5.2), ("dining", 8.0, 9.6), ("music", 11.2, 12.2)):
        env.box("radiator_" + name, (xa, 0, 0.15), (xb, 0.10, 0.75))
        env.box("sill_" + name, (xa - 0.1, 0, 0.85), (xb + 0.1, 0.2, 0.89))
    env.box("radiator_hall", (0.6, yn - 0.10, 0.15), (1.5, yn, 0.75))
    furnish_house(env, P)
    return env


def furnish_house(env, P):
    yn, Y1, X1 = P.Y_N, P.Y1, P.X1
    # living room: the piano turns round (3.2, 3.0) and leaves through A (x 2.3..3.7)
    env.item("sofa", E.sofa(0.5, 4.9, w=1.9, yaw=-1))
    env.item("coffee_table", E.table(1.45, 4.9, 1.0, 0.5, h=0.42, yaw=1))
    env.item("armchair", E.sofa(5.4, 5.45, w=0.95, seats=1, yaw=2))
    env.item("armchair", E.sofa(6.45, 3.6, w=0.95, seats=1, yaw=1))
    env.item("side_table", E.round_table(5.6, 4.3, r=0.35))
    env.item("tv_cabinet", E.cabinet(2.6, 0.3, 1.8, 0.45, 0.55, doors=3))
    env.item("bookshelf", E.bookshelf(6.55, 1.2, w=1.2, d=0.35, h=2.1, yaw=1))
    env.item("floor_lamp", E.floor_lamp(0.35, 0.45))
    env.item("plant", E.plant(5.7, 0.45))
    # dining room
    env.item("dining_table", E.table(8.75, 3.2, 0.95, 1.9))
    for cy in (2.6, 3.2, 3.8):
        env.item("dining_chair", E.chair(8.0, cy, yaw=-1))
        env.item("dining_chair", E.chair(9.5, cy, yaw=1))
    env.item("sideboard", E.cabinet(8.2, 5.7, 1.6, 0.45, 0.85, yaw=2, doors=3))
    env.item("plant", E.plant(10.1, 0.45))
    # music room: the piano comes in through B (x 12.55..14.05) and turns at (13.3, 2.9)
    env.item("shelves_music", E.bookshelf(15.8, 3.0, w=2.4, d=0.35, h=2.2, shelves=6, yaw=1))
    env.item("armchair", E.sofa(11.25, 4.6, w=0.95, seats=1, yaw=-1))
    env.item("side_table", E.round_table(11.2, 3.4, r=0.3))
    env.item("piano_bench", E.table(15.2, 5.5, 0.8, 0.35, h=0.5))
    env.item("floor_lamp", E.floor_lamp(15.6, 0.4))
    env.item("music_chair", E.chair(11.2, 1.0, yaw=1))
    env.item("plant", E.plant(14.9, 0.45))
    # hall: the piano crosses it between x 2.3 and 14.05, y 6.3 .. 8.6
    env.item("console_hall", E.table(2.3, yn - 0.2, 1.2, 0.36, h=0.8))
    env.item("plant", E.plant(15.6, 6.55))
    env.item("bench_hall", E.table(15.8, 8.2, 0.36, 1.2, h=0.45))
    # kitchen
    env.box("kitchen_counter", (0, Y1 - 0.6, 0), (4.5, Y1, 0.9))
    env.box("kitchen_counter", (0, yn + 0.15 + 1.2, 0), (0.6, Y1 - 0.6, 0.9))
    env.box("kitchen_cupboards", (0, Y1 - 0.35, 1.5), (4.5, Y1, 2.2))
    env.box("fridge", (3.8, yn + 0.15, 0), (4.5, yn + 0.85, 1.85))
    env.item("kitchen_island", E.cabinet(3.2, 10.95, 1.4, 0.6, 0.9, doors=2))
    # WC
    env.box("toilet", (6.25, Y1 - 0.75, 0), (6.75, Y1, 0.42))
    env.box("basin", (4.65, Y1 - 0.5, 0), (5.25, Y1, 0.85))
    # study
    env.item("desk", E.table(9.1, 11.4, 1.6, 0.75, yaw=0))
    env.item("desk_chair", E.chair(9.1, 10.75, yaw=2))
    env.item("bookshelf", E.bookshelf(10.8, 11.0, w=1.2, d=0.35, h=2.1, yaw=1))
    env.item("armchair", E.sofa(7.7, 11.35, w=0.95, seats=1, yaw=2))
    # utility room
    env.box("washer", (11.2, Y1 - 0.65, 0), (11.8, Y1, 0.85))
    env.box("dryer", (11.85, Y1 - 0.65, 0), (12.45, Y1, 0.85))
    env.item("utility_shelves", E.bookshelf(15.8, 11.0, w=1.5, d=0.4, h=2.0, yaw=1, books=False))
    env.item("boiler", [(E.box_mesh((14.2, Y1 - 0.4, 1.2), (14.8, Y1, 2.1)), None)])


def house_scene(plan, q_pass, extents_pass, center_height, clear=0.03):
    P = plan
    lo, hi = extents_pass
    z_pass = DOOR_H / 2 - (lo[2] + hi[2]) / 2
    xa = P.A_X - (lo[0] + hi[0]) / 2
    xb = P.B_X - (lo[0] + hi[0]) / 2
    y_hall = (P.Y_S + T + P.STAIR_Y[0]) / 2 - (lo[1] + hi[1]) / 2
    z_floor = center_height + clear
    start = ((3.2, 2.8, z_floor), yaw_quat(90))
    goal = ((13.3, 2.9, z_floor), yaw_quat(-90))
    up = upright_near(q_pass)
    path = ([start] + turn((3.2, 3.0, 1.30), 90, up) +
            [((3.2, 3.0, 1.30), q_pass),
             ((xa, 3.0, z_pass), q_pass),
             ((xa, y_hall, z_pass), q_pass),
             ((xb, y_hall, z_pass), q_pass),
             ((xb, 3.0, z_pass), q_pass),
             ((13.3, 3.0, 1.30), q_pass),
             ((13.3, 3.0, 1.30), yaw_quat(up))] +
            turn((13.3, 2.95, 1.0), up, 270 if up == 180 else -90)[:-1] + [goal])
    return start, goal, path
