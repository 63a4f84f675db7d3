#!/usr/bin/env python3
"""Turns the JSON lines of gplanner_plan_bench into the plan-time table of
bench/RESULTS.md: per scene and planner the median plan time, its range and how many
runs found a path; and the ratios of OMPL's LazyPRM and PRM medians to ours.

A run that found no path counts at its full time (the time limit), so a median over
runs that mostly failed is a lower bound, marked with ">".

usage: bench/format_plan_table.py RUNS.jsonl [RUNS.jsonl ...]
"""
import json
import statistics
import sys
from collections import defaultdict

PLANNERS = ["ours-lazyprm", "ours-prm", "ompl-lazyprm", "ompl-prm", "ompl-rrtconnect"]
SCENES = ["piano", "large_piano", "helicopter", "humanoid", "piano_detailed", "pr2_reach",
          "pr2_base_arm"]


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    runs = defaultdict(list)
    for path in sys.argv[1:]:
        for line in open(path):
            r = json.loads(line)
            runs[(r["scene"], r["planner"])].append(r)

    def median(scene, planner):
        v = runs.get((scene, planner))
        if not v:
            return None, False
        t = statistics.median(r["seconds"] for r in v)
        solved = sum(r["solved"] for r in v)
        return t, solved * 2 <= len(v)  # bound: half or more failed

    def cell(scene, planner):
        v = runs.get((scene, planner))
        if not v:
            return "-"
        t, bound = median(scene, planner)
        times = [r["seconds"] for r in v]
        solved = sum(r["solved"] for r in v)
        return "%s%s s (%s-%s), %d/%d" % (">" if bound else "", fmt(t), fmt(min(times)),
                                         fmt(max(times)), solved, len(v))

    print("| scene | " + " | ".join(PLANNERS) + " | OMPL LazyPRM / ours lazy | OMPL PRM / ours lazy |")
    print("| --- " * (len(PLANNERS) + 3) + "|")
    for scene in SCENES:
        if not any((scene, p) in runs for p in PLANNERS):
            continue
        ratios = []
        ours, ours_bound = median(scene, "ours-lazyprm")
        for base in ["ompl-lazyprm", "ompl-prm"]:
            t, bound = median(scene, base)
            if ours is None or t is None:
                ratios.append("-")
            elif ours_bound:
                ratios.append("ours failed")
            else:
                ratios.append("%s%.0fx" % (">" if bound else "", t / ours))
        print("| %s | %s | %s |" % (scene, " | ".join(cell(scene, p) for p in PLANNERS),
                                    " | ".join(ratios)))


def fmt(t):
    return "%.3f" % t if t < 1 else "%.2f" % t if t < 10 else "%.1f" % t


if __name__ == "__main__":
    main()
