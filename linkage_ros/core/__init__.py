"""
The kinematics of a suspension corner, ROS-free.

Scene and vehicle files, the mechanism, the compiled solver kernels, the paper's method,
continuation, alignment.

Imports numpy, scipy, PyYAML and numba only. The public names:

    load_scene(name_or_path) -> Scene                    scene files (mm), SceneError if bad
    Continuation(scene, method='fast').solve(travel_mm) -> Solution   one command at a time
    sweep(scene, travels_mm, method='fast') -> Sweep     a table of positions
    LinkageError                                         base of every bad-input error
"""

from .base.errors import LinkageError
from .base.status import Status
from .model.scene import load_scene, Scene, SceneError
from .solve.kinematics import Continuation, Settings, Solution, Sweep, sweep

__all__ = ['Continuation', 'LinkageError', 'load_scene', 'Scene', 'SceneError', 'Settings',
           'Solution', 'Status', 'Sweep', 'sweep']
