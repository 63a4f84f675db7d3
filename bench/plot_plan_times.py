#!/usr/bin/env python3
"""Draws the plan-time table of bench/RESULTS.md as an SVG picture: one row per scene,
one line per planner on a logarithmic time axis, from its fastest to its slowest run,
each run a mark (filled: found a path; hollow: none within the limit), the median a
bar. Reads the JSON lines of gplanner_plan_bench, as bench/format_plan_table.py does.

usage: bench/plot_plan_times.py OUT.svg TITLE RUNS.jsonl [RUNS.jsonl ...]
"""
import json
import math
import statistics
import sys
from collections import defaultdict
from xml.sax.saxutils import escape

PLANNERS = [  # (name in the runs, label, colour)
    ("ours-lazyprm", "ours: lazy PRM (GPU)", "#1b7837"),
    ("ours-prm", "ours: PRM (GPU)", "#5aae61"),
    ("ompl-lazyprm", "OMPL LazyPRM + FCL", "#762a83"),
    ("ompl-prm", "OMPL PRM + FCL", "#c2a5cf"),
    ("ompl-rrtconnect", "OMPL RRTConnect + FCL", "#e08214"),
]
SCENES = ["piano", "large_piano", "helicopter", "humanoid", "piano_detailed", "pr2_reach",
          "pr2_base_arm"]

LEFT, RIGHT, TOP = 130, 30, 60
WIDTH = 900
LANE = 13  # pixels per planner within a scene's row
ROW = LANE * len(PLANNERS) + 16


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    out, title = sys.argv[1], sys.argv[2]
    runs = defaultdict(list)
    for path in sys.argv[3:]:
        for line in open(path):
            r = json.loads(line)
            runs[(r["scene"], r["planner"])].append(r)
    scenes = [s for s in SCENES if any((s, p) in runs for p, _, _ in PLANNERS)]
    times = [r["seconds"] for v in runs.values() for r in v]
    lo = 10 ** math.floor(math.log10(min(times)))
    hi = 10 ** math.ceil(math.log10(max(times)))
    plot_width = WIDTH - LEFT - RIGHT

    def x(t):
        return LEFT + plot_width * (math.log10(t) - math.log10(lo)) / (
            math.log10(hi) - math.log10(lo))

    height = TOP + ROW * len(scenes) + 40 + 18 * len(PLANNERS)
    svg = [
        '<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" '
        'font-family="sans-serif" font-size="12">' % (WIDTH, height),
        '<rect width="100%" height="100%" fill="white"/>',
        '<text x="%d" y="20" font-size="14">%s</text>' % (LEFT, escape(title)),
        '<text x="%d" y="38" fill="#555">plan time in seconds, logarithmic; a mark per run '
        '(hollow: no path within the limit), a bar at the median</text>' % LEFT,
    ]
    bottom = TOP + ROW * len(scenes)
    decade = lo
    while decade <= hi * 1.0001:
        svg.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="#ddd"/>' %
                   (x(decade), TOP - 6, x(decade), bottom))
        svg.append('<text x="%.1f" y="%d" text-anchor="middle">%g</text>' %
                   (x(decade), bottom + 16, decade))
        decade *= 10
    for i, scene in enumerate(scenes):
        y0 = TOP + i * ROW
        svg.append('<text x="%d" y="%d" text-anchor="end">%s</text>' %
                   (LEFT - 8, y0 + ROW / 2, escape(scene)))
        svg.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="#bbb"/>' %
                   (LEFT, y0 + ROW - 4, WIDTH - RIGHT, y0 + ROW - 4))
        for j, (planner, _, colour) in enumerate(PLANNERS):
            v = runs.get((scene, planner))
            if not v:
                continue
            y = y0 + 6 + j * LANE
            t = [r["seconds"] for r in v]
            svg.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="%s"/>' %
                       (x(min(t)), y, x(max(t)), y, colour))
            for r in v:
                fill = colour if r["solved"] else "white"
                svg.append('<circle cx="%.1f" cy="%d" r="3.5" fill="%s" stroke="%s"/>' %
                           (x(r["seconds"]), y, fill, colour))
            m = statistics.median(t)
            svg.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="black" '
                       'stroke-width="2"/>' % (x(m), y - 5, x(m), y + 5))
    for j, (_, label, colour) in enumerate(PLANNERS):
        y = bottom + 40 + 18 * j
        svg.append('<circle cx="%d" cy="%d" r="4" fill="%s"/>' % (LEFT, y - 4, colour))
        svg.append('<text x="%d" y="%d">%s</text>' % (LEFT + 12, y, escape(label)))
    svg.append("</svg>")
    with open(out, "w") as f:
        f.write("\n".join(svg) + "\n")


if __name__ == "__main__":
    main()
