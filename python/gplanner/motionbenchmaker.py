"""MoveIt planning scenes and MotionBenchMaker problem sets, read by gplan's own loader.

A MoveIt problem (a robot's URDF and SRDF, a planning scene and a motion plan request)
becomes a gplanner scene file's `robot:` and `moveit:` keys (docs/scenes.md); these
helpers write that small file into a temporary folder and load it with load_scene, so
that what is accepted, refused and noticed is exactly what gplan does.
"""

import json
import os
import re
import tempfile

from ._core import load_scene


def _string(text):
    # A YAML double-quoted scalar holding `text` as it is (a JSON string is one).
    return json.dumps(text)


def _path(path):
    return _string(os.path.abspath(os.fspath(path)))


def load_moveit_scene(urdf, srdf, scene, request, packages=None, name=None):
    """The scene of a MoveIt problem: robot description, planning scene, request.

    packages: {package name: folder} for package:// mesh paths in the URDF; name: the
    scene's name (default: the request file's name). Raises gplanner.InputError naming
    the file, line and key of anything it cannot read.
    """
    if name is None:
        name = os.path.splitext(os.path.basename(os.fspath(request)))[0]
    lines = ["name: " + _string(name), "robot:", "  urdf: " + _path(urdf),
             "  srdf: " + _path(srdf)]
    if packages:
        lines.append("  packages:")
        for package, folder in sorted(packages.items()):
            lines.append("    " + _string(package) + ": " + _path(folder))
    lines += ["moveit:", "  scene: " + _path(scene), "  request: " + _path(request)]
    with tempfile.TemporaryDirectory(prefix="gplanner-") as folder:
        path = os.path.join(folder, "scene.yaml")
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join(lines) + "\n")
        return load_scene(path)


def motionbenchmaker_problems(root):
    """The problems of a MotionBenchMaker set laid out as VAMP ships it.

    root: the folder holding robot/ (URDF, SRDF, meshes/) and problems/<scenario>/
    (sceneNNNN.yaml, requestNNNN.yaml). Returns a list of dicts, in scenario then number
    order: scenario, number, scene, request, urdf, srdf, packages; load one with
    load_moveit_scene(p["urdf"], p["srdf"], p["scene"], p["request"], p["packages"]).
    """
    robot = os.path.join(root, "robot")
    urdfs = sorted(f for f in os.listdir(robot) if f.endswith(".urdf"))
    srdfs = sorted(f for f in os.listdir(robot) if f.endswith(".srdf"))
    if len(urdfs) != 1 or len(srdfs) != 1:
        raise ValueError("%s: one .urdf and one .srdf expected, found %d and %d"
                         % (robot, len(urdfs), len(srdfs)))
    problems = []
    folder = os.path.join(root, "problems")
    for scenario in sorted(os.listdir(folder)):
        files = os.listdir(os.path.join(folder, scenario))
        for f in sorted(files):
            match = re.fullmatch(r"request(\d+)\.yaml", f)
            if not match or "scene%s.yaml" % match.group(1) not in files:
                continue
            problems.append({
                "scenario": scenario, "number": int(match.group(1)),
                "scene": os.path.join(folder, scenario, "scene%s.yaml" % match.group(1)),
                "request": os.path.join(folder, scenario, f),
                "urdf": os.path.join(robot, urdfs[0]), "srdf": os.path.join(robot, srdfs[0]),
                "packages": {"meshes": os.path.join(robot, "meshes")}})
    return problems
