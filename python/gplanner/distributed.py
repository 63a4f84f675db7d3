"""Planning and benchmarking as tasks of Dask distributed, over the GPUs of many machines.

Two kinds of work go to the workers of a Dask cluster (Debian's python3-distributed):

- run_benchmark: a gplan-bench configuration (benchmarks/config/*.yaml, MotionBenchMaker
  ones included) split into shards (`gplan-bench CONFIG --shard I/N`), one task each. The
  shards' records are joined into one results.csv, and `gplan-bench CONFIG --report OUT`
  writes the summary here, so that the folder is the one a one-machine run writes.
- plan_problems: many planning problems (scene files, MotionBenchMaker problems), one task
  each, every seed in it: a path, its stats and what ran, per problem and seed.

Each worker uses the GPU it was given (CUDA_VISIBLE_DEVICES of its process; its Dask
resource GPU=1). A task that fails is retried (`retries`); one still failing is reported
(a record of the failure), never dropped. Workers read the scene and configuration files
by the paths the client gives them: the machines must share a file system (as on
clusters), or hold the same files at the same paths. The how-to: docs/distributed.md.

    python3 -m gplanner.distributed bench CONFIG -o OUT --scheduler tcp://HOST:8786
    python3 -m gplanner.distributed plan SCENE... --out plans.npz --local-workers 2
"""

import argparse
import collections
import csv
import dataclasses
import io
import json
import logging
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import uuid

import numpy as np
import yaml
from distributed import LocalCluster, Nanny, Scheduler, SpecCluster, as_completed, get_worker

from ._core import load_scene
from .motionbenchmaker import load_moveit_scene, motionbenchmaker_problems

__all__ = ["BenchmarkError", "BenchmarkRun", "ShardFailed", "ShardFailure", "find_gplan_bench",
           "local_gpu_cluster", "plan_problems", "run_benchmark"]

log = logging.getLogger(__name__)

# gplan-bench's exit statuses a shard may end with: done, and a returned path failing the
# fine FCL re-check (a result, kept). Any other is a failed shard (retried).
_SHARD_OK = (0, 3)
EXIT_SHARDS_FAILED = 4  # the command line's status when a shard failed after its retries
_STDERR_TAIL = 4000  # characters of a failed run's standard error kept
# The oldest results.csv header gplan-bench reads: a folder holding it alone is a run
# without records, which --report summarises (the configuration's check, below).
_EMPTY_CSV_HEADER = ("experiment,scene,planner,checker,run,seed,status,solved,time_s,"
                     "simplify_time_s,length,simplified_length,checks,graph_states,memory_mb,"
                     "path_check,work,collisions,note\n")


class BenchmarkError(ValueError):
    """A benchmark that cannot start: its configuration, output folder or cluster.

    The message is one line: the file or option, what is wrong, what to change.
    """


class ShardFailed(RuntimeError):
    """A shard's gplan-bench run that ended with another status than 0 or 3.

    Raised on the worker, so that Dask retries the task. status: gplan-bench's exit
    status (None where it did not run: no program, no folder); stderr: the tail of its
    standard error, or why it did not run.
    """

    def __init__(self, shard, shards, worker, host, status, stderr):
        super().__init__(shard, shards, worker, host, status, stderr)
        self.shard, self.shards, self.worker, self.host = shard, shards, worker, host
        self.status, self.stderr = status, stderr

    def __str__(self):
        what = ("gplan-bench exited with status %d" % self.status if self.status is not None
                else "gplan-bench did not run")
        last = self.stderr.strip().splitlines()[-1] if self.stderr.strip() else ""
        return "shard %d/%d on %s (%s): %s%s" % (self.shard, self.shards, self.worker,
                                                 self.host, what, ": " + last if last else "")


@dataclasses.dataclass
class ShardFailure:
    """A shard still failing after its retries: its records are missing from the results."""
    shard: int
    shards: int
    worker: str    # the worker of its last try ("?" where Dask lost it, e.g. a killed worker)
    host: str
    status: object  # gplan-bench's exit status, or None
    stderr: str    # the tail of its standard error, or the exception's message

    def describe(self):
        status = "status %s" % self.status if self.status is not None else "no exit status"
        lines = ["shard %d/%d on %s (host %s): %s" % (self.shard, self.shards, self.worker,
                                                      self.host, status)]
        lines += ["  " + line for line in self.stderr.rstrip().splitlines()]
        return "\n".join(lines)


@dataclasses.dataclass
class BenchmarkRun:
    """What run_benchmark wrote and how it went.

    out: the folder; shards: how many shards ran; records: results.csv's records (dicts
    of its columns, as text); failures: the shards that failed after their retries (their
    records are missing; OUT/failures.txt names them); report_status: the exit status of
    `gplan-bench CONFIG --report OUT` (0, or 3 when a returned path failed the FCL
    re-check); summary: OUT/summary.txt's text.
    """
    out: str
    config: str
    shards: int
    records: list
    failures: list
    report_status: int
    summary: str

    @property
    def ok(self):
        """Every shard ran and was summarised (a path failing the re-check, status 3, is a
        result: ok)."""
        return not self.failures and self.report_status in _SHARD_OK

    @property
    def exit_status(self):
        """The command line's exit status: 4 when a shard failed, else the report's."""
        return EXIT_SHARDS_FAILED if self.failures else self.report_status


# --- the gplan-bench program ---------------------------------------------------------

def _executable(path):
    return os.path.isfile(path) and os.access(path, os.X_OK)


