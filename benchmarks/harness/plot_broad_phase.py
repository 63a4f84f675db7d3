#!/usr/bin/env python3
"""Draws the plot of a `gplan-bench` broad-phase study from its CSV (written by
benchmarks/harness/broad_phase_record), with matplotlib, as PNG and SVG: OUT_DIR/broad_phase.png
and .svg, the median frame time (transfers included) against the sphere count, log-log,
one curve per method, the fastest method at each count marked and named under the axis
(the crossovers). Methods that did not run at a count (above their max_count, or no GPU)
have no point there. The output is deterministic: drawn twice, the files are identical.
gplan-bench runs this script embedded in its binary (benchmarks/harness/bench_plots.cpp) as
`python3 - CSV OUT_DIR`.

usage: plot_broad_phase.py CSV OUT_DIR
exit:  0 drawn, 1 an output could not be written, 2 the CSV is not a study's CSV
"""
import sys

# Run as `python3 - CSV OUT_DIR`, the working folder comes first in sys.path: a csv.py or
# matplotlib/ of the user's there must not stand in for the real ones.
if sys.path and sys.path[0] == "":
    del sys.path[0]

import math  # noqa: E402  (after sys.path is set)
import os  # noqa: E402

from plot_common import BadCsv, main, pyplot, read_csv, require, save  # noqa: E402

# The columns of write_broad_phase_csv_header() in benchmarks/harness/broad_phase_record.cpp.
COLUMNS = ["count", "method", "frames", "pairs_mean", "mean_ms", "median_ms", "min_ms",
           "max_ms", "fps_mean", "speedup", "reruns", "mismatches", "note"]
COLOURS = {"cpu-all-pairs": "#b2182b", "cpu-sort-sweep": "#e08214",
           "gpu-all-pairs": "#2166ac", "gpu-sort-sweep": "#762a83", "gpu-grid": "#1b7837",
           "gpu-lbvh": "#01665e"}
MARKERS = {"cpu-all-pairs": "o", "cpu-sort-sweep": "s", "gpu-all-pairs": "^",
           "gpu-sort-sweep": "D", "gpu-grid": "v", "gpu-lbvh": "P"}
SEED_COUNTS = (64, 320)


def point_of(row):
    """One CSV record as a point (a dict, the count, frames and median time parsed)."""
    require(row, ("method",))
    try:
        row["count"] = int(row["count"])
        row["frames"] = int(row["frames"])
        if row["frames"] > 0:
            row["median_ms"] = float(row["median_ms"])
            if not math.isfinite(row["median_ms"]) or row["median_ms"] < 0:
                raise ValueError(row["median_ms"])
    except ValueError:
        raise BadCsv("a count or time that is no number")
    return row


def read_points(path):
    points = read_csv(path, (COLUMNS,), "a broad-phase CSV", point_of)
    if not any(p["frames"] > 0 for p in points):
        raise BadCsv("%s: no method ran, nothing to plot" % path)
    return points


def fastest(points):
    """The fastest method at each count: [(count, method, median_ms)]."""
    best = {}
    for p in points:
        if p["frames"] > 0 and (p["count"] not in best or p["median_ms"] < best[p["count"]][1]):
            best[p["count"]] = (p["method"], p["median_ms"])
    return [(n, best[n][0], best[n][1]) for n in sorted(best)]


def draw(points, out_dir):
    os.makedirs(out_dir, exist_ok=True)
    figure, axes = pyplot.subplots(figsize=(9, 6))
    methods = list(dict.fromkeys(p["method"] for p in points))
    for index, method in enumerate(methods):
        own = sorted((p["count"], p["median_ms"]) for p in points
                     if p["method"] == method and p["frames"] > 0)
        if not own:
            continue
        axes.plot([n for n, _ in own], [ms for _, ms in own],
                  marker=MARKERS.get(method, "o"), color=COLOURS.get(method, "#4d4d4d"),
                  label=method, linewidth=1.3, markersize=5)
    winners = fastest(points)
    axes.scatter([n for n, _, _ in winners], [ms for _, _, ms in winners], s=120,
                 facecolors="none", edgecolors="black", linewidths=1.0, zorder=3,
                 label="fastest at the count")
    axes.axvspan(SEED_COUNTS[0], SEED_COUNTS[1], color="#bbbbbb", alpha=0.25,
                 label="the seed's counts (64 to 320)")
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("spheres (log scale)")
    axes.set_ylabel("median frame time, ms (log scale; transfers included)")
    axes.grid(True, which="major", alpha=0.3)
    axes.legend(fontsize=8, loc="upper left")
    ranges = []
    for n, method, _ in winners:
        if ranges and ranges[-1][0] == method:
            ranges[-1][2] = n
        else:
            ranges.append([method, n, n])
    text = "fastest: " + "; ".join("%s %s" % (m, str(a) if a == b else "%d-%d" % (a, b))
                                   for m, a, b in ranges)
    axes.set_title("Sphere broad phase: frame time against count\n" + text, fontsize=9)
    figure.tight_layout()
    save(figure, out_dir, "broad_phase")


if __name__ == "__main__":
    sys.exit(main(sys.argv, "plot_broad_phase.py", "gplan bench broad-phase", read_points, draw))
