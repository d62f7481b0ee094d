# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

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
joint_states message at once. Errors raise SceneError naming the vehicle file and the field;
a key the format does not know is one (with the closest known key suggested). The vehicle's
axle keys (wheelbase, cg_height, axles) are read by core.axle.axle, not here: they are kept in
Vehicle.extras with the free keys (description, source, notes, x_...).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

from .bundled import is_bare_name, resolve, vehicle_dir  # noqa: F401 (vehicle_dir: kept here)
from .fields import Fields, PLAIN_KEY, token_problem
from .scene import load_scene, resolve_scene_path, SceneError, UNITS_TO_MM
from .scene_moves import mirror, translate
from .yaml_file import read_yaml
from ..base.finite import is_finite_number
from ..base.limits import LENGTH_LIMIT_MM, within_length_limit
from ..base.ranges import shown

if TYPE_CHECKING:
    from os import PathLike

    from .scene import Scene
    from .vehicle_axles import VehicleAxles
    from .vehicle_mass import MassData


# The keys of a vehicle file and of a corner; AXLE_KEYS are read by vehicle_axles.py.
VEHICLE_KEYS = ('name', 'units', 'corners')
AXLE_KEYS = ('wheelbase', 'cg_height', 'axles')
MASS_KEYS = ('mass', 'tyre_rate')   # read by vehicle_mass.py
FILE_KEYS = VEHICLE_KEYS + AXLE_KEYS + MASS_KEYS
CORNER_KEYS = ('scene', 'offset', 'mirror', 'travel_joint', 'rack_joint')


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
    # masses and tyre rates (vehicle_mass.MassData); None: no setup sheet
    mass: MassData | None = None
    # the file's other keys as read: description, source, notes, x_...
    extras: dict = field(default_factory=dict, compare=False)

    @property
    def warnings(self) -> tuple[str, ...]:
        """Return the warnings of the corners' scenes (Scene.warnings), each once, in order."""
        return tuple(dict.fromkeys(w for scene in self.corners.values() for w in scene.warnings))


def load_vehicle(name_or_path: str | PathLike) -> Vehicle:
    """Load a vehicle file (bundled name under config/vehicles, or a path)."""
    path = resolve(name_or_path, 'vehicle')
    data = read_yaml(path, 'vehicle')
    check = Fields(str(path))
    if not isinstance(data, dict) or not isinstance(data.get('corners'), dict) \
            or not data['corners']:
        check.keys(data if isinstance(data, dict) else {}, FILE_KEYS)
        check.fail('corners', 'expected a mapping of corner names to {scene, offset, mirror}')
    check.keys(data, FILE_KEYS)
    units = data.get('units', 'mm')
    if not isinstance(units, str) or units not in UNITS_TO_MM:
        check.fail('units', f'unknown value {shown(units)} (expected one of: mm, m)')
    corners, joints = {}, {}
    for corner, spec in data['corners'].items():
        corners[corner] = _corner(path, corner, spec, UNITS_TO_MM[units])
        joints[corner] = _joints(path, corner, spec, corners[corner])
    axles = None
    if any(key in data for key in AXLE_KEYS):   # axle code loads only for a file that has axles
        from .vehicle_axles import parse_axles
        axles = parse_axles(path, data, corners, UNITS_TO_MM[units])
    mass = None
    if any(key in data for key in MASS_KEYS):   # so is the mass code
        from .vehicle_mass import parse_mass
        mass = parse_mass(path, data, axles, _axle_x(corners, axles), UNITS_TO_MM[units])
    return Vehicle(name=check.name(data, 'name') or path.stem, source=str(path),
                   corners=corners, joints=joints, axles=axles, mass=mass,
                   extras={k: v for k, v in data.items() if k not in FILE_KEYS})


def _axle_x(corners, axles):
    """Return {axle name: x (mm) of the mean of its wheel centres} of a file's axles."""
    if axles is None:
        return {}
    return {name: 0.5 * float(corners[a.left].wheel_center[0] + corners[a.right].wheel_center[0])
            for name, a in axles.axles.items()}


def _joints(path, corner, spec, scene):
    """Return (travel_joint, rack_joint) of a corner's spec, '' where not given."""
    names = []
    for key in ('travel_joint', 'rack_joint'):
        value = spec.get(key, '')
        if not isinstance(value, str):
            raise SceneError(path, f'corners.{corner}.{key}',
                             f'expected a joint name (text), got {shown(value)}')
        names.append(value)
    if names[1] and not scene.steered:
        raise SceneError(path, f'corners.{corner}.rack_joint',
                         f'scene {scene.source} has no steer: rack link for a rack to move')
    return tuple(names)


def _corner(path, corner, spec, scale):
    # a name that is not plain is shown by repr: a newline in it stays on the one line
    where = f'corners.{corner if PLAIN_KEY.match(str(corner)) else repr(corner)}'
    problem = token_problem(corner)     # it names the corner's topics and frames
    if problem:
        raise SceneError(path, where, f'corner name {problem}')
    if isinstance(spec, dict):
        Fields(str(path)).keys(spec, CORNER_KEYS, where)
    if not isinstance(spec, dict) or not isinstance(spec.get('scene'), str):
        raise SceneError(path, f'{where}.scene', 'missing (required): a scene name or path')
    scene = load_scene(_scene_file(path, where, spec['scene']))
    if spec.get('mirror', False) is True:
        scene = mirror(scene)
    elif spec.get('mirror', False) is not False:
        raise SceneError(path, f'{where}.mirror',
                         f"expected true or false, got {shown(spec['mirror'])}")
    offset = spec.get('offset', [0.0, 0.0, 0.0])
    if (not isinstance(offset, list) or len(offset) != 3
            or not all(is_finite_number(v) and within_length_limit(v, scale)
                       for v in offset)):
        raise SceneError(path, f'{where}.offset', 'expected [x, y, z], numbers within '
                         f'{LENGTH_LIMIT_MM:g} mm, got {shown(offset)}')
    return replace(translate(scene, [v * scale for v in offset]), name=corner)


def _scene_file(path, where, scene_ref):
    """
    Return the scene file a corner names: a path from the vehicle's folder, or bundled.

    A reference that names no file is the vehicle file's mistake, so the error names the
    vehicle and the corner's field, not the reference ('' would otherwise read as '.').
    """
    local = path.parent / scene_ref
    if not is_bare_name(scene_ref) and local.is_file():   # a bare name is a bundled scene
        return local
    try:
        found = resolve_scene_path(scene_ref)
    except SceneError as exc:
        raise SceneError(path, f'{where}.scene', f'{shown(scene_ref)}: {exc.problem}') from None
    if not found.is_file():   # a .yaml name is taken as a path without looking
        raise SceneError(path, f'{where}.scene', f'{shown(scene_ref)}: no such scene file (a '
                         f'relative path is read from {path.parent}) and not a bundled scene')
    return found
