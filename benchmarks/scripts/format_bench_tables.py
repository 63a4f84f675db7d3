#!/usr/bin/env python3
"""The Markdown tables of benchmarks/RESULTS.md from gplan bench's results.csv files.

usage: benchmarks/scripts/format_bench_tables.py seed RUN_DIR      the seed's three tables (RUN_DIR holds
                                                     seed_collision_queries/, seed_local_planning/,
                                                     seed_pr2/)
       benchmarks/scripts/format_bench_tables.py regression DIR   a planning run: median (solved/runs) per
                                                     scene and planner@checker
       benchmarks/scripts/format_bench_tables.py call-sizes FILE  gplanner_call_sizes' output on every scene
                                                     (reproduce.sh's call_sizes.md): routing, one
                                                     state, 16 states, one checkMotion
       benchmarks/scripts/format_bench_tables.py plugin DIR       OMPL's planners with FCL and through the
                                                     plugin (gpu, cpu): medians, the share of
                                                     FCL's time in checks and what it bounds,
                                                     the ratios to FCL
"""
import csv
import statistics
import sys

# Pan & Manocha's figures (GTX 480, 2010): basic / packet / balanced, ms.
SEED_QUERIES = {"piano": (224, 130, 3.7), "large_piano": (710, 529, 15.1),
                "helicopter": (272, 226, 2.3), "humanoid": (2316, 1823, 126)}
SEED_LOCAL = {"piano": (2076, 1344, 34), "large_piano": (7587, 6091, 66),
              "helicopter": (7413, 4645, 41), "humanoid": (8650, 8837, 1964)}
SEED_PR2 = {"collision-queries": (15952, 392), "local-planning": (643194, 6803)}


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def groups(rows):
    out = {}
    for r in rows:
        out.setdefault((r["scene"], r["planner"], r["checker"]), []).append(r)
    return out


def ms(seconds):
    value = seconds * 1000
    return "%.3g ms" % value if value < 100 else "{:,.0f} ms".format(value)


def median_time(rows):
    return statistics.median(float(r["time_s"]) for r in rows if r["time_s"])


def query_table(directory, table, seed):
    g = groups(read(directory + "/results.csv"))
    scenes = []
    for scene, planner, _ in g:
        if planner == table and scene not in scenes:
            scenes.append(scene)
    work = "configurations" if table == "collision-queries" else "edges"
    print("| scene | %s | gpu basic | gpu packet | gpu balanced | cpu (all cores) | fcl (all cores) "
          "| balanced vs basic | balanced vs fcl | seed (GTX 480): basic / packet / balanced "
          "| seed: balanced vs basic |" % work)
    print("|" + " --- |" * 11)
    for scene in scenes:
        t = {c: median_time(g[(scene, table, c)]) for c in
             ("gpu-basic", "gpu-packet", "gpu-balanced", "cpu", "fcl") if (scene, table, c) in g}
        n = g[(scene, table, "fcl")][0]["work"]
        s = seed.get(scene)
        print("| %s | {:,} | %s | %s | %s | %s | %s | %.1fx | %.0fx | %s | %s |".format(int(n)) % (
            scene, ms(t["gpu-basic"]), ms(t["gpu-packet"]), ms(t["gpu-balanced"]), ms(t["cpu"]),
            ms(t["fcl"]), t["gpu-basic"] / t["gpu-balanced"], t["fcl"] / t["gpu-balanced"],
            "%s / %s / %s ms" % s if s else "-", "%.0fx" % (s[0] / s[2]) if s else "-"))


def pr2_table(directory):
    g = groups(read(directory + "/results.csv"))
    print("| pr2_reach (15 DOF, self-collision) | work | cpu, ours (all cores) | fcl (all cores) "
          "| gpu balanced | gpu vs ours on the cpu | gpu vs fcl | seed: CPU / GPU | seed: ratio |")
    print("|" + " --- |" * 9)
    for table, name in (("collision-queries", "milestone computation"),
                        ("local-planning", "local planning")):
        t = {c: median_time(g[("pr2_reach", table, c)]) for c in ("cpu", "fcl", "gpu-balanced")}
        n = int(g[("pr2_reach", table, "fcl")][0]["work"])
        s = SEED_PR2[table]
        print("| %s | {:,} %s | %s | %s | %s | %.0fx | %.0fx | {:,} / {:,} ms | %.0fx |".format(n, *s) % (
            name, "configurations" if table == "collision-queries" else "edges", ms(t["cpu"]),
            ms(t["fcl"]), ms(t["gpu-balanced"]), t["cpu"] / t["gpu-balanced"],
            t["fcl"] / t["gpu-balanced"], s[0] / s[1]))


