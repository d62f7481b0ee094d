"""
Scene files: design-position hardpoints of one suspension corner, loaded and validated.

A scene is YAML with declared units (mm or m) and ISO 8855 axes (x forward, y left, z up).
Everything is converted to millimetres on load; the rest of the package works in mm.
A malformed scene raises SceneError naming the file, the field and the problem.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
import math
from pathlib import Path
from typing import Any, TYPE_CHECKING

import numpy as np
import yaml

from .errors import LinkageError
from .geometry import perpendicular, unit

if TYPE_CHECKING:
    from collections.abc import Sequence
    from os import PathLike

    from numpy.typing import ArrayLike

UNITS_TO_MM = {'mm': 1.0, 'm': 1000.0}
EQUATIONS_PER_TYPE = {'sphere': 1, 'circle': 2, 'line': 2}
SIDES = ('left', 'right')
# Relative size (to the scene's largest dimension) below which two points are "coincident"
# and a triangle or arm is "too thin" to define a frame.
THIN = 1e-6
# Lengths beyond this (1e6 km) are typos: their squares, which the solver forms, lose every
# digit of a suspension's millimetres, and near 1e154 mm they overflow.
LENGTH_LIMIT_MM = 1e12

SOURCE_CONFIG = Path(__file__).resolve().parents[2] / 'config'   # in a source checkout


class SceneError(LinkageError):
    """A scene or vehicle file is malformed; the message names the file, field and problem."""

    def __init__(self, source: str | PathLike, field_name: str, problem: str) -> None:
        super().__init__(f'{source}: {field_name}', problem)
        self.source, self.field = str(source), field_name


@dataclass(frozen=True)
class Constraint:
    """
    One guidance constraint of the carrier, in mm, vehicle frame, design position.

    type 'sphere': carrier point keeps its distance to base[0] (binary link, eq. 2).
    type 'circle': carrier point turns about the axis base[0]-base[1] (revolute arm, eqs. 3-4).
    type 'line': the carrier-fixed line through the carrier point and base[0] keeps passing
    through base[0] (MacPherson strut top mount).
    """

    name: str
    type: str             # noqa: A003 (the scene files' key; public field of Constraint)
    base: np.ndarray      # (k, 3): k = 1 for sphere and line, 2 for circle
    carrier: np.ndarray   # (3,)
    steer: str = ''

    @property
    def equations(self) -> int:
        """How many guidance equations the constraint gives: sphere 1, circle 2, line 2."""
        return EQUATIONS_PER_TYPE[self.type]


@dataclass(frozen=True)
class Scene:
    """A validated suspension corner. Lengths in mm, vehicle frame, design position."""

    name: str
    source: str
    side: str
    units: str
    wheel_center: np.ndarray      # M, (3,)
    spin_axis_point: np.ndarray   # N, (3,), inboard on the spin axis
    third_point: np.ndarray       # P, (3,), given or chosen off the spin axis
    constraints: tuple[Constraint, ...]
    travel: tuple[float, float, float]   # (min, max, step) in mm
    wheel_radius: float = 0.0     # mm; 0 = not given
    description: str = ''
    extras: dict = field(default_factory=dict, compare=False)

    @property
    def side_sign(self) -> float:
        """+1 for a left wheel, -1 for a right wheel (outboard direction along y)."""
        return 1.0 if self.side == 'left' else -1.0

    @property
    def size(self) -> float:
        """Largest hardpoint coordinate magnitude (mm): sets the scale of tolerances."""
        pts = [self.wheel_center, self.spin_axis_point]
        pts += [c.carrier for c in self.constraints]
        pts += [b for c in self.constraints for b in c.base]
        return float(max(np.max(np.abs(p)) for p in pts))

    @property
    def carrier_offsets(self) -> np.ndarray:
        """
        Carrier points relative to the wheel centre at design, (m, 3) mm: b0 - M0.

        In constraint order (geometry.carrier_points places them at a pose).
        """
        return np.array([c.carrier for c in self.constraints]) - self.wheel_center

    def to_mm(self, value: float | np.ndarray) -> float | np.ndarray:
        """Convert a length (or an array of them) from the scene's units to mm."""
        return value * UNITS_TO_MM[self.units]


