#!/usr/bin/env python3
"""Draws the plots of a `gplan-bench` error-against-time study from its CSV (written by
benchmarks/harness/error_time_record), with matplotlib, as PNG and SVG: for each scene
OUT_DIR/<scene>.png/.svg, error against time, one curve per knob and checker, in three
panels:

  states: precision, traversal and delta; time of one batch of the N states, error the
    states misclassified (missed + extra) as a percentage of N;
  edges: edge-resolution (or max-displacement) and certified-step; time of one batch of
    the M edges, error the edges misclassified (missed + extra) as a percentage of the
    edges the ground truth decides;
  planning: milestones and plan-edges; median plan time, error the runs whose returned
    path fails the ground truth as a percentage of the runs (each point labelled with
    its value and solved/runs).

Every point is labelled with its knob value. Errors of 0 are drawn on the axis's
linear part (a symmetric-log axis). The output is deterministic: drawn twice, the files
are identical. gplan-bench runs this script embedded in its binary (benchmarks/harness/bench_plots.cpp)
as `python3 - CSV OUT_DIR`.

usage: plot_error_time.py CSV OUT_DIR
exit:  0 drawn, 1 an output could not be written, 2 the CSV is not a study's CSV
"""
import sys

# Run as `python3 - CSV OUT_DIR`, the working folder comes first in sys.path: a csv.py or
# matplotlib/ of the user's there must not stand in for the real ones.
if sys.path and sys.path[0] == "":
    del sys.path[0]

import os  # noqa: E402  (after sys.path is set)

from plot_common import (BadCsv, field, file_stem, main, parse_count, parse_time,  # noqa: E402
                         pyplot, read_csv, require, save)

# The columns of write_error_time_csv_header() in benchmarks/harness/error_time_record.cpp.
COLUMNS = ["scene", "knob", "value", "checker", "time_s", "missed", "extra", "undecided",
           "total", "runs", "solved", "path_fails", "path_undecided"]
PANELS = [("states", ["precision", "traversal", "delta"],
           "states misclassified (% of N)"),
          ("edges", ["edge-resolution", "max-displacement", "certified-step"],
           "edges misclassified (% of those decided)"),
          ("planning", ["milestones", "plan-edges"],
           "paths failing the ground truth (% of runs)")]
COLOURS = ["#1b7837", "#2166ac", "#b2182b", "#762a83", "#e08214", "#8c510a", "#01665e",
           "#4d4d4d", "#5aae61", "#d6604d"]
MARKERS = ["o", "s", "^", "D", "v", "P", "X", "<", ">", "*"]
SHORTEST_TIME_S = 1e-6  # a log axis has no 0


def point_of(row):
    """One CSV record as a point (a dict, numbers parsed)."""
    row["time_s"] = field(row, "time_s", lambda text: parse_time(text, allow_empty=False))
    for column in COLUMNS[5:]:
        row[column] = field(row, column,
                            lambda text: parse_count(text, allow_empty=column != "total"))
    require(row, ("scene", "knob", "value", "checker"))
    return row


def read_points(path):
    points = read_csv(path, (COLUMNS,), "an error-time CSV", point_of)
    if not points:
        raise BadCsv("%s: holds no points, nothing to plot" % path)
    return points


def error_percent(point):
    """The point's error as a percentage, or None when it has nothing to measure."""
    if point["runs"] is not None:
        return 100.0 * point["path_fails"] / point["runs"] if point["runs"] else None
    decided = point["total"] - (point["undecided"] or 0)
    if decided <= 0 or point["missed"] is None:
        return None
    return 100.0 * (point["missed"] + point["extra"]) / decided


def draw_panel(axes, title, knobs, ylabel, points):
    curves = {}
    for point in points:
        if point["knob"] in knobs:
            curves.setdefault((point["knob"], point["checker"]), []).append(point)
    axes.set_title(title, fontsize=10)
    axes.set_xlabel("time (s, log scale)")
    axes.set_ylabel(ylabel, fontsize=9)
    if not curves:
        axes.text(0.5, 0.5, "no points", ha="center", va="center", transform=axes.transAxes)
        axes.set_xticks([])
        axes.set_yticks([])
        return
    highest = 0.0
    for index, ((knob, checker), own) in enumerate(curves.items()):
        xs, ys, labels = [], [], []
        for point in own:
            error = error_percent(point)
            if error is None:
                continue
            xs.append(max(point["time_s"], SHORTEST_TIME_S))
            ys.append(error)
            label = point["value"]
            if point["runs"] is not None:
                label += " (%d/%d)" % (point["solved"], point["runs"])
            labels.append(label)
        if not xs:
            continue
        highest = max(highest, max(ys))
        axes.plot(xs, ys, marker=MARKERS[index % len(MARKERS)],
                  color=COLOURS[index % len(COLOURS)], label="%s @%s" % (knob, checker),
                  linewidth=1.2, markersize=5)
        for x, y, label in zip(xs, ys, labels):
            axes.annotate(label, (x, y), textcoords="offset points", xytext=(4, 4), fontsize=6,
                          color=COLOURS[index % len(COLOURS)])
    axes.set_xscale("log")
    axes.set_yscale("symlog", linthresh=0.1)
    axes.set_ylim(-0.05, max(1.0, 2 * highest))  # errors of 0 on the axis's linear part
    axes.grid(True, which="major", alpha=0.3)
    axes.legend(fontsize=7, loc="best")


def draw(points, out_dir):
    scenes = list(dict.fromkeys(p["scene"] for p in points))
    stems = {}
    for scene in scenes:
        stem = file_stem(scene)
        if stem in stems:
            raise BadCsv("the scenes '%s' and '%s' would both be written to %s; rename one"
                         % (stems[stem], scene, stem))
        stems[stem] = scene
    os.makedirs(out_dir, exist_ok=True)
    for scene in scenes:
        own = [p for p in points if p["scene"] == scene]
        figure, axes = pyplot.subplots(1, len(PANELS), figsize=(6 * len(PANELS), 5))
        for panel, (title, knobs, ylabel) in zip(axes, PANELS):
            draw_panel(panel, title, knobs, ylabel, own)
        figure.suptitle("%s: error against time (ground truth: FCL in double, certified "
                        "at a fine step)" % scene, fontsize=11)
        figure.tight_layout()
        save(figure, out_dir, file_stem(scene))


if __name__ == "__main__":
    sys.exit(main(sys.argv, "plot_error_time.py", "gplan bench error-time", read_points, draw))
