"""linkage_ros: kinematics of spatial multi-link suspensions (Alexandru 2018) for ROS 2.

The core works without ROS:

    from linkage_ros import Continuation, load_scene, sweep
    scene = load_scene('five_link')                 # bundled name or path to a YAML scene
    table = sweep(scene, range(-80, 81))            # travels in mm -> Sweep
    solution = Continuation(scene).solve(12.5)      # one command -> Solution (mm, rad)

These names load numpy, scipy, PyYAML and numba only, never rclpy, mcap or rerun; and only
when first used, so that `import linkage_ros` (which every pytest run does for the plugin
linkage_ros.testing) costs nothing.
"""

import importlib

_EXPORTS = {
    'Continuation': 'kinematics', 'Settings': 'kinematics', 'Solution': 'kinematics',
    'Sweep': 'kinematics', 'sweep': 'kinematics',
    'load_scene': 'scene', 'Scene': 'scene', 'SceneError': 'scene',
}
__all__ = list(_EXPORTS)


def __getattr__(name):
    if name not in _EXPORTS:
        raise AttributeError(f'module {__name__!r} has no attribute {name!r}')
    return getattr(importlib.import_module(f'.{_EXPORTS[name]}', __name__), name)
