# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The kinematics of a suspension corner, ROS-free.

Five layers, each importing only from those before it, each with its face (__init__.__all__):

    base/      errors, Status, finiteness, limits, geometry, so3
    model/     what a file declares: scenes, elements, mounts, kingpin, vehicles, anti-roll bar
    solve/     the mechanism, the compiled kernels, Newton, continuation, the sweep
    measure/   what is measured from a solution: alignment, kingpin, motion, elements, bodies
    axle/      two corners together: heave, roll, roll centre, anti quantities, the bar's values

warmup.py sits above them all (it compiles every layer's kernels).

Imports numpy, scipy, PyYAML and numba only. The public names:

    load_scene(name_or_path) -> Scene                    scene files (mm), SceneError if bad
    Continuation(scene, method='fast').solve(travel_mm) -> Solution   one command at a time
    sweep(scene, travels_mm, method='fast') -> Sweep     a table of positions
    LinkageError                                         base of every bad-input error
"""

from .base import LinkageError, Status
from .model import load_scene, Scene, SceneError
from .solve import Continuation, Settings, Solution, Sweep, sweep

__all__ = ['Continuation', 'LinkageError', 'load_scene', 'Scene', 'SceneError', 'Settings',
           'Solution', 'Status', 'Sweep', 'sweep']
