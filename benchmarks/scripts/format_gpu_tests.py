#!/usr/bin/env python3
"""Turns the GPU test output that benchmarks/scripts/reproduce.sh writes (gpu_tests.txt: for each test
program a line "== program: NAME ARGS", its gtest output, then "== exit status: N") into
the GPU-test table of benchmarks/RESULTS.md: per program the tests run, passed, skipped
(named) and failed (named), and the time. Older files without those lines hold the
summaries of gplanner_tests and gplanner_stability_tests in that order.

usage: benchmarks/scripts/format_gpu_tests.py GPU_TESTS.txt
"""
import re
import sys

DEFAULT_PROGRAMS = ["gplanner_tests --gtest_filter=*Gpu*",
                    "gplanner_stability_tests --gtest_filter=*Gpu*"]
RAN = re.compile(r"^\[==========\] (\d+) tests? from \d+ test suites? ran\. \((\d+) ms total\)")
COUNT = re.compile(r"^\[  (PASSED|SKIPPED|FAILED) +\] (\d+) tests?")
NAMED = re.compile(r"^\[  (SKIPPED|FAILED) +\] ([\w/.]+)\s*(?:,.*)?$")


def blocks(lines):
    """(program, its lines, exit status or None) for each program in the file."""
    if any(line.startswith("== program: ") for line in lines):
        out = []
        for line in lines:
            if line.startswith("== program: "):
                out.append([line[len("== program: "):].strip(), [], None])
            elif line.startswith("== exit status: ") and out:
                out[-1][2] = int(line.split(":")[1])
            elif out:
                out[-1][1].append(line)
        return out
    out, current = [], []
    for line in lines:
        if RAN.match(line) and current and any(RAN.match(x) for x in current):
            out.append(current)
            current = []
        current.append(line)
    out.append(current)
    return [[DEFAULT_PROGRAMS[i] if i < len(DEFAULT_PROGRAMS) else "program %d" % (i + 1), b, None]
            for i, b in enumerate(out)]


def summary(program, lines, status):
    ran = time = None
    counts = {"PASSED": 0, "SKIPPED": 0, "FAILED": 0}
    names = {"SKIPPED": [], "FAILED": []}
    in_summary = False
    for line in lines:
        m = RAN.match(line)
        if m:
            ran, time, in_summary = int(m.group(1)), int(m.group(2)), True
            continue
        if not in_summary:
            continue
        m = COUNT.match(line)
        if m:
            counts[m.group(1)] = int(m.group(2))
            continue
        m = NAMED.match(line)
        if m:
            names[m.group(1)].append(m.group(2))

    def named(kind):
        n = counts[kind]
        return "%d (%s)" % (n, ", ".join("`%s`" % x for x in names[kind])) if names[kind] else str(n)

    if ran is None:
        return "| `%s` | no gtest summary%s | - | - | - | - |" % (
            program, "" if status is None else " (exit status %d)" % status)
    return "| `%s` | %d | %d | %s | %s | %.1f s |" % (
        program, ran, counts["PASSED"], named("SKIPPED"), named("FAILED"), time / 1e3)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        lines = f.read().splitlines()
    print("| program | tests run | passed | skipped | failed | time |")
    print("| --- | --- | --- | --- | --- | --- |")
    for program, block, status in blocks(lines):
        print(summary(program, block, status))


if __name__ == "__main__":
    main()