def find_gplan_bench(given=None):
    """The gplan-bench program of this machine, as an absolute path.

    given (a path, or a name looked up on PATH), else $GPLANNER_GPLAN_BENCH, else
    gplan-bench on PATH, else the gplan-bench beside $GPLANNER_GPLAN_BUILT (the build's
    gplan). Raises FileNotFoundError naming what was tried.
    """
    host = socket.gethostname()
    if given:
        given = os.fspath(given)
        found = given if os.sep in given and _executable(given) else (
            None if os.sep in given else shutil.which(given))
        if found:
            return os.path.abspath(found)
        raise FileNotFoundError("gplan-bench: %s (given) is not an executable program on %s; "
                                "give the path of gplan-bench there" % (given, host))
    tried = []
    env = os.environ.get("GPLANNER_GPLAN_BENCH")
    if env:
        if _executable(env):
            return os.path.abspath(env)
        raise FileNotFoundError("gplan-bench: $GPLANNER_GPLAN_BENCH=%s is not an executable "
                                "program on %s; fix it or unset it" % (env, host))
    tried.append("$GPLANNER_GPLAN_BENCH (unset)")
    found = shutil.which("gplan-bench")
    if found:
        return os.path.abspath(found)
    tried.append("gplan-bench on PATH (none)")
    built = os.environ.get("GPLANNER_GPLAN_BUILT")
    if built:
        beside = os.path.join(os.path.dirname(built), "gplan-bench")
        if _executable(beside):
            return os.path.abspath(beside)
        tried.append("%s (beside $GPLANNER_GPLAN_BUILT: none)" % beside)
    else:
        tried.append("beside $GPLANNER_GPLAN_BUILT (unset)")
    raise FileNotFoundError("gplan-bench: not found on %s: tried %s; install gplanner there, "
                            "or give its path (gplan_bench=, --gplan-bench, "
                            "$GPLANNER_GPLAN_BENCH)" % (host, ", ".join(tried)))


try:  # prctl, looked up before any fork (the child must not load libraries)
    import ctypes
    _prctl = ctypes.CDLL(None, use_errno=True).prctl
except (ImportError, OSError, AttributeError):
    _prctl = None
_PR_SET_PDEATHSIG, _SIGTERM = 1, int(signal.SIGTERM)


def _die_with_parent():
    # The shard's gplan-bench gets SIGTERM when the worker that started it ends (a worker
    # stopped or killed): no run is left behind (Linux).
    _prctl(_PR_SET_PDEATHSIG, _SIGTERM)


def _read_folder(folder):
    if not os.path.isdir(folder):
        return {}
    out = {}
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if os.path.isfile(path):
            with open(path, "rb") as f:
                out[name] = f.read()
    return out


def _run_shard(config, shard, shards, program, jobs, threads, gpus):
    """One shard on this worker: `gplan-bench CONFIG --shard I/N` in a folder of its own.

    Returns its results.csv text, failed_paths/, ompl/ and (the first shard) problems/
    files (name -> bytes), exit status, where it ran and how long it took; raises ShardFailed (Dask
    retries it) when gplan-bench did not end with 0 or 3.
    """
    try:
        worker = get_worker().address
    except ValueError:  # not on a worker (called directly)
        worker = "local"
    host = socket.gethostname()
    try:
        program = find_gplan_bench(program)
    except FileNotFoundError as e:
        raise ShardFailed(shard, shards, worker, host, None, str(e)) from None
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="gplanner-shard-") as scratch:
        out = os.path.join(scratch, "out")
        command = [program, config, "--shard", "%d/%d" % (shard, shards), "-o", out,
                   "--no-plots", "--jobs", str(jobs)]
        if threads is not None:
            command += ["--threads", str(threads)]
        if gpus is not None:
            command += ["--gpus", str(gpus)]
        try:
            done = subprocess.run(command, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                  stderr=subprocess.PIPE, cwd=scratch,
                                  preexec_fn=_die_with_parent if _prctl else None)
        except OSError as e:
            raise ShardFailed(shard, shards, worker, host, None,
                              "%s could not be started: %s" % (program, e)) from None
        stderr = done.stderr.decode("utf-8", "replace")[-_STDERR_TAIL:]
        csv_file = os.path.join(out, "results.csv")
        if done.returncode not in _SHARD_OK:
            raise ShardFailed(shard, shards, worker, host, done.returncode, stderr)
        if not os.path.isfile(csv_file):
            raise ShardFailed(shard, shards, worker, host, done.returncode,
                              stderr + "\n(no results.csv in its output folder)")
        with open(csv_file, encoding="utf-8") as f:
            text = f.read()
        return {"shard": shard, "shards": shards, "worker": worker, "host": host,
                "status": done.returncode, "seconds": time.monotonic() - started,
                "csv": text, "failed_paths": _read_folder(os.path.join(out, "failed_paths")),
                "ompl": _read_folder(os.path.join(out, "ompl")),
                # A problem set's scene files: every shard writes all of them; the first
                # shard's come back.
                "problems": _read_folder(os.path.join(out, "problems")) if shard == 1 else {},
                "stderr": stderr}


# --- the configuration ---------------------------------------------------------------

def _config_error(config, message):
    return BenchmarkError("%s: %s" % (config, message))


def _read_config(config):
    """The configuration's YAML as a dict, or None where gplan-bench is left to say why."""
    try:
        with open(config, encoding="utf-8") as f:
            data = yaml.safe_load(f)
    except (yaml.YAMLError, UnicodeDecodeError):
        return None
    return data if isinstance(data, dict) else None


def _problem_set(config, data):
    """A MotionBenchMaker configuration's problems as gplan-bench lists them: (scenario,
    number) in scenario then number order."""
    mbm = data["motionbenchmaker"]
    folder = os.path.join(os.path.dirname(config), str(mbm["problems"]))
    scenarios = mbm.get("scenarios")
    if scenarios is None:
        scenarios = sorted(d for d in os.listdir(folder)
                           if os.path.isdir(os.path.join(folder, d)))
    first = int(mbm.get("first", 0)) or None
    problems = []
    for scenario in scenarios:
        names = os.listdir(os.path.join(folder, str(scenario)))
        numbers = sorted(n[5:-5] for n in names
                         if n.startswith("scene") and n.endswith(".yaml") and n[5:-5].isdigit())
        problems += [(str(scenario), n) for n in numbers[:first]]
    return problems


@dataclasses.dataclass
class _Layout:
    """What a one-process run of the configuration runs, in its order: the scenes (or a
    problem set's scenarios), the groups' names (PLANNER@CHECKER, or TABLE@CHECKER for
    the query tables), and how many units a shard may take (scenes or problems)."""
    kind: str
    scenes: list
    groups: list
    alone: list  # per group: run in a process of its own (ours, the cpu backend, tables)
    runs: int
    problem_set: bool
    units: int


