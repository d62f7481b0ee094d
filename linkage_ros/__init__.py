# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage_ros: kinematics of spatial multi-link suspensions (Alexandru 2018) for ROS 2.

    linkage_ros.core     the kinematics, ROS-free (its public names are re-exported here)
    linkage_ros.cli      what every program does with a user's mistake
    linkage_ros.answer   what a corner answers, ROS-free (the protocol, health, CDR messages,
                         TF frames, pickups, the URDF), shared by the node and linkage-replay
    linkage_ros.ros      suspension_node, its messages and diagnostics, the pytest plugin
    linkage_ros.record   MCAP and Rerun files of a run
    linkage_ros.tools    linkage-sweep, linkage-replay, linkage-rerun, plots
    linkage_ros.bench    linkage-bench (a subcommand per benchmark) and the references

The core works without ROS:

    from linkage_ros import Continuation, load_scene, sweep
    scene = load_scene('five_link')                 # bundled name or path to a YAML scene
    table = sweep(scene, range(-80, 81))            # travels in mm -> Sweep
    solution = Continuation(scene).solve(12.5)      # one command -> Solution (mm, rad)

The names load numpy, scipy, PyYAML and numba only, never rclpy, mcap or rerun; and only when
first used, so that `import linkage_ros` (which every pytest run does for the plugin
linkage_ros.ros.testing) costs nothing.
"""

import importlib

__all__ = ['Continuation', 'LinkageError', 'load_scene', 'Scene', 'SceneError', 'Settings',
           'Solution', 'Status', 'Sweep', 'sweep']


def __getattr__(name):
    if name not in __all__:
        raise AttributeError(f'module {__name__!r} has no attribute {name!r}')
    return getattr(importlib.import_module('.core', __name__), name)
