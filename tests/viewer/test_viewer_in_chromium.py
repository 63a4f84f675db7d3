"""gplan plan --html opened in headless Chromium (Debian's), as a person sees it.

For the piano, a PR2 path and a MotionBenchMaker problem: the page draws with no error
(the viewer sets data-status="drawn", or "error: ..." from any uncaught error, and
Chromium logs no console error), a screenshot is not blank, and the robot moves between
two times of the animation (?t=0 and ?t=0.5, paused there). And names from input are
escaped: a scene named <script>...</script> runs nothing.

Environment: GPLAN (the gplan program), GPLANNER_SOURCE (the project), optionally
GPLANNER_SHARED_DATA (../shared/data; the MotionBenchMaker case skips without it).
"""

import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest
from matplotlib import image

SOURCE = pathlib.Path(os.environ.get("GPLANNER_SOURCE", pathlib.Path(__file__).parents[2]))
GPLAN = os.environ.get("GPLAN", str(SOURCE / "build" / "apps" / "gplan"))
SHARED = pathlib.Path(os.environ.get("GPLANNER_SHARED_DATA", SOURCE.parent / "shared" / "data"))
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


def chromium(tmp_path, url, *extra):
    """Runs headless Chromium on url (software WebGL); returns (stdout, stderr)."""
    assert CHROMIUM, "no chromium on PATH: scripts/setup.sh installs Debian's"
    profile = tmp_path / "profile"
    profile.mkdir(exist_ok=True)
    run = subprocess.run(
        [CHROMIUM, "--headless", "--no-sandbox", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         f"--user-data-dir={profile}", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--window-size=800,600", "--virtual-time-budget=5000", "--enable-logging=stderr",
         "--v=0", *extra, url],
        capture_output=True, text=True, timeout=120)
    return run.stdout, run.stderr


def console_errors(stderr):
    return [line for line in stderr.splitlines()
            if "CONSOLE" in line and ("rror" in line or "Uncaught" in line)]


