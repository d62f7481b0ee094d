# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The axles of a vehicle file, and the vehicle-level data that axle quantities need.

    wheelbase: 2800            # scene units of the file (units:); from two axles if absent
    cg_height: 550             # above the ground; needed for anti-dive, -lift and -squat
    axles:
      front: {left: front_left, right: front_right, brake_share: 0.6, drive_share: 0.0,
              brakes: outboard}          # outboard | inboard
      rear:  {left: rear_left, right: rear_right, brake_share: 0.4, drive_share: 1.0,
              brakes: outboard}

An axle may also have an anti_roll_bar (core/axle/anti_roll_bar.py, doc/anti_roll_bar.md), whose
module is imported only for a file that has one.

An axle is front or rear, and names the vehicle's left and right corners. brake_share and
drive_share (0 to 1, default 0) are the axle's shares of the braking and the driving force; an
axle with a share asks for its anti-dive (front) or anti-lift (rear) under braking, and its
anti-lift (front) or anti-squat (rear) under drive, which need cg_height and the wheelbase.
vehicle.py imports this module only for a file that has these keys. Errors raise SceneError
naming the vehicle file and the key.
"""

from __future__ import annotations

from dataclasses import dataclass, field
import math
from typing import TYPE_CHECKING

import numpy as np

from .fields import Fields
from .scene import SceneError
from ..base.errors import listed
from ..base.ranges import DOC as RANGES_DOC, RANGE, shown

if TYPE_CHECKING:
    from .anti_roll_bar import AntiRollBar
    from .scene import Scene

AXLE_NAMES = ('front', 'rear')
BRAKES = ('outboard', 'inboard')
AXLE_KEYS = ('left', 'right', 'brake_share', 'drive_share', 'brakes', 'anti_roll_bar')
# How far an axle's wheel centres may be from mirror images of each other, as a fraction of
# the track: in x and z, and the axle's middle off the centre plane y = 0. Beyond it the two
# corners are not one axle (a roll centre, a track and an Ackermann need a transverse pair).
AXLE_SKEW = 0.1


@dataclass(frozen=True)
class AxleSpec:
    """One axle of a vehicle file: its corners and its shares of braking and drive."""

    name: str                  # 'front' | 'rear'
    left: str                  # corner names
    right: str
    brake_share: float = 0.0   # 0..1 of the vehicle's braking force
    drive_share: float = 0.0   # 0..1 of the vehicle's driving force
    brakes: str = 'outboard'   # outboard (torque into the carrier) | inboard (into the body)
    anti_roll_bar: AntiRollBar | None = None


@dataclass(frozen=True)
class VehicleAxles:
    """The vehicle-level data of a vehicle file (mm)."""

    source: str
    wheelbase: float = math.nan   # mm; nan where neither given nor derivable
    cg_height: float = math.nan   # mm above the ground; nan where not given
    axles: dict[str, AxleSpec] = field(default_factory=dict)


def parse_axles(path: object, data: dict, corners: dict[str, Scene],
                scale: float) -> VehicleAxles:
    """
    Read wheelbase, cg_height and axles of a vehicle file's mapping; raise SceneError if bad.

    corners are the vehicle's placed scenes (mm); scale is mm per unit of the file.
    """
    axles = {}
    block = data.get('axles', {})
    if not isinstance(block, dict):
        raise SceneError(path, 'axles', 'expected a mapping of front and/or rear to {left, '
                         'right, brake_share, drive_share, brakes}')
    for name, spec in block.items():
        axles[name] = _axle(path, name, spec, corners, scale)
    wheelbase = _length(path, data, 'wheelbase', scale)
    if math.isnan(wheelbase) and len(axles) == 2:
        wheelbase = float(np.mean([corners[c].wheel_center[0] for c in
                                   (axles['front'].left, axles['front'].right)])
                          - np.mean([corners[c].wheel_center[0] for c in
                                     (axles['rear'].left, axles['rear'].right)]))
    cg_height = _length(path, data, 'cg_height', scale)
    for axle in axles.values():
        shares = [k for k in ('brake_share', 'drive_share') if getattr(axle, k)]
        if shares and math.isnan(cg_height):
            raise SceneError(path, 'cg_height', f'missing: axles.{axle.name}.{shares[0]} asks '
                             'for anti-dive, -lift or -squat, which need the height of the '
                             'centre of gravity above the ground')
        if shares and not wheelbase > 0:
            raise SceneError(path, 'wheelbase', f'missing: axles.{axle.name}.{shares[0]} '
                             'asks for anti-dive, -lift or -squat, which need the wheelbase '
                             '(give wheelbase, or a front and a rear axle)')
    return VehicleAxles(source=str(path), wheelbase=wheelbase, cg_height=cg_height,
                        axles=axles)


def _axle(path, name, spec, corners, scale):
    where = f'axles.{name}'
    if name not in AXLE_NAMES:
        raise SceneError(path, where, f'unknown axle (expected one of: {", ".join(AXLE_NAMES)})')
    if not isinstance(spec, dict):
        raise SceneError(path, where, 'expected a mapping {left, right, brake_share, '
                         'drive_share, brakes}')
    for key in spec:
        if key not in AXLE_KEYS:
            raise SceneError(path, f'{where}.{key}', f'unknown key (expected: '
                             f'{", ".join(AXLE_KEYS)})')
    sides = []
    for side in ('left', 'right'):
        corner = spec.get(side)
        if not isinstance(corner, str) or corner not in corners:
            raise SceneError(path, f'{where}.{side}', f'{shown(corner)} is not a corner of the '
                             f'vehicle (corners: {listed(list(corners))})')
        expected = 1.0 if side == 'left' else -1.0
        if corners[corner].side_sign != expected:
            raise SceneError(path, f'{where}.{side}', f'corner {corner} is a '
                             f'{corners[corner].side} wheel (mirror: true makes a right one)')
        sides.append(corner)
    _check_pair(path, where, sides, [corners[c].wheel_center for c in sides])
    shares = [_share(path, f'{where}.{key}', spec.get(key, 0.0))
              for key in ('brake_share', 'drive_share')]
    brakes = spec.get('brakes', 'outboard')
    if brakes not in BRAKES:
        raise SceneError(path, f'{where}.brakes', f'unknown value {shown(brakes)} (expected one '
                         f'of: {", ".join(BRAKES)})')
    bar = None
    if spec.get('anti_roll_bar') is not None:
        from .anti_roll_bar import parse_bar
        bar = parse_bar(str(path), f'{where}.anti_roll_bar', spec['anti_roll_bar'],
                        (corners[sides[0]], corners[sides[1]]), scale)
    return AxleSpec(name, *sides, *shares, brakes, bar)


def _check_pair(path, where, names, centres):
    """
    Refuse two corners that are no axle, raising SceneError that names the axle's field.

    A wheel on the wrong side (so a track <= 0, coincident wheels among them), or wheel
    centres (mm) further than AXLE_SKEW x track from mirror images: in x, in z, or about y = 0.
    """
    (left, right), track = centres, centres[0][1] - centres[1][1]
    for side, name, centre, sign in zip(('left', 'right'), names, centres, (1.0, -1.0)):
        if not sign * centre[1] > 0:
            raise SceneError(path, f'{where}.{side}', f'corner {name} is a {side} wheel with '
                             f'its centre at y = {centre[1]:.6g} mm: a {side} wheel is at '
                             f'{"+" if sign > 0 else "-"}y (y to the left); check its offset')
    problem = RANGE['height'].problem(track)
    if problem:
        raise SceneError(path, where, f'the track of {names[0]} and {names[1]} (y of the left '
                         f'wheel centre - y of the right) of {problem} ({RANGES_DOC})')
    skew = {'x': abs(left[0] - right[0]), 'z': abs(left[2] - right[2]),
            'y (middle off the centre plane)': abs(left[1] + right[1])}
    for axis, apart in skew.items():
        if apart > AXLE_SKEW * track:
            raise SceneError(path, where, f'the wheel centres of {names[0]} and {names[1]} '
                             f'are {apart:.6g} mm apart in {axis}, more than '
                             f'{AXLE_SKEW:g} x their track of {track:.6g} mm: an axle is a '
                             'left corner and its mirror image; check the offsets')


def _share(path, where, value):
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not 0.0 <= value <= 1.0:
        raise SceneError(path, where, f'expected a share from 0 to 1, got {shown(value)}')
    return float(value)


def _length(path, data, key, scale):
    """Return data[key] in mm, a length within the stated range of a height; NaN if absent."""
    if data.get(key) is None:
        return math.nan
    check = Fields(str(path))
    check.scale = scale
    return check.ranged(data, key, key, 'height')
