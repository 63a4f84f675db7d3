"""gplanner.distributed on a local Dask cluster of two CPU workers.

The merged shards of a benchmark equal a one-process gplan-bench run of the same
configuration (records, failed paths, report); a shard failing once is retried, one
failing every time is reported with its records missing and the others kept; a folder
with files in it is refused; plan_problems gives a record per problem and seed, equal to
planning in this process, and an error record (not retried) for a start in collision;
the command line end to end, and its one-line refusal of a bad configuration.
"""

import csv
import os
import pathlib
import stat
import subprocess
import sys

import numpy as np
import pytest

try:
    import distributed
    from distributed import Client, LocalCluster, get_task_stream
except ImportError as e:  # Debian's python3-distributed (scripts/setup.sh installs it)
    pytest.skip("no dask.distributed (%s): apt-get install python3-distributed" % e,
                allow_module_level=True)

import gplanner
from gplanner import distributed as gd
from conftest import SCENES, cube_scene

pytestmark = pytest.mark.filterwarnings(  # tornado 6.2 under distributed 2022.12
    "ignore:make_current is deprecated:DeprecationWarning")

# Fields of a record that a seed decides (the times are the machine's). Checked by hand
# first: two one-process runs of the configuration below gave the same values in each.
# (Not so for runs that end at their time limit, whose lengths depend on the time: the
# configuration holds none.) Not `checks`: the planners cut their checks into batches
# sized by the measured time, so a loaded machine (ctest's parallel tests) counts a
# few samples more or fewer for the same path.
SEEDED = ("seed", "status", "solved", "length", "simplified_length", "graph_states",
          "path_check", "rounds", "note")


@pytest.fixture(scope="module")
def client():
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as c:
        yield c


@pytest.fixture
def gplan_bench(gplan):
    path = os.path.join(os.path.dirname(os.path.abspath(gplan)), "gplan-bench")
    if not os.access(path, os.X_OK):
        pytest.skip("no gplan-bench beside %s" % gplan)
    return path


@pytest.fixture(scope="module")
def cubes(tmp_path_factory):
    """Three small scenes of a cube robot (each plans in a few milliseconds)."""
    folder = tmp_path_factory.mktemp("cubes")
    return [cube_scene(folder, ["box: [0.6, 0.6, 0.6]"], name="cube_box"),
            cube_scene(folder, ["box: [0.3, 0.3, 0.3]"], name="cube_small_box"),
            cube_scene(folder, ["box: [0.02, 3, 3]"], name="cube_wall")]


def write_config(folder, name, scenes, planners, runs):
    path = pathlib.Path(folder) / (name + ".yaml")
    path.write_text("name: %s\nkind: planning\nscenes: [%s]\nplanners: [%s]\nruns: %d\n"
                    "time_limit: 30\nseed: 1\n"
                    % (name, ", ".join(scenes), ", ".join(planners), runs))
    return str(path)


@pytest.fixture
def cube_config(tmp_path, cubes):
    """Our planners on the three cubes, one run each: 6 records, 2 a shard of 3."""
    return write_config(tmp_path, "cubes", cubes, ["ours-rrtconnect@cpu", "ours-lazyprm@cpu"], 1)


