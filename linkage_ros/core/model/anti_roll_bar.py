# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
An axle's anti-roll bar as a vehicle file declares it (a declaration; no solver).

A vehicle file gives the bar under its axle (doc/anti_roll_bar.md), in the file's units and the
vehicle frame, at design position:

    anti_roll_bar:
      axis: [[x, y, z], [x, y, z]]     two points of the axis the bar turns about in its
                                       body-fixed bushings
      arm_left: [x, y, z]              the end of the bar's left arm = the top of the left drop
                                       link
      drop_left: {arm: lower_arm, point: [x, y, z]}   the drop link's lower end, on the left
                                       corner: carrier: [x, y, z], arm: NAME + point, or
                                       link: NAME + point (core/model/mounts.py)
      arm_right, drop_right            the same on the right; leave both out for the left
                                       mirrored in y (y -> -y)
      rate: 40.0                       optional: N m per degree of twist, whatever the units
                                       (its stated range: base/ranges.py, bar_rate)

What the bar does at solved axle positions (twist, ratios, roll stiffness) is
core/axle/anti_roll_bar.py's. mm, vehicle frame.
"""

from __future__ import annotations

from dataclasses import dataclass
import math
from typing import TYPE_CHECKING

import numpy as np

from .fields import Fields
from .mounts import Mount, parse_mount
from ..base.ranges import shown

if TYPE_CHECKING:
    from .scene import Scene

KEYS = ('axis', 'arm_left', 'drop_left', 'arm_right', 'drop_right', 'rate')
SIDES = ('left', 'right')
# The drop link must not be this close to square to its arm's path at design (dead centre):
# sin of the angle between the link and the arm's tangent, below which theta' runs away.
DEAD_CENTRE = 1e-3


@dataclass(frozen=True)
class BarSide:
    """One arm of the bar and its drop link, at design (mm, vehicle frame)."""

    arm_end: np.ndarray   # (3,) the arm's end, the drop link's top
    mount: Mount          # the drop link's lower end, on the side's corner
    link_length: float    # mm, the drop link's length


@dataclass(frozen=True)
class AntiRollBar:
    """An anti-roll bar: its axis, its two arms and drop links, its rate (NaN if not given)."""

    axis_point: np.ndarray   # (3,) mm, a point of the axis
    axis: np.ndarray         # (3,) unit, directed to the left (+ y)
    left: BarSide
    right: BarSide
    rate: float = math.nan   # N m per degree of twist
    mirrored: bool = False   # the right side was mirrored from the left
    # (2, 3) mm: the two axis points as written, where the bar's bushings hold it (the loads)
    axis_points: np.ndarray | None = None

    @property
    def sides(self) -> tuple[BarSide, BarSide]:
        """Return the left and the right side."""
        return self.left, self.right

    @property
    def has_rate(self) -> bool:
        """Whether a torsional rate is given, so that torque and roll stiffness are defined."""
        return not math.isnan(self.rate)


def parse_bar(source: str, where: str, spec: object, corners: tuple[Scene, Scene],
              scale: float) -> AntiRollBar:
    """
    Read an axle's anti_roll_bar mapping; raise SceneError naming the file and the field.

    where: the field path of the mapping ('axles.front.anti_roll_bar'); corners: the axle's
    left and right scenes, placed on the vehicle (mm); scale: mm per unit of the file.
    """
    check = Fields(source)
    check.scale = scale
    if not isinstance(spec, dict):
        check.fail(where, 'expected a mapping {axis, arm_left, drop_left, arm_right, '
                   'drop_right, rate}')
    check.keys(spec, KEYS, where)
    axis = spec.get('axis')
    if not isinstance(axis, list) or len(axis) != 2:
        check.fail(f'{where}.axis', f'expected two points [[x, y, z], [x, y, z]] of the '
                   f"bar's axis, got {shown(axis)}")
    ends = [check.vector(p, f'{where}.axis[{i}]') * scale for i, p in enumerate(axis)]
    direction = ends[1] - ends[0]
    size = float(np.linalg.norm(direction))
    if not size > 0 or abs(direction[1]) <= 1e-6 * size:
        check.fail(f'{where}.axis', 'expected two points of an axis that runs across the car '
                   '(distinct points, the axis not square to y)')
    u = direction / size * math.copysign(1.0, direction[1])   # to the left
    given = [key for key in ('arm_right', 'drop_right') if key in spec]
    if len(given) == 1:
        missing = ({'arm_right', 'drop_right'} - set(given)).pop()
        check.fail(f'{where}.{missing}', 'missing: give arm_right and drop_right together, '
                   'or neither (the right side is then the left mirrored in y)')
    mirrored = not given
    sides = []
    for k, side in enumerate(SIDES):
        item = spec if not (mirrored and side == 'right') else _mirrored(spec)
        sides.append(_side(check, where, item, side, corners[k], ends[0], u, scale,
                           mirrored and side == 'right'))
    rate = check.ranged(spec, 'rate', f'{where}.rate', 'bar_rate', math.nan)   # N m/deg
    return AntiRollBar(ends[0], u, *sides, rate=rate, mirrored=mirrored,
                       axis_points=np.array(ends))


def _mirrored(spec):
    """Return the right side's keys of spec: the left side's points mirrored in y."""
    drop = spec.get('drop_left')
    drop = ({k: _flip(v) if k in ('carrier', 'point') else v for k, v in drop.items()}
            if isinstance(drop, dict) else drop)
    return {'arm_right': _flip(spec.get('arm_left')), 'drop_right': drop}


def _flip(point):
    """Return [x, -y, z] of a point as written, or the value unchanged if it is not one."""
    if isinstance(point, list) and len(point) == 3 and isinstance(point[1], (int, float)) \
            and not isinstance(point[1], bool):
        return [point[0], -point[1], point[2]]
    return point


def _side(check, where, item, side, scene, axis_point, u, scale, mirrored):
    """Read one side's arm end and drop link; check the arm, the link and dead centre."""
    said = f' (the {side} corner, {scene.name}' + (
        '; mirrored from arm_left and drop_left)' if mirrored else ')')
    arm_key, drop_key = f'arm_{side}', f'drop_{side}'
    arm_end = check.point(item, arm_key, f'{where}.{arm_key}') * scale
    drop = item.get(drop_key)
    field = f'{where}.{drop_key}'
    if not isinstance(drop, dict):
        check.fail(field, f'expected a mapping {{carrier: [x, y, z]}}, {{arm: NAME, point: '
                   f'[x, y, z]}} or {{link: NAME, point: [x, y, z]}} on the {side} corner '
                   f'({scene.name}), got {shown(drop)}')
    if 'along' in drop:
        check.fail(f'{field}.along', 'a drop link ends on the carrier, an arm or a link: '
                   'along: is for a strut element')

    def fail(field_name, problem):
        check.fail(field_name, problem + said)

    mount, _ = parse_mount(drop, scene.constraints, field, scale,
                           lambda key, name: check.point(drop, key, name), fail)
    offset = arm_end - axis_point
    radial = offset - (offset @ u) * u
    if not np.linalg.norm(radial) > 1e-6 * max(1.0, float(np.linalg.norm(offset))):
        fail(f'{where}.{arm_key}', "on the bar's axis: an arm needs a lever")
    link = arm_end - mount.point
    length = float(np.linalg.norm(link))
    if not length > 1e-9 * max(1.0, float(np.abs(arm_end).max())):
        fail(f'{field}', f'the drop link has no length: its lower end is {arm_key}')
    tangent = np.cross(u, offset)
    if abs(link @ tangent) <= DEAD_CENTRE * length * float(np.linalg.norm(tangent)):
        fail(f'{field}', f'the drop link is square to the path of {arm_key} at design (dead '
             'centre): it does not turn the bar')
    return BarSide(arm_end, mount, length)
