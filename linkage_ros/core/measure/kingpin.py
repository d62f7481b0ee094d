# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The geometric kingpin axis: the line through two ball joints, real or virtual (beyond the paper).

Lotus Suspension Analysis, Adams Car's "geometric" steer axis and Altair's kingpin requests
take the kingpin as the line through two points of the suspension:

    double wishbone   the carrier ball joints of the two arms (circle constraints)
    MacPherson        the strut's top mount (base of the line constraint) and the ball joint
                      of the lower arm
    five-link         virtual ball joints: each named pair of links gives the point of
                      closest approach of the two link lines (the midpoint of their common
                      perpendicular), which moves on the carrier as it travels

A scene names its kingpin (model/kingpin.py, Scene.kingpin); this module measures the axis
through those two points at solved positions.

The instantaneous steer axis (the screw axis of the carrier under rack input, alignment.py) is
the other convention; doc/alignment.md compares them. Frames and units: vehicle frame (x
forward, y left, z up), mm, rad; batched over n positions.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .alignment import ground_point
from ..model.kingpin import KingpinPoint

if TYPE_CHECKING:
    from ..model.scene import Scene


@dataclass(frozen=True)
class GeometricKingpin:
    """The geometric kingpin's alignment set at n positions, arrays (n,). NaN where undefined."""

    upper: np.ndarray                # (n, 3) upper kingpin point, mm
    lower: np.ndarray                # (n, 3) lower kingpin point, mm
    axis: np.ndarray                 # (n, 3) unit direction, lower to upper, pointing up
    caster: np.ndarray               # rad, + = top rearward
    kingpin_inclination: np.ndarray  # rad, + = top inboard
    scrub_radius: np.ndarray         # mm, + = axis meets the ground inboard of the patch
    mechanical_trail: np.ndarray     # mm, + = axis meets the ground ahead of the patch
    offset_wheel_centre: np.ndarray  # mm, + = axis inboard of the wheel centre at its height


def kingpin_points(scene: Scene) -> tuple[KingpinPoint, KingpinPoint] | None:
    """
    Return the (upper, lower) kingpin points of a scene, or None if it has no kingpin.

    From its `kingpin` key (Scene.kingpin, checked on load), else from two circles (the higher
    ball joint upper) or a line and a circle.
    """
    if scene.kingpin is not None:
        return scene.kingpin
    kinds = [c.type for c in scene.constraints]
    circles = [i for i, kind in enumerate(kinds) if kind == 'circle']
    lines = [i for i, kind in enumerate(kinds) if kind == 'line']
    if len(circles) == 2 and not lines:
        low, high = sorted(circles, key=lambda i: scene.constraints[i].carrier[2])
        return KingpinPoint('carrier', (high,)), KingpinPoint('carrier', (low,))
    if len(circles) == 1 and len(lines) == 1:
        return KingpinPoint('base', (lines[0],)), KingpinPoint('carrier', (circles[0],))
    return None


def point_positions(scene: Scene, point: KingpinPoint, joints: np.ndarray,
                    rack: float = 0.0) -> np.ndarray:
    """
    Return where a kingpin point is at n positions, (n, 3) mm.

    joints (n, m, 3) are the carrier joints in constraint order (Sweep.joints); rack (mm)
    moves the base points of steer: rack links along y.
    """
    first = point.constraints[0]
    if point.kind == 'carrier':
        return joints[:, first]
    if point.kind == 'base':
        return np.broadcast_to(_base(scene.constraints[first], rack), joints[:, first].shape)
    a, b = (scene.constraints[i] for i in point.constraints)
    return closest_approach(_base(a, rack), joints[:, point.constraints[0]],
                            _base(b, rack), joints[:, point.constraints[1]])


def _base(constraint, rack):
    return constraint.base[0] + (np.array([0.0, rack, 0.0]) if constraint.steer else 0.0)


def closest_approach(a0: np.ndarray, a1: np.ndarray, b0: np.ndarray,
                     b1: np.ndarray) -> np.ndarray:
    """
    Return the midpoint of the common perpendicular of lines a0-a1 and b0-b1, (n, 3).

    The lines pass through a0 and a1, b0 and b1 ((3,) or (n, 3) mm). Parallel lines have no
    such point (NaN).
    """
    u, v, w = a1 - a0, b1 - b0, a0 - b0
    uu, uv, vv = (u * u).sum(-1), (u * v).sum(-1), (v * v).sum(-1)
    uw, vw = (u * w).sum(-1), (v * w).sum(-1)
    det = uu * vv - uv * uv
    with np.errstate(divide='ignore', invalid='ignore'):
        s = np.where(det > 1e-12 * uu * vv, (uv * vw - vv * uw) / det, np.nan)
        t = np.where(det > 1e-12 * uu * vv, (uu * vw - uv * uw) / det, np.nan)
    return 0.5 * (a0 + s[..., None] * u + b0 + t[..., None] * v)


def geometric_kingpin(scene: Scene, joints: np.ndarray, center: np.ndarray,
                      patch: np.ndarray, rack: float = 0.0) -> GeometricKingpin:
    """
    Return the geometric kingpin's alignment set at n positions.

    joints (n, m, 3): carrier joints in constraint order; center (n, 3): wheel centres;
    patch (n, 3): contact patches (NaN without a wheel radius). All mm, vehicle frame. The
    ground is the horizontal plane through each patch. Scenes without a kingpin give NaN.
    """
    joints, center = np.asarray(joints, dtype=float), np.atleast_2d(center)
    points = kingpin_points(scene)
    if points is None:
        nan = np.full(len(center), np.nan)
        nan3 = np.full_like(center, np.nan)
        return GeometricKingpin(nan3, nan3, nan3, nan, nan, nan, nan, nan)
    upper, lower = (point_positions(scene, p, joints, rack) for p in points)
    axis = upper - lower
    axis = axis * (np.sign(axis[:, 2:3]) / np.linalg.norm(axis, axis=1, keepdims=True))
    side = scene.side_sign
    at_ground = ground_point(lower, axis, patch[:, 2])
    at_centre = ground_point(lower, axis, center[:, 2])
    return GeometricKingpin(
        upper=upper, lower=lower, axis=axis, caster=np.arctan2(-axis[:, 0], axis[:, 2]),
        kingpin_inclination=np.arctan2(-side * axis[:, 1], axis[:, 2]),
        scrub_radius=side * (patch[:, 1] - at_ground[:, 1]),
        mechanical_trail=at_ground[:, 0] - patch[:, 0],
        offset_wheel_centre=side * (center[:, 1] - at_centre[:, 1]))
