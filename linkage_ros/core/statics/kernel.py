# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The statics compiled (numba): the Lagrangian's derivatives and Newton on the KKT system.

A System is packed into arrays (pack.py, Model below). The same equations as system.py and
newton.py, which stay as the check (test_statics_kernel compares them); see there for the
model and the signs.

A term is a constraint row or an energy, on up to 3 weighted items grouped into up to 2
points (x_p = sum of w x_item): kinds LINK, BALL, LINE, TRAVEL (the constraints, in
System.constraints order, first), SPRING, BUSH, LOAD. Compiled with base/compiled.py's
jit, whose one cache key covers so3.py and rotation.py, compiled in here.
"""

import math
from typing import NamedTuple

import numpy as np

from .rotation import energy_terms, log_so3
from ..base.compiled import jit
from ..base.so3 import turn

# a Newton step predicted (quadratic convergence) below this fraction of the tolerance is not
# taken (converged()): it would move the pose by round-off
PREDICTED = 1e-3
CARRIER, ARM, HINGE, BASE = 0, 1, 2, 3
LINK, BALL, LINE, TRAVEL, SPRING, BUSH, LOAD = 0, 1, 2, 3, 4, 5, 6


class Model(NamedTuple):
    """A System as arrays. b: bodies (B); t: terms (T); it: their items (T, 3); r: turns."""

    b_kind: np.ndarray     # (B,) int64
    b_start: np.ndarray    # (B,) int64
    b_ref0: np.ndarray     # (B, 3)
    b_axis: np.ndarray     # (B, 3) hinge axis
    t_kind: np.ndarray     # (T,) int64
    it_body: np.ndarray    # (T, 3) int64; -1 fixed; -2 unused
    it_x0: np.ndarray      # (T, 3, 3)
    it_trans: np.ndarray   # (T, 3) 1.0 point, 0.0 direction
    it_w: np.ndarray       # (T, 3)
    it_point: np.ndarray   # (T, 3) int64: 0 or 1
    t_data: np.ndarray     # (T, 2): length, component, z, rate & free length
    t_vec: np.ndarray      # (T, 3): strut top, bushing's B
    t_stiff: np.ndarray    # (T, 3, 3): bushing stiffness
    r_body: np.ndarray     # (R,) int64
    r_turn: np.ndarray     # (R, 3, 3)
    n: int
    m: int


@jit
def _size(kind):
    return 6 if kind <= ARM else (1 if kind == HINGE else 3)


@jit
def _place(model, c, r, body, x0, trans, x, v):
    """Write an item's position x and v = R (x0 - ref0) (or R x0 for a direction)."""
    if body < 0:
        x[:] = x0
        v[:] = 0.0
        return
    ref = model.b_ref0[body]
    d0, d1, d2 = x0[0] - ref[0] * trans, x0[1] - ref[1] * trans, x0[2] - ref[2] * trans
    for i in range(3):
        v[i] = r[body, i, 0] * d0 + r[body, i, 1] * d1 + r[body, i, 2] * d2
        x[i] = v[i] + c[body, i] * trans


@jit
def places(fields, c, r, out):
    """Write where every term's items are at a pose, out (T, 3, 3) mm (unused slots: NaN)."""
    model = Model(*fields)
    v = np.empty(3)
    for t in range(len(model.t_kind)):
        for a in range(3):
            body = model.it_body[t, a]
            if body == -2:
                out[t, a] = np.nan
            else:
                _place(model, c, r, body, model.it_x0[t, a], model.it_trans[t, a], out[t, a], v)


@jit
def _jac(model, body, v, trans, out):
    """Write d x / d q_body (3, size) of an item into out[:, :size]."""
    kind = model.b_kind[body]
    out[:] = 0.0
    if kind == CARRIER or kind == ARM:
        for i in range(3):
            out[i, i] = trans
        out[1, 3], out[2, 3] = -v[2], v[1]      # e_x x v
        out[0, 4], out[2, 4] = v[2], -v[0]      # e_y x v
        out[0, 5], out[1, 5] = -v[1], v[0]      # e_z x v
    elif kind == HINGE:
        a = model.b_axis[body]
        out[0, 0] = a[1] * v[2] - a[2] * v[1]
        out[1, 0] = a[2] * v[0] - a[0] * v[2]
        out[2, 0] = a[0] * v[1] - a[1] * v[0]
    else:
        for i in range(3):
            out[i, i] = trans


@jit
def _second(model, body, v, g, factor, hess):
    """Add factor W^T ((v g^T + g v^T) / 2 - (g.v) I) W of an item to hess (exact)."""
    kind = model.b_kind[body]
    if kind == BASE:
        return
    gv = g[0] * v[0] + g[1] * v[1] + g[2] * v[2]
    start = model.b_start[body]
    if kind == HINGE:
        a = model.b_axis[body]
        av, ag = a @ v, a @ g
        hess[start, start] += factor * (av * ag - gv * (a @ a))
        return
    for i in range(3):
        for j in range(3):
            hess[start + 3 + i, start + 3 + j] += factor * (
                0.5 * (v[i] * g[j] + g[i] * v[j]) - (gv if i == j else 0.0))


