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
"""

from typing import NamedTuple

import numpy as np

from . import kernel, kkt
from ..base.compiled import bare, jitable

TOL_STEP = 1e-11       # mm (rotations times the lever): a step this small has converged
MAX_ITER = 30          # Newton iterations per load increment
MAX_HALVINGS = 6       # a load is split into at most 2**6 increments
# a Newton step predicted (quadratic convergence) below this fraction of the tolerance is not
# taken (converged()): it would move the pose by less than a tenth of the stop rule's
# 1e-11 mm per mm of lever (1e-12 rad), far inside the answers' 1e-9 deg and 1e-8 mm (the
# test's reference, statics_reference.py, keeps 1e-3). A command along a 1 kHz sine then
# takes one exact step after its chord step, not two in one of five (doc/benchmarks.md)
PREDICTED = 1e-1
POSE_ONLY = -1   # newton's finish: nothing assembled at the solution (its residual NaN)


class Work(NamedTuple):
    """What a Newton solve writes: at its end, grad, hess (symmetric) and rows of the pose."""

    grad: np.ndarray       # (n,)
    hess: np.ndarray       # (n, n)
    values: np.ndarray     # (m,)
    rows: np.ndarray       # (m, n)
    a: np.ndarray          # (K, K) the reduced KKT matrix, factorised
    piv: np.ndarray        # (2 K,) int64
    column: np.ndarray     # (n,) H[:, 2] of the factorised matrix (kkt.solve_full)
    row: np.ndarray        # (n,) H[2, :]
    jcol: np.ndarray       # (m,) J[:, 2]
    b: np.ndarray          # (K,)
    spare: np.ndarray      # (K,) kkt.solve's
    rhs: np.ndarray        # (n + m,)
    sol: np.ndarray        # (n + m,)
    dense: np.ndarray      # kkt.dense_bounds(K)
    steps: np.ndarray      # (MAX_ITER,) the scaled step of each iteration (NaN: not taken)
    info: np.ndarray       # (2,) int64: the last factorisation's kkt mode, 1 if dense
    scratch: kernel.Scratch


class Factor(NamedTuple):
    """
    A kept factorisation of the KKT system (views into a state: command.py).

    head (3,): valid (1.0), kkt mode, dense (1.0); a (K, K) and piv (2 K,) as kkt.factor
    wrote them; column, row (n,) and rows (m,): kkt.solve_full's H[:, 2], H[2, :], J[:, 2].
    """

    head: np.ndarray
    a: np.ndarray
    piv: np.ndarray
    column: np.ndarray
    row: np.ndarray
    rows: np.ndarray


@jitable
def work_size(model):
    """Return the sizes (floats, ints) of a Work's two flat arrays (work_of)."""
    n, m, size = model.n, model.m, len(model.perm)
    floats = (n + n * n + m + m * n + size * size + 2 * n + m + 2 * size + 2 * (n + m)
              + MAX_ITER + kernel.scratch_size(len(model.t_kind), len(model.h_slot)))
    return floats, 2 * size + 3 + 2


@jitable(inline='always')
def work_of(model, floats, ints):
    """
    Return the Work whose arrays are views into floats and ints (work_size's).

    A Statics keeps the two arrays, so a command allocates nothing; the views cost no
    reference counts in the kernels compiled without them.
    """
    n, m, size = model.n, model.m, len(model.perm)
    o = 0
    grad = floats[o:o + n]
    o += n
    hess = floats[o:o + n * n].reshape((n, n))
    o += n * n
    values = floats[o:o + m]
    o += m
    rows = floats[o:o + m * n].reshape((m, n))
    o += m * n
    a = floats[o:o + size * size].reshape((size, size))
    o += size * size
    column, row = floats[o:o + n], floats[o + n:o + 2 * n]
    jcol = floats[o + 2 * n:o + 2 * n + m]
    o += 2 * n + m
    b, spare = floats[o:o + size], floats[o + size:o + 2 * size]
    o += 2 * size
    rhs, sol = floats[o:o + n + m], floats[o + n + m:o + 2 * (n + m)]
    o += 2 * (n + m)
    steps = floats[o:o + MAX_ITER]
    o += MAX_ITER
    piv, dense = ints[:2 * size], ints[2 * size:2 * size + 3]
    info = ints[2 * size + 3:2 * size + 5]
    kkt.write_dense_bounds(dense, size)
    return Work(grad, hess, values, rows, a, piv, column, row, jcol, b, spare, rhs, sol,
                dense, steps, info, kernel.scratch_of(model, floats[o:]))


