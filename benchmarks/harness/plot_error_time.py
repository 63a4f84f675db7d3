#!/usr/bin/env python3
"""Draws the plots of a `gplan bench` error-against-time study from its CSV (written by
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
are identical. gplan runs this script embedded in its binary (benchmarks/harness/bench_plots.cpp)
as `python3 - CSV OUT_DIR`.

usage: plot_error_time.py CSV OUT_DIR
exit:  0 drawn, 1 an output could not be written, 2 the CSV is not a study's CSV
"""
import sys

# Run as `python3 - CSV OUT_DIR`, the working folder comes first in sys.path: a csv.py or
# matplotlib/ of the user's there must not stand in for the real ones.
if sys.path and sys.path[0] == "":
    del sys.path[0]

import csv  # noqa: E402  (after sys.path is set)
import math  # noqa: E402
import os  # noqa: E402
import tempfile  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
from matplotlib import pyplot  # noqa: E402  (after the backend is chosen)

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


class BadCsv(Exception):
    """The CSV is not one gplan wrote; the message names the file and line."""


def count(text, allow_empty):
    if text == "" and allow_empty:
        return None
    if not text.isdigit() or len(text) > 18:
        raise BadCsv("'%s' is no count" % text)
    return int(text)


def read_points(path):
    try:
        with open(path, newline="", encoding="utf-8", errors="replace") as file:
            reader = csv.reader(file, strict=True)
            points = []
            try:
                if next(reader, None) != COLUMNS:
                    raise BadCsv("%s:1: not an error-time CSV (the header differs from "
                                 "gplan's: %s)" % (path, ",".join(COLUMNS)))
                for fields in reader:
                    if fields == []:
                        continue
                    line = reader.line_num
                    if len(fields) != len(COLUMNS):
                        raise BadCsv("%s:%d: %d fields, not %d"
                                     % (path, line, len(fields), len(COLUMNS)))
                    row = dict(zip(COLUMNS, fields))
                    column = "time_s"
                    try:
                        row["time_s"] = float(row["time_s"])
                        if not math.isfinite(row["time_s"]) or row["time_s"] < 0:
                            raise BadCsv("'%s' is no time in seconds" % fields[4])
                        for column in COLUMNS[5:]:
                            row[column] = count(row[column], column != "total")
                    except ValueError:
                        raise BadCsv("%s:%d: column %s: '%s' is no number"
                                     % (path, line, column, row[column]))
                    except BadCsv as error:
                        raise BadCsv("%s:%d: column %s: %s" % (path, line, column, error))
                    for key in ("scene", "knob", "value", "checker"):
                        if row[key] == "":
                            raise BadCsv("%s:%d: column %s is empty" % (path, line, key))
                    points.append(row)
            except csv.Error as error:
                raise BadCsv("%s:%d: %s" % (path, reader.line_num, error))
    except OSError as error:
        raise BadCsv("%s: cannot be read (%s)" % (path, error.strerror or error))
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


def file_stem(name):
    stem = "".join(c if c.isascii() and (c.isalnum() or c in "._-") else "_" for c in name)
    return "_" + stem if stem.startswith(".") or stem == "" else stem


def save(figure, out_dir, stem):
    """Writes figure as out_dir/stem.png and .svg, each whole or not at all."""
    for extension, metadata in (("png", {"Software": None}),
                                ("svg", {"Date": None, "Creator": None})):
        path = os.path.realpath(os.path.join(out_dir, stem + "." + extension))
        handle, temporary = tempfile.mkstemp(prefix="." + stem + ".", suffix=".part",
                                             dir=os.path.dirname(path))
        try:
            with os.fdopen(handle, "wb") as file:
                figure.savefig(file, format=extension, metadata=metadata)
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(temporary, 0o666 & ~umask)
            os.replace(temporary, path)
        except BaseException:
            os.unlink(temporary)
            raise
    pyplot.close(figure)


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


def main(argv):
    if len(argv) != 3:
        print("usage: plot_error_time.py CSV OUT_DIR", file=sys.stderr)
        return 2
    matplotlib.rcdefaults()  # the same figures whatever the user's matplotlibrc says
    matplotlib.rcParams["svg.hashsalt"] = "gplan bench error-time"
    matplotlib.rcParams["path.simplify"] = True
    try:
        draw(read_points(argv[1]), argv[2])
    except BadCsv as error:
        print("plot_error_time.py: %s" % error, file=sys.stderr)
        return 2
    except OSError as error:
        print("plot_error_time.py: %s: cannot be written (%s)"
              % (error.filename or argv[2], error.strerror or error), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
