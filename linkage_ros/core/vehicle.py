"""
Vehicle files: a scene per corner, placed on the vehicle, right corners by mirroring.

    name: demo_vehicle
    units: mm                    # of the offsets: mm | m
    corners:
      front_left:  {scene: double_wishbone, offset: [1400, 0, 0],
                    travel_joint: front_left_travel, rack_joint: steering_rack}
      front_right: {scene: double_wishbone, offset: [1400, 0, 0], mirror: true}

A corner's scene is a bundled name or a path (relative paths from the vehicle file's
folder). mirror: true mirrors the scene in y (a left scene becomes the right corner) before
the offset is added. travel_joint and rack_joint (optional) name the joints of
sensor_msgs/JointState that carry the corner's wheel travel and, for a corner whose scene has
a steer: rack link, the steering rack: suspension_node then answers every named corner of a
joint_states message at once. Errors raise SceneError naming the vehicle file and the field.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path
import re
from typing import TYPE_CHECKING

import yaml

from .scene import (config_dir, LENGTH_LIMIT_MM, load_scene, mirror, resolve_scene_path,
                    SceneError, translate, UNITS_TO_MM, within_length_limit)

if TYPE_CHECKING:
    from os import PathLike

    from .scene import Scene
    from .vehicle_axles import VehicleAxles

CORNER_NAME = re.compile(r'^[a-z][a-z0-9_]*$')   # becomes a ROS namespace
AXLE_KEYS = ('wheelbase', 'cg_height', 'axles')   # read by vehicle_axles.py


@dataclass(frozen=True)
class Vehicle:
    """A vehicle file loaded: its corners' scenes placed on the vehicle, and their joints."""

    name: str
    source: str
    corners: dict[str, Scene]      # corner name -> Scene, in vehicle coordinates (mm)
    # corner name -> (travel_joint, rack_joint), '' where not named
    joints: dict[str, tuple[str, str]] = field(default_factory=dict)
    # wheelbase, cg_height and axles; None if the file has none of these keys
    axles: VehicleAxles | None = None


def vehicle_dir() -> Path:
    """Return the folder of the bundled vehicle files."""
    return config_dir() / 'vehicles'


def load_vehicle(name_or_path: str | PathLike) -> Vehicle:
    """Load a vehicle file (bundled name under config/vehicles, or a path)."""
    path = Path(name_or_path)
    if not path.is_file() and path.suffix not in ('.yaml', '.yml'):
        bundled = vehicle_dir() / f'{name_or_path}.yaml'
        if not str(name_or_path).strip() or not bundled.is_file():
            names = ', '.join(sorted(p.stem for p in vehicle_dir().glob('*.yaml')))
            what = 'a folder' if path.is_dir() else 'no such file'
            raise SceneError(repr(str(name_or_path)), 'vehicle', f'{what}, and not a bundled '
                             f'vehicle (bundled: {names})')
        path = bundled
    try:
        data = yaml.safe_load(path.read_text())
    except OSError as exc:
        raise SceneError(path, 'file', f'cannot read ({exc.strerror or exc})') from None
    except UnicodeDecodeError as exc:
        raise SceneError(path, 'file', f'not UTF-8 text ({exc})') from None
    except (yaml.YAMLError, ValueError, RecursionError) as exc:   # ValueError: 2001-13-45
        raise SceneError(path, 'file', f'not valid YAML ({exc})') from None
    if not isinstance(data, dict) or not isinstance(data.get('corners'), dict) \
            or not data['corners']:
        raise SceneError(path, 'corners', 'expected a mapping of corner names to '
                         '{scene, offset, mirror}')
    units = data.get('units', 'mm')
    if not isinstance(units, str) or units not in UNITS_TO_MM:
        raise SceneError(path, 'units', f'unknown value {units!r} (expected one of: mm, m)')
    corners, joints = {}, {}
    for corner, spec in data['corners'].items():
        corners[corner] = _corner(path, corner, spec, UNITS_TO_MM[units])
        joints[corner] = _joints(path, corner, spec, corners[corner])
    axles = None
    if any(key in data for key in AXLE_KEYS):   # axle code loads only for a file that has axles
        from .vehicle_axles import parse_axles
        axles = parse_axles(path, data, corners, UNITS_TO_MM[units])
    return Vehicle(name=str(data.get('name') or path.stem), source=str(path), corners=corners,
                   joints=joints, axles=axles)


def _joints(path, corner, spec, scene):
    """Return (travel_joint, rack_joint) of a corner's spec, '' where not given."""
    names = []
    for key in ('travel_joint', 'rack_joint'):
        value = spec.get(key, '')
        if not isinstance(value, str):
            raise SceneError(path, f'corners.{corner}.{key}',
                             f'expected a joint name (text), got {value!r}')
        names.append(value)
    if names[1] and not any(c.steer == 'rack' for c in scene.constraints):
        raise SceneError(path, f'corners.{corner}.rack_joint',
                         f'scene {scene.source} has no steer: rack link for a rack to move')
    return tuple(names)


def _corner(path, corner, spec, scale):
    where = f'corners.{corner}'
    if not isinstance(corner, str) or not CORNER_NAME.match(corner):
        raise SceneError(path, where, 'corner names are lower-case ROS names '
                         '(letters, digits, underscores), e.g. front_left')
    if not isinstance(spec, dict) or not isinstance(spec.get('scene'), str):
        raise SceneError(path, f'{where}.scene', 'missing (required): a scene name or path')
    scene = load_scene(_scene_file(path, where, spec['scene']))
    if spec.get('mirror', False) is True:
        scene = mirror(scene)
    elif spec.get('mirror', False) is not False:
        raise SceneError(path, f'{where}.mirror',
                         f"expected true or false, got {spec['mirror']!r}")
    offset = spec.get('offset', [0.0, 0.0, 0.0])
    if (not isinstance(offset, list) or len(offset) != 3
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                       and within_length_limit(v, scale) for v in offset)):
        raise SceneError(path, f'{where}.offset', 'expected [x, y, z], numbers within '
                         f'{LENGTH_LIMIT_MM:g} mm, got {offset!r}')
    return replace(translate(scene, [v * scale for v in offset]), name=corner)


def _scene_file(path, where, scene_ref):
    """
    Return the scene file a corner names: a path from the vehicle's folder, or as given.

    A reference that names no file is the vehicle file's mistake, so the error names the
    vehicle and the corner's field, not the reference ('' would otherwise read as '.').
    """
    local = path.parent / scene_ref
    if local.suffix in ('.yaml', '.yml') and local.is_file():
        return local
    try:
        found = resolve_scene_path(scene_ref)
    except SceneError as exc:
        raise SceneError(path, f'{where}.scene', f'{scene_ref!r}: {exc.problem}') from None
    if not found.is_file():   # a .yaml name is taken as a path without looking
        raise SceneError(path, f'{where}.scene', f'{scene_ref!r}: no such scene file (a '
                         f'relative path is read from {path.parent}) and not a bundled scene')
    return found
