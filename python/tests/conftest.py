"""Shared fixtures: the source tree, gplan, the shared data, and small scene files."""

import os
import pathlib

import pytest

SOURCE = pathlib.Path(os.environ.get("GPLANNER_SOURCE",
                                     pathlib.Path(__file__).resolve().parents[2]))
SCENES = SOURCE / "scenes"
SHIPPED = sorted(p.name for p in SCENES.glob("*.yaml"))

# A closed cube of side 0.2 about the origin, faces counter-clockwise seen from outside.
CUBE_OBJ = """v -0.1 -0.1 -0.1\nv 0.1 -0.1 -0.1\nv 0.1 0.1 -0.1\nv -0.1 0.1 -0.1
v -0.1 -0.1 0.1\nv 0.1 -0.1 0.1\nv 0.1 0.1 0.1\nv -0.1 0.1 0.1
f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5
f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8
"""


def cube_scene(folder, obstacles, start=(-1, 0, 0), goal=(1, 0, 0), name="cube"):
    """A scene file: the cube as a rigid robot among `obstacles` (YAML list items)."""
    (folder / "cube.obj").write_text(CUBE_OBJ)
    text = ("name: %s\nrobot:\n  mesh: cube.obj\nobstacles:\n%s\n"
            "bounds:\n  min: [-2, -2, -2]\n  max: [2, 2, 2]\n"
            "start:\n  base: {xyz: [%g, %g, %g], quat_wxyz: [1, 0, 0, 0]}\n"
            "goal:\n  base: {xyz: [%g, %g, %g], quat_wxyz: [1, 0, 0, 0]}\n"
            % ((name, "\n".join("  - " + o for o in obstacles)) + tuple(start) + tuple(goal)))
    path = folder / (name + ".yaml")
    path.write_text(text)
    return str(path)


@pytest.fixture
def gplan():
    path = os.environ.get("GPLANNER_GPLAN_BUILT")
    if not path or not os.access(path, os.X_OK):
        pytest.skip("gplan not given (GPLANNER_GPLAN_BUILT): run through ctest")
    return path


@pytest.fixture
def shared_data():
    folder = pathlib.Path(os.environ.get("GPLANNER_SHARED_DATA") or SOURCE / ".." / "shared" / "data")
    if not folder.is_dir():
        pytest.skip("no shared data at %s" % folder)
    return folder.resolve()
