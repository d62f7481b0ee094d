"""
An axle's anti-roll bar: its twist, its ratios to roll and to wheel travel, its roll stiffness.

A vehicle file gives the bar under its axle (doc/anti_roll_bar.md), in the file's units and the
vehicle frame, at design position:

    anti_roll_bar:
      axis: [[x, y, z], [x, y, z]]     two points of the axis the bar turns about in its
                                       body-fixed bushings
      arm_left: [x, y, z]              the end of the bar's left arm = the top of the left drop
                                       link
      drop_left: {arm: lower_arm, point: [x, y, z]}   the drop link's lower end, on the left
                                       corner: carrier: [x, y, z], arm: NAME + point, or
                                       link: NAME + point (core/measure/mounts.py)
      arm_right, drop_right            the same on the right; leave both out for the left
                                       mirrored in y (y -> -y)
      rate: 40.0                       optional: N m per degree of twist, whatever the units

Each arm turns with its half of the bar about the axis u (unit, directed to the left, + y),
by the angle theta (rad, right-hand about u) at which its drop link keeps its design length l:
with q the arm's design end from A0 (a point of the axis), r its distance from the axis, e1
its direction from the axis, e2 = u x e1 and d the drop link's lower end D from A0 + (q . u) u,

    |E(theta) - D| = l,  E(theta) = A0 + (q . u) u + r (cos(theta) e1 + sin(theta) e2)
    <=>  a cos(theta) + b sin(theta) = c,  a = d . e1, b = d . e2, c = (r^2 + |d|^2 - l^2) / 2r

solved in closed form on the design branch (the sign of w . t, w = E - D, t = u x (E - A0),
kept from design; NaN where the link cannot close). Its rates per mm of its own wheel's travel
follow from the drop link's (mounts.py: exact, implicit function theorem):

    theta' = w . D' / (w . t),   theta'' = (w . D'' - |w'|^2 - theta'^2 w . n) / (w . t)
    w' = t theta' - D',  n = u x t

The bar's twist is theta_left - theta_right (a symmetric bar turns both arms alike in heave:
no twist). In roll phi the wheels travel by -s and +s, s = (T / 2) tan(phi) (axle.py), so

    d twist / d phi     = -s' (theta_L' + theta_R')
    d2 twist / d phi^2  = s'^2 (theta_L'' - theta_R'') - s'' (theta_L' + theta_R')

With the torsional rate k (N m/deg) the bar stores V = k twist^2 / 2; the roll moment it resists
with is dV/dphi = k twist (d twist / d phi) (N m) and its roll stiffness
d2V/dphi^2 = k ((d twist / d phi)^2 + twist d2 twist / d phi^2) (N m/deg; twist in rad, its
second derivative in 1/rad). mm, rad, vehicle frame.
"""

from __future__ import annotations

from dataclasses import dataclass
import math
from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from ..base.geometry import cross
from ..measure.motion import guidance_rows, pose_batch
from ..measure.mounts import Mount, mount_motion, mount_table, parse_mount
from ..model.fields import Fields

if TYPE_CHECKING:
    from .axle import Axle
    from ..model.scene import Scene

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

    @property
    def sides(self) -> tuple[BarSide, BarSide]:
        """Return the left and the right side."""
        return self.left, self.right

    @property
    def has_rate(self) -> bool:
        """Whether a torsional rate is given, so that torque and roll stiffness are defined."""
        return not math.isnan(self.rate)


class BarValues(NamedTuple):
    """The bar at n axle positions, rad and mm; NaN where a drop link cannot close."""

    angle: np.ndarray          # (n, 2) each arm's turn about the axis from design, rad
    angle_rate: np.ndarray     # (n, 2) d angle / d its own wheel's travel, rad/mm
    angle_rate2: np.ndarray    # (n, 2) second derivative, rad/mm^2
    twist: np.ndarray          # (n,) angle_left - angle_right, rad
    ratio_travel: np.ndarray   # (n, 2) d twist / d left travel, d twist / d right travel, rad/mm
    ratio_roll: np.ndarray     # (n,) d twist / d roll, rad/rad
    ratio_roll_rate: np.ndarray   # (n,) d2 twist / d roll^2, 1/rad
    torque: np.ndarray         # (n,) N m, k twist (NaN without a rate)
    roll_moment: np.ndarray    # (n,) N m, the roll moment the bar resists with
    roll_stiffness: np.ndarray   # (n,) N m/deg


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
                   f"bar's axis, got {axis!r}")
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
    rate = math.nan
    if spec.get('rate') is not None:
        rate = check.number(spec, 'rate', f'{where}.rate', length=False)
        if not rate > 0:
            check.fail(f'{where}.rate', f'must be positive (N m per degree of twist), got '
                       f'{spec["rate"]!r}')
    return AntiRollBar(ends[0], u, *sides, rate=rate, mirrored=mirrored)


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
                   f'({scene.name}), got {drop!r}')
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