def link_polylines(scene: Scene, joints: ArrayLike) -> list[np.ndarray]:
    """
    Return the drawn links of a scene for its carrier joints (..., m, 3) mm.

    The joints are in constraint order. One polyline (..., k, 3) per constraint: base ->
    joint for a link (sphere) or a strut (line), axis[0] -> joint -> axis[1] for an arm
    (circle).
    """
    joints = np.asarray(joints, dtype=float)
    lines = []
    for j, c in enumerate(scene.constraints):
        ends = c.base if c.type == 'circle' else c.base[:1]
        joint = joints[..., j, :]
        points = [ends[0], joint] + ([ends[1]] if len(ends) == 2 else [])
        lines.append(np.stack(np.broadcast_arrays(*points), axis=-2))
    return lines


def bundled_scenes() -> list[str]:
    """Return the names of the scenes shipped in config/scenes."""
    return sorted(p.stem for p in scene_dir().glob('*.yaml'))


def config_dir() -> Path:
    """Return the package's config/ folder: the source tree's, or the installed share/ one."""
    if SOURCE_CONFIG.is_dir():
        return SOURCE_CONFIG
    try:
        from ament_index_python.packages import get_package_share_directory
        return Path(get_package_share_directory('linkage_ros')) / 'config'
    except Exception:  # not in an ament install: fall back to sys.prefix/share
        import sys
        return Path(sys.prefix) / 'share' / 'linkage_ros' / 'config'


def scene_dir() -> Path:
    """Return the folder of the bundled scenes."""
    return config_dir() / 'scenes'


def resolve_scene_path(name_or_path: str | PathLike) -> Path:
    """Resolve a bundled scene name ('five_link') or a path to a YAML file; else SceneError."""
    bundled = f'bundled: {", ".join(bundled_scenes())}'
    if not str(name_or_path).strip():   # Path('') would be the current folder
        raise SceneError(repr(str(name_or_path)), 'scene', 'empty: give a bundled scene name '
                         f'or the path of a scene YAML file ({bundled})')
    path = Path(name_or_path)
    if path.suffix in ('.yaml', '.yml') or path.is_file():
        return path
    candidate = scene_dir() / f'{name_or_path}.yaml'
    if candidate.exists():
        return candidate
    if path.is_dir():
        raise SceneError(name_or_path, 'scene', f'a folder, not a scene file ({bundled})')
    raise SceneError(name_or_path, 'scene', f'no such file, and not a bundled scene ({bundled})')


def load_scene(name_or_path: str | PathLike) -> Scene:
    """Load and validate a scene file; returns a Scene in mm. Raises SceneError."""
    path = resolve_scene_path(name_or_path)
    try:
        text = path.read_text()
    except OSError as exc:
        raise SceneError(path, 'file', f'cannot read ({exc.strerror or exc})') from None
    except UnicodeDecodeError as exc:
        raise SceneError(path, 'file', f'not UTF-8 text ({exc})') from None
    try:
        data = yaml.safe_load(text)
    except (yaml.YAMLError, ValueError, RecursionError) as exc:   # ValueError: 2001-13-45
        raise SceneError(path, 'file', f'not valid YAML ({exc})') from None
    return parse_scene(data, source=str(path))


