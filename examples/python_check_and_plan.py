#!/usr/bin/env python3
"""gplanner from Python: check a million configurations, plan a MotionBenchMaker problem,
and plot the path's joint values.

    PYTHONPATH=build/python /usr/bin/python3 examples/python_check_and_plan.py \
        [--data ../shared/data/motionbenchmaker/panda] [--problem 0] [--backend gpu] \
        [--n 1000000] [--out panda_path.png]

Prints what it did and writes the plot (PNG, matplotlib's Agg backend: no display).
"""

import argparse
import os
import time

import numpy as np

import gplanner


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data",
                                                       "motionbenchmaker", "panda"),
                        help="a MotionBenchMaker set: robot/ and problems/")
    parser.add_argument("--problem", type=int, default=0, help="its index, in name order")
    parser.add_argument("--backend", default="gpu", help="gpu, cpu or fcl")
    parser.add_argument("--n", type=int, default=1_000_000, help="configurations to check")
    parser.add_argument("--time-limit", type=float, default=10.0, help="seconds to plan")
    parser.add_argument("--out", default="panda_path.png", help="the plot (PNG)")
    args = parser.parse_args()

    problems = gplanner.motionbenchmaker_problems(args.data)
    p = problems[args.problem]
    scene = gplanner.load_moveit_scene(p["urdf"], p["srdf"], p["scene"], p["request"],
                                       p["packages"], name="%s %d" % (p["scenario"], p["number"]))
    checker = scene.checker(args.backend)
    print("%s: %d DOF, checked on the %s backend %s" % (scene.name, scene.dof, checker.backend,
                                                        checker.notice))

    q = scene.sample(args.n, seed=1)
    started = time.perf_counter()
    hit = checker.check(q)
    seconds = time.perf_counter() - started
    print("checked %d configurations in %.3f s: %d collide (%.1f %%)"
          % (len(q), seconds, hit.sum(), 100.0 * hit.mean()))

    result = checker.plan(seed=1, time_limit=args.time_limit)
    stats = result.stats
    if not result.solved:
        raise SystemExit("no path: " + stats["stop_reason"])
    problem = scene.recheck(result.path)
    print("planned in %.1f ms: %d waypoints, length %.3f, %d GPU calls; FCL re-check: %s"
          % (1e3 * stats["seconds"], len(result.path), stats["length"],
             stats["gpu_calls"]["total"], problem or "pass"))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    lengths = np.concatenate([[0], np.cumsum(np.abs(np.diff(result.path, axis=0)).sum(axis=1))])
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for j in range(scene.width):
        ax.plot(lengths, result.path[:, j], marker="o", markersize=3, label="joint %d" % (j + 1))
    ax.set_xlabel("distance along the path (sum of joint motions, rad)")
    ax.set_ylabel("joint value (rad)")
    ax.set_title("%s: the path's joint values at its %d waypoints" % (scene.name, len(result.path)))
    ax.legend(fontsize=8, ncol=4)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print("wrote " + args.out)


if __name__ == "__main__":
    main()
