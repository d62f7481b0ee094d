# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Pseudo-arclength continuation: following the solution curve through its travel limits.

Near a turning point (fold) of the travel, the carrier moves like sqrt(limit - travel) and
continuation in travel stalls short of the limit. Parametrized by arclength along the
solution curve in (pose, travel) space, the curve is regular through the fold: this module
walks it to reach travels close to the limit, and locates the limit itself (where d travel /
d arclength changes sign) by the maximum of a cubic Hermite fit between two curve points.

Curve coordinates, all in mm: wheel-centre x, y; rotation increment times the mechanism's
lever (so a unit step moves the carrier by about 1 mm); travel. The arclength steps are for
a road-vehicle corner and scale with the mechanism (the scale argument of walk). A singular
system is an answer (Status.SINGULAR), never an exception.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .mechanism import is_singular, linearize
from ..base.geometry import exp_so3
from ..base.status import Status

if TYPE_CHECKING:
    from .mechanism import Mechanism

# A point of the solution curve: (center (3,) mm, rotation (3, 3) relative to design, travel mm).
CurvePoint = tuple[np.ndarray, np.ndarray, float]
# Arclength steps (mm along the curve) for a scale of 1: the first, the longest, the one below
# which a turn of the travel is located (the limit's bracket), the one below which the curve
# is lost.
START_STEP, MAX_STEP, RESOLUTION, SMALLEST_STEP = 0.05, 2.0, 0.02, 1e-6


def solve(a: np.ndarray, b: np.ndarray) -> np.ndarray | None:
    """Return x with a x = b, or None if LAPACK finds a singular or x is not finite."""
    try:
        x = np.linalg.solve(a, b)
    except np.linalg.LinAlgError:
        return None
    return x if np.isfinite(x).all() else None


def curve_system(mech: Mechanism, center: np.ndarray, rotation: np.ndarray,
                 rack: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Return the residuals (5,) and the (5, 6) Jacobian in curve coordinates at a pose."""
    f, jac = linearize(mech, center, rotation, rack)
    return f, np.column_stack((jac[:, :2], jac[:, 3:6] / mech.lever, jac[:, 2]))


def curve_tangent(jac: np.ndarray, previous: np.ndarray) -> np.ndarray | None:
    """Return the unit null vector of jac (5, 6), oriented along previous (6,); None if none."""
    t = solve(np.vstack((jac, previous)), np.eye(6)[5])
    return None if t is None else t / np.linalg.norm(t)


def move(mech: Mechanism, center: np.ndarray, rotation: np.ndarray, travel: float,
         dy: np.ndarray) -> CurvePoint:
    """Return the pose and travel moved by a curve-coordinate increment dy (6,)."""
    center = center.copy()
    center[:2] += dy[:2]
    travel = travel + dy[5]
    center[2] = mech.design_center[2] + travel
    return center, exp_so3(dy[2:5] / mech.lever) @ rotation, travel


def arc_step(mech: Mechanism, point: CurvePoint, tangent: np.ndarray, dsigma: float, tol: float,
             max_iter: int, rack: float = 0.0) -> tuple[CurvePoint, np.ndarray] | None:
    """
    Take one predictor-corrector step of length dsigma along tangent from point.

    point = (center, rotation, travel). The corrector stays on the hyperplane square to the
    tangent through the predicted point. Returns (point, jacobian) or None if it fails.
    """
    center, rotation, travel = move(mech, *point, dsigma * tangent)
    offset = 0.0   # tangent . (y - y_predicted), kept at 0
    for _ in range(max_iter + 1):
        f, jac = curve_system(mech, center, rotation, rack)
        if np.abs(f).max() <= tol and abs(offset) <= tol:
            return (center, rotation, travel), jac
        dy = solve(np.vstack((jac, tangent)), -np.append(f, offset))
        if dy is None:
            return None
        offset += tangent @ dy
        center, rotation, travel = move(mech, center, rotation, travel, dy)
    return None


def walk(mech: Mechanism, center: np.ndarray, rotation: np.ndarray, travel: float,
         target: float, tol: float, max_iter: int, rack: float = 0.0, scale: float = 1.0,
         max_steps: int = 2000) -> tuple[Status, tuple[CurvePoint, float] | float]:
    """
    Follow the solution curve from the pose at travel towards target (mm), rack fixed.

    The arclength steps are START_STEP ... RESOLUTION times scale. Returns (Status.OK,
    ((center, rotation, travel), step)) with the curve point just beyond target and the
    arclength of the last step (the pose at target lies on the curve within that length,
    for a final correction); (Status.OUT_OF_REACH, travel_limit) if the travel turns back
    first; (Status.CURVE_LOST, travel) if the curve cannot be followed; (Status.SINGULAR,
    travel) if the curve has no tangent where it starts (the Jacobian is rank-deficient).
    """
    direction = math.copysign(1.0, target - travel)
    point = (center, rotation, travel)
    _, jac = curve_system(mech, center, rotation, rack)
    # A rank-deficient Jacobian has no tangent, though LAPACK may answer (a consistent system
    # by chance): checked once here, at the cost of an SVD. On the way a singular point makes
    # the corrector fail, and the step is halved.
    bordered = np.vstack((jac, np.eye(6)[5] * direction))
    tangent = None if is_singular(bordered) else curve_tangent(jac, bordered[5])
    if tangent is None:
        return Status.SINGULAR, travel
    step = START_STEP * scale
    for _ in range(max_steps):
        found = arc_step(mech, point, tangent, step, tol, max_iter, rack)
        new_tangent = None if found is None else curve_tangent(found[1], tangent)
        if new_tangent is None or new_tangent @ tangent < 0.9:
            step /= 2                         # failed, or too sharp a turn: it skipped ahead
            if step < SMALLEST_STEP * scale:
                return Status.CURVE_LOST, point[2]
            continue
        new_point = found[0]
        if new_tangent[5] * direction <= 0:   # travel turned back: the limit is in between
            if step > RESOLUTION * scale:
                step /= 4
                continue
            return Status.OUT_OF_REACH, hermite_peak(point[2], new_point[2], tangent[5],
                                                     new_tangent[5], step)
        if (new_point[2] - target) * direction >= 0:
            return Status.OK, (new_point, step)
        point, tangent = new_point, new_tangent
        step = min(2 * step, MAX_STEP * scale)
    return Status.CURVE_LOST, point[2]


def hermite_peak(s0: float, s1: float, slope0: float, slope1: float, length: float) -> float:
    """
    Return the extreme value of the cubic Hermite s(sigma) on [0, length].

    The cubic has s(0) = s0, s(length) = s1 and ds/dsigma = slope0, slope1 at the ends (the
    slopes have opposite signs).
    """
    def cubic(u):
        h00, h10 = 2 * u**3 - 3 * u**2 + 1, u**3 - 2 * u**2 + u
        h01, h11 = -2 * u**3 + 3 * u**2, u**3 - u**2
        return h00 * s0 + h10 * length * slope0 + h01 * s1 + h11 * length * slope1
    u = np.linspace(0.0, 1.0, 2001)
    values = cubic(u)
    return float(values.max() if slope0 > 0 else values.min())