def bar_values(axle: Axle, bar: AntiRollBar, roll: np.ndarray, rack: np.ndarray,
               center: np.ndarray, rotation: np.ndarray,
               jacobians: tuple[np.ndarray, np.ndarray] | None = None) -> BarValues:
    """
    Return the bar at n solved axle positions.

    roll (n,) rad (+ = right side down), rack (n,) mm; center (n, 2, 3) and
    rotation (n, 2, 3, 3) the wheels' poses; jacobians: each wheel's (n, 5, 6) Jacobians at
    them if known (axle_quantities has them), else linearized here.
    """
    n = len(roll)
    angle, rate, rate2 = (np.empty((n, 2)) for _ in range(3))
    for k, (scene, mech, side) in enumerate(zip(axle.scenes, axle.mechanisms, bar.sides)):
        poses = pose_batch(mech, np.ascontiguousarray(center[:, k]),
                           np.ascontiguousarray(rotation[:, k]), rack,
                           None if jacobians is None else jacobians[k])
        point, velocity, acceleration = (
            a[:, 0] for a in mount_motion(guidance_rows(scene, mech),
                                          mount_table(scene, [side.mount]), poses))
        angle[:, k], rate[:, k], rate2[:, k] = arm_angle(bar, side, point, velocity,
                                                         acceleration)
    twist = angle[:, 0] - angle[:, 1]
    half = 0.5 * axle.design_track
    secant2 = 1.0 / np.cos(roll) ** 2
    s1, s2 = half * secant2, 2.0 * half * secant2 * np.tan(roll)   # ds/dphi, d2s/dphi2
    both = rate[:, 0] + rate[:, 1]
    ratio_roll = -s1 * both
    ratio_roll_rate = s1**2 * (rate2[:, 0] - rate2[:, 1]) - s2 * both
    torque = bar.rate * np.degrees(twist)
    return BarValues(
        angle=angle, angle_rate=rate, angle_rate2=rate2, twist=twist,
        ratio_travel=np.column_stack((rate[:, 0], -rate[:, 1])), ratio_roll=ratio_roll,
        ratio_roll_rate=ratio_roll_rate, torque=torque, roll_moment=torque * ratio_roll,
        roll_stiffness=bar.rate * (ratio_roll**2 + twist * ratio_roll_rate))


def arm_angle(bar: AntiRollBar, side: BarSide, point: np.ndarray, velocity: np.ndarray,
              acceleration: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """
    Return an arm's angle theta (rad) and its first and second rates per travel, (n,) each.

    point, velocity, acceleration (n, 3): the drop link's lower end D and its first and second
    derivatives per travel (mm, mm/mm, 1/mm). NaN where the link cannot reach the arm.
    """
    u, a0 = bar.axis, bar.axis_point
    q = side.arm_end - a0
    along = q @ u
    radial = q - along * u
    r = float(np.linalg.norm(radial))
    e1 = radial / r
    e2 = np.cross(u, e1)
    d = point - (a0 + along * u)
    a, b = d @ e1, d @ e2
    c = (r * r + np.einsum('ij,ij->i', d, d) - side.link_length**2) / (2.0 * r)
    tangent = np.cross(u, q)
    branch = -math.copysign(1.0, (side.arm_end - side.mount.point) @ tangent)
    with np.errstate(invalid='ignore'):
        theta = np.arctan2(b, a) - branch * np.arccos(c / np.hypot(a, b))   # NaN beyond reach
    theta = (theta + math.pi) % (2.0 * math.pi) - math.pi
    cos, sin = np.cos(theta)[:, None], np.sin(theta)[:, None]
    end = a0 + along * u + r * (cos * e1 + sin * e2)              # E(theta)
    w = end - point
    t = cross(u, end - a0)
    n = cross(u, t)
    wt = np.einsum('ij,ij->i', w, t)
    rate = np.einsum('ij,ij->i', w, velocity) / wt
    w1 = t * rate[:, None] - velocity
    rate2 = (np.einsum('ij,ij->i', w, acceleration) - np.einsum('ij,ij->i', w1, w1)
             - rate**2 * np.einsum('ij,ij->i', w, n)) / wt
    return theta, rate, rate2


def bar_notes(axle: Axle, values: BarValues) -> tuple[str, ...]:
    """Say where the bar's drop links cannot close (NaN rows), once; () if they always do."""
    lost = int(np.isnan(values.twist).sum())
    if not lost:
        return ()
    return (f"{axle.name} axle: the anti-roll bar's drop links cannot close at {lost} "
            f'position{"s" * (lost != 1)} (its columns are NaN there)',)
