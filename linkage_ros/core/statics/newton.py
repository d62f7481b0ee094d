# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Newton on the Lagrange (KKT) system of a corner's statics, from the kinematic pose.

    [ H   J^T ] [ dq     ]     [ grad V - Q ]
    [ J    0  ] [ lambda ] = - [ c          ]

H the Hessian of L = V - work + lambda . c (exact: system.py), J = dc/dq. The step is taken
in the bodies' coordinates (system.moved). A load too large for one Newton solve is applied
in increments (halved on failure), each solve continuing from the last. newton() runs the
compiled kernel (kernel.py, on the System packed by pack.py); newton_python() is the same in
numpy, kept as its check.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from . import kernel
from .system import assemble, moved, Pose, System

TOL_STEP = 1e-11       # mm (rotations times the lever): a step this small has converged
MAX_ITER = 30          # Newton iterations per load increment
MAX_HALVINGS = 6       # a load is split into at most 2**6 increments


class Equilibrium(NamedTuple):
    """A solved equilibrium: pose, multipliers, the factorised-system inputs, convergence."""

    ok: bool
    pose: Pose
    multipliers: np.ndarray
    hess: np.ndarray
    rows: np.ndarray
    residual: float        # N: largest unbalanced generalized force (moments / lever)
    iterations: int


def kkt(hess: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """Return the KKT matrix [[H, J^T], [J, 0]] (n + m, n + m)."""
    n, m = hess.shape[0], rows.shape[0]
    out = np.zeros((n + m, n + m))
    out[:n, :n], out[:n, n:], out[n:, :n] = hess, rows.T, rows
    return out


def imbalance(system: System, grad: np.ndarray, lever: float) -> float:
    """Return the largest unbalanced generalized force (N), rotation rows divided by lever."""
    scaled = grad.copy()
    for body in system.bodies:
        if body.kind in ('carrier', 'arm'):
            scaled[body.start + 3:body.start + 6] /= lever
        elif body.kind == 'hinge':
            scaled[body.start] /= lever
    return float(np.max(np.abs(scaled))) if scaled.size else 0.0


def newton(system: System, model: kernel.Model, pose: Pose, multipliers: np.ndarray,
           force: np.ndarray, moment: np.ndarray, lever: float) -> Equilibrium:
    """Solve one equilibrium by Newton (compiled) from pose and multipliers."""
    c, r, lam = pose.c.copy(), pose.r.copy(), np.array(multipliers, dtype=float)
    hess, rows = np.empty((model.n, model.n)), np.empty((model.m, model.n))
    ok, iterations, residual = kernel.newton(
        tuple(model), c, r, lam, np.asarray(force, dtype=float),
        np.asarray(moment, dtype=float), lever, TOL_STEP, MAX_ITER, hess, rows)
    return Equilibrium(bool(ok), Pose(c, r), lam, hess, rows,
                       residual if math.isfinite(residual) else math.inf, int(iterations))


def newton_python(system: System, pose: Pose, multipliers: np.ndarray, force: np.ndarray,
                  moment: np.ndarray, lever: float) -> Equilibrium:
    """Solve one equilibrium by Newton (numpy) from pose and multipliers; ok False if not."""
    n, last = system.size, 0.0   # no step before the first
    for iteration in range(1, MAX_ITER + 1):
        grad, hess, values, rows, _ = assemble(system, pose, multipliers, force, moment)
        rhs = -np.concatenate((grad - rows.T @ multipliers, values))
        try:
            sol = np.linalg.solve(kkt(hess, rows), rhs)
        except np.linalg.LinAlgError:
            break
        if not np.isfinite(sol).all():
            break
        step, multipliers = sol[:n], sol[n:]
        pose = moved(system, pose, step)
        size = _step_size(system, step, lever)
        if kernel.converged(size, last, TOL_STEP * max(1.0, lever)):
            grad, hess, values, rows, _ = assemble(system, pose, multipliers, force, moment)
            return Equilibrium(True, pose, multipliers, hess, rows,
                               imbalance(system, grad, lever), iteration)
        if not size < 1e3 * lever:   # diverging (or NaN)
            break
        last = size
    grad, hess, values, rows, _ = assemble(system, pose, multipliers, force, moment)
    residual = imbalance(system, grad, lever)
    return Equilibrium(False, pose, multipliers, hess, rows,
                       residual if math.isfinite(residual) else math.inf, MAX_ITER)


def _step_size(system, step, lever):
    scaled = step.copy()
    for body in system.bodies:
        if body.kind in ('carrier', 'arm'):
            scaled[body.start + 3:body.start + 6] *= lever
        elif body.kind == 'hinge':
            scaled[body.start] *= lever
    return float(np.max(np.abs(scaled))) if scaled.size else 0.0


def loaded(system: System, model: kernel.Model | None, start: Equilibrium, force: np.ndarray,
           moment: np.ndarray, lever: float) -> Equilibrium:
    """
    Solve the equilibrium under force (N) and moment (N mm) from the zero-load one.

    In one Newton solve if it converges, else in 2, 4, ... 2**MAX_HALVINGS equal increments.
    model None: by newton_python.
    """
    last = start
    for halvings in range(MAX_HALVINGS + 1):
        parts = 2 ** halvings
        here = start
        for k in range(1, parts + 1):
            args = (here.pose, here.multipliers, force * k / parts, moment * k / parts, lever)
            here = (newton_python(system, *args) if model is None
                    else newton(system, model, *args))
            if not here.ok:
                last = here
                break
        else:
            return here
    return last