@jit
def _term(model, t, xs, force, g, h, eye):
    """Return term t's value at points xs; write d/dx_p g (2, 3), d2/dx_p dx_q h (2, 2, 3, 3)."""
    kind = model.t_kind[t]
    g[:] = 0.0
    h[:] = 0.0
    value = 0.0
    if kind == LINK:
        length = model.t_data[t, 0]
        dd = 0.0
        for i in range(3):
            d = xs[0, i] - xs[1, i]
            dd += d * d
            g[0, i], g[1, i] = d / length, -d / length
            h[0, 0, i, i], h[1, 1, i, i] = 1.0 / length, 1.0 / length
            h[0, 1, i, i], h[1, 0, i, i] = -1.0 / length, -1.0 / length
        value = (dd - length * length) / (2.0 * length)
    elif kind == BALL:
        k = int(model.t_data[t, 0])
        value = xs[0, k] - xs[1, k]
        g[0, k], g[1, k] = 1.0, -1.0
    elif kind == LINE:
        for i in range(3):
            gap = model.t_vec[t, i] - xs[0, i]
            value += gap * xs[1, i]
            g[0, i], g[1, i] = -xs[1, i], gap
            h[0, 1, i, i], h[1, 0, i, i] = -1.0, -1.0
    elif kind == TRAVEL:
        value = xs[0, 2] - model.t_data[t, 0]
        g[0, 2] = 1.0
    elif kind == SPRING:
        rate, free = model.t_data[t, 0], model.t_data[t, 1]
        d = xs[1] - xs[0]
        length = math.sqrt(d @ d)
        u = d / length
        f = rate * (length - free)
        value = 0.5 * rate * (length - free) ** 2
        g[0], g[1] = -f * u, f * u
        k = rate * np.outer(u, u) + f / length * (eye - np.outer(u, u))
        h[0, 0], h[1, 1], h[0, 1], h[1, 0] = k, k, -k, -k
    elif kind == BUSH:
        k = model.t_stiff[t]
        d0, d1, d2 = (xs[0, 0] - model.t_vec[t, 0], xs[0, 1] - model.t_vec[t, 1],
                      xs[0, 2] - model.t_vec[t, 2])
        for i in range(3):
            g[0, i] = k[i, 0] * d0 + k[i, 1] * d1 + k[i, 2] * d2
            for j in range(3):
                h[0, 0, i, j] = k[i, j]
        value = 0.5 * (d0 * g[0, 0] + d1 * g[0, 1] + d2 * g[0, 2])
    else:   # LOAD
        for i in range(3):
            value -= force[i] * xs[0, i]
            g[0, i] = -force[i]
    return value


@jit
def assemble(model, c, r, lam, force, moment, grad, hess, values, rows):
    """Write the gradient (n,) and Hessian (n, n) of L, c (m,) and dc/dq (m, n) at a pose."""
    grad[:] = 0.0
    hess[:] = 0.0
    rows[:] = 0.0
    x = np.empty((3, 3))
    v = np.empty((3, 3))
    jacs = np.empty((3, 3, 6))
    xs = np.empty((2, 3))
    g, h, eye = np.empty((2, 3)), np.empty((2, 2, 3, 3)), np.eye(3)
    hj = np.empty((3, 6))
    nonzero = np.zeros((2, 2), dtype=np.bool_)   # which blocks of h the term has
    for t in range(len(model.t_kind)):
        xs[:] = 0.0
        for a in range(3):
            body = model.it_body[t, a]
            if body == -2:
                continue
            _place(model, c, r, body, model.it_x0[t, a], model.it_trans[t, a], x[a], v[a])
            xs[model.it_point[t, a]] += model.it_w[t, a] * x[a]
            if body >= 0:
                _jac(model, body, v[a], model.it_trans[t, a], jacs[a])
        value = _term(model, t, xs, force, g, h, eye)
        kind = model.t_kind[t]
        nonzero[:] = kind == SPRING
        nonzero[0, 0] = kind == LINK or kind == SPRING or kind == BUSH
        nonzero[1, 1] = kind == LINK or kind == SPRING
        nonzero[0, 1] = nonzero[1, 0] = kind != BALL and kind != TRAVEL and kind != BUSH \
            and kind != LOAD
        factor = lam[t] if t < model.m else 1.0
        if t < model.m:
            values[t] = value
        for a in range(3):
            body = model.it_body[t, a]
            if body < 0:
                continue
            p, w = model.it_point[t, a], model.it_w[t, a]
            sa, na = model.b_start[body], _size(model.b_kind[body])
            for j in range(na):
                part = w * (g[p, 0] * jacs[a, 0, j] + g[p, 1] * jacs[a, 1, j]
                            + g[p, 2] * jacs[a, 2, j])
                grad[sa + j] += factor * part
                if t < model.m:
                    rows[t, sa + j] += part
            _second(model, body, v[a], g[p], factor * w, hess)
            for b in range(3):
                other = model.it_body[t, b]
                if other < 0:
                    continue
                q = model.it_point[t, b]
                sb, nb = model.b_start[other], _size(model.b_kind[other])
                scale = factor * w * model.it_w[t, b]
                if scale == 0.0 or not nonzero[p, q]:
                    continue
                for k in range(3):   # hj = h[p, q] J_b, then J_a^T hj
                    for j in range(nb):
                        hj[k, j] = (h[p, q, k, 0] * jacs[b, 0, j] + h[p, q, k, 1] * jacs[b, 1, j]
                                    + h[p, q, k, 2] * jacs[b, 2, j])
                for i in range(na):
                    for j in range(nb):
                        hess[sa + i, sb + j] += scale * (jacs[a, 0, i] * hj[0, j]
                                                         + jacs[a, 1, i] * hj[1, j]
                                                         + jacs[a, 2, i] * hj[2, j])
    for k in range(len(model.r_body)):
        body = model.r_body[k]
        _, g3, h3 = energy_terms(log_so3(r[body]), model.r_turn[k])
        s = model.b_start[body]
        grad[s + 3:s + 6] += g3
        hess[s + 3:s + 6, s + 3:s + 6] += h3
    grad[3:6] -= moment
    for i in range(model.n):
        for j in range(i):
            mean = 0.5 * (hess[i, j] + hess[j, i])
            hess[i, j], hess[j, i] = mean, mean


