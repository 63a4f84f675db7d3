#!/usr/bin/env python3
"""Draws the plots of a `gplan-bench` run from its CSV (written by benchmarks/harness/bench_record),
with matplotlib, as PNG and SVG:

  planning runs: per scene OUT_DIR/<scene>.png/.svg, the plan-time distribution of every
    planner@checker (a box on a logarithmic time axis, every run a dot over it, runs that
    found no path a distinct mark at their time, each box labelled solved/runs, the
    fastest FCL group marked as the baseline), and OUT_DIR/plan_times.png/.svg, one panel
    per scene with the same content;
  query tables (collision-queries, local-planning): OUT_DIR/<table>.png/.svg, the median
    batch time per checker per scene as grouped bars on a logarithmic axis.

A CSV holding several experiments gets a folder OUT_DIR/<experiment>/ for each. The
output is deterministic: drawn twice, the files are identical. gplan-bench runs this script
embedded in its binary (benchmarks/harness/bench_plots.cpp) as `python3 - CSV OUT_DIR`.

usage: plot_bench.py CSV OUT_DIR
exit:  0 drawn, 1 an output could not be written, 2 the CSV is not a gplan-bench CSV
"""
import sys

# Run as `python3 - CSV OUT_DIR`, the working folder comes first in sys.path: a csv.py or
# matplotlib/ of the user's there must not stand in for the real ones.
if sys.path and sys.path[0] == "":
    del sys.path[0]

import math  # noqa: E402  (after sys.path is set)
import os  # noqa: E402
import statistics  # noqa: E402

from plot_common import (BadCsv, check_file_names, field, file_stem, main, parse_count,  # noqa: E402
                         parse_time, pyplot, read_csv, require, save)
from matplotlib import transforms  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

# The columns of bench_csv_columns() in benchmarks/harness/bench_record.cpp, in order.
COLUMNS = ["experiment", "scene", "planner", "checker", "run", "seed", "status", "solved",
           "time_s", "simplify_time_s", "length", "simplified_length", "checks",
           "check_time_s", "graph_states", "memory_mb", "path_check", "work", "collisions",
           "sampling_s", "state_checks_s", "knn_s", "search_s", "edge_checks_s", "rounds",
           "gpu_calls", "device", "note"]
STAGE_COLUMNS = ["sampling_s", "state_checks_s", "knn_s", "search_s", "edge_checks_s", "rounds"]
# The columns of CSVs written before device (runs until issue 36), before gpu_calls (issue
# 33's first runs), before the stage columns (runs until issue 33), and before
# check_time_s (runs until issue 22).
COLUMNS_BEFORE_DEVICE = [c for c in COLUMNS if c != "device"]
COLUMNS_BEFORE_GPU_CALLS = [c for c in COLUMNS_BEFORE_DEVICE if c != "gpu_calls"]
COLUMNS_BEFORE_STAGES = [c for c in COLUMNS_BEFORE_GPU_CALLS if c not in STAGE_COLUMNS]
COLUMNS_BEFORE_CHECK_TIME = [c for c in COLUMNS_BEFORE_STAGES if c != "check_time_s"]
QUERY_TABLES = {"collision-queries": "collision queries (milestone computation)",
                "local-planning": "local planning (roadmap edges)"}
PLANNER_ORDER = ["ours-lazyprm", "ours-prm", "ompl-rrtconnect", "ompl-prm", "ompl-lazyprm"]
CHECKER_ORDER = ["gpu", "gpu-basic", "gpu-packet", "gpu-balanced", "cpu", "fcl"]
CHECKER_COLOURS = {"gpu": "#1b7837", "gpu-basic": "#a6dba0", "gpu-packet": "#5aae61",
                   "gpu-balanced": "#1b7837", "cpu": "#2166ac", "fcl": "#b2182b"}
OTHER_COLOURS = ["#762a83", "#e08214", "#8c510a", "#01665e", "#4d4d4d"]
SHORTEST_TIME_S = 1e-6  # times below it (a log axis has no 0) are drawn at it
OVERVIEW = "plan_times"
LEGEND_HEIGHT_IN = 0.6  # the planning figures' legend, below the panels
TITLE_HEIGHT_IN = 0.35  # inches above the panels for the figure's title