def _layout(config, data):
    kind = data.get("kind")
    if kind in ("error-time", "broad-phase"):
        raise _config_error(config, "kind: %s is one study, not split into shards; run "
                                    "gplan-bench %s on one machine" % (kind, config))
    if kind == "planning":
        groups = [str(p) for p in data.get("planners") or []]
        alone = []
        for g in groups:  # OMPL's planners with FCL or on the gpu run on one thread, together
            planner, _, checker = g.partition("@")
            ompl = not planner.startswith("ours-")
            one_thread = ompl and checker.split("-")[0] in ("fcl", "gpu")
            alone.append(not one_thread)
        runs = int(data.get("runs", 10))
    else:  # queries
        groups = ["%s@%s" % (t, c) for t in data.get("tables") or []
                  for c in data.get("checkers") or []]
        alone = [True] * len(groups)
        runs = int(data.get("repeat", 5))
    if kind == "planning" and "motionbenchmaker" in data:
        problems = _problem_set(config, data)
        scenes = []
        for scenario, _ in problems:
            if scenario not in scenes:
                scenes.append(scenario)
        return _Layout(kind, scenes, groups, alone, runs, True, len(problems))
    scenes = [os.path.splitext(os.path.basename(str(s)))[0] for s in data.get("scenes") or []]
    return _Layout(kind, scenes, groups, alone, runs, False, len(scenes))


def _check_config(program, config):
    """Has gplan-bench (here) read the configuration: its own message where it refuses it."""
    with tempfile.TemporaryDirectory(prefix="gplanner-check-") as folder:
        with open(os.path.join(folder, "results.csv"), "w", encoding="utf-8") as f:
            f.write(_EMPTY_CSV_HEADER)
        done = subprocess.run([program, config, "--report", folder, "--no-plots"],
                              stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE)
    if done.returncode != 0:
        lines = done.stderr.decode("utf-8", "replace").strip().splitlines()
        message = lines[-1] if lines else "status %d" % done.returncode
        if message.startswith("gplan-bench: "):
            message = message[len("gplan-bench: "):]
        raise BenchmarkError(message)


# --- the records ---------------------------------------------------------------------

def _csv_records(text):
    """A CSV's header line and its records, each as written (a quoted field may hold line
    breaks: a record ends where its quotes are balanced)."""
    lines = text.splitlines(keepends=True)
    if not lines:
        return "", []
    header, records, pending = lines[0], [], ""
    for line in lines[1:]:
        pending += line
        if pending.count('"') % 2 == 0:
            if pending.strip():
                records.append(pending if pending.endswith("\n") else pending + "\n")
            pending = ""
    if pending.strip():
        records.append(pending + "\n")
    return header, records


def _fields(header, record):
    names = next(csv.reader([header]))
    values = next(csv.reader(io.StringIO(record)))
    return dict(zip(names, values))


def _order(layout, rows):
    """The records' order in a one-process run, as sort keys, or None where one cannot be
    placed (then they are sorted by scene, planner, checker and run).

    A run writes the groups that run alone (our planners, the cpu backend, the query
    tables) first, then OMPL's one-thread groups (@fcl, @gpu), each group's runs in
    order; groups go by scene (a problem set: by problem), then by the configuration's
    planner order. A problem set's problems with the start or goal in collision come last.
    """
    keys = []
    for r in rows:
        try:
            run = int(r["run"])
        except (KeyError, ValueError):
            return None
        name = "%s@%s" % (r.get("planner"), r.get("checker"))
        if name in layout.groups:
            g = layout.groups.index(name)
        else:  # the checker column saying what ran: the configured group of that planner
            same = [i for i, n in enumerate(layout.groups)
                    if n.partition("@")[0] == r.get("planner")]
            if len(same) != 1:
                return None
            g = same[0]
        if r.get("scene") not in layout.scenes:
            return None
        s = layout.scenes.index(r["scene"])
        problem = run // layout.runs if layout.problem_set else 0
        rank = 2 if r.get("status") == "invalid" else (0 if layout.alone[g] else 1)
        keys.append((rank, s, problem, g, run))
    return keys


def _sorted_records(layout, header, records):
    rows = [_fields(header, r) for r in records]
    keys = _order(layout, rows)
    if keys is None:
        log.warning("the records are sorted by scene, planner, checker and run (some cannot "
                    "be placed in a one-process run's order)")
        keys = [(r.get("scene"), r.get("planner"), r.get("checker"), int(r.get("run") or 0))
                for r in rows]
    order = sorted(range(len(records)), key=lambda i: keys[i])
    return [records[i] for i in order], [rows[i] for i in order]


# --- run_benchmark -------------------------------------------------------------------

def _prepare(config, out, gplan_bench):
    """The checks made here before any task: the configuration (read by this machine's
    gplan-bench), the output folder, the program. Returns the configuration's absolute
    path, the program and the configuration's layout; raises BenchmarkError."""
    config = os.path.abspath(os.fspath(config))
    if not os.path.isfile(config):
        raise _config_error(config, "bench configuration does not exist; fix the path")
    _check_out(out)
    try:
        program = find_gplan_bench(gplan_bench)
    except FileNotFoundError as e:
        raise BenchmarkError(str(e)) from None
    data = _read_config(config)
    if data is not None and data.get("kind") in ("error-time", "broad-phase"):
        _layout(config, data)  # refused, with the reason
    _check_config(program, config)  # gplan-bench's own message where it refuses it
    try:
        return config, program, _layout(config, data)
    except BenchmarkError:
        raise
    except (AttributeError, KeyError, OSError, TypeError, ValueError) as e:
        raise _config_error(config, "cannot be read here (%s); check it with gplan-bench %s"
                            % (e, config)) from None


def _workers(client):
    return client.scheduler_info().get("workers", {})