def work(model):
    """Return a Work for the Model's sizes, its own arrays (Python's: work_of)."""
    floats, ints = work_size(model)
    return work_of(model, np.empty(floats), np.zeros(ints, dtype=np.int64))


@bare
def converged(size, last, tol):
    """
    Tell whether Newton has converged: its step (scaled) is below tol, or the next one will be.

    Newton converges quadratically: the next step is about size^3 / last^2 (last: the step
    before). Below PREDICTED * tol it is round-off: the step after it is not taken.
    """
    return size < tol or size * size * size < PREDICTED * tol * last * last


@bare
def factorise(model, w):
    """
    Factorise the KKT matrix of w.hess and w.rows into w (a, piv, column, row, jcol, info).

    Along the Model's bounds, or, should a cluster be singular, densely (w.dense). Returns
    the kkt mode and whether it was dense (the bounds to solve with: w.dense, else the
    Model's).
    """
    n, hess, rows, column, row, jcol = model.n, w.hess, w.rows, w.column, w.row, w.jcol
    for i in range(n):   # (fields read into names first: numba counts a reference to a
        column[i], row[i] = hess[i, 2], hess[2, i]   # tuple's field at each read in a loop)
    for k in range(model.m):
        jcol[k] = rows[k, 2]
    kkt.gather(w.hess, w.rows, model.perm, n, w.a)
    mode = kkt.factor(w.a, w.piv, model.bounds)
    dense = mode == kkt.FAILED
    if dense:
        kkt.gather(w.hess, w.rows, model.perm, n, w.a)
        mode = kkt.factor(w.a, w.piv, w.dense)
    w.info[0], w.info[1] = mode, 1 if dense else 0
    return mode, dense


@bare
def _rhs(model, lam, w):
    """Write the Newton right-hand side -(grad - J^T lam, c) into w.rhs."""
    n, m, grad, rows, values, rhs = model.n, model.m, w.grad, w.rows, w.values, w.rhs
    for i in range(n):
        total = grad[i]
        for k in range(m):
            total -= rows[k, i] * lam[k]
        rhs[i] = -total
    for k in range(m):
        rhs[n + k] = -values[k]


@bare
def _take(model, c, r, lam, w):
    """
    Take w.sol as the step (c, r) and the new multipliers; return its scaled size, mm.

    A step that is not finite (NaN returned), or longer than a thousand levers, is not taken.
    """
    n, lever, sol = model.n, model.consts[kernel.LEVER], w.sol
    size = kernel.scaled_max(model, sol, lever, False)
    for k in range(model.m):
        if not np.isfinite(sol[n + k]):
            size = np.nan
    if not size < 1e3 * lever:
        return size
    for k in range(model.m):
        lam[k] = sol[n + k]
    kernel.move(model, c, r, sol)
    return size


@jitable(inline='always')
def over(w, factor):
    """
    Return w factorising into factor's arrays (a, column, row, jcol; the pivots stay w's).

    A solve with a kept factorisation (chord) and the Newton after it then copy nothing but
    the pivots (keep): the state's float array cannot hold them as integers.
    """
    return Work(w.grad, w.hess, w.values, w.rows, factor.a, w.piv, factor.column, factor.row,
                factor.rows, w.b, w.spare, w.rhs, w.sol, w.dense, w.steps, w.info, w.scratch)


@bare
def keep(w, factor):
    """Keep w's last factorisation in factor, whose arrays w factorised into (over(w, factor))."""
    factor.head[0], factor.head[1], factor.head[2] = 1.0, w.info[0], w.info[1]
    for k in range(len(w.piv)):
        factor.piv[k] = w.piv[k]


