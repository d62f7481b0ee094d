# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The fast variant: Newton on the carrier pose, tangent predictor, branch-checked steps.

Unknowns: the wheel-centre x, y and a rotation increment omega (5 in all; Z_M is imposed).
The carrier is rigid by construction, so the paper's eq. 1 and eqs. 5-7 drop out and the
system is the 5 guidance equations of mechanism.py. It converges to the same poses as the
paper's method (same equations on the same mechanism), in fewer and cheaper iterations.

The iterations run compiled (kernel.py); these are their Python faces, one pose each, plus
the implicit-function-theorem slopes of a batch of solved poses (alignment.py).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from . import kernel
from .mechanism import is_singular, linearize

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from .mechanism import Mechanism

FREE = list(kernel.FREE)   # Jacobian columns of the unknowns; column 2 is dZ_M (travel)


def correct(mech: Mechanism, travel: float, center: ArrayLike, rotation: ArrayLike,
            tol: float, max_iter: int,
            rack: float = 0.0) -> tuple[np.ndarray, np.ndarray, int, bool, np.ndarray | None]:
    """
    Run Newton iterations from (center, rotation) to the pose at travel and rack (mm).

    Stops when every guidance equation holds to tol (mm, a length). Returns (center,
    rotation, iterations, converged, jacobian at the returned pose): the Jacobian serves
    the next tangent and the condition number without another linearization.
    """
    center = np.array(center, dtype=float)
    rotation = np.array(rotation, dtype=float)
    jac = np.empty((kernel.N_EQUATIONS, 6))
    iterations, converged, _ = kernel.correct(mech.equations, mech.design_center[2],
                                              float(travel), float(rack), center, rotation,
                                              float(tol), int(max_iter), jac)
    return center, rotation, iterations, converged, jac if converged else None


def predict(mech: Mechanism, center: np.ndarray, rotation: np.ndarray, jac: np.ndarray,
            travel_step: float, rack_step: float = 0.0,
            rack: float = 0.0) -> tuple[np.ndarray, np.ndarray] | None:
    """
    Guess to first order (tangent) the pose travel_step and rack_step (mm) further on.

    From the solved pose (center, rotation) at rack (mm) whose Jacobian is jac. Returns the
    guess (center, rotation), or None if the Jacobian is singular.
    """
    guess_center, guess_rotation = np.empty(3), np.empty((3, 3))
    if not kernel.predict(mech.equations, center, rotation, jac, float(rack),
                          float(travel_step), float(rack_step), guess_center, guess_rotation):
        return None
    return guess_center, guess_rotation


def solve_free(jac: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """
    Solve J_free x = rhs for a batch: jac (..., 5, 6), rhs (..., 5) -> x (..., 5).

    NaN where J_free is singular (mechanism.is_singular): numerics never raise, and a singular
    position has no slope.
    """
    a, b = np.asarray(jac, dtype=float)[..., FREE], np.asarray(rhs, dtype=float)
    a, b = np.broadcast_arrays(a, b[..., None])
    singular = is_singular(a)
    x = np.linalg.solve(np.where(singular[..., None, None], np.eye(5), a), b)[..., 0]
    x[singular] = np.nan
    return x


def slope_of(jac: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """
    Return d(center)/d(travel) (..., 3) and d(omega)/d(travel) (..., 3) at a solution.

    From the Jacobian there, by the implicit function theorem: J_free dx = -J_travel.
    Batched; NaN at a singular position.
    """
    dx = solve_free(jac, -jac[..., 2])
    d_center = np.concatenate((dx[..., :2], np.ones(dx.shape[:-1] + (1,))), axis=-1)
    return d_center, dx[..., 2:]


def tangent(mech: Mechanism, center: ArrayLike, rotation: ArrayLike,
            rack: ArrayLike = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Return slope_of() at the pose (center, rotation)."""
    return slope_of(linearize(mech, center, rotation, rack)[1])


def rack_slope_of(jac: np.ndarray, rack_column: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """
    Return d(center)/d(rack) (..., 3) and d(omega)/d(rack) (..., 3) at fixed travel.

    From the Jacobian and the rack column (mechanism.rack_derivative) at a solution. NaN at
    a singular position.
    """
    dx = solve_free(jac, -rack_column)
    d_center = np.concatenate((dx[..., :2], np.zeros(dx.shape[:-1] + (1,))), axis=-1)
    return d_center, dx[..., 2:]