class Run:
    """The fields of one CSV record the plots use."""

    def __init__(self, experiment, scene, planner, checker, solved, time_s, work):
        self.experiment = experiment
        self.scene = scene
        self.planner = planner
        self.checker = checker
        self.solved = solved
        self.time_s = time_s  # None when not measured (a crash, an error)
        self.work = work  # None when not given


def run_of(row):
    """One CSV record as a Run; BadCsv on anything bench_record.cpp would not write."""
    def solved(text):
        if text not in ("0", "1"):
            raise BadCsv("'%s' is not 0 or 1" % text)
        return text == "1"
    run = Run(row["experiment"], row["scene"], row["planner"], row["checker"],
              field(row, "solved", solved), field(row, "time_s", parse_time),
              field(row, "work", parse_count))
    require(row, ("experiment", "scene", "planner", "checker"))
    return run


def read_runs(path):
    """The CSV's records as Runs; BadCsv on anything bench_record.cpp would not write."""
    runs = read_csv(path, (COLUMNS, COLUMNS_BEFORE_DEVICE, COLUMNS_BEFORE_GPU_CALLS,
                           COLUMNS_BEFORE_STAGES, COLUMNS_BEFORE_CHECK_TIME),
                    "a gplan-bench CSV", run_of)
    if not runs:
        raise BadCsv("%s: holds no runs, nothing to plot" % path)
    return runs


def ordered(names, order):
    """`names` without repeats, those in `order` first in its order, then the rest sorted."""
    names = set(names)
    return [n for n in order if n in names] + sorted(names - set(order))


def in_order_seen(names):
    """`names` without repeats, in the order they first come."""
    return list(dict.fromkeys(names))


def colour(checker, others):
    if checker in CHECKER_COLOURS:
        return CHECKER_COLOURS[checker]
    return OTHER_COLOURS[others.index(checker) % len(OTHER_COLOURS)]


def time_text(seconds):
    """A time with a unit that keeps it short: 392 ms, 15.95 s, 48.2 µs."""
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("µs", 1e-6), ("ns", 1e-9)):
        if seconds >= scale or unit == "ns":
            value = seconds / scale
            digits = 0 if value >= 100 else 1 if value >= 10 else 2
            return "%.*f %s" % (digits, value, unit)


# Planning runs ------------------------------------------------------------------------

def planning_groups(runs):
    """{(planner, checker): [Run]} in the order drawn (top to bottom)."""
    planners = ordered((r.planner for r in runs), PLANNER_ORDER)
    checkers = ordered((r.checker for r in runs), CHECKER_ORDER)
    groups = {}
    for planner in planners:
        for checker in checkers:
            members = [r for r in runs if r.planner == planner and r.checker == checker]
            if members:
                groups[(planner, checker)] = members
    return groups


def baseline_group(groups):
    """The FCL group with the shortest median time: what the others are measured against."""
    medians = {key: statistics.median(r.time_s for r in members if r.time_s is not None)
               for key, members in groups.items()
               if key[1] == "fcl" and any(r.time_s is not None for r in members)}
    return min(medians, key=lambda key: (medians[key], key)) if medians else None


