# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
An axle's anti-roll bar: its twist, its ratios to roll and to wheel travel, its roll stiffness.

A vehicle file gives the bar under its axle (core/model/anti_roll_bar.py, the declaration;
doc/anti_roll_bar.md).

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

import math
from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from ..base.geometry import cross
from ..measure.motion import guidance_rows, pose_batch
from ..measure.mounts import mount_motion, mount_table

if TYPE_CHECKING:
    from ..model.anti_roll_bar import AntiRollBar, BarSide
    from ..model.scene import Scene
    from ..solve.mechanism import Mechanism


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
    drop_point: np.ndarray | None = None   # (n, 2, 3) each drop link's lower end D, mm


def bar_values(scenes: tuple[Scene, Scene], mechanisms: tuple[Mechanism, Mechanism],
               design_track: float, bar: AntiRollBar, roll: np.ndarray, rack: np.ndarray,
               center: np.ndarray, rotation: np.ndarray,
               jacobians: tuple[np.ndarray, np.ndarray] | None = None) -> BarValues:
    """
    Return the bar at n solved axle positions.

    scenes, mechanisms, design_track (mm): the axle's (Axle.scenes, .mechanisms,
    .design_track); roll (n,) rad (+ = right side down), rack (n,) mm; center (n, 2, 3) and
    rotation (n, 2, 3, 3) the wheels' poses; jacobians: each wheel's (n, 5, 6) Jacobians at
    them if known (axle_quantities has them), else linearized here.
    """
    n = len(roll)
    angle, rate, rate2 = (np.empty((n, 2)) for _ in range(3))
    drop = np.empty((n, 2, 3))
    for k, (scene, mech, side) in enumerate(zip(scenes, mechanisms, bar.sides)):
        poses = pose_batch(mech, np.ascontiguousarray(center[:, k]),
                           np.ascontiguousarray(rotation[:, k]), rack,
                           None if jacobians is None else jacobians[k])
        point, velocity, acceleration = (
            a[:, 0] for a in mount_motion(guidance_rows(scene, mech),
                                          mount_table(scene, [side.mount]), poses))
        angle[:, k], rate[:, k], rate2[:, k] = arm_angle(bar, side, point, velocity,
                                                         acceleration)
        drop[:, k] = point
    twist = angle[:, 0] - angle[:, 1]
    half = 0.5 * design_track
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
        roll_stiffness=bar.rate * (ratio_roll**2 + twist * ratio_roll_rate), drop_point=drop)


def arm_angle(bar: AntiRollBar, side: BarSide, point: np.ndarray, velocity: np.ndarray,
              acceleration: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """
    Return an arm's angle theta (rad) and its first and second rates per travel, (n,) each.

    point, velocity, acceleration (n, 3): the drop link's lower end D and its first and second
    derivatives per travel (mm, mm/mm, 1/mm). NaN where the link cannot reach the arm.
    """
    u, a0 = bar.axis, bar.axis_point
    centre, r, e1, e2 = _arm_circle(bar, side)
    d = point - centre
    a, b = d @ e1, d @ e2
    c = (r * r + np.einsum('ij,ij->i', d, d) - side.link_length**2) / (2.0 * r)
    tangent = np.cross(u, side.arm_end - a0)
    branch = -math.copysign(1.0, (side.arm_end - side.mount.point) @ tangent)
    with np.errstate(invalid='ignore'):
        theta = np.arctan2(b, a) - branch * np.arccos(c / np.hypot(a, b))   # NaN beyond reach
    theta = (theta + math.pi) % (2.0 * math.pi) - math.pi
    end = arm_end(bar, side, theta)
    w = end - point
    t = cross(u, end - a0)
    n = cross(u, t)
    wt = np.einsum('ij,ij->i', w, t)
    rate = np.einsum('ij,ij->i', w, velocity) / wt
    w1 = t * rate[:, None] - velocity
    rate2 = (np.einsum('ij,ij->i', w, acceleration) - np.einsum('ij,ij->i', w1, w1)
             - rate**2 * np.einsum('ij,ij->i', w, n)) / wt
    return theta, rate, rate2


def arm_end(bar: AntiRollBar, side: BarSide, theta: np.ndarray) -> np.ndarray:
    """Return the arm's end E(theta) (n, 3) mm, the arm turned by theta (n,) rad from design."""
    centre, r, e1, e2 = _arm_circle(bar, side)
    cos, sin = np.cos(theta)[:, None], np.sin(theta)[:, None]
    return centre + r * (cos * e1 + sin * e2)


def _arm_circle(bar: AntiRollBar, side: BarSide):
    """Return the circle of an arm's end: its centre A0 + (q . u) u, radius r, e1 and e2."""
    u, a0 = bar.axis, bar.axis_point
    q = side.arm_end - a0
    along = q @ u
    radial = q - along * u
    r = float(np.linalg.norm(radial))
    e1 = radial / r
    return a0 + along * u, r, e1, np.cross(u, e1)


def bar_notes(axle_name: str, values: BarValues) -> tuple[str, ...]:
    """Say where the bar's drop links cannot close (NaN rows), once; () if they always do."""
    lost = int(np.isnan(values.twist).sum())
    if not lost:
        return ()
    return (f"{axle_name} axle: the anti-roll bar's drop links cannot close at {lost} "
            f'position{"s" * (lost != 1)} (its columns are NaN there)',)
