"""The time-limit table (benchmarks/scripts/reproduce.sh time-limit) in Markdown: per shipped scene,
backend and milestone count, gplan plan's exit, planning, setup and wall time, and how
far the wall time less the setup went past the limit (the bound: the larger of 5 % and
100 ms)."""
import json
import sys


def main(path):
    rows = [json.loads(line) for line in open(path) if line.strip()]
    print("| scene | backend | milestones | exit | planning (s) | setup (s) | wall (s) "
          "| wall - setup - limit |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    worst = None
    for r in rows:
        run = r["run"]
        if not run:
            print("| ? | ? | %s | %d | - | - | %.3f | no result |" % (r["milestones_arg"], r["exit"], r["wall"]))
            continue
        over = r["wall"] - run["setup_seconds"] - r["limit"]
        bound = max(0.05 * r["limit"], 0.1)
        worst = over if worst is None else max(worst, over)
        print("| %s | %s | %s | %d | %.3f | %.3f | %.3f | %+.0f ms%s |" % (
            run["name"], run["backend"], r["milestones_arg"], r["exit"], run["seconds"],
            run["setup_seconds"], r["wall"], 1000 * over, "" if over <= bound else " (over the bound)"))
    if worst is not None:
        print("\nWorst: %+.0f ms past the limit of 1 s (the bound: 100 ms)." % (1000 * worst))


if __name__ == "__main__":
    main(sys.argv[1])