def draw_planning_panel(axes, scene, runs, checkers):
    """One scene's plan-time distributions on `axes`, a row per planner@checker."""
    groups = planning_groups(runs)
    baseline = baseline_group(groups)
    keys = list(groups)
    rows = range(len(keys), 0, -1)  # the first group at the top
    label_place = transforms.blended_transform_factory(axes.transAxes, axes.transData)
    for key, row in zip(keys, rows):
        members = groups[key]
        times = [max(r.time_s, SHORTEST_TIME_S) for r in members if r.time_s is not None]
        is_baseline = key == baseline
        if times:
            axes.boxplot([times], positions=[row], vert=False, widths=0.6, whis=(0, 100),
                         patch_artist=True, manage_ticks=False,
                         boxprops={"facecolor": colour(key[1], checkers), "alpha": 0.35,
                                   "linewidth": 2.5 if is_baseline else 1.0},
                         medianprops={"color": "black",
                                      "linewidth": 2.5 if is_baseline else 1.5})
        timed = [r for r in members if r.time_s is not None]
        for index, run in enumerate(timed):
            # The dots spread over the box's height, in run order (no randomness).
            offset = 0.0 if len(timed) == 1 else 0.44 * (index / (len(timed) - 1) - 0.5)
            time_s = max(run.time_s, SHORTEST_TIME_S)
            if run.solved:
                axes.plot(time_s, row + offset, "o", markersize=4, color="black", alpha=0.7,
                          zorder=3)
            else:
                axes.plot(time_s, row + offset, "x", markersize=6, markeredgewidth=1.5,
                          color="#d7191c", zorder=3)
        solved = sum(r.solved for r in members)
        label = "%d/%d" % (solved, len(members))
        if len(timed) < len(members):
            label += " (%d untimed)" % (len(members) - len(timed))
        axes.text(1.01, row, label, transform=label_place, va="center", fontsize=8)
    axes.set_xscale("log")
    axes.set_yticks(list(rows))
    axes.set_yticklabels(["%s@%s%s" % (key[0], key[1], "\n(baseline)" if key == baseline
                                       else "") for key in keys], fontsize=8)
    for tick, key in zip(axes.get_yticklabels(), keys):
        if key == baseline:
            tick.set_fontweight("bold")
    axes.set_ylim(0.4, len(keys) + 0.6)
    axes.set_title(scene, fontsize=10, loc="left")
    axes.grid(True, axis="x", which="major", alpha=0.3)
    if baseline is not None:
        median = statistics.median(max(r.time_s, SHORTEST_TIME_S) for r in groups[baseline]
                                   if r.time_s is not None)
        axes.axvline(median, color=CHECKER_COLOURS["fcl"], linestyle="--", linewidth=1,
                     zorder=1)


def planning_legend(figure, runs):
    handles = [Line2D([], [], marker="o", linestyle="", color="black",
                                       alpha=0.7, markersize=4, label="run that found a path"),
               Line2D([], [], marker="x", linestyle="", color="#d7191c",
                                       markersize=6, markeredgewidth=1.5,
                                       label="run without a path (ran to the time limit)"),
               Line2D([], [], color=CHECKER_COLOURS["fcl"], linestyle="--",
                                       label="baseline's median (fastest FCL group)")]
    note = "boxes: quartiles and median, whiskers: fastest and slowest run; right: solved/runs"
    if any(r.time_s is not None and r.time_s < SHORTEST_TIME_S for r in runs):
        note += "; times under 1 µs drawn at 1 µs"
    figure.legend(handles=handles, loc="lower center", ncol=3, fontsize=8, frameon=False,
                  title=note, title_fontsize=8)


def draw_planning(experiment, runs, out_dir):
    scenes = in_order_seen(r.scene for r in runs)
    checkers = ordered((r.checker for r in runs), CHECKER_ORDER)
    title = "%s: plan time per planner@checker, seconds (log scale)" % experiment
    row_height = 0.45
    for scene in scenes:
        scene_runs = [r for r in runs if r.scene == scene]
        rows = len(planning_groups(scene_runs))
        figure, axes = pyplot.subplots(figsize=(9, 1.9 + row_height * rows))
        draw_planning_panel(axes, scene, scene_runs, checkers)
        axes.set_xlabel("plan time (s)")
        figure.suptitle(title, fontsize=11)
        planning_legend(figure, scene_runs)
        figure.tight_layout(rect=(0, LEGEND_HEIGHT_IN / figure.get_figheight(),
                                  1, 1 - TITLE_HEIGHT_IN / figure.get_figheight()))
        save(figure, out_dir, file_stem(scene))

    heights = [0.9 + row_height * len(planning_groups([r for r in runs if r.scene == s]))
               for s in scenes]
    figure, panels = pyplot.subplots(len(scenes), 1, figsize=(9, 1.4 + sum(heights)),
                                     sharex=True, squeeze=False,
                                     gridspec_kw={"height_ratios": heights})
    for scene, axes in zip(scenes, panels[:, 0]):
        draw_planning_panel(axes, scene, [r for r in runs if r.scene == scene], checkers)
    panels[-1, 0].set_xlabel("plan time (s)")
    figure.suptitle(title + ", every scene", fontsize=11)
    planning_legend(figure, runs)
    # The title's own band at the top: tight_layout does not keep the panels out of it.
    figure.tight_layout(rect=(0, LEGEND_HEIGHT_IN / figure.get_figheight(),
                              1, 1 - TITLE_HEIGHT_IN / figure.get_figheight()))
    save(figure, out_dir, OVERVIEW)


