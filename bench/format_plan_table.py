#!/usr/bin/env python3
"""Turns the JSON lines of gplanner_plan_bench into the plan-time tables of
bench/RESULTS.md: per scene and planner the median plan time, its range and how many
runs found a path; the ratios of OMPL's LazyPRM and PRM medians to ours (issue 4); and,
where runs of OMPL's planners with our checker as the OMPL plugin are present
(ompl-*@gpu), each OMPL planner with the FCL checker beside the same planner with ours
and the ratio of their medians (issue 5).

A run that found no path counts at its full time (the time limit), so a median over
runs that mostly failed is a lower bound, marked with ">".

usage: bench/format_plan_table.py [--only TABLE[,TABLE...]] RUNS.jsonl [RUNS.jsonl ...]
  TABLE: main (ours and OMPL's planners, each as it ends), first-path (ours less its
  shortcutting), simplify (OMPL's followed by simplifySolution), plugin (OMPL's
  planners with FCL and with our GPU checker); default: each one the runs allow.
"""
import json
import statistics
import sys
from collections import defaultdict

PLANNERS = ["ours-lazyprm", "ours-prm", "ompl-lazyprm", "ompl-prm", "ompl-rrtconnect"]
TABLES = ["main", "first-path", "simplify", "plugin"]
SCENES = ["piano", "large_piano", "helicopter", "humanoid", "piano_detailed", "pr2_reach",
          "pr2_base_arm"]


def main():
    args = sys.argv[1:]
    only = None
    if args and args[0] == "--only":
        if len(args) < 2:
            sys.exit(__doc__)
        only = set(args[1].split(","))
        if only - set(TABLES):
            sys.exit("format_plan_table.py: no table named %s; the tables are %s"
                     % (", ".join(sorted(only - set(TABLES))), ", ".join(TABLES)))
        args = args[2:]
    if not args:
        sys.exit(__doc__)
    runs = defaultdict(list)
    for path in args:
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

    tables = []  # (name, printer) of the tables these runs allow, in TABLES' order
    if any(p in PLANNERS for _, p in runs):
        tables.append(("main", lambda: print_ours_against_ompl(runs, median, cell)))
    if any("shortcut_seconds" in r for s in SCENES for r in runs.get((s, "ours-lazyprm"), [])):
        tables.append(("first-path", lambda: print_first_path(runs, median)))
    if any("simplify_seconds" in r for v in runs.values() for r in v):
        tables.append(("simplify", lambda: print_with_simplification(runs, median)))
    if any(p.endswith("@gpu") for _, p in runs):
        tables.append(("plugin", lambda: print_plugin_against_fcl(runs, median, cell)))
    tables = [(name, printer) for name, printer in tables if only is None or name in only]
    for i, (_, printer) in enumerate(tables):
        if i:
            print()
        printer()


def print_ours_against_ompl(runs, median, cell):
    print("| scene | " + " | ".join(PLANNERS) + " | OMPL LazyPRM / ours lazy | OMPL PRM / ours lazy |")
    print("| --- " * (len(PLANNERS) + 3) + "|")
    for scene in SCENES:
        if not any((scene, p) in runs for p in PLANNERS):
            continue
        ours, ours_bound = median(scene, "ours-lazyprm")
        ratios = [ratio(*median(scene, base), ours, ours_bound)
                  for base in ["ompl-lazyprm", "ompl-prm"]]
        print("| %s | %s | %s |" % (scene, " | ".join(cell(scene, p) for p in PLANNERS),
                                    " | ".join(ratios)))


def print_first_path(runs, median):
    """Ours to the first path (its time less the shortcutting) against OMPL's LazyPRM
    and PRM to theirs (their solve, before any simplification)."""
    print("| scene | ours-lazyprm to the first path | OMPL LazyPRM / it | OMPL PRM / it |")
    print("| --- | --- | --- | --- |")
    for scene in SCENES:
        v = [r for r in runs.get((scene, "ours-lazyprm"), []) if "shortcut_seconds" in r]
        if not v:
            continue
        times = [r["seconds"] - (r["shortcut_seconds"] if r["solved"] else 0) for r in v]
        ours = statistics.median(times)
        ours_bound = sum(r["solved"] for r in v) * 2 <= len(v)
        ratios = [ratio(*median(scene, base), ours, ours_bound)
                  for base in ["ompl-lazyprm", "ompl-prm"]]
        print("| %s | %s s (%s-%s) | %s |" % (scene, fmt(ours), fmt(min(times)), fmt(max(times)),
                                            " | ".join(ratios)))