def records(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def key(r):
    return (r["scene"], r["planner"], r["checker"], r["run"])


def failing_program(folder, gplan_bench, shard, times):
    """A gplan-bench that fails (exit 1) the first `times` calls for `shard` (I/N), then
    runs the real one; every call is logged in folder/calls.txt."""
    script = pathlib.Path(folder) / "gplan-bench-failing"
    calls = pathlib.Path(folder) / "calls.txt"
    script.write_text(
        "#!/bin/sh\n"
        'echo "$*" >> "%s"\n'
        'case " $* " in *" --shard %s "*)\n'
        '  if [ "$(grep -c -- "--shard %s " "%s")" -le %d ]; then\n'
        '    echo "simulated failure of shard %s" >&2; exit 1\n'
        "  fi;;\n"
        "esac\n"
        'exec "%s" "$@"\n' % (calls, shard, shard, calls, times, shard, gplan_bench))
    script.chmod(script.stat().st_mode | stat.S_IXUSR)
    return str(script), calls


# --- run_benchmark -------------------------------------------------------------------

def test_merged_shards_equal_a_one_process_run(client, gplan_bench, cubes, tmp_path):
    # Ours on the cpu backend (alone) and OMPL's RRTConnect with FCL (one thread, run
    # after them) on a shipped scene and two cubes; OMPL's coarser motion check cuts the
    # cubes' corners, so some paths fail the re-check (failed_paths/, status 3) as well.
    config = write_config(tmp_path, "mixed", [str(SCENES / "pr2_base_arm.yaml")] + cubes[::2],
                          ["ours-rrtconnect@cpu", "ours-lazyprm@cpu", "ompl-rrtconnect@fcl"], 2)
    alone = tmp_path / "alone"
    one = subprocess.run([gplan_bench, config, "-o", str(alone), "--no-plots"],
                         capture_output=True, text=True)
    assert one.returncode in (0, 3), one.stderr

    lines = []
    run = gd.run_benchmark(client, config, tmp_path / "merged", gplan_bench=gplan_bench,
                           progress=lines.append)
    out = tmp_path / "merged"
    assert run.shards == 3 and run.failures == [] and run.ok
    assert run.report_status == one.returncode and run.exit_status == one.returncode
    assert sum("done on" in line for line in lines) == 3
    expected, merged = records(alone / "results.csv"), records(out / "results.csv")
    assert len(expected) == 3 * 3 * 2
    # The same records in the same order (a one-process run's), the seeded fields equal.
    assert [key(r) for r in merged] == [key(r) for r in expected]
    for a, b in zip(expected, merged):
        assert {f: a[f] for f in SEEDED} == {f: b[f] for f in SEEDED}, key(a)
    assert [key(r) for r in run.records] == [key(r) for r in expected]
    assert (out / "results.csv").read_text().count("experiment,") == 1  # one header
    # The paths that failed the re-check, byte for byte; the config; the OMPL logs.
    failed = sorted(p.name for p in (alone / "failed_paths").glob("*"))
    assert sorted(p.name for p in (out / "failed_paths").glob("*")) == failed
    for name in failed:
        assert (out / "failed_paths" / name).read_bytes() == \
            (alone / "failed_paths" / name).read_bytes()
    assert (out / "config.yaml").read_text() == pathlib.Path(config).read_text()
    assert sorted(p.name for p in (out / "ompl").glob("*")) == \
        sorted(p.name for p in (alone / "ompl").glob("*"))
    assert not (out / "results.partial.csv").exists() and not (out / "failures.txt").exists()
    # The summary names every group; gplan-bench --report reads the folder as its own.
    summary = (out / "summary.txt").read_text()
    assert summary == run.summary
    groups = {(r["scene"], r["planner"] + "@" + r["checker"]) for r in expected}
    rows = {tuple(line.split()[:2]) for line in summary.splitlines()}
    assert groups <= rows
    (out / "summary.txt").unlink()
    again = subprocess.run([gplan_bench, config, "--report", str(out), "--no-plots"],
                           capture_output=True, text=True)
    assert again.returncode == one.returncode, again.stderr
    assert groups <= {tuple(line.split()[:2])
                      for line in (out / "summary.txt").read_text().splitlines()}


def test_a_shard_failing_once_is_retried(client, gplan_bench, cube_config, tmp_path):
    program, calls = failing_program(tmp_path, gplan_bench, "2/3", times=1)
    run = gd.run_benchmark(client, cube_config, tmp_path / "out", shards=3, retries=2,
                           gplan_bench=program, progress=lambda line: None)
    assert run.ok and run.failures == [] and run.exit_status == 0
    shard_calls = [line for line in calls.read_text().splitlines() if "--shard" in line]
    assert sorted(line.split("--shard ")[1].split()[0] for line in shard_calls) == \
        ["1/3", "2/3", "2/3", "3/3"]  # shard 2 ran twice: failed, then retried
    assert sorted(key(r) for r in records(tmp_path / "out" / "results.csv")) == sorted(
        (scene, planner, "cpu", "0") for scene in ("cube_box", "cube_small_box", "cube_wall")
        for planner in ("ours-rrtconnect", "ours-lazyprm"))


def test_a_shard_failing_after_its_retries_is_reported_not_lost(client, gplan_bench,
                                                                cube_config, tmp_path):
    program, calls = failing_program(tmp_path, gplan_bench, "2/3", times=100)
    out = tmp_path / "out"
    run = gd.run_benchmark(client, cube_config, out, shards=3, retries=1, gplan_bench=program,
                           progress=lambda line: None)
    assert not run.ok and run.exit_status == gd.EXIT_SHARDS_FAILED
    assert run.report_status == 0  # the shards that ran are summarised
    [failure] = run.failures
    assert (failure.shard, failure.shards, failure.status) == (2, 3, 1)
    assert failure.worker in client.scheduler_info()["workers"]
    assert "simulated failure of shard 2/3" in failure.stderr
    assert calls.read_text().count("--shard 2/3") == 2  # tried, and retried once
    text = (out / "failures.txt").read_text()
    assert "shard 2/3 on %s" % failure.worker in text and "status 1" in text
    assert "simulated failure of shard 2/3" in text
    assert "INCOMPLETE" in run.summary and "2/3" in run.summary.split("INCOMPLETE")[1]
    # Shard 2 of 3 is the second scene: missing; the others' records are all there.
    assert sorted(key(r) for r in records(out / "results.csv")) == sorted(
        (scene, planner, "cpu", "0") for scene in ("cube_box", "cube_wall")
        for planner in ("ours-rrtconnect", "ours-lazyprm"))


def test_a_folder_with_files_is_refused_and_left_as_it_was(client, gplan_bench, cube_config,
                                                           tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "results.csv").write_text("an earlier run\n")
    with pytest.raises(gd.BenchmarkError, match="has files in it; name a new or empty folder"):
        gd.run_benchmark(client, cube_config, out, gplan_bench=gplan_bench)
    assert os.listdir(out) == ["results.csv"]
    assert (out / "results.csv").read_text() == "an earlier run\n"
    # A configuration gplan-bench refuses: its message, and no folder made.
    bad = tmp_path / "bad.yaml"
    bad.write_text(pathlib.Path(cube_config).read_text().replace("ours-lazyprm@cpu",
                                                                 "ours-rrt@cpu"))
    with pytest.raises(gd.BenchmarkError, match=r"bad\.yaml:\d+: planners\[1\]: 'ours-rrt@cpu'"):
        gd.run_benchmark(client, str(bad), tmp_path / "new", gplan_bench=gplan_bench)
    assert not (tmp_path / "new").exists()
    with pytest.raises(gd.BenchmarkError, match="nowhere/gplan-bench"):
        gd.run_benchmark(client, cube_config, tmp_path / "new",
                         gplan_bench=str(tmp_path / "nowhere" / "gplan-bench"))


# --- plan_problems -------------------------------------------------------------------

def test_plan_problems_equal_plans_made_here(client, tmp_path):
    files = [str(SCENES / "pr2_base_arm.yaml"), str(SCENES / "humanoid.yaml")]
    blocked = cube_scene(tmp_path, ["box: [1, 1, 1]"], start=(0, 0, 0), goal=(1.5, 0, 0),
                         name="blocked")
    missing = str(tmp_path / "nowhere.yaml")
    with get_task_stream(client) as stream:
        got = gd.plan_problems(client, files + [blocked, missing], backend="cpu", seeds=(1, 2),
                               time_limit=60, progress=lambda line: None)
    assert [(r["problem"], r["seed"]) for r in got] == [
        (f, s) for f in files + [blocked, missing] for s in (1, 2)]
    for r in got[:4]:
        scene = gplanner.load_scene(r["problem"])
        assert r["error"] is None and r["solved"] and r["backend"] == "cpu", r
        assert r["path"].dtype == np.float32 and r["path"].shape[1] == scene.width
        np.testing.assert_array_equal(r["path"][0], scene.start)
        np.testing.assert_array_equal(r["path"][-1], scene.goal)
        here = scene.checker("cpu").plan(seed=r["seed"], time_limit=60)
        np.testing.assert_array_equal(r["path"], here.path)
        assert r["stats"]["length"] == here.stats["length"]
        assert r["stats"]["planner"] == here.stats["planner"]
    # A start in collision, a file that does not exist: error records, tried once.
    for r in got[4:]:
        assert not r["solved"] and r["path"].shape[0] == 0 and r["stats"] == {}
    assert "blocked.yaml" in got[4]["error"] and "start" in got[4]["error"]
    assert got[4]["path"].shape == (0, 7) and got[4]["error"] == got[5]["error"]
    assert "nowhere.yaml" in got[6]["error"]
    tries = [t["status"] for t in stream.data if str(t["key"]).startswith("gplanner-plan-")]
    assert tries == ["OK"] * 4  # no error, so no retry


def test_plan_problems_refuses_misuse_before_any_task(client):
    scene = str(SCENES / "pr2_base_arm.yaml")
    with pytest.raises(ValueError, match="planner: 'rrt' is not one of"):
        gd.plan_problems(client, [scene], planner="rrt")
    with pytest.raises(ValueError, match="seeds"):
        gd.plan_problems(client, [scene], seeds=[-1])
    with pytest.raises(TypeError, match="give a scene file"):
        gd.plan_problems(client, [3])


# --- the cluster of this host --------------------------------------------------------

def test_local_gpu_cluster_gives_each_worker_its_gpu():
    with gd.local_gpu_cluster(gpus=2, threads_per_worker=1) as cluster, Client(cluster) as c:
        c.wait_for_workers(2)
        workers = c.scheduler_info()["workers"]
        assert sorted(w["resources"].get("GPU") for w in workers.values()) == [1, 1]
        assert sorted(w["nthreads"] for w in workers.values()) == [1, 1]
        seen = c.run(lambda: (os.environ.get("CUDA_VISIBLE_DEVICES"),
                              os.environ.get("NCCL_NVLS_ENABLE")))
        visible = os.environ.get("CUDA_VISIBLE_DEVICES")
        assert sorted(seen.values()) == [(d, "0") for d in
                                         (visible.split(",")[:2] if visible else ["0", "1"])]


# --- the command line ----------------------------------------------------------------

def cli(*args, **env):
    return subprocess.run([sys.executable, "-m", "gplanner.distributed"] + list(args),
                          capture_output=True, text=True, env=dict(os.environ, **env),
                          timeout=300)


def test_the_command_line_runs_a_benchmark_end_to_end(gplan_bench, cube_config, tmp_path):
    out = tmp_path / "out"
    done = cli("bench", cube_config, "-o", str(out), "--local-workers", "2",
               GPLANNER_GPLAN_BENCH=gplan_bench)
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr
    assert "shard 3/3 done on" in done.stderr and "results: %s (6 records)" % out in done.stderr
    assert len(records(out / "results.csv")) == 6
    summary = (out / "summary.txt").read_text()
    assert "cube_small_box  ours-lazyprm@cpu" in summary and summary in done.stdout


def test_the_command_line_refuses_bad_input_in_one_line(gplan_bench, cube_config, tmp_path):
    done = cli("bench", str(tmp_path / "nothere.yaml"), "-o", str(tmp_path / "out"),
               "--local-workers", "2", GPLANNER_GPLAN_BENCH=gplan_bench)
    assert done.returncode == 2
    assert done.stderr.count("\n") == 1 and "nothere.yaml" in done.stderr
    assert "does not exist; fix the path" in done.stderr
    assert not (tmp_path / "out").exists()
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "keep.txt").write_text("mine")
    done = cli("bench", cube_config, "-o", str(tmp_path / "full"), "--local-workers", "1",
               GPLANNER_GPLAN_BENCH=gplan_bench)
    assert done.returncode == 2 and done.stderr.count("\n") == 1, done.stderr
    assert "has files in it" in done.stderr
    assert os.listdir(tmp_path / "full") == ["keep.txt"]
    done = cli("bench", cube_config, "--local-workers", "1")  # no -o
    assert done.returncode == 2 and "Traceback" not in done.stderr and "-o" in done.stderr