def _resources(client, resources, amount):
    """The resources each task asks for: `resources` as given ({} for none); by default
    GPU=`amount` where every worker has GPU resources, none otherwise."""
    workers = _workers(client)
    if resources is None:
        has_gpus = workers and all("GPU" in w.get("resources", {}) for w in workers.values())
        resources = {"GPU": amount or 1} if has_gpus else {}
    offered = [w.get("resources", {}) for w in workers.values()]
    for name, need in resources.items():
        if not any(r.get(name, 0) >= need for r in offered):
            raise BenchmarkError(
                "resources %s=%s: no worker of the cluster has it (its workers: %s); start "
                "workers with --resources %s=%s, or ask for none (resources={})"
                % (name, need, ", ".join(sorted(str(r) for r in offered)), name, need))
    return resources or None


def _check_out(out):
    if os.path.lexists(out):
        if not os.path.isdir(out):
            raise BenchmarkError("%s: is not a folder; name a new folder for the results" % out)
        if os.listdir(out):
            raise BenchmarkError("%s: the folder has files in it; name a new or empty folder "
                                 "(the results of an earlier run are not replaced)" % out)


def _write(path, data):
    with open(path, "wb" if isinstance(data, bytes) else "w", encoding=None
              if isinstance(data, bytes) else "utf-8") as f:
        f.write(data)


def _safe_name(name):
    return name and name == os.path.basename(name) and not name.startswith(".")


def run_benchmark(client, config, out, *, shards=None, jobs=1, threads=None, gpus_per_task=None,
                  retries=2, gplan_bench=None, resources=None, plots=False, progress=None):
    """Runs a gplan-bench configuration on a Dask cluster, one task per shard.

    client: a distributed.Client. config: a planning or queries configuration (YAML,
    benchmarks/config/*.yaml; MotionBenchMaker ones included); its scene files, problem
    folders and robots must be at the same paths on every worker (a shared file system).
    out: a new or empty folder (a folder with files in it is refused: results are never
    replaced). shards: how many (default 4 per worker, at most one per scene or problem).
    Each task runs `gplan-bench CONFIG --shard I/N --no-plots --jobs J` on its worker (with
    `--threads T` and `--gpus G` where threads and gpus_per_task are given) in a
    temporary folder there. resources: what each task asks of a worker (default GPU=1,
    or GPU=gpus_per_task, where every worker has GPU resources; none otherwise; {} for
    none). retries: how many more tries a failing shard gets (gplan-bench ending other
    than 0 or 3, on any worker). gplan_bench: the program (a path, or a name on each
    worker's PATH), else find_gplan_bench() on each worker; the report runs here with
    the same choice. progress: called with a line per shard done or failed (default: the
    log, logger gplanner.distributed).

    Writes OUT/results.csv (one header, every shard's records in the order a
    one-process run writes them; where a record cannot be placed so, all are sorted by
    scene, planner, checker and run), OUT/failed_paths/, OUT/ompl/ (a scene's OMPL log;
    SCENE.shard-I-of-N.log where several shards ran the scene, as a problem set's
    scenarios), OUT/problems/ (a problem set's scene files), OUT/config.yaml, and, from
    `gplan-bench CONFIG --report OUT`, OUT/summary.txt (and plots/ when plots).
    OUT/results.partial.csv holds the records of the shards done while it runs. A shard
    failing after its retries is named in OUT/failures.txt (shard, worker, exit status,
    the end of its standard error), its records missing, and summary.txt ends saying so.
    Raises BenchmarkError (a one-line message) when the run cannot start.
    """
    say = progress or log.info
    out = os.fspath(out)
    if gplan_bench is not None and os.sep in os.fspath(gplan_bench):
        gplan_bench = os.path.abspath(os.fspath(gplan_bench))  # the same path on the workers
    for name, value in (("jobs", jobs), ("threads", threads), ("gpus_per_task", gpus_per_task)):
        if value is not None and (not isinstance(value, int) or value < 1):
            raise BenchmarkError("%s: %r; give a whole number of 1 or more" % (name, value))
    if not isinstance(retries, int) or retries < 0:
        raise BenchmarkError("retries: %r; give a whole number of 0 or more" % (retries,))
    config, program, layout = _prepare(config, out, gplan_bench)
    workers = _workers(client)
    if not workers:
        raise BenchmarkError("the cluster has no workers; start some (dask worker SCHEDULER "
                             "--resources GPU=1, one per GPU) and run again")
    wanted = shards if shards is not None else 4 * len(workers)
    if not isinstance(wanted, int) or wanted < 1:
        raise BenchmarkError("shards: %r; give a whole number of 1 or more" % (shards,))
    n = min(wanted, layout.units)
    if shards is not None and n < shards:
        say("%d shards asked, %s has %d scene(s) or problems: %d shards"
            % (shards, config, layout.units, n))
    task_resources = _resources(client, resources, gpus_per_task)

    os.makedirs(out, exist_ok=True)
    say("%s: %d shards on %d workers%s" % (config, n, len(workers), " (each asks %s)"
                                           % task_resources if task_resources else ""))
    run_id = uuid.uuid4().hex[:8]
    futures = {client.submit(_run_shard, config, i, n, gplan_bench, jobs, threads, gpus_per_task,
                             key="gplan-bench-shard-%d-of-%d-%s" % (i, n, run_id),
                             retries=retries, resources=task_resources, pure=False): i
               for i in range(1, n + 1)}
    done, failures, header = _collect_shards(client, futures, n, retries, out, say)
    rows = _write_folder(out, config, layout, header, done, failures, n, retries)
    status, summary = _report(program, config, out, plots, failures, n, say)
    say("results: %s (%d records%s)" % (out, len(rows), ", %d shards FAILED: failures.txt"
                                        % len(failures) if failures else ""))
    return BenchmarkRun(out=out, config=config, shards=n, records=rows, failures=failures,
                        report_status=status, summary=summary)