def parse_scene(data: Any, source: str = '<scene>') -> Scene:
    """Validate a scene mapping (as read from YAML) and return a Scene in mm."""
    check = _Checker(source)
    if not isinstance(data, dict):
        check.fail('file', 'expected a mapping of scene keys')
    units = check.choice(data, 'units', tuple(UNITS_TO_MM))
    side = check.choice(data, 'side', SIDES)
    scale = check.scale = UNITS_TO_MM[units]
    carrier = check.mapping(data, 'carrier')
    wheel_center = check.point(carrier, 'wheel_center', 'carrier.wheel_center') * scale
    spin_point = check.point(carrier, 'spin_axis_point', 'carrier.spin_axis_point') * scale
    given_p = None
    if carrier.get('third_point') is not None:
        given_p = check.point(carrier, 'third_point', 'carrier.third_point') * scale
    constraints = tuple(_parse_constraint(check, item, i, scale)
                        for i, item in enumerate(check.sequence(data, 'constraints')))
    travel = _parse_travel(check, data.get('travel'), scale)
    radius = check.number(data, 'wheel_radius', 'wheel_radius', default=0.0, minimum=0.0) * scale
    scene_size = _size([wheel_center, spin_point] + [c.carrier for c in constraints]
                       + [b for c in constraints for b in c.base])
    _check_geometry(check, wheel_center, spin_point, constraints, scene_size)
    third_point = given_p if given_p is not None else choose_third_point(
        wheel_center, spin_point, [c.carrier for c in constraints])
    _check_third_point(check, wheel_center, spin_point, third_point, constraints,
                       'carrier.third_point' if given_p is not None else 'carrier',
                       given_p is not None, scene_size)
    if data.get('kingpin') is not None:   # a misspelt joint fails on load, not in a sweep
        from .kingpin import check_kingpin
        check_kingpin(source, data['kingpin'], constraints)
    return Scene(name=str(data.get('name') or Path(source).stem), source=source, side=side,
                 units=units, wheel_center=wheel_center, spin_axis_point=spin_point,
                 third_point=third_point, constraints=constraints, travel=travel,
                 wheel_radius=radius, description=str(data.get('description', '')).strip(),
                 extras={k: v for k, v in data.items() if k not in _KNOWN_KEYS})


_KNOWN_KEYS = {'name', 'units', 'side', 'carrier', 'constraints', 'travel', 'wheel_radius',
               'description'}


def choose_third_point(wheel_center: np.ndarray, spin_point: np.ndarray,
                       carrier_points: Sequence[np.ndarray]) -> np.ndarray:
    """
    Choose P (mm) off the spin axis so no carrier joint lies near the M-N-P plane.

    Eqs. 5-7 locate a joint from its distances to M, N, P; the two roots merge when the
    joint is in the M-N-P plane, so the plane is turned about the spin axis to keep every
    joint as far from it as possible. P sits one M-N distance from M, square to the axis.
    """
    axis = unit(wheel_center - spin_point)
    e1 = perpendicular(axis)
    e2 = np.cross(axis, e1)
    offsets = np.array([p - wheel_center for p in carrier_points]).reshape(-1, 3)
    angles = np.radians(np.arange(0.0, 180.0, 0.5))
    normals = -np.sin(angles)[:, None] * e1 + np.cos(angles)[:, None] * e2
    clearance = np.min(np.abs(offsets @ normals.T), axis=0) if len(offsets) else np.ones(1)
    best = angles[int(np.argmax(clearance))]
    radius = float(np.linalg.norm(wheel_center - spin_point))
    return wheel_center + radius * (np.cos(best) * e1 + np.sin(best) * e2)


def _parse_constraint(check, item, index, scale):
    where = f'constraints[{index}]'
    if not isinstance(item, dict):
        check.fail(where, 'expected a mapping with name, type, base or axis, carrier')
    name = item.get('name')
    where = f'constraints[{index}] ({name})' if name else where
    kind = check.choice(item, 'type', tuple(EQUATIONS_PER_TYPE), f'{where}.type')
    if kind == 'circle':
        axis = item.get('axis')
        if not isinstance(axis, (list, tuple)) or len(axis) != 2:
            check.fail(f'{where}.axis', 'expected two points [[x, y, z], [x, y, z]] on the '
                       'revolute axis')
        base = np.array([check.vector(p, f'{where}.axis[{i}]') for i, p in enumerate(axis)])
    else:
        base = check.point(item, 'base', f'{where}.base')[None, :]
    carrier = check.point(item, 'carrier', f'{where}.carrier')
    steer = item.get('steer', '')
    if steer not in ('', None, 'rack'):
        check.fail(f'{where}.steer', f"unknown value {steer!r} (expected 'rack')")
    return Constraint(name=str(name or f'{kind}_{index}'), type=kind, base=base * scale,
                      carrier=carrier * scale, steer=steer or '')


