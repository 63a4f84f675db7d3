#!/usr/bin/env python3
"""Turns the JSON lines of benchmarks/scripts/collision_table.sh into the Markdown tables of
benchmarks/RESULTS.md.

usage: benchmarks/scripts/format_collision_table.py TABLE.jsonl [AGREEMENT.jsonl] [PEAK_RATES.json]
TABLE.jsonl gives the timing table (and with PEAK_RATES.json the work at peak rates),
AGREEMENT.jsonl the agreement with fcl; either may be given as "" to leave it out.
"""
import json
import sys

# The seed's figures (Pan & Manocha, GTX 480, 50,000 queries): basic, packet, balanced ms.
SEED = {"piano": (224, 130, 3.7), "large_piano": (710, 529, 15.1),
        "helicopter": (272, 226, 2.3), "humanoid": (2316, 1823, 126)}


def load(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.startswith("{")]


def millions(count):
    """A count in millions to three significant digits, trailing zeros kept."""
    m = count / 1e6
    return "{:.0f}".format(m) if m >= 99.95 else "{:.1f}".format(m) if m >= 9.995 else \
        "{:.2f}".format(m) if m >= 0.9995 else "{:.3f}".format(m)


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
        out += ["", "Work per traversal and its price at the GPU's peak test rates ({:.3g} BV tests/s, {:.3g} triangle tests/s, measured by gplanner_peak_rates); the kernels' time measured against that price:".format(
            peak["bv_tests_per_s"], peak["triangle_tests_per_s"]), "",
            "| scene | BV tests, millions: basic / packet / balanced | triangle tests, millions | basic: measured / at peak rate | packet | balanced |",
            "| --- | --- | --- | --- | --- | --- |"]
        traversals = ("basic", "packet", "balanced")
        for name, runs in by_scene.items():
            r = [runs.get("gpu/" + t) for t in traversals]
            if not any(r):
                continue

            def counts(key):
                return " / ".join(millions(x[key]) if x else "-" for x in r)

            def price(x):
                if not x:
                    return "-"
                ideal = 1e3 * (x["bv_tests"] / peak["bv_tests_per_s"] + x["triangle_tests"] / peak["triangle_tests_per_s"])
                return "{:.2f} / {:.3f} ms ({:.0f}x)".format(x["gpu_ms"], ideal, x["gpu_ms"] / ideal)

            out.append("| {} | {} | {} | {} |".format(name, counts("bv_tests"), counts("triangle_tests"),
                                                    " | ".join(price(x) for x in r)))
    return "\n".join(out)


# The runs of benchmarks/scripts/collision_table.sh's agreement, in its order, one column each.
AGREEMENT_RUNS = ["gpu basic", "gpu packet", "gpu balanced", "cpu"]


def agreement_table(rows):
    """One row per scene; each cell holds one figure where gpu basic, packet, balanced
    and cpu give the same, else each run's figure, named."""
    by_scene = {}
    for r in rows:
        backend = r["backend"] + (" " + r["traversal"] if "traversal" in r else "")
        by_scene.setdefault(r["name"], {})[backend] = r
    out = ["| scene | configurations | disagreements with fcl | missed collisions | extra within band | extra outside band |",
           "| --- | --- | --- | --- | --- | --- |"]
    for name, runs in by_scene.items():
        named = [b for b in AGREEMENT_RUNS if b in runs] + [b for b in runs if b not in AGREEMENT_RUNS]

        def cell(get):
            values = [get(runs[b]) for b in named]
            if named == AGREEMENT_RUNS and len(set(values)) == 1:
                return "{:,}".format(values[0])
            return ", ".join("{} {:,}".format(b, v) for b, v in zip(named, values))

        out.append("| {} | {} | {} | {} | {} | {} |".format(
            name, cell(lambda r: r["n"]), cell(lambda r: r["compare"]["disagreements"]),
            cell(lambda r: r["compare"]["missed_collisions"]), cell(lambda r: r["compare"]["extra_within_band"]),
            cell(lambda r: r["compare"]["extra_outside_band"])))
    return "\n".join(out)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    peak = json.load(open(sys.argv[3])) if len(sys.argv) > 3 and sys.argv[3] else None
    tables = []
    if sys.argv[1]:
        tables.append(timing_table(load(sys.argv[1]), peak))
    if len(sys.argv) > 2 and sys.argv[2]:
        tables.append(agreement_table(load(sys.argv[2])))
    print("\n\n".join(tables))


if __name__ == "__main__":
    main()