def _collect_shards(client, futures, n, retries, out, say):
    """The shards' results as they end: those done (each record also appended to
    OUT/results.partial.csv at once), those failed after their retries, and the CSV
    header. Interrupted, it cancels the tasks left."""
    partial = os.path.join(out, "results.partial.csv")
    done, failures, header = [], [], None
    try:
        for count, future in enumerate(as_completed(futures), 1):
            i, failure = futures[future], None
            if future.status == "finished":
                result = future.result()
                shard_header, result["records"] = _csv_records(result["csv"])
                if header is None:
                    header = shard_header
                    _write(partial, header)
                if shard_header == header:
                    with open(partial, "a", encoding="utf-8") as f:
                        f.writelines(result["records"])
                    done.append(result)
                    say("shard %d/%d done on %s (%s): %d records in %.1f s, status %d (%d of %d)"
                        % (i, n, result["worker"], result["host"], len(result["records"]),
                           result["seconds"], result["status"], count, n))
                else:
                    failure = ShardFailure(i, n, result["worker"], result["host"],
                                           result["status"], "its results.csv has another "
                                           "header than the other shards' (another "
                                           "gplan-bench on that worker?)")
            elif future.status == "error":
                error = future.exception()
                if isinstance(error, ShardFailed):
                    failure = ShardFailure(i, n, error.worker, error.host, error.status,
                                           error.stderr)
                else:  # e.g. KilledWorker: the worker died running it
                    failure = ShardFailure(i, n, "?", "?", None,
                                           "%s: %s" % (type(error).__name__, error))
            else:
                failure = ShardFailure(i, n, "?", "?", None, "the task was %s" % future.status)
            if failure is not None:
                failures.append(failure)
                last = failure.stderr.strip().splitlines()[-1:] or [""]
                say("shard %d/%d FAILED after %d tries (%d of %d): %s: %s"
                    % (i, n, retries + 1, count, n, failure.describe().splitlines()[0], last[0]))
    except BaseException:
        client.cancel(list(futures))
        raise
    return (sorted(done, key=lambda r: r["shard"]), sorted(failures, key=lambda f: f.shard),
            header or _EMPTY_CSV_HEADER)


def _write_folder(out, config, layout, header, done, failures, n, retries):
    """The joined folder, as a one-process run writes it (and failures.txt); returns the
    records as dicts, in their order."""
    records, rows = _sorted_records(layout, header, [r for d in done for r in d["records"]])
    _write(os.path.join(out, "results.csv"), header + "".join(records))
    partial = os.path.join(out, "results.partial.csv")
    if os.path.exists(partial):
        os.remove(partial)
    shutil.copyfile(config, os.path.join(out, "config.yaml"))
    logs = collections.Counter(name for d in done for name in d["ompl"])
    for result in done:
        for folder in ("failed_paths", "ompl", "problems"):
            for name, content in result[folder].items():
                if not _safe_name(name):
                    continue
                if folder == "ompl" and logs[name] > 1:  # a scenario in several shards
                    name = "%s.shard-%d-of-%d.log" % (os.path.splitext(name)[0],
                                                      result["shard"], n)
                os.makedirs(os.path.join(out, folder), exist_ok=True)
                path = os.path.join(out, folder, name)
                _write(path, content)
    if failures:
        _write(os.path.join(out, "failures.txt"),
               "%d of %d shards failed after %d tries each; their records are missing from "
               "results.csv:\n%s\n" % (len(failures), n, retries + 1,
                                       "\n".join(f.describe() for f in failures)))
    return rows


def _report(program, config, out, plots, failures, n, say):
    """`gplan-bench CONFIG --report OUT` here: its exit status and summary.txt's text
    (which ends saying which shards are missing, where some are)."""
    command = [program, config, "--report", out] + ([] if plots else ["--no-plots"])
    report = subprocess.run(command, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE)
    if report.returncode not in _SHARD_OK:
        say("gplan-bench --report %s ended with status %d: %s"
            % (out, report.returncode, report.stderr.decode("utf-8", "replace").strip()[-500:]))
    summary_file = os.path.join(out, "summary.txt")
    if not os.path.isfile(summary_file):
        return report.returncode, ""
    if failures:
        with open(summary_file, "a", encoding="utf-8") as f:
            f.write("\nINCOMPLETE: %d of %d shards failed after their retries (%s); their "
                    "records are missing: see failures.txt\n"
                    % (len(failures), n, ", ".join("%d/%d" % (x.shard, n) for x in failures)))
    with open(summary_file, encoding="utf-8") as f:
        return report.returncode, f.read()


# --- plan_problems -------------------------------------------------------------------

_PLANNERS = ("auto", "rrtconnect", "lazyprm", "prm")
_BACKENDS = ("gpu", "cpu", "fcl")
_CACHE_SIZE = 4  # checkers kept per worker process (each holds its scene's models)
_cache = collections.OrderedDict()
_cache_lock = threading.Lock()


def _problems(problems):
    """The problems as (label, problem) pairs: a scene file (as given; loaded by its
    absolute path) or a MotionBenchMaker problem dict (SCENARIO/NUMBER); a folder is a
    MotionBenchMaker set (motionbenchmaker_problems)."""
    if isinstance(problems, (str, os.PathLike, dict)):
        problems = [problems]
    out = []
    for p in problems:
        if isinstance(p, dict):
            missing = {"scenario", "number", "scene", "request", "urdf", "srdf"} - set(p)
            if missing:
                raise ValueError("problem %r: no %s; give motionbenchmaker_problems()' dicts"
                                 % (p, ", ".join(sorted(missing))))
            q = dict(p)
            for key in ("scene", "request", "urdf", "srdf"):
                q[key] = os.path.abspath(q[key])
            q["packages"] = {k: os.path.abspath(v) for k, v in (p.get("packages") or {}).items()}
            name = os.path.basename(q["scene"])  # sceneNNNN.yaml: NNNN as in the file name
            number = name[5:-5] if name.startswith("scene") and name.endswith(".yaml") else ""
            out.append(("%s/%s" % (q["scenario"], number or q["number"]), q))
        elif isinstance(p, (str, os.PathLike)):
            path = os.fspath(p)
            if os.path.isdir(path):
                out += _problems(motionbenchmaker_problems(path))
            else:
                out.append((path, os.path.abspath(path)))
        else:
            raise TypeError("problem %r: give a scene file, a MotionBenchMaker folder or a "
                            "problem dict" % (p,))
    return out