def group_median(runs):
    """(median time, whether it is a lower bound, solved, runs, median share in checks)."""
    times = sorted((float(r["time_s"]), r["solved"] == "1") for r in runs if r["time_s"])
    n = len(times)
    median = statistics.median(t for t, _ in times)
    bound = (not times[n // 2][1]) or (n % 2 == 0 and not times[n // 2 - 1][1])
    shares = [float(r["check_time_s"]) / float(r["time_s"]) for r in runs
              if r.get("check_time_s") and r["time_s"] and float(r["time_s"]) > 0]
    return (median, bound, sum(r["solved"] == "1" for r in runs), len(runs),
            statistics.median(shares) if shares else None)


def ratio(reference, ours):
    """FCL's median over ours, marked as gplan bench's summary marks bounds."""
    if ours[0] <= 0:
        return "-"
    if reference[1] and ours[1]:
        return "-"  # both lower bounds: unknown
    return "%s%.3gx" % (">" if reference[1] else "<" if ours[1] else "", reference[0] / ours[0])


def regression(directory):
    rows = read(directory + "/results.csv")
    g = groups(rows)
    scenes, labels = [], []
    for scene, planner, checker in g:
        if scene not in scenes:
            scenes.append(scene)
        if planner + "@" + checker not in labels:
            labels.append(planner + "@" + checker)
    print("| scene | " + " | ".join(labels) + " |")
    print("|" + " --- |" * (len(labels) + 1))
    for scene in scenes:
        cells = []
        for label in labels:
            planner, checker = label.split("@")
            runs = g.get((scene, planner, checker), [])
            if not runs:
                cells.append("-")
                continue
            median, bound, solved, count, _ = group_median(runs)
            failed = sum(r["path_check"] == "fail" for r in runs)
            cells.append("%s%.3g s, %d/%d%s" % (">" if bound else "", median, solved, count,
                                                 ", **%d failed re-check**" % failed if failed else ""))
        print("| %s | %s |" % (scene, " | ".join(cells)))


def plugin(directory):
    g = groups(read(directory + "/results.csv"))
    scenes, planners = [], []
    for scene, planner, _ in g:
        if scene not in scenes:
            scenes.append(scene)
        if planner not in planners:
            planners.append(planner)
    print("| scene | planner | @fcl | in checks @fcl (at most, checks free) | @gpu | vs FCL "
          "| in checks @gpu | @cpu | vs FCL |")
    print("|" + " --- |" * 9)

    def cell(m):
        return "%s%.3g s, %d/%d" % (">" if m[1] else "", m[0], m[2], m[3])

    def share(m):
        return "-" if m[4] is None else "%.0f%%" % (100 * m[4])

    for scene in scenes:
        for planner in planners:
            if any((scene, planner, c) not in g for c in ("fcl", "gpu", "cpu")):
                continue
            fcl, gpu, cpu = (group_median(g[(scene, planner, c)]) for c in ("fcl", "gpu", "cpu"))
            most = ("-" if fcl[4] is None else ">200x" if fcl[4] >= 0.995
                    else "%.3gx" % (1 / (1 - fcl[4])))
            print("| %s | %s | %s | %s (%s) | %s | %s | %s | %s | %s |" % (
                scene, planner.replace("ompl-", ""), cell(fcl), share(fcl), most, cell(gpu),
                ratio(fcl, gpu), share(gpu), cell(cpu), ratio(fcl, cpu)))


def call_sizes(path):
    """One row per scene from the Markdown gplanner_call_sizes prints."""
    scenes, scene = [], None
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line.startswith("## "):
                scene = {"name": line[3:].split("/")[-1].replace(".yaml", ""), "rows": {}}
                scenes.append(scene)
            elif line.startswith("gpu backend routing") and scene:
                words = line.split()
                scene["calling"] = words[words.index("calling") - 4]
                scene["host"] = words[words.index("host") - 2]
            elif (line.startswith("| configurations per call") or
                  line.startswith("| one checkMotion")) and scene:
                scene["columns"] = [c.strip() for c in line.strip("|").split("|")]
            elif line.startswith("|") and scene and "columns" in scene:
                cells = [c.strip() for c in line.strip("|").split("|")]
                scene["rows"][cells[0]] = dict(zip(scene["columns"], cells))
    print("| scene | host up to (calling thread) | one state: routed / GPU alone / our core, 1 "
          "thread / FCL, 1 thread | 16 states: routed / our core, all cores / FCL, 1 thread "
          "| one checkMotion, mean: routed / our core, 1 thread / FCL + DiscreteMotionValidator "
          "| routed vs FCL, one checkMotion |")
    print("|" + " --- |" * 6)
    for sc in sorted(scenes, key=lambda x: x["name"]):
        r = sc["rows"]
        one, sixteen = r["1"], r["16"]
        motion = {k: v["mean"].split(" (")[0] for k, v in r.items() if "mean" in v}
        routed = motion["gpu (routed), our motion validator"]
        fcl = motion["FCL, 1 thread, OMPL's DiscreteMotionValidator"]
        print("| %s | %s (%s) | %s / %s / %s / %s | %s / %s / %s | %s / %s / %s | %.1fx |" % (
            sc["name"], sc["host"], sc["calling"], one["gpu (routed)"], one["GPU alone"],
            one["our core, 1 thread"], one["FCL, 1 thread"], sixteen["gpu (routed)"],
            sixteen["our core, all cores"], sixteen["FCL, 1 thread"], routed,
            motion["our core, 1 thread, our motion validator"], fcl,
            float(fcl.split()[0]) / float(routed.split()[0])))


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("seed", "regression", "plugin", "call-sizes"):
        sys.exit(__doc__)
    if sys.argv[1] == "seed":
        print("Table 1: collision queries\n")
        query_table(sys.argv[2] + "/seed_collision_queries", "collision-queries", SEED_QUERIES)
        print("\nTable 2: local planning\n")
        query_table(sys.argv[2] + "/seed_local_planning", "local-planning", SEED_LOCAL)
        print("\nTable 3: the PR2\n")
        pr2_table(sys.argv[2] + "/seed_pr2")
    elif sys.argv[1] == "plugin":
        plugin(sys.argv[2])
    elif sys.argv[1] == "call-sizes":
        call_sizes(sys.argv[2])
    else:
        regression(sys.argv[2])