def _parse_travel(check, block, scale):
    if block is None:
        return (-80.0, 80.0, 1.0)
    if not isinstance(block, dict):
        check.fail('travel', 'expected a mapping {min, max, step}')
    low = check.number(block, 'min', 'travel.min') * scale
    high = check.number(block, 'max', 'travel.max') * scale
    step = check.number(block, 'step', 'travel.step', minimum=0.0) * scale
    if step <= 0:
        check.fail('travel.step', f'must be positive, got {step / scale:g}')
    if high < low:
        check.fail('travel', f'max ({high / scale:g}) is below min ({low / scale:g})')
    return (low, high, step)


def _check_geometry(check, wheel_center, spin_point, constraints, size):
    tiny = THIN * size
    if np.linalg.norm(wheel_center - spin_point) <= tiny:
        check.fail('carrier.spin_axis_point', 'coincides with carrier.wheel_center: the spin '
                   'axis needs two distinct points')
    total = sum(c.equations for c in constraints)
    if total != 5:
        counts = ', '.join(f'{c.name} ({c.type}) {c.equations}' for c in constraints) or 'none'
        check.fail('constraints', f'give {total} equations ({counts}); the carrier has 5 '
                   'degrees of freedom once the travel is imposed, so exactly 5 are needed '
                   '(sphere = 1, circle = 2, line = 2)')
    for i, c in enumerate(constraints):
        where = f'constraints[{i}] ({c.name})'
        for j, b in enumerate(c.base):
            if np.linalg.norm(b - c.carrier) <= tiny:
                field_name = f'{where}.axis[{j}]' if c.type == 'circle' else f'{where}.base'
                check.fail(field_name, 'coincides with the carrier point: zero-length link')
        if c.type == 'circle':
            if np.linalg.norm(c.base[1] - c.base[0]) <= tiny:
                check.fail(f'{where}.axis', 'the two axis points coincide: no revolute axis')
            u = unit(c.base[1] - c.base[0])
            arm = c.carrier - c.base[0]
            if np.linalg.norm(arm - (arm @ u) * u) <= tiny:
                check.fail(f'{where}.carrier', 'lies on the revolute axis: zero-length arm')


def _check_third_point(check, wheel_center, spin_point, third_point, constraints, where,
                       given, size):
    axis = wheel_center - spin_point
    offset = third_point - wheel_center
    # Triangle height over the longest side: 0 for collinear M, N, P.
    height = np.linalg.norm(np.cross(axis, offset)) / np.linalg.norm(axis)
    if height <= 1e-3 * max(np.linalg.norm(axis), np.linalg.norm(offset)):
        check.fail(where, 'wheel_center, spin_axis_point and third_point are (nearly) '
                   f'collinear (triangle height {height:.3g} mm): too thin to define a frame')
    normal = unit(np.cross(axis, offset))
    for i, c in enumerate(constraints):
        if abs((c.carrier - wheel_center) @ normal) <= THIN * size:
            problem = (f'constraints[{i}] ({c.name}).carrier lies in the plane of wheel_center, '
                       'spin_axis_point and third_point, where eqs. 5-7 cannot locate it')
            hint = ('; move third_point or leave it out to have one chosen' if given
                    else '; every choice of third point leaves it there (it is on the spin axis)')
            check.fail(where, problem + hint)


def _finite(value):
    """Tell whether a number is finite (an integer beyond the float range is not)."""
    try:
        return math.isfinite(value)
    except OverflowError:
        return False


def within_length_limit(value: float, scale: float) -> bool:
    """Tell whether value (scene units, scale mm each) is a length within LENGTH_LIMIT_MM."""
    try:
        return abs(value) * scale <= LENGTH_LIMIT_MM   # False for NaN
    except OverflowError:                              # an integer beyond the float range
        return False