def _checker(problem, backend, device):
    # A problem's scene and checker, built once per worker process (the GPU routing is
    # measured when a gpu checker is made) and kept for the next tasks of the problem.
    key = (json.dumps(problem, sort_keys=True), backend, repr(device))
    with _cache_lock:
        if key in _cache:
            _cache.move_to_end(key)
            return _cache[key]
        if isinstance(problem, dict):
            scene = load_moveit_scene(problem["urdf"], problem["srdf"], problem["scene"],
                                      problem["request"], problem.get("packages"))
        else:
            scene = load_scene(problem)
        checker = (scene.checker(backend) if device is None
                   else scene.checker(backend, device=device))
        _cache[key] = (scene, checker)
        while len(_cache) > _CACHE_SIZE:
            _cache.popitem(last=False)
        return scene, checker


def _error_records(label, seeds, message, width=0):
    return [{"problem": label, "seed": s, "solved": False,
             "path": np.zeros((0, width), np.float32), "stats": {}, "backend": None,
             "error": message} for s in seeds]


def _plan_problem(label, problem, planner, backend, seeds, time_limit, device):
    """Every seed of one problem on this worker: a record per seed. Bad input (InputError:
    a file that does not load, a start or goal in collision; ValueError: a device that
    is none) gives error records, not an exception: it will not get better on a retry.
    Any other exception is raised (Dask retries it)."""
    try:
        scene, checker = _checker(problem, backend, device)
    except ValueError as e:  # InputError is one
        return _error_records(label, seeds, str(e))
    records = []
    for seed in seeds:
        try:
            result = checker.plan(planner=planner, seed=seed, time_limit=time_limit)
        except ValueError as e:  # the start or goal collides: the same for every seed
            return _error_records(label, seeds, str(e), scene.width)
        records.append({"problem": label, "seed": seed, "solved": bool(result.solved),
                        "path": result.path, "stats": dict(result.stats),
                        "backend": checker.backend, "error": None})
    return records


def plan_problems(client, problems, *, planner="auto", backend="gpu", seeds=(1,), time_limit=None,
                  device=None, retries=2, resources=None, progress=None):
    """Plans many problems on a Dask cluster: one task per problem, all its seeds in it.

    problems: scene files, MotionBenchMaker problem dicts (motionbenchmaker_problems), or
    a MotionBenchMaker folder (expanded), or a list of these; the files must be at the
    same paths on every worker. planner, backend, time_limit: as Checker.plan and
    Scene.checker (a gpu checker falls back to the cpu without a GPU: `backend` in the
    record says what ran). device: passed to Scene.checker where given. A worker keeps
    the last few problems' checkers (built once: the gpu checker measures its routing).
    resources: what each task asks of a worker (default GPU=1 for the gpu backend where
    every worker has GPU resources, none otherwise; {} for none). retries: more tries
    for a task that raised. progress: called with a line per problem done.

    Returns one record per problem and seed, in problem then seed order: a dict of
    problem (the scene file as given, or SCENARIO/NUMBER), seed, solved, path (float32
    [W, width], start to goal; [0, width] when none), stats (PlanResult.stats), backend
    (what ran) and error (None, or why there is no plan: a file that does not load, a
    start or goal in collision, a bad device (these not retried), or the exception of a
    task still failing after its retries).
    """
    say = progress or log.info
    if planner not in _PLANNERS:
        raise ValueError("planner: %r is not one of %s" % (planner, ", ".join(_PLANNERS)))
    if backend not in _BACKENDS:
        raise ValueError("backend: %r is not one of %s" % (backend, ", ".join(_BACKENDS)))
    if time_limit is not None and not time_limit > 0:
        raise ValueError("time_limit: %r; give seconds above 0, or None" % (time_limit,))
    seeds = list([seeds] if isinstance(seeds, int) else seeds)
    if not seeds or not all(isinstance(s, (int, np.integer)) and s >= 0 for s in seeds):
        raise ValueError("seeds: %r; give one or more whole numbers of 0 or more" % (seeds,))
    seeds = [int(s) for s in seeds]
    problems = _problems(problems)
    if not _workers(client):
        raise ValueError("the cluster has no workers; start some and run again")
    task_resources = _resources(client, resources, 1) if backend == "gpu" or resources else None
    run_id = uuid.uuid4().hex[:8]
    futures = {client.submit(_plan_problem, label, p, planner, backend, seeds, time_limit,
                             device, key="gplanner-plan-%d-%s" % (i, run_id), retries=retries,
                             resources=task_resources, pure=False): i
               for i, (label, p) in enumerate(problems)}
    results = [None] * len(problems)
    try:
        for count, future in enumerate(as_completed(futures), 1):
            i = futures[future]
            label = problems[i][0]
            if future.status == "finished":
                results[i] = future.result()
                solved = sum(r["solved"] for r in results[i])
                errors = [r["error"] for r in results[i] if r["error"]]
                say("%s: %d of %d seeds solved%s (%d of %d)"
                    % (label, solved, len(seeds), ": " + errors[0] if errors else "", count,
                       len(problems)))
            else:
                if future.status == "error":
                    error = future.exception()
                    message = "failed after %d tries: %s: %s" % (retries + 1,
                                                                 type(error).__name__, error)
                else:
                    message = "the task was %s" % future.status
                results[i] = _error_records(label, seeds, message)
                say("%s: %s (%d of %d)" % (label, message, count, len(problems)))
    except BaseException:
        client.cancel(list(futures))
        raise
    return [r for records in results for r in records]


# --- local_gpu_cluster ---------------------------------------------------------------

def _visible_gpus():
    visible = os.environ.get("CUDA_VISIBLE_DEVICES")
    if visible is not None:
        return [d.strip() for d in visible.split(",") if d.strip()]
    try:
        listed = subprocess.run(["nvidia-smi", "-L"], stdout=subprocess.PIPE,
                                stderr=subprocess.DEVNULL, timeout=60).stdout.decode()
    except (OSError, subprocess.SubprocessError):
        return []
    return [str(i) for i, line in enumerate(l for l in listed.splitlines()
                                            if l.startswith("GPU "))]


