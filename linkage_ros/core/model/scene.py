# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Scene files: design-position hardpoints of one suspension corner, loaded and validated.

A scene is YAML with declared units (mm or m) and ISO 8855 axes (x forward, y left, z up).
Everything is converted to millimetres on load; the rest of the package works in mm.
A malformed scene raises SceneError naming the file, the field and the problem; a key the
format does not know is one (with the closest known key suggested). A scene that loads but
looks wrong (the size of a road vehicle's wheel missed by far: a unit slip?) carries
warnings, one line each, for the programs to print: the core prints nothing.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property
import math
from pathlib import Path
import re
from typing import Any, Callable, TYPE_CHECKING

import numpy as np

# bundled_scenes, config_dir and scene_dir are also read from here, where they were.
from .bundled import bundled_scenes, config_dir, resolve, scene_dir  # noqa: F401
from .constraint import Constraint, EQUATIONS_PER_TYPE  # noqa: F401 (also read from here)
from .elements import parse_elements
from .fields import Fields, FREE_KEYS
from .kingpin import check_kingpin, KEY as KINGPIN_KEY
from .layout import Layout, layout_of
# LENGTH_LIMIT_MM, SceneError and within_length_limit are also read from here, where they were.
from .yaml_file import read_yaml, SceneError  # noqa: F401 (SceneError: kept here)
from ..base.errors import LinkageError, listed
from ..base.geometry import perpendicular, spin_axis_of, unit
from ..base.limits import LENGTH_LIMIT_MM, positions_needed, within_length_limit  # noqa: F401
from ..base.ranges import shown

if TYPE_CHECKING:
    from collections.abc import Sequence
    from os import PathLike

    from numpy.typing import ArrayLike

UNITS_TO_MM = {'mm': 1.0, 'm': 1000.0}
SIDES = ('left', 'right')
# Relative size (to the scene's largest dimension) below which two points are "coincident"
# and a triangle or arm is "too thin" to define a frame.
THIN = 1e-6
# Wheel radius and half-track (|y| of the wheel centre) of a road vehicle, mm: a scene
# outside is solved as given, with a warning (mechanisms of other sizes are legitimate).
PLAUSIBLE_MM = (50.0, 3000.0)

# The keys of a scene file, of its blocks, and of a constraint (base for a sphere or a line,
# axis for a circle); FREE_KEYS (description, source, notes) and x_... keys are allowed in
# every mapping, reference at the top.
SCENE_KEYS = ('name', 'units', 'side', 'wheel_radius', 'carrier', 'constraints', 'travel',
              'elements')
# Keys of features beyond the solver, checked by their own modules and kept in Scene.extras.
FEATURE_KEYS = ('kingpin',)
SCENE_FREE_KEYS = FREE_KEYS + ('reference',)
CARRIER_KEYS = ('wheel_center', 'spin_axis_point', 'static', 'third_point')
STATIC_KEYS = ('camber', 'toe')
TRAVEL_KEYS = ('min', 'max', 'step')
ALL_CONSTRAINT_KEYS = ('name', 'type', 'base', 'axis', 'carrier', 'steer', 'bushing')


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
    # One line each, naming the file: what looks wrong in a scene that loads (see
    # scene_warnings). The programs print them once on stderr; the node logs them.
    warnings: tuple[str, ...] = field(default=(), compare=False)
    elements: tuple = ()          # springs, dampers, lengths (elements.Element), mm
    # the `kingpin` key, checked (kingpin.KingpinPoint upper, lower); None: the default axis
    kingpin: tuple | None = None

    @property
    def side_sign(self) -> float:
        """+1 for a left wheel, -1 for a right wheel (outboard direction along y)."""
        return 1.0 if self.side == 'left' else -1.0

    @property
    def has_bushings(self) -> bool:
        """Whether a constraint declares a bushing (the scene then has statics compliance)."""
        return any(c.bushing is not None for c in self.constraints)

    @property
    def steered(self) -> bool:
        """Whether a steer: rack link moves with the rack (it takes rack commands)."""
        return any(c.steer == 'rack' for c in self.constraints)

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

    @cached_property
    def point_names(self) -> tuple[str, ...]:
        """
        Return the names of the hardpoints, in the order of the rows of points.

        `<constraint>.base` (a link's or a strut's body point), `<constraint>.axis0` and
        `<constraint>.axis1` (an arm's revolute axis), `<constraint>.carrier` (the carrier
        joint), then wheel_center and spin_axis_point.
        """
        names = []
        for c in self.constraints:
            ends = ('axis0', 'axis1') if c.type == 'circle' else ('base',)
            names += [f'{c.name}.{end}' for end in ends] + [f'{c.name}.carrier']
        return tuple(names + ['wheel_center', 'spin_axis_point'])

    @cached_property
    def points(self) -> np.ndarray:
        """Return the hardpoint table (k, 3) mm, design position, rows as point_names."""
        rows = []
        for c in self.constraints:
            rows += list(c.base) + [c.carrier]
        table = np.array(rows + [self.wheel_center, self.spin_axis_point], dtype=float)
        table.flags.writeable = False
        return table

    @cached_property
    def layout(self) -> Layout:
        """Return the row map of the guidance equations into points (layout.layout_of)."""
        return layout_of(self)

    def to_mm(self, value: float | np.ndarray) -> float | np.ndarray:
        """Convert a length (or an array of them) from the scene's units to mm."""
        return value * UNITS_TO_MM[self.units]

    @property
    def file_stem(self) -> str:
        """Return the scene's name made safe as a file name's stem in any folder (safe_stem)."""
        return safe_stem(self.name)


def safe_stem(name: str) -> str:
    """
    Return name as a file-name stem that stays in the folder it is written to.

    Anything but letters, digits, '_', '.', '-' becomes '_' (so no '/' is left), and leading
    and trailing '.', '_', '-' go (no '..', no hidden file, no option): '../escaped' ->
    'escaped', '/tmp/x' -> 'tmp_x'. At most 100 characters; 'scene' if nothing is left.
    """
    stem = re.sub(r'[^A-Za-z0-9_.-]+', '_', str(name)).strip('._-')
    return stem[:100].rstrip('._-') or 'scene'


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


def resolve_scene_path(name_or_path: str | PathLike) -> Path:
    """Resolve a bundled scene name ('five_link') or a path to a YAML file; else SceneError."""
    return resolve(name_or_path, 'scene')


def load_scene(name_or_path: str | PathLike) -> Scene:
    """Load and validate a scene file; returns a Scene in mm. Raises SceneError."""
    path = resolve_scene_path(name_or_path)
    return parse_scene(read_yaml(path, 'scene'), source=str(path))


def parse_scene(data: Any, source: str = '<scene>') -> Scene:
    """Validate a scene mapping (as read from YAML) and return a Scene in mm."""
    check = Fields(source)
    if not isinstance(data, dict):
        check.fail('file', 'expected a mapping of scene keys')
    check.keys(data, SCENE_KEYS + FEATURE_KEYS, free=SCENE_FREE_KEYS)
    units = check.choice(data, 'units', tuple(UNITS_TO_MM))
    side = check.choice(data, 'side', SIDES)
    scale = check.scale = UNITS_TO_MM[units]
    carrier = check.mapping(data, 'carrier')
    check.keys(carrier, CARRIER_KEYS, 'carrier')
    wheel_center = check.point(carrier, 'wheel_center', 'carrier.wheel_center') * scale
    constraints = tuple(_parse_constraint(check, item, i, scale)
                        for i, item in enumerate(check.sequence(data, 'constraints')))
    names = [c.name for c in constraints]
    for i, name in enumerate(names):
        if name in names[:i]:   # two of a name would share their pickups' topics and frames
            check.fail(f'constraints[{i}] ({name}).name', f'used twice (constraints['
                       f'{names.index(name)}] too): names make topics, frames and columns, '
                       'so each constraint needs its own')
    spin_point = _spin_axis_point(check, carrier, wheel_center, side, constraints)
    given_p = None
    if carrier.get('third_point') is not None:
        given_p = check.point(carrier, 'third_point', 'carrier.third_point') * scale
    travel = _parse_travel(check, data.get('travel'), scale)
    radius = check.ranged(data, 'wheel_radius', 'wheel_radius', 'wheel_radius', 0.0)   # mm
    scene_size = _size([wheel_center, spin_point] + [c.carrier for c in constraints]
                       + [b for c in constraints for b in c.base])
    _check_geometry(check, wheel_center, spin_point, constraints, scene_size)
    third_point = given_p if given_p is not None else choose_third_point(
        wheel_center, spin_point, [c.carrier for c in constraints])
    _check_third_point(check, wheel_center, spin_point, third_point, constraints,
                       'carrier.third_point' if given_p is not None else 'carrier',
                       given_p is not None, scene_size)
    kingpin = None   # a misspelt joint fails on load, not in a sweep
    if data.get(KINGPIN_KEY) is not None:
        kingpin = check_kingpin(source, data[KINGPIN_KEY], constraints)
    scene = Scene(name=check.name(data, 'name') or Path(source).stem, source=source,
                  side=side, units=units, wheel_center=wheel_center, spin_axis_point=spin_point,
                  third_point=third_point, constraints=constraints, travel=travel,
                  wheel_radius=radius, description=check.text(data, 'description').strip(),
                  extras={k: v for k, v in data.items()
                          if k not in SCENE_KEYS and k != 'description'},
                  elements=parse_elements(check, data.get('elements'), constraints),
                  kingpin=kingpin)
    return replace(scene, warnings=scene_warnings(scene))


# Checks of a loaded scene that need a layer above this one (solve/mechanism.py registers the
# singular-design check): a declaration never imports the solver. linkage_ros.core imports
# solve, so every scene is parsed with them in place.
CHECKS: list[Callable[[Scene], tuple[str, ...]]] = []


def _checked(scene: Scene) -> tuple[str, ...]:
    return tuple(line for check in CHECKS for line in check(scene))


def scene_warnings(scene: Scene) -> tuple[str, ...]:
    """
    Return what looks wrong in a scene that loads, one line each, naming its file.

    A size no road vehicle has: a wheel radius or a half-track (|y| of the wheel centre)
    outside PLAUSIBLE_MM, as a scene written in mm but labelled units: m gives (a corner
    768 km wide). The scene is solved as given: mechanisms of other sizes are legitimate.
    """
    low, high = PLAUSIBLE_MM
    sizes = [(f'wheel_radius {scene.wheel_radius:.6g} mm', scene.wheel_radius)] \
        if scene.wheel_radius else []
    sizes.append((f'half-track {abs(scene.wheel_center[1]):.6g} mm (|y| of the wheel centre)',
                  abs(scene.wheel_center[1])))
    odd = [(said, size) for said, size in sizes if not low <= size <= high]
    if not odd:
        return _checked(scene)
    guess = ''
    if scene.units == 'm' and all(size > high for _, size in odd):
        guess = ': a file written in mm but labelled units: m?'
    elif scene.units == 'mm' and all(size < low for _, size in odd):
        guess = ': a file written in m but labelled units: mm?'
    verb = 'is' if len(odd) == 1 else 'are'
    return (f'{scene.source}: {" and ".join(said for said, _ in odd)} {verb} outside '
            f'{low:g}-{high:g} mm, implausible for a road vehicle{guess} (solved as given)',
            ) + _checked(scene)


def _spin_axis_point(check, carrier, wheel_center, side, constraints):
    """
    Return N (mm): carrier.spin_axis_point, or derived from carrier.static {camber, toe}.

    Static camber and toe (deg; camber + = top outboard, toe + = toe-in, on either side) give
    the outboard spin axis a = (cos c sin t, s cos c cos t, -sin c), s = +1 left, -1 right:
    the inverse of geometry.camber_toe. N is placed inboard on it, as far from M as the
    carrier's joints are on average (a distance of the scene's own size).
    """
    if 'static' not in carrier:
        return check.point(carrier, 'spin_axis_point', 'carrier.spin_axis_point') * check.scale
    if 'spin_axis_point' in carrier:
        check.fail('carrier.static', 'give spin_axis_point or static, not both (static '
                   'derives the spin axis from the camber and toe)')
    block = check.mapping(carrier, 'static', 'carrier.static')
    check.keys(block, STATIC_KEYS, 'carrier.static')
    angles = []
    for key in STATIC_KEYS:
        value = check.number(block, key, f'carrier.static.{key}', length=False)
        if not abs(value) < 90.0:
            check.fail(f'carrier.static.{key}', f'{value:g} deg: must be between -90 and 90 '
                       'deg, or the spin axis does not point outboard')
        angles.append(math.radians(value))
    camber, toe = angles
    axis = spin_axis_of(camber, toe, 1.0 if side == 'left' else -1.0)
    reach = [np.linalg.norm(c.carrier - wheel_center) for c in constraints]
    distance = float(np.mean(reach)) if reach and np.mean(reach) > 0 else 100.0
    return wheel_center - distance * axis


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
    check.keys(item, ALL_CONSTRAINT_KEYS, where)
    name = check.token(item, 'name', f'{where}.name')   # topics and frames are made of it
    where = f'constraints[{index}] ({name})'
    kind = check.choice(item, 'type', tuple(EQUATIONS_PER_TYPE), f'{where}.type')
    other = 'base' if kind == 'circle' else 'axis'
    if other in item:
        check.fail(f'{where}.{other}', f'not used by a {kind}, which takes '
                   + ('axis: two points on the revolute axis' if kind == 'circle' else 'base'))
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
        check.fail(f'{where}.steer', f"unknown value {shown(steer)} (expected 'rack')")
    bushing = None
    if 'bushing' in item:   # bushing.py is read only by a scene that has one (null refused)
        from .bushing import parse_bushing
        bushing = parse_bushing(check, item['bushing'], where, kind)
    return Constraint(name=name or f'{kind}_{index}', type=kind, base=base * scale,
                      carrier=carrier * scale, steer=steer or '', bushing=bushing)


def _parse_travel(check, block, scale):
    if block is None:
        return (-80.0, 80.0, 1.0)
    if not isinstance(block, dict):
        check.fail('travel', 'expected a mapping {min, max, step}')
    check.keys(block, TRAVEL_KEYS, 'travel')
    low = check.number(block, 'min', 'travel.min') * scale
    high = check.number(block, 'max', 'travel.max') * scale
    step = check.number(block, 'step', 'travel.step', minimum=0.0) * scale
    if step <= 0:
        check.fail('travel.step', f'must be positive, got {step / scale:g}')
    if high < low:
        check.fail('travel', f'max ({high / scale:g}) is below min ({low / scale:g})')
    try:
        positions_needed(low, high, step)
    except LinkageError as exc:   # a step so small that the sweep could not be held
        check.fail('travel.step', exc.problem)
    return (low, high, step)


def _check_geometry(check, wheel_center, spin_point, constraints, size):
    tiny = THIN * size
    if np.linalg.norm(wheel_center - spin_point) <= tiny:
        check.fail('carrier.spin_axis_point', 'coincides with carrier.wheel_center: the spin '
                   'axis needs two distinct points')
    total = sum(c.equations for c in constraints)
    if total != 5:
        counts = listed([f'{c.name} ({c.type}) {c.equations}' for c in constraints]) or 'none'
        check.fail('constraints', f'give {total} equations from {len(constraints)} '
                   f'constraints ({counts}); the carrier has 5 '
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


def _size(points):
    return float(max(np.max(np.abs(p)) for p in points))