def _size(points):
    return float(max(np.max(np.abs(p)) for p in points))


class _Checker:
    """Field readers that raise SceneError with the file and field named."""

    def __init__(self, source):
        self.source = source
        self.scale = 1.0   # mm per scene unit, once units is read

    def length(self, value, where, what):
        """Refuse a finite number whose length in mm is beyond LENGTH_LIMIT_MM."""
        if not within_length_limit(value, self.scale):
            self.fail(where, f'{what} {value!r} is beyond {LENGTH_LIMIT_MM:g} mm in magnitude '
                      '(a typo? lengths this large leave no precision for millimetres)')

    def fail(self, field_name, problem):
        raise SceneError(self.source, field_name, problem)

    def _get(self, data, key, where):
        if key not in data or data[key] is None:
            self.fail(where, 'missing (required)')
        return data[key]

    def mapping(self, data, key):
        value = self._get(data, key, key)
        if not isinstance(value, dict):
            self.fail(key, f'expected a mapping, got {type(value).__name__}')
        return value

    def sequence(self, data, key):
        value = self._get(data, key, key)
        if not isinstance(value, list):
            self.fail(key, f'expected a list, got {type(value).__name__}')
        return value

    def choice(self, data, key, options, where=None):
        where = where or key
        value = self._get(data, key, where)
        if value not in options:
            self.fail(where, f'unknown value {value!r} (expected one of: {", ".join(options)})')
        return value

    def number(self, data, key, where, default=None, minimum=None):
        if data.get(key) is None:
            if default is None:
                self.fail(where, 'missing (required)')
            return default
        value = data[key]
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            self.fail(where, f'expected a number, got {value!r}')
        if not _finite(value):
            self.fail(where, f'must be finite, got {value!r}')
        if minimum is not None and value < minimum:
            self.fail(where, f'must be at least {minimum:g}, got {value!r}')
        self.length(value, where, 'value')
        return float(value)

    def point(self, data, key, where):
        return self.vector(self._get(data, key, where), where)

    def vector(self, value, where):
        if not isinstance(value, (list, tuple)):
            self.fail(where, f'expected a point [x, y, z], got {value!r}')
        if len(value) != 3:
            self.fail(where, f'expected 3 coordinates [x, y, z], got {len(value)}')
        for v in value:
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                self.fail(where, f'coordinate {v!r} is not a number')
            if not _finite(v):
                self.fail(where, f'coordinate {v!r} is not finite')
            self.length(v, where, 'coordinate')
        return np.array(value, dtype=float)


def mirror(scene: Scene) -> Scene:
    """Return the scene of the opposite wheel: every point mirrored in the x-z plane (y -> -y)."""
    flip = np.array([1.0, -1.0, 1.0])
    constraints = tuple(Constraint(name=c.name, type=c.type, base=c.base * flip,
                                   carrier=c.carrier * flip, steer=c.steer)
                        for c in scene.constraints)
    side = 'right' if scene.side == 'left' else 'left'
    return Scene(name=f'{scene.name}_{side}', source=scene.source, side=side, units=scene.units,
                 wheel_center=scene.wheel_center * flip,
                 spin_axis_point=scene.spin_axis_point * flip,
                 third_point=scene.third_point * flip, constraints=constraints,
                 travel=scene.travel, wheel_radius=scene.wheel_radius,
                 description=scene.description, extras=scene.extras)


def translate(scene: Scene, offset: ArrayLike) -> Scene:
    """Return the scene moved by offset (3,) mm: a corner placed on the vehicle."""
    offset = np.asarray(offset, dtype=float)
    constraints = tuple(Constraint(name=c.name, type=c.type, base=c.base + offset,
                                   carrier=c.carrier + offset, steer=c.steer)
                        for c in scene.constraints)
    return replace(scene, wheel_center=scene.wheel_center + offset,
                   spin_axis_point=scene.spin_axis_point + offset,
                   third_point=scene.third_point + offset, constraints=constraints)
