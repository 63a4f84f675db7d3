"""gplanner: exact triangle-mesh collision checks and plans, batched on the GPU.

    import gplanner, numpy as np
    scene = gplanner.load_scene("scenes/piano.yaml")    # any scene file gplan reads
    checker = scene.checker("gpu")                      # "gpu", "cpu" or "fcl"
    q = scene.sample(100_000, seed=1)                   # float32 [N, width]: gplan check's rows
    hit = checker.check(q)                              # bool [N], True = collides
    bad = checker.check_motions(q[:1000], q[1:1001])    # bool [1000], True = not certified free
    result = checker.plan(seed=1, time_limit=1.0)       # lazy PRM on this checker's backend
    result.solved, result.path, result.stats            # path: float32 [W, width]

Configuration rows are the planner's: the base pose first (floating: x y z qw qx qy qz;
planar: x y theta; fixed: none), then one value per planned joint, in the scene frame
(the world frame unless the scene lies far from the origin: Scene.frame_origin). Arrays
in are float32 or float64, shape [N, width] or [width] (one row); C-contiguous float32
is read without a copy. A row with a NaN or infinite value is reported colliding, as
gplan reports it. Calls release the GIL (a checker may be shared by threads) and stop
at Ctrl-C (KeyboardInterrupt). Bad input raises gplanner.InputError (a ValueError)
with gplan's one-line message (file, line, key, what to change); bad arrays raise
TypeError or ValueError. The reference: python/README.md.
"""

from ._core import Checker, InputError, PlanResult, Scene, __version__, load_scene
from .motionbenchmaker import load_moveit_scene, motionbenchmaker_problems

__all__ = ["Checker", "InputError", "PlanResult", "Scene", "__version__", "load_scene",
           "load_moveit_scene", "motionbenchmaker_problems", "plan"]


def plan(scene, planner="auto", backend="gpu", seed=None, time_limit=None, milestones=None,
         device=0):
    """Plans the scene's start to goal on a new checker of `backend` (see Checker.plan).

    A checker is built for the call (its BVHs, and on the GPU its measured routing): to
    plan several times, make one with Scene.checker and call its plan(). `device`: the
    gpu backend's CUDA device (0, 1, ... or "all"), as Scene.checker's.
    """
    return scene.checker(backend, device=device).plan(planner=planner, seed=seed,
                                                      time_limit=time_limit,
                                                      milestones=milestones)


def _scene_plan(self, planner="auto", backend="gpu", seed=None, time_limit=None,
                milestones=None, device=0):
    return plan(self, planner, backend, seed, time_limit, milestones, device)


_scene_plan.__doc__ = plan.__doc__
Scene.plan = _scene_plan