def local_gpu_cluster(gpus=None, threads_per_worker=None, **scheduler_options):
    """A Dask cluster on this host with one worker process per GPU.

    Worker i (a Nanny) sees only its GPU (CUDA_VISIBLE_DEVICES) and has the resource
    GPU=1, as a worker started by `CUDA_VISIBLE_DEVICES=i dask worker SCHEDULER
    --resources GPU=1` on a machine of a cluster. gpus: how many (the first ones), or
    the devices' indices; default: those of CUDA_VISIBLE_DEVICES, else every GPU that
    `nvidia-smi -L` lists (a count where none is listed: devices 0 to N-1, as on a host
    whose GPUs nvidia-smi cannot see). threads_per_worker: default the host's cores over
    the GPUs. scheduler_options: distributed.Scheduler's (no dashboard unless
    dashboard_address is given).
    Raises ValueError when there is no GPU (make a distributed.LocalCluster instead).
    """
    visible = _visible_gpus()
    if gpus is None:
        devices = visible
    elif isinstance(gpus, int):
        if gpus < 1:
            raise ValueError("gpus: %d; give 1 or more" % gpus)
        if visible and gpus > len(visible):
            raise ValueError("gpus: %d, but this host has %d (%s)"
                             % (gpus, len(visible), ", ".join(visible)))
        devices = visible[:gpus] if visible else [str(i) for i in range(gpus)]
    else:
        devices = [str(d) for d in gpus]
    if not devices:
        raise ValueError("no GPU on this host (nvidia-smi -L lists none); make a "
                         "distributed.LocalCluster for CPU workers instead")
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    threads = threads_per_worker or max(1, (cores or 1) // len(devices))
    scheduler_options.setdefault("dashboard", "dashboard_address" in scheduler_options)
    scheduler_options.setdefault("dashboard_address", ":0")  # its HTTP server: any free port
    workers = {
        "gpu-%s" % d: {"cls": Nanny, "options": {
            "nthreads": threads, "resources": {"GPU": 1}, "silence_logs": logging.WARNING,
            # NCCL_NVLS_ENABLE=0: NVLink multicast off (our code uses no NCCL; harmless).
            "env": {"CUDA_VISIBLE_DEVICES": d, "NCCL_NVLS_ENABLE": "0"}}}
        for d in devices}
    return SpecCluster(scheduler={"cls": Scheduler, "options": scheduler_options},
                       workers=workers, name="gplanner-local-gpus",
                       silence_logs=logging.WARNING)  # as LocalCluster: warnings and errors


# --- the command line ----------------------------------------------------------------

_USAGE = """python3 -m gplanner.distributed bench CONFIG -o OUT [CLUSTER] [OPTIONS]
       python3 -m gplanner.distributed plan PROBLEM... --out FILE.npz|FILE.json [CLUSTER]
                                        [OPTIONS]"""
_EPILOG = """CLUSTER: --scheduler ADDRESS (a running Dask scheduler, e.g. tcp://HOST:8786),
--local-workers N (N worker processes here, one thread each) or --local-gpus [N] (a
worker per GPU here); default: --local-gpus where nvidia-smi lists a GPU, else
--local-workers 1. Exit: bench: the report's status (0, or 3 when a returned path
failed the FCL re-check); 4 when a shard failed after its retries (results written,
OUT/failures.txt names it); plan: 0, or 4 when a problem has no plan for an error
(the record's error); 2 bad usage or input. How-to: docs/distributed.md."""


class _UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise _UsageError(message)


def _parser():
    parser = _Parser(prog="python3 -m gplanner.distributed", usage=_USAGE, epilog=_EPILOG,
                     description="gplan-bench configurations and plans as Dask tasks.",
                     formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", metavar="{bench,plan}", parser_class=_Parser)

    def cluster_options(p):
        group = p.add_mutually_exclusive_group()
        group.add_argument("--scheduler", metavar="ADDRESS", help="a running Dask scheduler")
        group.add_argument("--local-workers", type=int, metavar="N",
                           help="N local worker processes of one thread")
        group.add_argument("--local-gpus", type=int, nargs="?", const=0, metavar="N",
                           help="a local worker per GPU (N: the first N)")
        p.add_argument("--retries", type=int, default=2, metavar="R",
                       help="more tries for a failing task (default 2)")
        p.add_argument("-q", "--quiet", action="store_true", help="no progress lines")

    bench = commands.add_parser("bench", help="run a gplan-bench configuration in shards",
                                usage="python3 -m gplanner.distributed bench CONFIG -o OUT "
                                      "[CLUSTER] [OPTIONS]", epilog=_EPILOG,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    bench.add_argument("config", metavar="CONFIG", help="a gplan-bench configuration (YAML)")
    bench.add_argument("-o", "--out", required=True, metavar="OUT",
                       help="a new or empty folder for the results")
    bench.add_argument("--shards", type=int, metavar="N",
                       help="how many shards (default 4 per worker, at most one per scene)")
    bench.add_argument("--jobs", type=int, default=1, metavar="J", help="gplan-bench --jobs")
    bench.add_argument("--threads", type=int, metavar="T", help="gplan-bench --threads")
    bench.add_argument("--gpus", type=int, metavar="G",
                       help="gplan-bench --gpus, and GPU=G asked of a worker per shard")
    bench.add_argument("--plots", action="store_true", help="draw the report's plots here")
    bench.add_argument("--gplan-bench", metavar="PATH", help="the gplan-bench program")
    cluster_options(bench)

    plan = commands.add_parser("plan", help="plan problems, every seed of one in one task",
                               usage="python3 -m gplanner.distributed plan PROBLEM... --out "
                                     "FILE.npz|FILE.json [CLUSTER] [OPTIONS]", epilog=_EPILOG,
                               formatter_class=argparse.RawDescriptionHelpFormatter)
    plan.add_argument("problems", nargs="+", metavar="PROBLEM",
                      help="a scene file, or a MotionBenchMaker folder (robot/, problems/)")
    plan.add_argument("--out", required=True, metavar="FILE",
                      help="a new .npz (arrays) or .json file for the records")
    plan.add_argument("--planner", default="auto", choices=_PLANNERS)
    plan.add_argument("--backend", default="gpu", choices=_BACKENDS)
    plan.add_argument("--seeds", default="1", metavar="S",
                      help="seeds: 1,2,5 or a range 1-100 (default 1)")
    plan.add_argument("--time-limit", type=float, metavar="SECONDS")
    cluster_options(plan)
    return parser


def _seeds(text):
    seeds = []
    for part in text.split(","):
        low, dash, high = part.strip().partition("-")
        if not low.isdigit() or (dash and not high.isdigit()):
            raise _UsageError("--seeds %s: give whole numbers, e.g. 1,2,5 or 1-100" % text)
        seeds += list(range(int(low), int(high) + 1)) if dash else [int(low)]
    if not seeds:
        raise _UsageError("--seeds %s: no seed; give one or more" % text)
    return seeds


def _cluster(args, say):
    """The client of the cluster the options name, and the local cluster to close."""
    from distributed import Client
    if args.scheduler:
        try:
            return Client(args.scheduler, timeout="20s"), None
        except (OSError, TimeoutError) as e:
            raise BenchmarkError("--scheduler %s: cannot reach it (%s); start `dask scheduler` "
                                 "there, or name its address" % (args.scheduler, e)) from None
    if args.local_workers is not None:
        if args.local_workers < 1:
            raise _UsageError("--local-workers %d: give 1 or more" % args.local_workers)
        cluster = LocalCluster(n_workers=args.local_workers, threads_per_worker=1,
                               processes=True, dashboard_address=None)
    elif args.local_gpus is not None or _visible_gpus():
        try:
            cluster = local_gpu_cluster(args.local_gpus or None)
        except ValueError as e:
            raise _UsageError("--local-gpus: %s; use --local-workers N" % str(e).split(";")[0])
        say("a local worker per GPU: %d" % len(cluster.workers))
    else:
        say("no GPU here (nvidia-smi -L lists none): one local worker")
        cluster = LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                               dashboard_address=None)
    return Client(cluster), cluster


def _save_plans(records, path):
    if path.endswith(".json"):
        rows = [dict(r, path=r["path"].tolist()) for r in records]
        with open(path, "x", encoding="utf-8") as f:
            json.dump(rows, f, indent=1, default=str)
            f.write("\n")
        return
    arrays = {"problem": np.array([str(r["problem"]) for r in records]),
              "seed": np.array([r["seed"] for r in records], np.int64),
              "solved": np.array([r["solved"] for r in records], bool),
              "backend": np.array([r["backend"] or "" for r in records]),
              "error": np.array([r["error"] or "" for r in records]),
              "stats": np.array([json.dumps(r["stats"], default=str) for r in records])}
    for i, r in enumerate(records):
        arrays["path_%d" % i] = r["path"]
    with open(path, "xb") as f:
        np.savez_compressed(f, **arrays)


def main(argv=None):
    """The command line (python3 -m gplanner.distributed --help); returns the exit status."""
    try:
        args = _parser().parse_args(argv)
        if args.command is None:
            raise _UsageError("give a command: bench or plan")
    except _UsageError as e:
        print("gplanner.distributed: %s\nusage: %s" % (e, _USAGE), file=sys.stderr)
        return 2
    except SystemExit as e:  # --help
        return e.code if isinstance(e.code, int) else 0

    def say(line):
        if not args.quiet:
            print(line, file=sys.stderr, flush=True)

    client = cluster = None
    try:
        if args.command == "plan":
            if not args.out.endswith((".npz", ".json")):
                raise _UsageError("--out %s: name a .npz or .json file" % args.out)
            if os.path.lexists(args.out):
                raise BenchmarkError("--out %s: exists; name a new file (results are not "
                                     "replaced)" % args.out)
            seeds = _seeds(args.seeds)
            for p in args.problems:
                if not os.path.exists(p):
                    raise BenchmarkError("%s: does not exist; fix the path" % p)
            _problems(args.problems)  # a bad MotionBenchMaker folder: said here, now
            if args.time_limit is not None and not args.time_limit > 0:
                raise _UsageError("--time-limit %s: give seconds above 0" % args.time_limit)
        else:
            for name in ("shards", "jobs", "threads", "gpus"):
                value = getattr(args, name)
                if value is not None and value < 1:
                    raise _UsageError("--%s %d: give 1 or more" % (name, value))
            config = _prepare(args.config, args.out, args.gplan_bench)[0]
        if args.retries < 0:
            raise _UsageError("--retries %d: give 0 or more" % args.retries)
        client, cluster = _cluster(args, say)
        if args.command == "plan":
            records = plan_problems(client, args.problems, planner=args.planner,
                                    backend=args.backend, seeds=seeds,
                                    time_limit=args.time_limit, retries=args.retries,
                                    progress=say)
            _save_plans(records, args.out)
            errors = sum(1 for r in records if r["error"])
            say("%s: %d records, %d solved, %d errors"
                % (args.out, len(records), sum(r["solved"] for r in records), errors))
            return EXIT_SHARDS_FAILED if errors else 0
        run = run_benchmark(client, config, args.out, shards=args.shards, jobs=args.jobs,
                            threads=args.threads, gpus_per_task=args.gpus,
                            retries=args.retries, gplan_bench=args.gplan_bench,
                            plots=args.plots, progress=say)
        sys.stdout.write(run.summary)
        for failure in run.failures:
            say("FAILED: " + failure.describe().splitlines()[0])
        return run.exit_status
    except _UsageError as e:
        print("gplanner.distributed: %s" % e, file=sys.stderr)
        return 2
    except (BenchmarkError, ValueError, FileNotFoundError) as e:
        print("gplanner.distributed: %s" % e, file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("gplanner.distributed: interrupted", file=sys.stderr)
        return 130
    finally:
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()


if __name__ == "__main__":
    # The module's own functions (gplanner.distributed), not this copy's (__main__), go to
    # the workers: they import it by name.
    from gplanner.distributed import main as _main
    sys.exit(_main())
