#!/usr/bin/env python3
"""The Python module's overhead on a check (issue 34): one call of N configurations and
one call of one row, through gplanner's Checker.check against the same C++ checker call
timed in C++ (Checker._check_seconds: no Python between its clocks), on the same rows,
checker and process. Medians of R calls each (after a warm-up call). Prints one JSON
line: the times, the overhead (Python's median less C++'s) and its share of the C++ call.

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/programs/python_overhead.py \
        SCENE [--backend gpu] [--n 100000] [--repeat 15] [--single-repeat 20000]

Targets: at most 5 % of the C++ call for 100,000 configurations, at most 5 us for one row.
"""

import argparse
import json
import statistics
import time

import gplanner


def python_seconds(check, q, repeat):
    seconds = []
    for _ in range(repeat):
        started = time.perf_counter()
        check(q)
        seconds.append(time.perf_counter() - started)
    return seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene")
    parser.add_argument("--backend", default="gpu")
    parser.add_argument("--n", type=int, default=100_000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--repeat", type=int, default=15)
    parser.add_argument("--single-repeat", type=int, default=20_000)
    args = parser.parse_args()
    scene = gplanner.load_scene(args.scene)
    checker = scene.checker(args.backend)
    q = scene.sample(args.n, seed=args.seed)
    one = q[:1].copy()
    report = {"benchmark": "python_overhead", "scene": scene.name, "backend": checker.backend,
              "n": args.n, "version": gplanner.__version__}
    for label, rows, repeat in (("batch", q, args.repeat), ("one_row", one, args.single_repeat)):
        checker.check(rows)  # warm-up: first launches, caches
        # Interleaved, so that both see the same state of the machine.
        py, cpp = [], []
        for _ in range(5):
            py += python_seconds(checker.check, rows, repeat // 5 or 1)
            cpp += checker._check_seconds(rows, repeat // 5 or 1)
        py_median, cpp_median = statistics.median(py), statistics.median(cpp)
        report[label] = {"python_s": py_median, "cpp_s": cpp_median,
                         "overhead_s": py_median - cpp_median,
                         "overhead_share": (py_median - cpp_median) / cpp_median,
                         "calls": len(py)}
    print(json.dumps(report))


if __name__ == "__main__":
    main()
