"""The Python module against answers known by construction and against gplan itself.

Known answers (a cube inside a closed box collides, beside it is free; every shipped
scene's start and goal are free), verdicts equal to `gplan check --out` for the same
rows (cpu and fcl), motions through and beside a thin wall, a plan whose path passes the
fine FCL re-check, a checker shared by threads, bad arrays and bad files (clear
exceptions), Ctrl-C in a long plan, MotionBenchMaker problems; on a GPU, the gpu backend
against the cpu backend.
"""

import os
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import gplanner
from conftest import SCENES, SHIPPED, cube_scene

IDENTITY = [1, 0, 0, 0]


def at(x, y=0.0, z=0.0):
    return np.array([x, y, z] + IDENTITY, dtype=np.float32)


# --- known answers -------------------------------------------------------------------

def test_cube_inside_a_closed_box_collides_and_beside_it_is_free(tmp_path):
    # A solid box 1 m wide: the cube wholly inside touches no triangle, and collides.
    scene = gplanner.load_scene(cube_scene(tmp_path, ["box: [1, 1, 1]"], start=(-1.5, 0, 0),
                                           goal=(1.5, 0, 0)))
    for backend in ("cpu", "fcl"):
        checker = scene.checker(backend)
        q = np.stack([at(0), at(0.2, 0.1), at(-1.5), at(0.55), at(0.65), at(1.5)])
        assert checker.check(q).tolist() == [True, True, False, True, False, False], backend


@pytest.mark.parametrize("name", SHIPPED)
def test_every_shipped_scene_has_a_free_start_and_goal(name):
    scene = gplanner.load_scene(str(SCENES / name))
    checker = scene.checker("cpu")
    assert scene.start.shape == (scene.width,) and scene.start.dtype == np.float32
    assert checker.check(np.stack([scene.start, scene.goal])).tolist() == [False, False]
    assert checker.check(scene.start).tolist() == [False]  # one row as a 1-D array


@pytest.mark.parametrize("backend", ["cpu", "fcl"])
@pytest.mark.parametrize("name", ["piano.yaml", "pr2_base_arm.yaml", "humanoid.yaml"])
def test_verdicts_are_gplan_checks_for_the_same_rows(gplan, tmp_path, name, backend):
    out = tmp_path / "verdicts.txt"
    scene_file = str(SCENES / name)
    subprocess.run([gplan, "check", scene_file, "--n", "2000", "--seed", "7", "--backend",
                    backend, "--out", str(out)], check=True, capture_output=True)
    table = np.loadtxt(out)
    scene = gplanner.load_scene(scene_file)
    q = scene.sample(2000, seed=7)
    assert q.shape == (2000, scene.width) and q.dtype == np.float32
    np.testing.assert_allclose(q, table[:, :-1], rtol=1e-6, atol=1e-6)  # the same rows
    hit = scene.checker(backend).check(q)
    assert hit.dtype == np.bool_
    assert hit.tolist() == (table[:, -1] == 1).tolist()
    assert 0 < hit.sum() < 2000


def test_motions_through_a_thin_wall_are_caught_and_beside_it_pass(tmp_path):
    scene = gplanner.load_scene(cube_scene(tmp_path, ["box: [0.02, 1, 1]"], start=(-1, 0, 0),
                                           goal=(1, 1.5, 0)))
    checker = scene.checker("cpu")
    a = np.stack([at(-0.5), at(-0.5, 0.9)])
    b = np.stack([at(0.9), at(0.9, 0.9)])  # through the wall; beside it (y = 0.9)
    assert checker.check_motions(a, b, certified=True).tolist() == [True, False]
    assert checker.check_motions(a, b, certified=False).tolist() == [True, False]
    assert checker.check(np.concatenate([a, b])).tolist() == [False] * 4  # ends are free


# --- plans ---------------------------------------------------------------------------

def test_a_plan_passes_the_fine_recheck(tmp_path):
    scene = gplanner.load_scene(str(SCENES / "pr2_base_arm.yaml"))
    checker = scene.checker("cpu")
    result = checker.plan(seed=1, time_limit=60)
    assert result.solved and result.stats["stop_reason"] == "solved"
    assert result.path.shape[1] == scene.width and result.path.shape[0] >= 2
    np.testing.assert_array_equal(result.path[0], scene.start)
    np.testing.assert_array_equal(result.path[-1], scene.goal)
    assert scene.recheck(result.path) == ""
    assert result.stats["path_check"] == "certified"
    assert set(result.stats["times"]) == {"sampling", "state_checks", "knn", "search",
                                          "edge_checks", "shortcutting"}
    assert set(result.stats["gpu_calls"]) == {"state_checks", "knn", "search", "edge_checks",
                                              "shortcutting", "total"}
    assert result.stats["gpu_calls"]["total"] == 0  # the cpu backend
    # The same seed, the same path.
    again = gplanner.plan(scene, backend="cpu", seed=1, time_limit=60)
    np.testing.assert_array_equal(again.path, result.path)
    # auto (the default) took the trees here, and says so; lazy PRM when named, or when
    # the roadmap is sized.
    assert result.stats["planner"] == "rrtconnect" and result.stats["planner_asked"] == "auto"
    assert result.stats["planner_reason"]
    roadmap = checker.plan(seed=1, time_limit=60, milestones=500)
    assert roadmap.solved and roadmap.stats["planner"] == "lazyprm"
    assert scene.recheck(roadmap.path) == ""
    named = checker.plan(planner="lazyprm", seed=1, time_limit=60)
    assert named.stats["planner"] == "lazyprm" and named.stats["planner_reason"] == ""
    with pytest.raises(ValueError, match="milestones"):
        checker.plan(planner="rrtconnect", milestones=100)


