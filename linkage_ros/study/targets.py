# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The targets file of a fit: which hardpoint coordinates may move, and the curves to meet.

    scene: double_wishbone            # bundled name, or a path (relative to this file)
    free:                             # coordinates that may move, bounds relative to design
      tie_rod.base: {x: [-30, 30], y: [-30, 30], z: [-30, 30]}     # mm
    targets:                          # curves over travel: [FROM, TO, STEP] in mm
      - {quantity: toe_deg, travel: [-50, 50, 5], value: 0.0, weight: 1.0}
      - {quantity: camber_gain_deg_per_mm, travel: [0, 0, 1], value: -0.02, weight: 10.0,
         tolerance: 0.001}

value: a constant or a list, one per travel; weight: default 1; tolerance (optional, the
quantity's unit): the largest error that counts as met. A point may also be given as
`{x: [lo, hi]}` alone (the other axes stay) or as `[lo, hi]` (every axis). Bounds and
travels are in mm whatever the scene's units, as every length of linkage-study. Every mistake
raises SceneError naming the file, the field and the problem.
"""

from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import numpy as np

from ..core.model import bundled_scenes, FREE_KEYS, read_yaml, SceneError
from ..core.solve import travel_count, travel_range
from ..core.vary import available, AXES, Design, did_you_mean, load_design

KEYS = ('scene', 'free', 'targets')
MOST_TRAVELS = 10_000   # per target: each is a solve and a row of the Jacobian
TARGET_KEYS = ('quantity', 'travel', 'value', 'weight', 'tolerance')


class Target(NamedTuple):
    """One target curve: a quantity at travels (mm) to meet values, with a weight."""

    quantity: str
    travel: np.ndarray   # (n,) mm
    value: np.ndarray    # (n,) the quantity's unit
    weight: float
    tolerance: float     # NaN: not judged


class Targets(NamedTuple):
    """A fit problem: the design, its free coordinates and their bounds (mm), the targets."""

    source: str
    design: Design
    free: tuple[tuple[int, int], ...]   # (point index, axis) per free coordinate
    lower: np.ndarray                   # (m,) mm, relative to design
    upper: np.ndarray
    targets: tuple[Target, ...]

    def names(self) -> list[str]:
        """Return the free coordinates as 'point.axis'."""
        return [f'{self.design.names[i]}.{AXES[a]}' for i, a in self.free]


def load_targets(path: str) -> Targets:
    """Read and check a targets file. Raises SceneError (file, field, problem)."""
    data = read_yaml(path, 'targets')
    source = str(path)

    def fail(where, problem):
        raise SceneError(source, where, problem)

    if not isinstance(data, dict):
        fail('file', 'expected a mapping with scene, free and targets')
    for key in data:
        if key not in KEYS and key not in FREE_KEYS and not str(key).startswith('x_'):
            fail(str(key), f'unknown key (known: {", ".join(KEYS)})')
    for key in KEYS:
        if key not in data:
            fail(key, 'missing')
    design = _design(source, data['scene'], fail)
    free, lower, upper = _free(design, data['free'], fail)
    have = available(design.scene)
    items = data['targets']
    if not isinstance(items, list) or not items:
        fail('targets', 'expected a list of targets {quantity, travel, value, weight}')
    targets = tuple(_target(item, f'targets[{i}]', have, design, fail)
                    for i, item in enumerate(items))
    return Targets(source, design, tuple(free), np.array(lower), np.array(upper), targets)


def _design(source, scene, fail):
    if not isinstance(scene, str) or not scene:
        fail('scene', f'expected a bundled scene name or a path, got {scene!r}')
    beside = (Path(source).parent / scene).absolute()   # a path is relative to this file
    name = scene if scene in bundled_scenes() or not beside.exists() else str(beside)
    return load_design(name)


def _number(value, where, fail):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not np.isfinite(value):
        fail(where, f'expected a finite number, got {value!r}')
    return float(value)


def _free(design, free, fail):
    if not isinstance(free, dict) or not free:
        fail('free', 'expected a mapping of points to bounds, e.g. tie_rod.base: '
             '{x: [-30, 30], y: [-30, 30], z: [-30, 30]}')
    coordinates, lower, upper = [], [], []
    for name, bounds in free.items():
        where = f'free.{name}'
        if name not in design.names:
            fail(where, f'not a hardpoint of the scene {design.scene.name} (its points: '
                 f'{", ".join(design.names)})')
        per_axis = bounds if isinstance(bounds, dict) else dict.fromkeys(AXES, bounds)
        for axis, pair in per_axis.items():
            if axis not in AXES:
                fail(f'{where}.{axis}', 'not an axis (x, y or z)')
            if not isinstance(pair, list) or len(pair) != 2:
                fail(f'{where}.{axis}', f'expected bounds [min, max] in mm relative to the '
                     f'design, got {pair!r}')
            low, high = (_number(v, f'{where}.{axis}', fail) for v in pair)
            if low > high:
                fail(f'{where}.{axis}', f'min {low:g} is above max {high:g}')
            if low == high:
                fail(f'{where}.{axis}', f'min and max are both {low:g}: leave the axis out '
                     'to keep it where it is')
            coordinates.append((design.names.index(name), AXES.index(axis)))
            lower.append(low)
            upper.append(high)
    return coordinates, lower, upper


def _target(item, where, have, design, fail):
    if not isinstance(item, dict):
        fail(where, 'expected a mapping {quantity, travel, value, weight}')
    for key in item:
        if key not in TARGET_KEYS and key not in FREE_KEYS:
            fail(f'{where}.{key}', f'unknown key (known: {", ".join(TARGET_KEYS)})')
    quantity = item.get('quantity')
    if quantity not in have:
        fail(f'{where}.quantity', f'{quantity!r} is not a quantity of the scene '
             f'{design.scene.name}{did_you_mean(quantity, have)} (its quantities: '
             f'{", ".join(have)})')
    span = item.get('travel')
    if not isinstance(span, list) or len(span) != 3:
        fail(f'{where}.travel', f'expected [FROM, TO, STEP] in mm, got {span!r}')
    start, stop, step = (_number(v, f'{where}.travel', fail) for v in span)
    if not step > 0:
        fail(f'{where}.travel', 'STEP must be above 0')
    count = travel_count(start, stop, step)   # counted before any is made
    if count > MOST_TRAVELS:
        fail(f'{where}.travel', f'{count:.6g} travels: at most {MOST_TRAVELS} per target')
    travels = travel_range(start, stop, step)
    value = item.get('value')
    if isinstance(value, list):
        if len(value) != len(travels):
            fail(f'{where}.value', f'{len(value)} values for {len(travels)} travels: give one '
                 'per travel, or a constant')
        values = np.array([_number(v, f'{where}.value', fail) for v in value])
    else:
        values = np.full(len(travels), _number(value, f'{where}.value', fail))
    weight = _number(item.get('weight', 1.0), f'{where}.weight', fail)
    if not weight > 0:
        fail(f'{where}.weight', f'must be above 0, got {weight:g}')
    tolerance = item.get('tolerance')
    tolerance = np.nan if tolerance is None else _number(tolerance, f'{where}.tolerance', fail)
    if not (np.isnan(tolerance) or tolerance > 0):
        fail(f'{where}.tolerance', f'must be above 0, got {tolerance:g}')
    return Target(quantity, travels, values, weight, tolerance)