@bare
def chord(model, c, r, lam, inputs, factor, w):
    """
    Take one step from (c, r, lam) with a kept factorisation (a chord step); its size, mm.

    From the last command's equilibrium, with that command's matrix, this is the tangent
    prediction of the new one: the next Newton step is of second order in the change. A step
    that is not finite or longer than a thousand levers is not taken (0.0). w: over(work,
    factor), so that the Newton that follows factorises into factor's arrays: the caller
    marks factor not kept (head[0] 0) before it, keep marks it again.
    """
    kernel.assemble(model, c, r, lam, inputs, kernel.RESIDUAL, w)
    _rhs(model, lam, w)
    for k in range(len(w.piv)):
        w.piv[k] = int(factor.piv[k])
    kkt.solve_full(w, model.perm, w.dense if factor.head[2] == 1.0 else model.bounds,
                   int(factor.head[1]))
    step = _take(model, c, r, lam, w)
    return step if step < 1e3 * model.consts[kernel.LEVER] else 0.0


@bare
def newton(model, c, r, lam, inputs, max_iter, w, finish=kernel.SYMMETRIC, last=0.0):
    """
    Solve the equilibrium from (c, r, lam) in place; return (ok, iterations, residual N).

    finish: what of the solution's pose w.grad, w.hess and w.rows hold at the end
    (kernel.assemble's: SYMMETRIC the Hessian of L too, the rates' matrix; RESIDUAL the
    residual alone; POSE_ONLY: a solve that converges leaves them at the last iterate, its
    residual NaN, for a caller that wants the pose alone). w.steps holds the scaled step of
    each iteration, w.a and w.info the last factorisation (keep). last: the step before the
    first (a chord step's), for the stop rule. A step that is not finite, or would move a
    point farther than a thousand levers, is not taken: the residual is the last finite
    pose's.
    """
    lever = model.consts[kernel.LEVER]
    tol = TOL_STEP * max(1.0, lever)
    steps = w.steps
    for k in range(len(steps)):
        steps[k] = np.nan
    for iteration in range(1, max_iter + 1):
        kernel.assemble(model, c, r, lam, inputs, kernel.EXACT, w)
        _rhs(model, lam, w)
        mode, dense = factorise(model, w)
        if mode == kkt.FAILED:
            break
        kkt.solve_full(w, model.perm, w.dense if dense else model.bounds, mode)
        size = _take(model, c, r, lam, w)
        if iteration <= len(steps):
            steps[iteration - 1] = size
        if not size < 1e3 * lever:   # diverging, or NaN: not taken
            break
        if converged(size, last, tol):
            if finish == POSE_ONLY:
                return True, iteration, np.nan
            kernel.assemble(model, c, r, lam, inputs, finish, w)
            return True, iteration, kernel.scaled_max(model, w.grad, lever, True)
        last = size
    kernel.assemble(model, c, r, lam, inputs, kernel.SYMMETRIC, w)
    residual = kernel.scaled_max(model, w.grad, lever, True)
    return False, max_iter, residual if np.isfinite(residual) else np.inf


@bare
def copy_pose(c, r, lam, to_c, to_r, to_lam):
    """Copy a pose and its multipliers (c (B, 3), r (B, 3, 3), lam (m,)) to another's."""
    for k in range(c.shape[0]):
        for i in range(3):
            to_c[k, i] = c[k, i]
            for j in range(3):
                to_r[k, i, j] = r[k, i, j]
    for k in range(len(lam)):
        to_lam[k] = lam[k]


@bare
def loaded(model, c, r, lam, inputs, w, c0, r0, lam0, force, moment):
    """
    Solve the equilibrium under inputs' load from the one in (c, r, lam), in place.

    In one Newton solve if it converges, else in 2, 4, ... 2**MAX_HALVINGS equal increments
    of the load from the start. Returns (ok, iterations, residual N) of the last solve; w
    holds its residual (kernel.RESIDUAL). c0, r0, lam0, force (3,), moment (3,): scratch.
    """
    copy_pose(c, r, lam, c0, r0, lam0)
    ok, iterations, residual = False, 0, np.inf
    for halvings in range(MAX_HALVINGS + 1):
        parts = 2 ** halvings
        copy_pose(c0, r0, lam0, c, r, lam)
        for k in range(1, parts + 1):
            for i in range(3):
                force[i] = inputs.force[i] * (k / parts)
                moment[i] = inputs.moment[i] * (k / parts)
            part = kernel.Inputs(inputs.z, inputs.rack, inputs.x_load, force, moment)
            ok, iterations, residual = newton(model, c, r, lam, part, MAX_ITER, w,
                                              kernel.RESIDUAL)
            if not ok:
                break
        if ok:
            return ok, iterations, residual
    return ok, iterations, residual
