"""
Pseudo-arclength continuation: following the solution curve through its travel limits.

Near a turning point (fold) of the travel, the carrier moves like sqrt(limit - travel) and
continuation in travel stalls short of the limit. Parametrized by arclength along the
solution curve in (pose, travel) space, the curve is regular through the fold: this module
walks it to reach travels close to the limit, and locates the limit itself (where d travel /
d arclength changes sign) by the maximum of a cubic Hermite fit between two curve points.

Curve coordinates, all in mm: wheel-centre x, y; rotation increment times the mechanism's
lever (so a unit step moves the carrier by about 1 mm); travel.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .geometry import exp_so3
from .mechanism import linearize

if TYPE_CHECKING:
    from .mechanism import Mechanism

# A point of the solution curve: (center (3,) mm, rotation (3, 3) relative to design, travel mm).
CurvePoint = tuple[np.ndarray, np.ndarray, float]


def curve_system(mech: Mechanism, center: np.ndarray, rotation: np.ndarray,
                 rack: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Return the residuals (5,) and the (5, 6) Jacobian in curve coordinates at a pose."""
    f, jac = linearize(mech, center, rotation, rack)
    return f, np.column_stack((jac[:, :2], jac[:, 3:6] / mech.lever, jac[:, 2]))


def curve_tangent(jac: np.ndarray, previous: np.ndarray) -> np.ndarray:
    """Return the unit null vector of jac (5, 6), oriented along previous (6,)."""
    t = np.linalg.solve(np.vstack((jac, previous)), np.eye(6)[5])
    return t / np.linalg.norm(t)


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
        dy = np.linalg.solve(np.vstack((jac, tangent)), -np.append(f, offset))
        if not np.all(np.isfinite(dy)):
            return None
        offset += tangent @ dy
        center, rotation, travel = move(mech, center, rotation, travel, dy)
    return None


def walk(mech: Mechanism, center: np.ndarray, rotation: np.ndarray, travel: float,
         target: float, tol: float, max_iter: int, rack: float = 0.0, start_step: float = 0.05,
         max_step: float = 2.0, resolution: float = 0.02,
         max_steps: int = 2000) -> tuple[str, tuple[CurvePoint, float] | float]:
    """
    Follow the solution curve from the pose at travel towards target (mm), rack fixed.

    Returns ('reached', ((center, rotation, travel), step)) with the curve point just beyond
    target and the arclength of the last step (the pose at target lies on the curve within
    that length, for a final correction), ('limit', travel_limit) if the
    travel turns back first, or ('stalled', travel) if the curve cannot be followed.
    """
    direction = math.copysign(1.0, target - travel)
    point = (center, rotation, travel)
    _, jac = curve_system(mech, center, rotation, rack)
    tangent = curve_tangent(jac, np.eye(6)[5] * direction)
    step = start_step
    for _ in range(max_steps):
        found = arc_step(mech, point, tangent, step, tol, max_iter, rack)
        if found is None:
            step /= 2
            if step < 1e-6:
                return 'stalled', point[2]
            continue
        new_point, jac = found
        new_tangent = curve_tangent(jac, tangent)
        if new_tangent @ tangent < 0.9:       # too sharp a turn: the step skipped ahead
            step /= 2
            continue
        if new_tangent[5] * direction <= 0:   # travel turned back: the limit is in between
            if step > resolution:
                step /= 4
                continue
            return 'limit', hermite_peak(point[2], new_point[2], tangent[5], new_tangent[5],
                                         step)
        if (new_point[2] - target) * direction >= 0:
            return 'reached', (new_point, step)
        point, tangent = new_point, new_tangent
        step = min(2 * step, max_step)
    return 'stalled', point[2]


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
