#!/usr/bin/env python3
"""Turns the JSON lines of bench/collision_table.sh into the Markdown tables of
bench/RESULTS.md.

usage: bench/format_collision_table.py TABLE.jsonl [AGREEMENT.jsonl] [PEAK_RATES.json]
(AGREEMENT.jsonl may be given as "" to print the peak-rate table alone)
"""
import json
import sys

# The seed's figures (Pan & Manocha, GTX 480, 50,000 queries): basic, packet, balanced ms.
SEED = {"piano": (224, 130, 3.7), "large_piano": (710, 529, 15.1),
        "helicopter": (272, 226, 2.3), "humanoid": (2316, 1823, 126)}


def load(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.startswith("{")]


def timing_table(rows, peak):
    by_scene = {}
    for r in rows:
        key = r["backend"] + ("/" + r["traversal"] if "traversal" in r else "")
        by_scene.setdefault(r["name"], {})[key] = r
    out = ["| scene | robot / obstacle triangles | queries | gpu basic | gpu packet | gpu balanced | cpu (all cores) | fcl (all cores) | balanced vs basic | gpu best vs fcl | seed GTX 480: basic / packet / balanced |",
           "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for name, runs in by_scene.items():
        ms = {k: 1e3 * v["seconds"] for k, v in runs.items()}
        any_run = next(iter(runs.values()))
        best = min(ms.get("gpu/" + t, float("inf")) for t in ("basic", "packet", "balanced"))
        seed = SEED.get(name)
        out.append("| {} | {:,} / {:,} | {:,} | {:.2f} ms | {:.2f} ms | {:.2f} ms | {:.1f} ms | {:.1f} ms | {:.1f}x | {:.0f}x | {} |".format(
            name, any_run["robot_triangles"], any_run["obstacle_triangles"], any_run["n"],
            ms.get("gpu/basic", float("nan")), ms.get("gpu/packet", float("nan")), ms.get("gpu/balanced", float("nan")),
            ms.get("cpu", float("nan")), ms.get("fcl", float("nan")),
            ms.get("gpu/basic", float("nan")) / ms.get("gpu/balanced", float("nan")),
            ms.get("fcl", float("nan")) / best,
            "{} / {} / {} ms".format(*seed) if seed else "-"))
    if peak:
        out += ["", "Work per traversal and its price at the GPU's peak test rates ({:.3g} BV tests/s, {:.3g} triangle tests/s, measured by gplanner_peak_rates):".format(
            peak["bv_tests_per_s"], peak["triangle_tests_per_s"]), "",
            "| scene | traversal | BV tests | triangle tests | at peak rate | measured | measured / peak |",
            "| --- | --- | --- | --- | --- | --- | --- |"]
        for name, runs in by_scene.items():
            for t in ("basic", "packet", "balanced"):
                r = runs.get("gpu/" + t)
                if not r:
                    continue
                ideal = 1e3 * (r["bv_tests"] / peak["bv_tests_per_s"] + r["triangle_tests"] / peak["triangle_tests_per_s"])
                out.append("| {} | {} | {:,} | {:,} | {:.3f} ms | {:.2f} ms | {:.0f}x |".format(
                    name, t, r["bv_tests"], r["triangle_tests"], ideal, r["gpu_ms"], r["gpu_ms"] / ideal))
    return "\n".join(out)


def agreement_table(rows):
    out = ["| scene | backend | configurations | disagreements with fcl | missed collisions | extra within band | extra outside band |",
           "| --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        c = r["compare"]
        backend = r["backend"] + (" " + r["traversal"] if "traversal" in r else "")
        out.append("| {} | {} | {:,} | {} | {} | {} | {} |".format(
            r["name"], backend, r["n"], c["disagreements"], c["missed_collisions"], c["extra_within_band"],
            c["extra_outside_band"]))
    return "\n".join(out)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    peak = json.load(open(sys.argv[3])) if len(sys.argv) > 3 else None
    print(timing_table(load(sys.argv[1]), peak))
    if len(sys.argv) > 2 and sys.argv[2]:
        print()
        print(agreement_table(load(sys.argv[2])))


if __name__ == "__main__":
    main()