def test_the_command_line_plans_problems(cubes, tmp_path):
    out = tmp_path / "plans.npz"
    done = cli("plan", cubes[0], cubes[2], "--out", str(out), "--local-workers", "1",
               "--backend", "cpu", "--seeds", "1-2")
    assert done.returncode == 0, done.stderr
    assert "%s: 4 records, 4 solved, 0 errors" % out in done.stderr
    saved = np.load(out)
    assert saved["problem"].tolist() == [cubes[0]] * 2 + [cubes[2]] * 2
    assert saved["seed"].tolist() == [1, 2, 1, 2] and saved["solved"].all()
    scene = gplanner.load_scene(cubes[2])
    np.testing.assert_array_equal(saved["path_3"], scene.checker("cpu").plan(seed=2).path)
    done = cli("plan", cubes[0], "--out", str(out), "--local-workers", "1")  # exists
    assert done.returncode == 2 and "exists; name a new file" in done.stderr


def test_distributed_is_not_imported_by_gplanner():
    # `import gplanner` works without dask: the module is imported only by name.
    done = subprocess.run([sys.executable, "-c", "import sys, gplanner; "
                           "print('distributed' in sys.modules, 'dask' in sys.modules)"],
                          capture_output=True, text=True)
    assert done.stdout.split() == ["False", "False"], done.stderr
    assert distributed.__version__