def test_a_path_through_the_wall_fails_the_recheck(tmp_path):
    scene = gplanner.load_scene(cube_scene(tmp_path, ["box: [0.02, 1, 1]"], start=(-1, 0, 0),
                                           goal=(1, 0, 0)))
    message = scene.recheck(np.stack([scene.start, scene.goal]))
    assert "segment 0" in message and "collides" in message


# --- threads -------------------------------------------------------------------------

def test_a_checker_shared_by_threads_answers_as_alone():
    scene = gplanner.load_scene(str(SCENES / "piano.yaml"))
    checker = scene.checker("cpu", threads=2)
    q = scene.sample(4000, seed=3)
    alone = checker.check(q)
    results = [None] * 4

    def work(i):
        results[i] = checker.check(q[i * 1000:(i + 1) * 1000])

    threads = [threading.Thread(target=work, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert np.concatenate(results).tolist() == alone.tolist()


# --- bad input -----------------------------------------------------------------------

def test_bad_arrays_raise_clear_exceptions():
    scene = gplanner.load_scene(str(SCENES / "piano.yaml"))
    checker = scene.checker("cpu")
    q = scene.sample(10, seed=1)
    with pytest.raises(ValueError, match=r"q: shape \(N, 7\) expected .* got \(10, 6\)"):
        checker.check(q[:, :6])
    with pytest.raises(ValueError, match=r"got \(2, 3, 7\)"):
        checker.check(np.zeros((2, 3, 7), np.float32))
    with pytest.raises(TypeError, match="float32 or float64 rows expected, got dtype int64"):
        checker.check(np.zeros((3, 7), np.int64))
    with pytest.raises(TypeError, match="float16"):
        checker.check(q.astype(np.float16))
    with pytest.raises(ValueError, match="a and b: as many rows"):
        checker.check_motions(q[:3], q[:4])
    # float64, non-contiguous and list input give the same verdicts as float32 rows.
    expected = checker.check(q).tolist()
    assert checker.check(q.astype(np.float64)).tolist() == expected
    wide = np.zeros((10, 14), np.float32)
    wide[:, ::2] = q
    assert checker.check(wide[:, ::2]).tolist() == expected
    assert checker.check(q.tolist()).tolist() == expected
    # A row that is no configuration collides, as in gplan; an empty batch is empty.
    bad = q[:3].copy()
    bad[1, 0] = np.nan
    bad[2, 3:] = 0  # a zero quaternion
    assert checker.check(bad).tolist()[1:] == [True, True]
    assert checker.check(np.zeros((0, 7), np.float32)).shape == (0,)
    with pytest.raises(ValueError, match="n: a count"):
        scene.sample(-1)


def test_bad_files_and_settings_raise_gplans_messages(tmp_path):
    missing = str(tmp_path / "nowhere.yaml")
    with pytest.raises(gplanner.InputError, match="nowhere.yaml"):
        gplanner.load_scene(missing)
    broken = tmp_path / "broken.yaml"
    broken.write_text("name: broken\nrobot:\n  mesh: cube.obj\nobstacles: [\n")
    with pytest.raises(gplanner.InputError, match=r"broken\.yaml:\d+"):
        gplanner.load_scene(str(broken))
    assert issubclass(gplanner.InputError, ValueError)
    scene = gplanner.load_scene(str(SCENES / "piano.yaml"))
    with pytest.raises(ValueError, match="backend"):
        scene.checker("cuda")
    checker = scene.checker("cpu")
    with pytest.raises(ValueError, match="planner: 'rrt' is not one of auto, lazyprm, prm, rrtconnect"):
        checker.plan(planner="rrt")
    with pytest.raises(ValueError, match="time_limit"):
        checker.plan(time_limit=0)
    # A start in collision: gplan's message, naming the scene file's line.
    blocked = gplanner.load_scene(cube_scene(tmp_path, ["box: [1, 1, 1]"], start=(0, 0, 0),
                                             goal=(1.5, 0, 0), name="blocked"))
    with pytest.raises(gplanner.InputError, match=r"blocked\.yaml:\d+: start"):
        blocked.checker("cpu").plan()


# --- Ctrl-C --------------------------------------------------------------------------

def test_ctrl_c_stops_a_long_plan(tmp_path):
    # A wall across all of the bounds: no path; the plan would run for 600 s.
    scene = gplanner.load_scene(cube_scene(tmp_path, ["box: [0.02, 10, 10]"]))
    checker = scene.checker("cpu")
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    started = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        checker.plan(time_limit=600)
    assert time.monotonic() - started < 5
    # The checker still works afterwards.
    assert checker.check(scene.start).tolist() == [False]


# --- MoveIt and MotionBenchMaker -----------------------------------------------------

def test_motionbenchmaker_problems_load_as_gplan_loads_them(shared_data):
    root = shared_data / "motionbenchmaker" / "panda"
    if not root.is_dir():
        pytest.skip("no MotionBenchMaker data at %s" % root)
    problems = gplanner.motionbenchmaker_problems(str(root))
    assert len(problems) == 700
    assert {p["scenario"] for p in problems} >= {"box_panda", "cage_panda"}
    first = problems[0]
    scene = gplanner.load_moveit_scene(first["urdf"], first["srdf"], first["scene"],
                                       first["request"], first["packages"])
    assert scene.width == 7 and scene.name == "request0001"
    checker = scene.checker("cpu")
    assert checker.check(np.stack([scene.start, scene.goal])).tolist() == [False, False]


# --- the GPU -------------------------------------------------------------------------

def test_gpu_checks_equal_the_cpu_backends_within_the_band():
    scene = gplanner.load_scene(str(SCENES / "piano.yaml"))
    gpu = scene.checker("gpu")
    if gpu.backend != "gpu":
        pytest.skip("no GPU: " + gpu.notice)
    q = scene.sample(100_000, seed=2)
    on_gpu, on_cpu = gpu.check(q), scene.checker("cpu").check(q)
    # The same core on both: differences only within the tolerance band (a handful).
    assert (on_gpu != on_cpu).sum() <= 10
    assert not np.any(on_cpu & ~on_gpu) or (on_cpu & ~on_gpu).sum() <= 10
    assert gpu.device_calls >= 1
    result = gpu.plan(seed=1, time_limit=30)
    assert result.solved and scene.recheck(result.path) == ""
    assert result.stats["gpu_calls"]["total"] > 0


def test_the_device_is_chosen_per_checker_and_a_bad_one_is_said():
    scene = gplanner.load_scene(str(SCENES / "pr2_base_arm.yaml"))
    for bad in ("1", -1, True, 1.0, "every"):
        with pytest.raises(ValueError, match="device"):
            scene.checker("gpu", device=bad)
    assert scene.checker("cpu").devices == []
    first = scene.checker("gpu", device=0)
    if first.backend != "gpu":  # no GPU: the cpu backend, whatever the device, and said
        for device in (0, 3, "all"):
            checker = scene.checker("gpu", device=device)
            assert checker.backend == "cpu" and checker.devices == []
            assert "no GPU" in checker.notice
        return
    assert first.devices == [0]
    q = scene.sample(50_000, seed=4)
    every = scene.checker("gpu", device="all")
    assert every.devices == list(range(len(every.devices))) and len(every.devices) >= 1
    assert every.check(q).tolist() == first.check(q).tolist()
    with pytest.raises(ValueError, match="sees %d CUDA device" % len(every.devices)):
        scene.checker("gpu", device=len(every.devices))


# --- the example ---------------------------------------------------------------------

def test_the_example_checks_plans_and_plots(shared_data, tmp_path, monkeypatch, capsys):
    import runpy
    import sys
    from conftest import SOURCE
    pytest.importorskip("matplotlib")
    root = shared_data / "motionbenchmaker" / "panda"
    if not root.is_dir():
        pytest.skip("no MotionBenchMaker data at %s" % root)
    out = tmp_path / "path.png"
    example = str(SOURCE / "examples" / "python_check_and_plan.py")
    monkeypatch.setattr(sys, "argv", [example, "--data", str(root), "--backend", "cpu",
                                      "--n", "20000", "--out", str(out)])
    runpy.run_path(example, run_name="__main__")  # in this process: its module, its numpy
    printed = capsys.readouterr().out
    assert "checked 20000 configurations" in printed
    assert "FCL re-check: pass" in printed
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 10_000


def test_the_readmes_example_runs(capsys):
    import re
    from conftest import SOURCE
    readme = (SOURCE / "README.md").read_text()
    code = re.search(r"## In Python.*?```python\n(.*?)```", readme, re.S).group(1)
    cwd = os.getcwd()
    os.chdir(SOURCE)  # the example's paths are the repository's
    try:
        exec(compile(code, "README.md", "exec"), {})
    finally:
        os.chdir(cwd)
    printed = capsys.readouterr().out.splitlines()
    assert len(printed) == 2, printed
    solved, rows, columns = printed[0].split()[:3]  # "True (22, 7) 1.01"
    assert solved in ("True", "False") and columns == "7)", printed
    if solved == "True":
        assert printed[1] == "passes FCL's fine re-check"
    else:  # 1 s on a slow machine without a GPU: no path, and the re-check says why
        assert rows == "(0," and "fewer than 2 waypoints" in printed[1]
