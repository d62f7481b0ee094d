"""The fast variant: Newton on the carrier pose, LU solves, tangent predictor, batched sweeps.

Unknowns: the wheel-centre x, y and a rotation increment omega (5 in all; Z_M is imposed).
The carrier is rigid by construction, so the paper's eq. 1 and eqs. 5-7 drop out and the
system is the 5 guidance equations of mechanism.py. It converges to the same poses as the
paper's method (same equations on the same mechanism), in fewer and cheaper iterations.
"""

import numpy as np

from .geometry import exp_so3
from .mechanism import linearize

FREE = [0, 1, 3, 4, 5]   # Jacobian columns of the unknowns; column 2 is dZ_M (travel)


def correct(mech, travel, center, rotation, tol, max_iter, rack=0.0):
    """Newton iterations from (center, rotation) to the pose at travel and rack (mm).

    Stops when every guidance equation holds to tol (mm, a length). Returns (center,
    rotation, iterations, converged, jacobian at the returned pose): the Jacobian serves
    the next tangent and the condition number without another linearization.
    """
    center = np.array(center, dtype=float)
    center[2] = mech.design_center[2] + travel
    for iteration in range(max_iter + 1):
        f, jac = linearize(mech, center, rotation, rack)
        worst = np.abs(f).max()
        if worst <= tol:
            return center, rotation, iteration, True, jac
        if iteration == max_iter or not np.isfinite(worst):
            break
        try:
            dx = np.linalg.solve(jac[:, FREE], -f)
        except np.linalg.LinAlgError:
            break
        center[:2] += dx[:2]
        rotation = exp_so3(dx[2:]) @ rotation
    return center, rotation, iteration, False, None


def slope_of(jac):
    """d(center)/d(travel) (..., 3) and d(omega)/d(travel) (..., 3) from the Jacobian at a
    solution, by the implicit function theorem: J_free dx = -J_travel. Batched."""
    dx = np.linalg.solve(jac[..., FREE], -jac[..., 2:3])[..., 0]
    d_center = np.concatenate((dx[..., :2], np.ones(dx.shape[:-1] + (1,))), axis=-1)
    return d_center, dx[..., 2:]


def tangent(mech, center, rotation, rack=0.0):
    """slope_of() at the pose (center, rotation)."""
    return slope_of(linearize(mech, center, rotation, rack)[1])


def rack_slope_of(jac, rack_column):
    """d(center)/d(rack) (..., 3) and d(omega)/d(rack) (..., 3) at fixed travel, from the
    Jacobian and the rack column (mechanism.rack_derivative) at a solution."""
    dx = np.linalg.solve(jac[..., FREE], -rack_column[..., None])[..., 0]
    d_center = np.concatenate((dx[..., :2], np.zeros(dx.shape[:-1] + (1,))), axis=-1)
    return d_center, dx[..., 2:]


def predict(center, rotation, slope, travel_step):
    """First-order (tangent) guess of the pose travel_step (mm) further on. Batched: travel_step
    (n,) with center (n, 3), rotation (n, 3, 3) and slope arrays (n, 3)."""
    d_center, d_omega = slope
    h = np.asarray(travel_step, dtype=float)[..., None]
    return center + d_center * h, exp_so3(d_omega * h) @ rotation


def correct_batch(mech, travel, center, rotation, tol, max_iter, rack=0.0):
    """correct() for n poses at once: travel (n,), center (n, 3), rotation (n, 3, 3).

    Returns (center, rotation, iterations (n,), converged (n,)); poses that converged are
    frozen while the others iterate.
    """
    center = np.array(center, dtype=float)
    rotation = np.array(rotation, dtype=float)
    center[:, 2] = mech.design_center[2] + travel
    iterations = np.zeros(len(travel), dtype=int)
    converged = np.zeros(len(travel), dtype=bool)
    idx = np.arange(len(travel))
    for iteration in range(max_iter + 1):
        f, jac = linearize(mech, center[idx], rotation[idx], rack)
        worst = np.abs(f).max(axis=1)
        done = worst <= tol
        converged[idx[done]] = True
        iterations[idx[done]] = iteration
        keep = ~done & np.isfinite(worst)
        idx, f, jac = idx[keep], f[keep], jac[keep]
        if not len(idx) or iteration == max_iter:
            break
        try:
            dx = np.linalg.solve(jac[:, :, FREE], -f[..., None])[..., 0]
        except np.linalg.LinAlgError:
            break
        center[idx, :2] += dx[:, :2]
        rotation[idx] = exp_so3(dx[:, 2:]) @ rotation[idx]
    iterations[~converged] = max_iter
    return center, rotation, iterations, converged
