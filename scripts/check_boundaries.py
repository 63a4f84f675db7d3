#!/usr/bin/env python3
"""Fails when a module boundary is crossed (run by CTest as `ModuleBoundaries`).

The modules are the top-level folders of the product (common, collision_gpu, knn_gpu,
planner, apps, examples) and the benchmark harness (benchmarks/harness). Rules:

1. A module includes its own `detail/` headers only; another module's internals are
   reached through its public headers. Tests (tests/, benchmarks/tests/) and the
   micro-benchmarks (benchmarks/programs/), which test and time internals, may include any.
2. No source includes a file of another folder by a relative path (`#include "../..."`),
   and no CMakeLists.txt puts another module's private `src/` folder on an include path.
3. Every CMakeLists.txt that builds a target of a module or of benchmarks/ (tests aside)
   compiles it with ${GPLANNER_WARNINGS}.

usage: scripts/check_boundaries.py [ROOT]   (default: the repository this script is in)
       scripts/check_boundaries.py --self-test (a tree with one breach of each rule)
"""
import pathlib
import re
import sys

MODULES = ["common", "collision_gpu", "knn_gpu", "planner", "apps", "examples",
           "benchmarks/harness"]
MAY_REACH_INTERNALS = ["tests", "benchmarks/tests", "benchmarks/programs"]
SOURCES = {".h", ".hpp", ".cpp", ".cu", ".cuh"}
SKIP = {"build", ".git", "benchmarks/runs"}

DETAIL = re.compile(r'#\s*include\s*[<"]gplanner/([a-z_]+)/detail/')
RELATIVE = re.compile(r'#\s*include\s*"\.\./')
SRC_DIR = re.compile(r'\$\{(?:PROJECT_SOURCE_DIR|CMAKE_SOURCE_DIR)\}/([a-z_/]+?)/src\b')


def owner(path, prefixes):
    text = path.as_posix()
    for prefix in sorted(prefixes, key=len, reverse=True):
        if text == prefix or text.startswith(prefix + "/"):
            return prefix
    return None


def files(root):
    for path in sorted(root.rglob("*")):
        rel = path.relative_to(root)
        if any(rel.as_posix() == s or rel.as_posix().startswith(s + "/") or
               rel.parts[0].startswith("build") or rel.parts[0].startswith(".")
               for s in SKIP):
            continue
        if path.is_file():
            yield rel, path


def self_test():
    """Each rule finds its breach in a small tree, and nothing else is reported."""
    import tempfile
    with tempfile.TemporaryDirectory() as folder:
        root = pathlib.Path(folder)
        breaches = {
            "planner/src/a.cpp": '#include "gplanner/collision_gpu/detail/query.h"\n',
            "apps/b.cpp": '#include "../planner/src/scene/yaml_reader.h"\n',
            "apps/CMakeLists.txt": "add_library(x a.cpp)\n"
                                   "target_include_directories(x PRIVATE "
                                   "${PROJECT_SOURCE_DIR}/planner/src)\n",
            "tests/c_test.cpp": '#include "gplanner/collision_gpu/detail/query.h"\n',
            "collision_gpu/src/d.cu": '#include "gplanner/collision_gpu/detail/query.h"\n',
        }
        for name, text in breaches.items():
            (root / name).parent.mkdir(parents=True, exist_ok=True)
            (root / name).write_text(text)
        found = check(root)
    expected = ["planner/src/a.cpp:1:", "apps/b.cpp:1:", "apps/CMakeLists.txt:2:",
                "apps/CMakeLists.txt: builds"]
    ok = len(found) == len(expected) and all(
        any(p.startswith(e) for p in found) for e in expected)
    print("check_boundaries self-test:", "passed" if ok else "FAILED", *found, sep="\n  ")
    return 0 if ok else 1


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else
                        pathlib.Path(__file__).resolve().parent.parent)
    problems = check(root)
    for problem in problems:
        print(problem)
    print(f"check_boundaries: {len(problems)} problem(s)")
    return 1 if problems else 0


def check(root):
    problems = []
    for rel, path in files(root):
        if rel.suffix in SOURCES:
            module = owner(rel, MODULES)
            free = owner(rel, MAY_REACH_INTERNALS)
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                match = DETAIL.search(line)
                if match and free is None and module != match.group(1):
                    problems.append(f"{rel}:{number}: includes {match.group(1)}'s detail/ "
                                    "(internal); use its public headers")
                if RELATIVE.search(line):
                    problems.append(f"{rel}:{number}: includes by a relative path out of "
                                    "its folder; include by the module's include path")
        elif rel.name == "CMakeLists.txt":
            text = path.read_text()
            here = rel.parent.as_posix()
            for match in SRC_DIR.finditer(text):
                if match.group(1) != here:
                    number = text[:match.start()].count("\n") + 1
                    problems.append(f"{rel}:{number}: puts {match.group(1)}/src (private to "
                                    "that module) on an include path")
            builds = re.search(r"^\s*add_(library|executable)\(", text, re.M)
            if builds and "GPLANNER_WARNINGS" not in text and owner(rel, MODULES + [
                    "benchmarks"]) is not None and owner(rel, MAY_REACH_INTERNALS) is None:
                problems.append(f"{rel}: builds targets without ${{GPLANNER_WARNINGS}}")
    return problems


if __name__ == "__main__":
    sys.exit(main())
