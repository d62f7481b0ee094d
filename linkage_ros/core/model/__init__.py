# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
model: what a file declares.

Scenes (scene.py: parser and checks; constraint.py), their elements, mounts and kingpin as
declared, vehicles and their axles (vehicle_axles.py and an anti-roll bar's declaration,
anti_roll_bar.py, load only for a file that has them: AxleSpec and VehicleAxles are read
from here lazily), YAML reading, field checks and the bundled files, and one loader for a
scene or a vehicle (target.py). Imports base only; a declaration never imports the solver
(solve/mechanism.py registers the singular-design check into scene.CHECKS).
"""

from .bundled import bundled_scenes, config_dir, scene_dir, vehicle_dir
from .constraint import Constraint
from .elements import Element, parse_elements
from .fields import Fields, FREE_KEYS, name_problem, NAME_TOKEN_MAX, NAME_TOKEN_RULE, \
    token_problem
from .kingpin import check_kingpin, KingpinPoint
from .mounts import LINE_TOLERANCE, Mount, parse_mount
from .scene import (link_polylines, load_scene, parse_scene, resolve_scene_path, safe_stem,
                    Scene, UNITS_TO_MM)
from .scene_moves import link_fraction, mirror, translate, with_points
from .target import is_vehicle, load_target, of_scene, Target
from .vehicle import load_vehicle, Vehicle
from .yaml_file import FILE_LIMIT_BYTES, parse_yaml, read_yaml, SceneError, VALUES_LIMIT

__all__ = ['AxleSpec', 'bundled_scenes', 'check_kingpin', 'config_dir', 'Constraint', 'Element',
           'Fields', 'FILE_LIMIT_BYTES', 'FREE_KEYS', 'is_vehicle', 'KingpinPoint',
           'LINE_TOLERANCE', 'link_fraction', 'link_polylines', 'load_scene', 'load_target',
           'load_vehicle', 'mirror', 'Mount', 'name_problem', 'NAME_TOKEN_MAX',
           'NAME_TOKEN_RULE', 'of_scene', 'parse_elements', 'parse_mount', 'parse_scene',
           'parse_yaml', 'read_yaml', 'resolve_scene_path', 'safe_stem', 'Scene', 'scene_dir',
           'SceneError', 'Target', 'token_problem', 'translate', 'UNITS_TO_MM', 'VALUES_LIMIT',
           'Vehicle', 'vehicle_dir', 'VehicleAxles', 'with_points']
LAZY = ('AxleSpec', 'VehicleAxles')   # vehicle_axles.py: loaded by a vehicle file with axles


def __getattr__(name):
    """Return AxleSpec or VehicleAxles, loading vehicle_axles.py only when asked (PEP 562)."""
    if name in LAZY:
        from . import vehicle_axles
        return getattr(vehicle_axles, name)
    raise AttributeError(f'module {__name__!r} has no attribute {name!r}')
