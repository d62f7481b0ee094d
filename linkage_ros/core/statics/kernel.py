# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The statics compiled (numba): the model's arrays, the Lagrangian's derivatives, the step.

A System (system.py) is packed into two flat arrays (pack.py): ints (int64) and reals
(float64), each field of Model below a view into them (unpack: two arrays cross into
compiled code, not forty: each array costs a tenth of a microsecond there). The equations
are those of system.py; the numpy formulation of the same is the tests' reference
(test/core/statics_reference.py).

A term is a constraint row or an energy, on up to 3 weighted items grouped into up to 2
points (x_p = sum of w x_item): kinds LINK, BALL, LINE, TRAVEL (the constraints, in
System.constraints order, the travel last), SPRING, BUSH, LOAD. The held height z, the
steering rack and the load (its point x0, force F N, moment M N mm) are each solve's inputs.

assemble writes the residual the Newton solve drives to zero, r = (grad L - M, c), and its
derivative in the bodies' coordinates. With exact False that is the Hessian of L (symmetric,
the stiffness of the rates); with exact True, the derivative of the residual at any pose: a
body's rotation w is a left increment, R <- exp(w) R, and exp(w) exp(d) = exp(w + d + w x d
/ 2 + ...) (Baker-Campbell-Hausdorff), so the gradient g_w of any function of the pose moves
by (H - [g_w]x / 2) d, H its symmetric second derivative. The moment M fixed in space is no
function of the pose (not conservative): its part of g_w has no H and no correction, and the
matrix is not symmetric where g_w of the rest is not zero (under a moment, at equilibrium
too). Compiled with base/compiled.py's decorators (one cache key over every kernel source;
bare: without numba's reference counting, for the kernels that allocate nothing).
"""

import math
from typing import NamedTuple

import numpy as np

from .rotation import energy_into, log_into
from ..base.compiled import bare, jitable
from ..base.force_table import table_force
from ..base.so3 import turn

CARRIER, ARM, HINGE, BASE = 0, 1, 2, 3
LINK, BALL, LINE, TRAVEL, SPRING, BUSH, LOAD = 0, 1, 2, 3, 4, 5, 6
# what assemble writes: the residual alone (grad, values, rows), with the symmetric Hessian
# of L, or with the residual's exact derivative (module docstring)
RESIDUAL, SYMMETRIC, EXACT = 0, 1, 2
# what a spring's moving item passes its share of the spring force on to (Model.s_move)
NOTHING, PICKUP, BALL_JOINT, RIGID_ARM = 0, 1, 2, 3
# ints begins with these scalars, then a header of 4 per field (offset, shape of up to 3)
N, M, N_SCALARS = 0, 1, 8


class Model(NamedTuple):
    """
    A System as arrays (pack.py): bodies (B), terms (T) and their items (T, 3), turns (R).

    Then the reduced KKT system's order (kkt.py: perm (K,) the unknowns, bounds the clusters'
    starts, the root's, K and the root's coordinate count), the pickups' layout (forces.py:
    c_ per constraint row, s_ per spring, u_ per bushing, h_ per rigid arm, l_ per link, p_
    per body pickup) and consts (design wheel centre (3,), spin axis (3,), side sign, wheel
    radius mm, lever mm).
    """

    b_kind: np.ndarray     # (B,) int64
    b_start: np.ndarray    # (B,) int64
    b_ref0: np.ndarray     # (B, 3)
    b_axis: np.ndarray     # (B, 3) hinge axis
    t_kind: np.ndarray     # (T,) int64
    it_body: np.ndarray    # (T, 3) int64; -1 fixed; -2 unused
    it_point: np.ndarray   # (T, 3) int64: 0 or 1
    t_table: np.ndarray    # (T, 2) int64: a spring's force table rows [start, stop), or -1
    it_x0: np.ndarray      # (T, 3, 3)
    it_trans: np.ndarray   # (T, 3) 1.0 point, 0.0 direction
    it_w: np.ndarray       # (T, 3)
    it_rack: np.ndarray    # (T, 3) 1.0: a fixed point the rack moves along y
    t_data: np.ndarray     # (T, 2): length, component, -, rate & free length
    t_vec: np.ndarray      # (T, 3): strut top, bushing's B at rack 0
    t_rack: np.ndarray     # (T,) 1.0: the bushing's B moves with the rack
    t_stiff: np.ndarray    # (T, 3, 3): bushing stiffness
    r_body: np.ndarray     # (R,) int64
    r_turn: np.ndarray     # (R, 3, 3) N mm/rad, all the body's bushings
    table: np.ndarray      # (rows, 2): force tables' [deflection mm, force N] rows
    perm: np.ndarray       # (K,) int64
    bounds: np.ndarray     # (C + 3,) int64
    c_ball: np.ndarray     # (m,) int64 ball joint slot of a row (-1: the travel)
    c_body: np.ndarray     # (m,) int64 body pickup of a rigid link's base or a strut top
    c_hinge: np.ndarray    # (m,) int64 rigid arm of a ball joint's first row
    s_body: np.ndarray     # (S,) int64 body pickup of the spring's body end
    s_move: np.ndarray     # (S, 2, 2) int64 each moving item's (target kind, slot)
    u_body: np.ndarray     # (U,) int64 body pickup of a bushing
    u_rot: np.ndarray      # (U,) int64 its arm's turn (index into r_body), -1 none
    h_slot: np.ndarray     # (H, 2) int64 body pickups of a rigid arm's pivots
    l_row: np.ndarray      # (L,) int64 a link's constraint row
    l_slot: np.ndarray     # (L, 2) int64 its base's body pickup and its ball joint slot
    u_share: np.ndarray    # (U,) the bushing's share of its arm's turn
    u_axis: np.ndarray     # (U, 3) its design axis
    h_axis: np.ndarray     # (H, 2, 3) a rigid arm's pivots axis[0], axis[1]
    p_point: np.ndarray    # (P, 3) where each body pickup acts, at rack 0
    p_rack: np.ndarray     # (P,) 1.0: it moves with the rack
    consts: np.ndarray     # (11,)
    n: int
    m: int


# Model's array fields: (kind 'i' int64 or 'f' float64, dimensions); pack.py writes in this
# order and unpack reads (test_statics_kernel checks the round trip)
FIELDS = (('i', 1), ('i', 1), ('f', 2), ('f', 2), ('i', 1), ('i', 2), ('i', 2), ('i', 2),
          ('f', 3), ('f', 2), ('f', 2), ('f', 2), ('f', 2), ('f', 2), ('f', 1), ('f', 3),
          ('i', 1), ('f', 3), ('f', 2), ('i', 1), ('i', 1),
          ('i', 1), ('i', 1), ('i', 1), ('i', 1), ('i', 3), ('i', 1), ('i', 1), ('i', 2),
          ('i', 1), ('i', 2), ('f', 1), ('f', 2), ('f', 3), ('f', 2), ('f', 1), ('f', 1))
CENTER, SPIN, SIDE, RADIUS, LEVER = 0, 3, 6, 7, 8   # consts


@jitable(inline='always')
def _i1(ints, k):
    h = N_SCALARS + 4 * k
    return ints[ints[h]:ints[h] + ints[h + 1]]


@jitable(inline='always')
def _i2(ints, k):
    h = N_SCALARS + 4 * k
    return ints[ints[h]:ints[h] + ints[h + 1] * ints[h + 2]].reshape((ints[h + 1], ints[h + 2]))


@jitable(inline='always')
def _i3(ints, k):
    h = N_SCALARS + 4 * k
    size = ints[h + 1] * ints[h + 2] * ints[h + 3]
    return ints[ints[h]:ints[h] + size].reshape((ints[h + 1], ints[h + 2], ints[h + 3]))


@jitable(inline='always')
def _f1(ints, reals, k):
    h = N_SCALARS + 4 * k
    return reals[ints[h]:ints[h] + ints[h + 1]]


@jitable(inline='always')
def _f2(ints, reals, k):
    h = N_SCALARS + 4 * k
    size = ints[h + 1] * ints[h + 2]
    return reals[ints[h]:ints[h] + size].reshape((ints[h + 1], ints[h + 2]))


@jitable(inline='always')
def _f3(ints, reals, k):
    h = N_SCALARS + 4 * k
    size = ints[h + 1] * ints[h + 2] * ints[h + 3]
    return reals[ints[h]:ints[h] + size].reshape((ints[h + 1], ints[h + 2], ints[h + 3]))


def unpack(ints, reals):
    """Return the Model whose fields are views into ints and reals (Python's: model_of)."""
    return model_of(ints, reals)


@jitable(inline='always')
def model_of(ints, reals):
    """Return the Model whose fields are views into ints and reals (FIELDS' layout)."""
    return Model(
        _i1(ints, 0), _i1(ints, 1), _f2(ints, reals, 2), _f2(ints, reals, 3), _i1(ints, 4),
        _i2(ints, 5), _i2(ints, 6), _i2(ints, 7), _f3(ints, reals, 8), _f2(ints, reals, 9),
        _f2(ints, reals, 10), _f2(ints, reals, 11), _f2(ints, reals, 12),
        _f2(ints, reals, 13), _f1(ints, reals, 14), _f3(ints, reals, 15), _i1(ints, 16),
        _f3(ints, reals, 17), _f2(ints, reals, 18), _i1(ints, 19), _i1(ints, 20),
        _i1(ints, 21), _i1(ints, 22), _i1(ints, 23), _i1(ints, 24), _i3(ints, 25),
        _i1(ints, 26), _i1(ints, 27), _i2(ints, 28), _i1(ints, 29), _i2(ints, 30),
        _f1(ints, reals, 31), _f2(ints, reals, 32), _f3(ints, reals, 33),
        _f2(ints, reals, 34), _f1(ints, reals, 35), _f1(ints, reals, 36), ints[N], ints[M])


class Inputs(NamedTuple):
    """What one solve is given: held height z (mm), rack (mm), the load (N, N mm, mm)."""

    z: float
    rack: float
    x_load: np.ndarray     # (3,) the load's point on the carrier, design position
    force: np.ndarray      # (3,) N, fixed direction
    moment: np.ndarray     # (3,) N mm, fixed in space


class Scratch(NamedTuple):
    """Work arrays of assemble and forces.pickups (views into a work array: scratch_of)."""

    x: np.ndarray          # (3, 3) item places
    v: np.ndarray          # (3, 3) item offsets R (x0 - ref0)
    jacs: np.ndarray       # (3, 3, 6) d x / d q_body
    xs: np.ndarray         # (2, 3) the points
    g: np.ndarray          # (2, 3)
    h: np.ndarray          # (2, 2, 3, 3)
    hj: np.ndarray         # (3, 6)
    phi: np.ndarray        # (3,)
    g3: np.ndarray         # (3,)
    h3: np.ndarray         # (3, 3)
    rot: np.ndarray        # (5, 3, 3) energy_into's
    at: np.ndarray         # (T, 3, 3) every item's place (forces.places)
    rigid: np.ndarray      # (H, 6) the loads on each rigid arm (forces.pickups)


@jitable
def scratch_size(terms, rigid):
    """Return the size of a Scratch for terms terms and rigid rigid arms (floats)."""
    return 9 + 9 + 54 + 6 + 6 + 36 + 18 + 3 + 3 + 9 + 45 + 9 * terms + 6 * rigid


@jitable(inline='always')
def scratch_of(model, out):
    """Return the Scratch whose arrays are views into out (scratch_size floats)."""
    terms, rigid = len(model.t_kind), len(model.h_slot)
    x, v, jacs = out[0:9].reshape((3, 3)), out[9:18].reshape((3, 3)), out[18:72].reshape(
        (3, 3, 6))
    xs, g, h = out[72:78].reshape((2, 3)), out[78:84].reshape((2, 3)), out[84:120].reshape(
        (2, 2, 3, 3))
    hj, phi, g3, h3 = out[120:138].reshape((3, 6)), out[138:141], out[141:144], out[
        144:153].reshape((3, 3))
    rot = out[153:198].reshape((5, 3, 3))
    at = out[198:198 + 9 * terms].reshape((terms, 3, 3))
    o = 198 + 9 * terms
    return Scratch(x, v, jacs, xs, g, h, hj, phi, g3, h3, rot, at,
                   out[o:o + 6 * rigid].reshape((rigid, 6)))


@bare
def size_of(kind):
    """Return how many coordinates a body of this kind has."""
    return 6 if kind <= ARM else (1 if kind == HINGE else 3)


@bare
def spring_at(rate, free, start, stop, table, length):
    """
    Return a spring's (tension N, stiffness d tension / d length N/mm) at length (mm).

    A rate (start < 0), or rows [start, stop) of table (a force table, base.table_force).
    """
    if start < 0:
        return rate * (length - free), rate
    pushed, slope = table_force(table[start:stop, 0], table[start:stop, 1], free - length)
    return -pushed, slope


@bare
def assemble(model, c, r, lam, inputs, what, w):
    """
    Write r = (grad L - M (n,), c (m,)), its derivative (hess (n, n), rows = dc/dq (m, n)).

    Into w (a newton.Work): w.grad, w.values, w.hess, w.rows, with w.scratch.

    what: EXACT the derivative of the residual at this pose (module docstring), SYMMETRIC
    the symmetric Hessian of L, RESIDUAL no Hessian (hess left as it is). The load's point
    is a carrier point (inputs.x_load, design).

    One loop over the terms, each written out here: a helper that took arrays would cost a
    reference count taken and given back per array per call (numba), more than the
    arithmetic of a term. Per term: its items' places x, v = R (x0 - ref0) and d x / d q
    (jacs), the term's value, gradient g in its points and second derivative h; then
    grad += factor J^T g, the rotation's own second derivative (v g^T + g v^T) / 2 - (g.v) I
    (exact) and J_a^T h J_b, factor the multiplier of a constraint row, 1 for an energy.
    """
    n, m = model.n, model.m
    grad, hess, values, rows, work = w.grad, w.hess, w.values, w.rows, w.scratch
    second = what != RESIDUAL
    for i in range(n):
        grad[i] = 0.0
        if second:
            for j in range(n):
                hess[i, j] = 0.0
    for k in range(m):
        for j in range(n):
            rows[k, j] = 0.0
    x, v, jacs, xs, g, h, hj = work.x, work.v, work.jacs, work.xs, work.g, work.h, work.hj
    rack, z, load, force = inputs.rack, inputs.z, inputs.x_load, inputs.force
    b_kind, b_start, b_ref0, b_axis = model.b_kind, model.b_start, model.b_ref0, model.b_axis
    t_kind, it_body, it_point, it_w = model.t_kind, model.it_body, model.it_point, model.it_w
    it_x0, it_trans, it_rack = model.it_x0, model.it_trans, model.it_rack
    t_data, t_vec, t_stiff, t_rack, t_table = (model.t_data, model.t_vec, model.t_stiff,
                                               model.t_rack, model.t_table)
    table = model.table
    last = len(t_kind) - 1
    for t in range(len(t_kind)):
        kind = t_kind[t]
        for i in range(3):
            xs[0, i] = xs[1, i] = g[0, i] = g[1, i] = 0.0
        for a in range(3):   # the items: places, v, d x / d q
            body = it_body[t, a]
            if body == -2:
                continue
            if t == last:   # the load: its point is an input
                x0x, x0y, x0z = load[0], load[1], load[2]
            else:
                x0x, x0y, x0z = it_x0[t, a, 0], it_x0[t, a, 1], it_x0[t, a, 2]
            if body < 0:
                x[a, 0], x[a, 1], x[a, 2] = x0x, x0y + rack * it_rack[t, a], x0z
            else:
                trans = it_trans[t, a]
                d0 = x0x - b_ref0[body, 0] * trans
                d1 = x0y - b_ref0[body, 1] * trans
                d2 = x0z - b_ref0[body, 2] * trans
                for i in range(3):
                    v[a, i] = r[body, i, 0] * d0 + r[body, i, 1] * d1 + r[body, i, 2] * d2
                    x[a, i] = v[a, i] + c[body, i] * trans
                bk = b_kind[body]
                if bk == HINGE:
                    a0, a1, a2 = b_axis[body, 0], b_axis[body, 1], b_axis[body, 2]
                    jacs[a, 0, 0] = a1 * v[a, 2] - a2 * v[a, 1]
                    jacs[a, 1, 0] = a2 * v[a, 0] - a0 * v[a, 2]
                    jacs[a, 2, 0] = a0 * v[a, 1] - a1 * v[a, 0]
                else:   # the translation, then (6-DOF) e_k x v
                    for i in range(3):
                        for j in range(3):
                            jacs[a, i, j] = trans if i == j else 0.0
                    if bk <= ARM:
                        jacs[a, 0, 3], jacs[a, 1, 3], jacs[a, 2, 3] = 0.0, -v[a, 2], v[a, 1]
                        jacs[a, 0, 4], jacs[a, 1, 4], jacs[a, 2, 4] = v[a, 2], 0.0, -v[a, 0]
                        jacs[a, 0, 5], jacs[a, 1, 5], jacs[a, 2, 5] = -v[a, 1], v[a, 0], 0.0
            p, w = it_point[t, a], it_w[t, a]
            for i in range(3):
                xs[p, i] += w * x[a, i]
        curved = second and (kind == LINK or kind == SPRING or kind == BUSH or kind == LINE)
        if curved:
            for p in range(2):
                for q in range(2):
                    for i in range(3):
                        for j in range(3):
                            h[p, q, i, j] = 0.0
        value = 0.0   # the term at xs: its value, g = d/dx_p, h = d2/dx_p dx_q
        if kind == LINK:
            length = t_data[t, 0]
            dd = 0.0
            for i in range(3):
                d = xs[0, i] - xs[1, i]
                dd += d * d
                g[0, i], g[1, i] = d / length, -d / length
                h[0, 0, i, i], h[1, 1, i, i] = 1.0 / length, 1.0 / length
                h[0, 1, i, i], h[1, 0, i, i] = -1.0 / length, -1.0 / length
            value = (dd - length * length) / (2.0 * length)
        elif kind == BALL:
            k = int(t_data[t, 0])
            value = xs[0, k] - xs[1, k]
            g[0, k], g[1, k] = 1.0, -1.0
        elif kind == LINE:
            for i in range(3):
                gap = t_vec[t, i] - xs[0, i]
                value += gap * xs[1, i]
                g[0, i], g[1, i] = -xs[1, i], gap
                h[0, 1, i, i], h[1, 0, i, i] = -1.0, -1.0
        elif kind == TRAVEL:
            value = xs[0, 2] - z
            g[0, 2] = 1.0
        elif kind == SPRING:
            d0, d1, d2 = xs[1, 0] - xs[0, 0], xs[1, 1] - xs[0, 1], xs[1, 2] - xs[0, 2]
            length = math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
            u0, u1, u2 = d0 / length, d1 / length, d2 / length
            f, stiffness = spring_at(t_data[t, 0], t_data[t, 1], t_table[t, 0], t_table[t, 1],
                                     table, length)
            across = f / length
            for i in range(3):
                ui = u0 if i == 0 else (u1 if i == 1 else u2)
                g[0, i], g[1, i] = -f * ui, f * ui
                for j in range(3):
                    uj = u0 if j == 0 else (u1 if j == 1 else u2)
                    k = (stiffness - across) * ui * uj + (across if i == j else 0.0)
                    h[0, 0, i, j], h[1, 1, i, j] = k, k
                    h[0, 1, i, j], h[1, 0, i, j] = -k, -k
        elif kind == BUSH:
            d0 = xs[0, 0] - t_vec[t, 0]
            d1 = xs[0, 1] - t_vec[t, 1] - rack * t_rack[t]
            d2 = xs[0, 2] - t_vec[t, 2]
            for i in range(3):
                g[0, i] = t_stiff[t, i, 0] * d0 + t_stiff[t, i, 1] * d1 + t_stiff[t, i, 2] * d2
                for j in range(3):
                    h[0, 0, i, j] = t_stiff[t, i, j]
            value = 0.5 * (d0 * g[0, 0] + d1 * g[0, 1] + d2 * g[0, 2])
        else:   # LOAD
            for i in range(3):
                value -= force[i] * xs[0, i]
                g[0, i] = -force[i]
        factor = lam[t] if t < m else 1.0
        if t < m:
            values[t] = value
        for a in range(3):   # into grad, rows and hess
            body = it_body[t, a]
            if body < 0:
                continue
            p, w = it_point[t, a], it_w[t, a]
            bk, sa = b_kind[body], b_start[body]
            na = size_of(bk)
            for j in range(na):
                part = w * (g[p, 0] * jacs[a, 0, j] + g[p, 1] * jacs[a, 1, j]
                            + g[p, 2] * jacs[a, 2, j])
                grad[sa + j] += factor * part
                if t < m:
                    rows[t, sa + j] += part
            if second and bk != BASE:   # the rotation's own second derivative, exact
                fw = factor * w
                gv = g[p, 0] * v[a, 0] + g[p, 1] * v[a, 1] + g[p, 2] * v[a, 2]
                if bk == HINGE:
                    a0, a1, a2 = b_axis[body, 0], b_axis[body, 1], b_axis[body, 2]
                    av = a0 * v[a, 0] + a1 * v[a, 1] + a2 * v[a, 2]
                    ag = a0 * g[p, 0] + a1 * g[p, 1] + a2 * g[p, 2]
                    hess[sa, sa] += fw * (av * ag - gv * (a0 * a0 + a1 * a1 + a2 * a2))
                else:
                    for i in range(3):
                        for j in range(3):
                            hess[sa + 3 + i, sa + 3 + j] += fw * (
                                0.5 * (v[a, i] * g[p, j] + g[p, i] * v[a, j])
                                - (gv if i == j else 0.0))
            if not curved:
                continue
            for b in range(3):
                other = it_body[t, b]
                if other < 0:
                    continue
                q = it_point[t, b]
                sb, nb = b_start[other], size_of(b_kind[other])
                scale = factor * w * it_w[t, b]
                if scale == 0.0:
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
    r_body, r_turn, phi, g3, h3, rot = (model.r_body, model.r_turn, work.phi, work.g3,
                                        work.h3, work.rot)
    for k in range(len(r_body)):
        body = r_body[k]
        log_into(r[body], phi)
        energy_into(phi, r_turn[k], g3, h3, rot)
        s = b_start[body] + 3
        for i in range(3):
            grad[s + i] += g3[i]
            if second:
                for j in range(3):
                    hess[s + i, s + j] += h3[i, j]
    if second:   # the terms add both triangles alike: the mean clears the round-off
        for i in range(n):
            for j in range(i):
                mean = 0.5 * (hess[i, j] + hess[j, i])
                hess[i, j], hess[j, i] = mean, mean
    if what == EXACT:
        for k in range(len(b_kind)):
            if b_kind[k] > ARM:
                continue
            s = b_start[k] + 3
            g0, g1, g2 = 0.5 * grad[s], 0.5 * grad[s + 1], 0.5 * grad[s + 2]
            hess[s, s + 1] += g2   # - [g]x / 2
            hess[s, s + 2] -= g1
            hess[s + 1, s] -= g2
            hess[s + 1, s + 2] += g0
            hess[s + 2, s] += g1
            hess[s + 2, s + 1] -= g0
    moment = inputs.moment
    for i in range(3):
        grad[3 + i] -= moment[i]


@bare
def scaled_max(model, vec, lever, divide):
    """
    Return max |vec[:n]| with rotation coordinates divided (or multiplied) by lever.

    A NaN anywhere gives NaN (a residual that is not finite is said so, never hidden).
    """
    out = 0.0
    b_kind, b_start = model.b_kind, model.b_start
    for k in range(len(b_kind)):
        kind, s = b_kind[k], b_start[k]
        for i in range(size_of(kind)):
            turn_ = (kind <= ARM and i >= 3) or kind == HINGE
            value = abs(vec[s + i])
            if turn_:
                value = value / lever if divide else value * lever
            if not value <= out:   # larger, or NaN
                out = value
                if value != value:
                    return value
    return out


@bare
def move(model, c, r, step):
    """Move every body by a coordinate step (step[:n]): c += T dq, R <- exp(W dq) R."""
    b_kind, b_start, b_axis = model.b_kind, model.b_start, model.b_axis
    for k in range(len(b_kind)):
        kind, s = b_kind[k], b_start[k]
        if kind <= ARM:
            for i in range(3):
                c[k, i] += step[s + i]
            turn(step[s + 3], step[s + 4], step[s + 5], r[k], r[k])
        elif kind == HINGE:
            turn(b_axis[k, 0] * step[s], b_axis[k, 1] * step[s], b_axis[k, 2] * step[s], r[k],
                 r[k])
        else:
            for i in range(3):
                c[k, i] += step[s + i]