@jit
def _scaled_max(model, vec, lever, divide):
    """Return max |vec| with rotation coordinates divided (or multiplied) by lever."""
    out = 0.0
    for k in range(len(model.b_kind)):
        kind, s = model.b_kind[k], model.b_start[k]
        for i in range(_size(kind)):
            turn_ = (kind <= ARM and i >= 3) or kind == HINGE
            value = abs(vec[s + i])
            if turn_:
                value = value / lever if divide else value * lever
            out = max(out, value)
    return out


@jit
def converged(size, last, tol):
    """
    Tell whether Newton has converged: its step (scaled) is below tol, or the next one will be.

    Newton converges quadratically: the next step is about size^3 / last^2 (last: the step
    before). Below PREDICTED * tol it is round-off: the step after it is not taken.
    """
    return size < tol or size * size * size < PREDICTED * tol * last * last


@jit
def newton(fields, c, r, lam, force, moment, lever, tol_step, max_iter, hess, rows):
    """
    Solve the equilibrium from (c, r, lam) in place; return (ok, iterations, residual N).

    fields: tuple(model) (numba types a plain tuple in C, a named one in Python: 20 us more
    a call here); hess (n, n) and rows (m, n) hold the Hessian and dc/dq at the solution.
    """
    model = Model(*fields)
    n, m = model.n, model.m
    grad, values = np.empty(n), np.empty(m)
    matrix, rhs = np.zeros((n + m, n + m)), np.empty(n + m)
    last = 0.0   # no step before the first
    for iteration in range(1, max_iter + 1):
        assemble(model, c, r, lam, force, moment, grad, hess, values, rows)
        matrix[:n, :n] = hess
        matrix[:n, n:] = rows.T
        matrix[n:, :n] = rows
        matrix[n:, n:] = 0.0
        rhs[:n] = -(grad - rows.T @ lam)
        rhs[n:] = -values
        sol = np.linalg.solve(matrix, rhs)
        if not np.all(np.isfinite(sol)):
            break
        step = sol[:n]
        lam[:] = sol[n:]
        _move(model, c, r, step)
        size = _scaled_max(model, step, lever, False)
        if converged(size, last, tol_step * max(1.0, lever)):
            assemble(model, c, r, lam, force, moment, grad, hess, values, rows)
            return True, iteration, _scaled_max(model, grad, lever, True)
        if not size < 1e3 * lever:
            break
        last = size
    assemble(model, c, r, lam, force, moment, grad, hess, values, rows)
    return False, max_iter, _scaled_max(model, grad, lever, True)


@jit
def kkt_solve(hess, rows, rhs):
    """Return the solution of [[H, J^T], [J, 0]] x = rhs (n + m, k): newton.kkt, compiled."""
    n, m = hess.shape[0], rows.shape[0]
    matrix = np.zeros((n + m, n + m))
    matrix[:n, :n] = hess
    matrix[:n, n:] = rows.T
    matrix[n:, :n] = rows
    return np.linalg.solve(matrix, rhs)


@jit
def _move(model, c, r, step):
    """Move every body by a coordinate step: c += T dq, R <- exp(W dq) R."""
    for k in range(len(model.b_kind)):
        kind, s = model.b_kind[k], model.b_start[k]
        if kind <= ARM:
            c[k] += step[s:s + 3]
            turn(step[s + 3], step[s + 4], step[s + 5], r[k], r[k])
        elif kind == HINGE:
            a = model.b_axis[k] * step[s]
            turn(a[0], a[1], a[2], r[k], r[k])
        else:
            c[k] += step[s:s + 3]
