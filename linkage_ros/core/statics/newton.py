# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Newton on the Lagrange (KKT) system of a corner's statics, compiled, with the exact matrix.

    [ A   J^T ] [ dq     ]     [ grad L - M ]
    [ J    0  ] [ lambda ] = - [ c          ]

A the derivative of the residual grad L - M at the pose (kernel.assemble, exact: with the
load's own stiffness and the moment fixed in space), J = dc/dq; the step is taken in the
bodies' coordinates (kernel.move), and the system is solved reduced and along its structure
(kkt.py). So Newton converges quadratically from anywhere near an equilibrium, a loaded one
too (test_statics_newton). A load too large for one Newton solve is applied in increments
(loaded: halved on failure), each solve continuing from the last. Nothing here raises: a
solve returns ok False, and its last finite residual (N; inf if none).

numba's disk cache follows each file alone: kernel.py and kkt.py are compiled in here, their
digests below (test_statics_kernel says the values to set after an edit there).
"""

from typing import NamedTuple

from numba import njit
import numpy as np

from . import kernel, kkt

KERNEL_DIGEST = 'e5ff0fb8efa959ef2e3b5f2009faf1931c9ded81016bac2d633c81d6a85e84f0'
KKT_DIGEST = 'd3d12e75f6d1f2b5c080b7cec2ca788eb028cbb9006dbf7774ffd86a948fcd9b'
TOL_STEP = 1e-11       # mm (rotations times the lever): a step this small has converged
MAX_ITER = 30          # Newton iterations per load increment
MAX_HALVINGS = 6       # a load is split into at most 2**6 increments
# a Newton step predicted (quadratic convergence) below this fraction of the tolerance is not
# taken (converged()): it would move the pose by round-off
PREDICTED = 1e-3
jit = njit(cache=True, nogil=True, error_model='numpy')


class Work(NamedTuple):
    """What a Newton solve writes: at its end, grad, hess (symmetric) and rows of the pose."""

    grad: np.ndarray       # (n,)
    hess: np.ndarray       # (n, n)
    values: np.ndarray     # (m,)
    rows: np.ndarray       # (m, n)
    a: np.ndarray          # (K, K) the reduced KKT matrix, factorised
    piv: np.ndarray        # (2 K,) int64
    b: np.ndarray          # (K,)
    rhs: np.ndarray        # (n + m,)
    sol: np.ndarray        # (n + m,)
    dense: np.ndarray      # kkt.dense_bounds(K)
    steps: np.ndarray      # (MAX_ITER,) the scaled step of each iteration (NaN: not taken)
    scratch: kernel.Scratch


@jit
def work(model):
    """Return a Work for the Model's sizes."""
    n, m, size = model.n, model.m, len(model.perm)
    return Work(np.empty(n), np.empty((n, n)), np.empty(m), np.empty((m, n)),
                np.empty((size, size)), np.empty(2 * size, dtype=np.int64), np.empty(size),
                np.empty(n + m), np.empty(n + m), kkt.dense_bounds(size),
                np.full(MAX_ITER, np.nan), kernel.scratch())


@jit
def converged(size, last, tol):
    """
    Tell whether Newton has converged: its step (scaled) is below tol, or the next one will be.

    Newton converges quadratically: the next step is about size^3 / last^2 (last: the step
    before). Below PREDICTED * tol it is round-off: the step after it is not taken.
    """
    return size < tol or size * size * size < PREDICTED * tol * last * last


@jit
def factorise(hess, rows, perm, bounds, a, piv, dense):
    """
    Factorise the KKT matrix of hess and rows into a and piv; return (kkt mode, bounds used).

    Along bounds (the Model's), or, should a cluster be singular, densely (dense).
    """
    kkt.gather(hess, rows, perm, hess.shape[0], a)
    mode = kkt.factor(a, piv, bounds)
    if mode != kkt.FAILED:
        return mode, bounds
    kkt.gather(hess, rows, perm, hess.shape[0], a)
    return kkt.factor(a, piv, dense), dense


@jit
def newton(model, c, r, lam, inputs, max_iter, w):
    """
    Solve the equilibrium from (c, r, lam) in place; return (ok, iterations, residual N).

    At the end w.hess (the symmetric Hessian) and w.rows hold the pose's, w.steps the scaled
    step of each iteration. A step that is not finite, or would move a point farther than
    a thousand levers, is not taken: the residual is the last finite pose's.
    """
    n = model.n
    lever = model.consts[kernel.LEVER]
    tol = TOL_STEP * max(1.0, lever)
    w.steps[:] = np.nan
    last = 0.0   # no step before the first
    for iteration in range(1, max_iter + 1):
        kernel.assemble(model, c, r, lam, inputs, True, w.grad, w.hess, w.values, w.rows,
                        w.scratch)
        for i in range(n):
            total = w.grad[i]
            for k in range(model.m):
                total -= w.rows[k, i] * lam[k]
            w.rhs[i] = -total
        for k in range(model.m):
            w.rhs[n + k] = -w.values[k]
        mode, bounds = factorise(w.hess, w.rows, model.perm, model.bounds, w.a, w.piv,
                                 w.dense)
        if mode == kkt.FAILED:
            break
        kkt.solve_full(w.a, w.piv, bounds, mode, model.perm, w.hess, w.rows, w.rhs, w.sol,
                       w.b)
        step = w.sol[:n]
        size = kernel.scaled_max(model.b_kind, model.b_start, step, lever, False)
        if iteration <= len(w.steps):
            w.steps[iteration - 1] = size
        if not size < 1e3 * lever or not np.all(np.isfinite(w.sol)):   # diverging, or NaN
            break
        lam[:] = w.sol[n:]
        kernel.move(model.b_kind, model.b_start, model.b_axis, c, r, step)
        if converged(size, last, tol):
            kernel.assemble(model, c, r, lam, inputs, False, w.grad, w.hess, w.values,
                            w.rows, w.scratch)
            return True, iteration, kernel.scaled_max(model.b_kind, model.b_start, w.grad, lever,
                                                      True)
        last = size
    kernel.assemble(model, c, r, lam, inputs, False, w.grad, w.hess, w.values, w.rows,
                    w.scratch)
    residual = kernel.scaled_max(model.b_kind, model.b_start, w.grad, lever, True)
    return False, max_iter, residual if np.isfinite(residual) else np.inf


@jit
def loaded(model, c, r, lam, inputs, w):
    """
    Solve the equilibrium under inputs' load from the one in (c, r, lam), in place.

    In one Newton solve if it converges, else in 2, 4, ... 2**MAX_HALVINGS equal increments
    of the load from the start. Returns (ok, iterations, residual N) of the last solve.
    """
    c0, r0, lam0 = c.copy(), r.copy(), lam.copy()
    ok, iterations, residual = False, 0, np.inf
    for halvings in range(MAX_HALVINGS + 1):
        parts = 2 ** halvings
        c[:], r[:], lam[:] = c0, r0, lam0
        for k in range(1, parts + 1):
            part = kernel.Inputs(inputs.z, inputs.rack, inputs.x_load,
                                 inputs.force * (k / parts), inputs.moment * (k / parts))
            ok, iterations, residual = newton(model, c, r, lam, part, MAX_ITER, w)
            if not ok:
                break
        if ok:
            return ok, iterations, residual
    return ok, iterations, residual