def print_with_simplification(runs, median):
    """Both with their paths shortened: ours (its shortcutting included) against
    OMPL's LazyPRM and PRM followed by SimpleSetup::simplifySolution, as OMPL's
    Benchmark runs them (a run that found no path: its time, nothing to simplify)."""
    print("| scene | ours-lazyprm | ompl-lazyprm + simplify | ompl-prm + simplify "
          "| OMPL LazyPRM / ours lazy | OMPL PRM / ours lazy | path length: ours / OMPL LazyPRM / OMPL PRM |")
    print("| --- " * 7 + "|")
    for scene in SCENES:
        bases = ["ompl-lazyprm", "ompl-prm"]
        if not any(r.get("simplify_seconds") is not None for b in bases
                   for r in runs.get((scene, b), [])):
            continue
        ours, ours_bound = median(scene, "ours-lazyprm")
        cells, ratios, lengths = [], [], []
        v = runs.get((scene, "ours-lazyprm"), [])
        lengths.append(fmt(statistics.median(r["length"] for r in v if r["solved"]))
                       if any(r["solved"] for r in v) else "-")
        for b in bases:
            v = runs.get((scene, b), [])
            if not v:
                cells.append("-")
                ratios.append("-")
                lengths.append("-")
                continue
            times = [r["seconds"] + r.get("simplify_seconds", 0) for r in v]
            t = statistics.median(times)
            solved = sum(r["solved"] for r in v)
            bound = solved * 2 <= len(v)
            cells.append("%s%s s (%s-%s), %d/%d" % (">" if bound else "", fmt(t), fmt(min(times)),
                                                   fmt(max(times)), solved, len(v)))
            lengths.append(fmt(statistics.median(r["simplified_length"] for r in v
                                                 if r["solved"])) if solved else "-")
            ratios.append(ratio(t, bound, ours, ours_bound))
        print("| %s | %s | %s | %s | %s |" % (scene, fmt(ours) + " s" if ours is not None else "-",
                                             " | ".join(cells), " | ".join(ratios),
                                             " / ".join(lengths)))


def print_plugin_against_fcl(runs, median, cell):
    bases = ["ompl-rrtconnect", "ompl-lazyprm", "ompl-prm"]
    header = []
    for b in bases:
        header += [b + " (fcl)", b + "@gpu", "fcl / gpu"]
    print("| scene | " + " | ".join(header) + " |")
    print("| --- " * (len(header) + 1) + "|")
    for scene in SCENES:
        if not any((scene, b + "@gpu") in runs for b in bases):
            continue
        cells = []
        for b in bases:
            fcl, fcl_bound = median(scene, b)
            gpu, gpu_bound = median(scene, b + "@gpu")
            if fcl is None or gpu is None:
                ratio = "-"
            elif gpu_bound and fcl_bound:
                ratio = "both failed"
            elif gpu_bound:
                ratio = "<%.2gx" % (fcl / gpu)
            else:
                ratio = "%s%.2gx" % (">" if fcl_bound else "", fcl / gpu)
            cells += [cell(scene, b), cell(scene, b + "@gpu"), ratio]
        print("| %s | %s |" % (scene, " | ".join(cells)))


def ratio(t, bound, ours, ours_bound):
    """A baseline's median time t over ours: "-" where either is missing, "ours failed"
    where half or more of ours found no path, ">" where t is a lower bound."""
    if t is None or ours is None:
        return "-"
    if ours_bound:
        return "ours failed"
    return "%s%.0fx" % (">" if bound else "", t / ours)


def fmt(t):
    return "%.3f" % t if t < 1 else "%.2f" % t if t < 10 else "%.1f" % t


if __name__ == "__main__":
    main()