def plan_html(tmp_path, scene, *options):
    html = tmp_path / "view.html"
    run = subprocess.run([GPLAN, "plan", str(scene), "--backend", "cpu", "--seed", "1",
                          "--time-limit", "120", "--html", str(html), *options],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    assert html.stat().st_size > 0
    return html


def screenshot(tmp_path, html, t):
    png = tmp_path / f"t{t}.png"
    _, stderr = chromium(tmp_path, f"{html.as_uri()}?t={t}", f"--screenshot={png}")
    assert png.exists(), stderr[-2000:]
    return image.imread(str(png))[:, :, :3]


def check_page(tmp_path, html):
    dom, stderr = chromium(tmp_path, html.as_uri() + "?t=0", "--dump-dom")
    assert 'data-status="drawn"' in dom, dom[:300] + stderr[-2000:]
    assert console_errors(stderr) == [], console_errors(stderr)
    first, middle = screenshot(tmp_path, html, 0), screenshot(tmp_path, html, 0.5)
    # Not blank: many pixels away from the background, of several shades.
    background = np.array([0xf4, 0xf4, 0xf4]) / 255
    drawn = np.abs(first - background).sum(axis=2) > 0.05
    assert drawn.mean() > 0.05, f"only {drawn.mean():.3f} of the picture is drawn"
    assert len(np.unique((first * 15).astype(int).reshape(-1, 3), axis=0)) > 8
    # The robot moved: pixels below the panel differ between the two times.
    changed = np.abs(first - middle).sum(axis=2)[150:, :] > 0.1
    assert changed.mean() > 0.002, f"only {changed.mean():.4f} of the picture changed"


def test_piano(tmp_path):
    check_page(tmp_path, plan_html(tmp_path, SOURCE / "scenes" / "piano.yaml"))


def test_roadmap_on_request(tmp_path):
    """--html-roadmap draws lazy PRM's roadmap (milestones, edges); the trees keep none."""
    html = plan_html(tmp_path, SOURCE / "scenes" / "pr2_base_arm.yaml", "--html-roadmap")
    assert '"roadmap":{"milestones":' in html.read_text()
    check_page(tmp_path, html)
    dom, _ = chromium(tmp_path, html.as_uri() + "?t=0", "--dump-dom")
    assert " milestones (" in dom and "lazyprm" in dom
    refused = subprocess.run([GPLAN, "plan", str(SOURCE / "scenes" / "pr2_base_arm.yaml"), "--planner",
                              "rrtconnect", "--html", str(tmp_path / "x.html"), "--html-roadmap"],
                             capture_output=True, text=True, timeout=60)
    assert refused.returncode == 2 and "keeps no roadmap" in refused.stderr


def test_pr2_path(tmp_path):
    check_page(tmp_path, plan_html(tmp_path, SOURCE / "scenes" / "pr2_base_arm.yaml"))


def test_motionbenchmaker_problem(tmp_path):
    panda = SHARED / "motionbenchmaker" / "panda"
    if not panda.is_dir():
        pytest.skip(f"no {panda} (set GPLANNER_SHARED_DATA)")
    scene = tmp_path / "box.yaml"
    scene.write_text(
        f"name: box_0001\nrobot:\n  urdf: {panda}/robot/panda.urdf\n  srdf: {panda}/robot/panda.srdf\n"
        f"  packages: {{meshes: {panda}/robot/meshes}}\nmoveit:\n"
        f"  scene: {panda}/problems/box_panda/scene0001.yaml\n"
        f"  request: {panda}/problems/box_panda/request0001.yaml\n")
    check_page(tmp_path, plan_html(tmp_path, scene))


def test_names_from_input_run_nothing(tmp_path):
    (tmp_path / "cube.obj").write_text(
        "v -0.1 -0.1 -0.1\nv 0.1 -0.1 -0.1\nv 0.1 0.1 -0.1\nv -0.1 0.1 -0.1\n"
        "v -0.1 -0.1 0.1\nv 0.1 -0.1 0.1\nv 0.1 0.1 0.1\nv -0.1 0.1 0.1\n"
        "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
        "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n")
    hostile = "<script>document.body.dataset.status='pwned'</script><img src=x onerror=alert(1)>"
    scene = tmp_path / "hostile.yaml"
    scene.write_text(
        f"name: \"{hostile}\"\nrobot:\n  mesh: cube.obj\nobstacles:\n"
        f"  - {{name: \"</script><script>alert(2)</script>\", box: [0.2, 0.2, 0.2], pose: {{xyz: [0, 1, 0]}}}}\n"
        "bounds:\n  min: [-2, -1.5, -1]\n  max: [2, 1.5, 1]\n"
        "start:\n  base: {xyz: [-1, 0, 0], quat_wxyz: [1, 0, 0, 0]}\n"
        "goal:\n  base: {xyz: [1, 0, 0], quat_wxyz: [1, 0, 0, 0]}\n")
    html = plan_html(tmp_path, scene)
    text = html.read_text()
    assert "<script>document" not in text and "</script><script>alert" not in text
    assert "<img src=x" not in text
    dom, stderr = chromium(tmp_path, html.as_uri(), "--dump-dom")
    assert 'data-status="drawn"' in dom, dom[:300]
    assert 'data-status="pwned"' not in dom  # the name's script never ran
    # The name is shown as text, escaped in the DOM.
    assert "&lt;script&gt;document.body.dataset.status='pwned'&lt;/script&gt;" in dom
    assert console_errors(stderr) == [], console_errors(stderr)


def test_view_of_a_path_file(tmp_path):
    """gplan view draws a path file in its scene; a path file of another scene is refused."""
    path_file = tmp_path / "path.yaml"
    run = subprocess.run([GPLAN, "plan", str(SOURCE / "scenes" / "pr2_base_arm.yaml"), "--backend",
                          "cpu", "--seed", "2", "--out", str(path_file)],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    html = tmp_path / "view.html"
    run = subprocess.run([GPLAN, "view", str(path_file), "--html", str(html)],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr
    check_page(tmp_path, html)
    wrong = subprocess.run([GPLAN, "view", str(path_file), "--scene",
                            str(SOURCE / "scenes" / "piano.yaml"), "--html", str(tmp_path / "x.html")],
                           capture_output=True, text=True, timeout=120)
    assert wrong.returncode == 2
    assert "entries" in wrong.stderr and "--scene" in wrong.stderr
    assert not (tmp_path / "x.html").exists()


def test_colliding_rows_with_their_pair_in_red(tmp_path):
    """gplan check --html: the colliding rows, each with the pair FCL names drawn red."""
    html = tmp_path / "rows.html"
    run = subprocess.run([GPLAN, "check", str(SOURCE / "scenes" / "pr2_base_arm.yaml"), "--n", "300",
                          "--backend", "cpu", "--html", str(html)],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    text = html.read_text()
    assert '"rows":[{"label":"row ' in text
    dom, stderr = chromium(tmp_path, html.as_uri() + "?t=0", "--dump-dom")
    assert 'data-status="drawn"' in dom, dom[:300]
    assert console_errors(stderr) == [], console_errors(stderr)
    assert "link '" in dom  # the first row's pair, named in the panel
    picture = screenshot(tmp_path, html, 0)
    red = (picture[:, :, 0] > 0.7) & (picture[:, :, 1] < 0.35) & (picture[:, :, 2] < 0.35)
    assert red.mean() > 0.0005, f"only {red.mean():.5f} of the picture is red"