# Query tables -------------------------------------------------------------------------

def draw_query_table(experiment, table, runs, out_dir):
    """The median batch time per checker per scene, grouped bars on a log axis."""
    scenes = in_order_seen(r.scene for r in runs)
    checkers = ordered((r.checker for r in runs), CHECKER_ORDER)
    width = 0.8 / len(checkers)
    figure, axes = pyplot.subplots(figsize=(max(6.0, 1.3 + 0.45 * len(scenes) * len(checkers)),
                                            5.2))
    missing_place = transforms.blended_transform_factory(axes.transData, axes.transAxes)
    for index, checker in enumerate(checkers):
        for position, scene in enumerate(scenes):
            x = position + (index - (len(checkers) - 1) / 2) * width
            times = [r.time_s for r in runs
                     if r.scene == scene and r.checker == checker and r.time_s is not None]
            if not times:
                if any(r.scene == scene and r.checker == checker for r in runs):
                    axes.text(x, 0.01, "no time", transform=missing_place, rotation=90,
                              ha="center", va="bottom", fontsize=7)
                continue
            median = max(statistics.median(times), SHORTEST_TIME_S)
            bars = axes.bar(x, median, width, color=colour(checker, checkers))
            axes.bar_label(bars, labels=[time_text(median)], rotation=90, padding=2,
                           fontsize=7)
    axes.legend(handles=[Patch(color=colour(c, checkers), label=c) for c in checkers],
                title="checker", fontsize=8, title_fontsize=8, loc="upper left",
                bbox_to_anchor=(1.01, 1))
    axes.set_yscale("log")
    # From the decade below the shortest bar, with room for the labels above the tallest.
    heights = [bar.get_height() for container in axes.containers for bar in container]
    if heights:
        axes.set_ylim(10 ** math.floor(math.log10(min(heights))) / 2, max(heights) * 8)
    work = {}
    for r in runs:
        if r.work is not None:
            work.setdefault(r.scene, set()).add(r.work)
    unit = "configurations" if table == "collision-queries" else "edges"
    axes.set_xlim(-0.5, len(scenes) - 0.5)
    axes.set_xticks(range(len(scenes)))
    axes.set_xticklabels(["%s\n%s %s" % (s, "/".join(str(w) for w in sorted(work[s])), unit)
                          if s in work else s for s in scenes], fontsize=8)
    axes.set_ylabel("median batch time (s)")
    axes.grid(True, axis="y", which="major", alpha=0.3)
    axes.set_title("%s: %s\nmedian time of one batch call per checker, seconds (log scale)"
                   % (experiment, QUERY_TABLES.get(table, table)), fontsize=11)
    figure.tight_layout()
    save(figure, out_dir, file_stem(table))


def draw(runs, out_dir):
    experiments = in_order_seen(r.experiment for r in runs)
    check_file_names(("the experiment", e) for e in experiments)
    for experiment in experiments:
        own = [r for r in runs if r.experiment == experiment]
        scenes = in_order_seen(r.scene for r in own if r.planner not in QUERY_TABLES)
        tables = in_order_seen(r.planner for r in own if r.planner in QUERY_TABLES)
        check_file_names([("the scene", s) for s in scenes] +
                         [("the overview", OVERVIEW)] * bool(scenes) +
                         [("the table", t) for t in tables])
    for experiment in experiments:
        folder = out_dir if len(experiments) == 1 else os.path.join(out_dir,
                                                                    file_stem(experiment))
        os.makedirs(folder, exist_ok=True)
        own = [r for r in runs if r.experiment == experiment]
        planning = [r for r in own if r.planner not in QUERY_TABLES]
        if planning:
            draw_planning(experiment, planning, folder)
        for table in in_order_seen(r.planner for r in own if r.planner in QUERY_TABLES):
            draw_query_table(experiment, table, [r for r in own if r.planner == table],
                             folder)


if __name__ == "__main__":
    sys.exit(main(sys.argv, "plot_bench.py", "gplan bench", read_runs, draw))
