#!/usr/bin/env python3
"""Turns the JSON line of gplanner_knn_bench into the k-NN table of benchmarks/RESULTS.md:
the GPU's all-points search against the CPU reference (brute force, all threads) and
OMPL's GNAT (one thread), with how often their neighbour sets agree.

usage: benchmarks/scripts/format_knn_table.py KNN.jsonl
"""
import json
import sys


def agree(fraction):
    """The bench's agreement is the fraction of points whose neighbour sets are equal
    up to ties."""
    if fraction >= 1:
        return "same neighbour sets (up to ties)"
    return "{:.4%} of the neighbour sets the same (up to ties)".format(fraction)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        rows = [json.loads(line) for line in f if line.startswith("{")]
    if not rows:
        sys.exit("format_knn_table.py: no JSON line in " + sys.argv[1])
    r = rows[-1]
    print("| {:,} {} milestones, k = {} | time | against the GPU |".format(r["points"], r["robot"], r["k"]))
    print("| --- | --- | --- |")
    print("| GPU all-kNN ({}; median of {} runs after a warm-up, GPU time from upload to download) "
          "| {:.2f} ms ({:.2f} to {:.2f}); search kernel {:.2f} ms; wall clock of the call {:.1f} ms | |".format(
              r["device"], r["gpu_runs"], r["gpu_ms"], r["gpu_ms_min"], r["gpu_ms_max"], r["gpu_search_ms"],
              r["gpu_wall_ms"]))
    if "cpu_reference_ms" in r:
        print("| CPU reference, brute force, {} threads | {:,.0f} ms | {:,.0f}x; {} |".format(
            r["cpu_threads"], r["cpu_reference_ms"], r["cpu_over_gpu"], agree(r["gpu_matches_cpu"])))
    if "gnat_total_ms" in r:
        print("| OMPL's GNAT, one thread: build + {:,} queries | {:,.0f} + {:,.0f} ms | {:,.0f}x; {} |".format(
            r["points"], r["gnat_build_ms"], r["gnat_query_ms"], r["gnat_total_over_gpu"],
            agree(r["gnat_matches_gpu"])))


if __name__ == "__main__":
    main()
