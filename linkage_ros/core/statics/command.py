# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
One command of a corner's statics, compiled: a loaded answer (solve) or the rates (rates).

Each is one call from Python (statics.Statics): two arrays of the Model (kernel.unpack), the
state (the last zero-load and the last loaded equilibrium, state_views) and io (the command
and the answer, the offsets below). Where the command's zero-load equilibrium is needed (a
load at the contact patch, which sits on the wheel where the unloaded pose puts it; the
rates), it is solved from the last one (or taken as it is, at the same travel and rack);
the loaded one from the last loaded one (WARM) or from the zero-load one in increments
(ZERO). A start that fails says so (code); statics.py then starts from the kinematic pose.

Compiled with base/compiled.py's decorators (one cache key over every kernel source).
"""

import math
from typing import NamedTuple

import numpy as np

from . import forces, kernel, kkt, newton
from ..base.compiled import bare, jit, jitable
from ..base.patch import patch_offset, point_velocity


# io: the command, then what it gives
Z, RACK, AT_CP, FORCE, MOMENT, ZERO_FROM, LOADED_FROM = 0, 1, 2, 3, 6, 9, 10
CODE, ITERATIONS, RESIDUAL, ZERO_ITERATIONS, ZERO_RESIDUAL, ANSWER = 11, 12, 13, 14, 15, 16
# where a solve starts: WARM the last equilibrium if it is kept and within WARM_MM of the
# command (zero-load: the same one if at the same travel and rack), KINEMATIC the pose
# written into the zero-load state (statics.py), ZERO the zero-load equilibrium of this
# command, the load in increments
WARM, KINEMATIC, ZERO = 0, 1, 2
# a last equilibrium at most this far in travel and in rack (mm) starts the next Newton (a
# node at 1 kHz, a sweep); farther, the kinematic pose does
WARM_MM = 5.0
# what a command gives (io[CODE]): COLD no zero-load equilibrium near enough to start from
OK, ZERO_FAILED, LOADED_FAILED, BEYOND, COLD = 0, 1, 2, 3, 4
# the rates in io from ANSWER: RATES values (RATE_COLUMNS' order), the 6x6 matrix in the
# table's units, then in SI
RATES, MATRIX, MATRIX_SI, RATES_SIZE = 0, 12, 48, 84
DEG = 180.0 / math.pi
PER_KN = 1000.0            # N per kN
PER_KNM = 1e6              # N mm per kN m


class Equilibrium(NamedTuple):
    """Views of one equilibrium in the state: where (z, rack mm), valid, c, r, lambda."""

    head: np.ndarray       # (3,): z, rack, valid (1.0)
    c: np.ndarray          # (B, 3)
    r: np.ndarray          # (B, 3, 3)
    lam: np.ndarray        # (m,)


class Extra(NamedTuple):
    """A command's own scratch, after the newton.Work in its float work array (extra_of)."""

    c: np.ndarray          # (B, 3) the pose being solved
    r: np.ndarray          # (B, 3, 3)
    lam: np.ndarray        # (m,)
    c0: np.ndarray         # (B, 3) newton.loaded's start
    r0: np.ndarray         # (B, 3, 3)
    lam0: np.ndarray       # (m,)
    x_load: np.ndarray     # (3,) the load's carrier point
    zero: np.ndarray       # (3,) zeros: the zero load
    force: np.ndarray      # (3,) newton.loaded's increments
    moment: np.ndarray     # (3,)
    rates: np.ndarray      # (9, 8): dm, turn (3 each), held, toe, camber per load


@jitable
def state_offset(bodies, n, m, size, which):
    """
    Return where part which of a state starts (4: the state's size).

    The parts: the zero-load equilibrium (0) and the loaded one (1), each its head (z, rack,
    valid), c, r and lambda; then the factorisation each was last solved with (2, 3:
    newton.Factor: head, a (K, K), piv (2 K,), column, row (n,), rows (m,)). bodies, n, m,
    size: the Model's bodies, coordinates, rows and reduced KKT size K.
    """
    equilibrium = 3 + 12 * bodies + m
    factor = 3 + size * size + 2 * size + 2 * n + m
    return which * equilibrium if which <= 2 else 2 * equilibrium + (which - 2) * factor


@jitable
def sizes(model):
    """Return (state, work floats, work ints) sizes: the arrays a Statics keeps for a Model."""
    bodies, n, m, size = len(model.b_kind), model.n, model.m, len(model.perm)
    floats, ints = newton.work_size(model)
    return (state_offset(bodies, n, m, size, 4), floats + 2 * (12 * bodies + m) + 12 + 72,
            ints)


@jitable(inline='always')
def extra_of(model, floats):
    """Return the Extra whose arrays are views into floats (what follows the Work)."""
    bodies, m = len(model.b_kind), model.m
    c = floats[0:3 * bodies].reshape((bodies, 3))
    r = floats[3 * bodies:12 * bodies].reshape((bodies, 3, 3))
    lam = floats[12 * bodies:12 * bodies + m]
    p = 12 * bodies + m
    c0 = floats[p:p + 3 * bodies].reshape((bodies, 3))
    r0 = floats[p + 3 * bodies:p + 12 * bodies].reshape((bodies, 3, 3))
    lam0 = floats[p + 12 * bodies:p + 12 * bodies + m]
    q = 2 * p
    zero = floats[q + 3:q + 6]
    for i in range(3):
        zero[i] = 0.0
    return Extra(c, r, lam, c0, r0, lam0, floats[q:q + 3], zero, floats[q + 6:q + 9],
                 floats[q + 9:q + 12], floats[q + 12:q + 84].reshape((9, 8)))


@jitable(inline='always')
def views(state, bodies, m, which):
    """Return the Equilibrium views of a state: which 0 the zero-load one, 1 the loaded one."""
    o = state_offset(bodies, 0, m, 0, which)
    c = state[o + 3:o + 3 + 3 * bodies].reshape((bodies, 3))
    r = state[o + 3 + 3 * bodies:o + 3 + 12 * bodies].reshape((bodies, 3, 3))
    return Equilibrium(state[o:o + 3], c, r, state[o + 3 + 12 * bodies:o + 3 + 12 * bodies + m])


@jitable(inline='always')
def factor_views(state, model, which):
    """Return the newton.Factor views of a state's factorisation which (0 zero, 1 loaded)."""
    n, m, size = model.n, model.m, len(model.perm)
    o = state_offset(len(model.b_kind), n, m, size, 2 + which)
    a = state[o + 3:o + 3 + size * size].reshape((size, size))
    head = state[o:o + 3]
    o += 3 + size * size
    return newton.Factor(head, a, state[o:o + 2 * size], state[o + 2 * size:o + 2 * size + n],
                         state[o + 2 * size + n:o + 2 * size + 2 * n],
                         state[o + 2 * size + 2 * n:o + 2 * size + 2 * n + m])


@bare
def _near(head, z, rack):
    """Tell whether an equilibrium (its head: z, rack, valid) is kept and within WARM_MM."""
    return head[2] == 1.0 and abs(head[0] - z) <= WARM_MM and abs(head[1] - rack) <= WARM_MM


@bare
def _zero_load(model, state, io, w, extra, finish):
    """
    Make the zero-load state the equilibrium at io's travel and rack; return ok.

    Taken as it is at the same travel and rack (WARM), else solved from it (WARM: the last
    one; KINEMATIC: the pose statics.py wrote there) and kept if it converges; finish: what
    w holds of it then (newton.newton's).
    """
    z, rack = io[Z], io[RACK]
    zero = views(state, len(model.b_kind), model.m, 0)
    same = zero.head[2] == 1.0 and zero.head[0] == z and zero.head[1] == rack
    if same and io[ZERO_FROM] == WARM:
        io[ZERO_ITERATIONS] = 0.0
        return True
    c, r, lam = extra.c, extra.r, extra.lam
    newton.copy_pose(zero.c, zero.r, zero.lam, c, r, lam)
    center = model.consts[kernel.CENTER:kernel.CENTER + 3]
    inputs = kernel.Inputs(z, rack, center, extra.zero, extra.zero)
    kept = factor_views(state, model, 0)
    w = newton.over(w, kept)   # (Newton factorises into the kept arrays: not kept till keep)
    last = 0.0
    if io[ZERO_FROM] == WARM and kept.head[0] == 1.0:   # the tangent, then Newton
        last = newton.chord(model, c, r, lam, inputs, kept, w)
    kept.head[0] = 0.0
    ok, iterations, residual = newton.newton(model, c, r, lam, inputs, newton.MAX_ITER, w,
                                             finish, last)
    io[ZERO_ITERATIONS], io[ZERO_RESIDUAL] = iterations, residual
    if ok:
        zero.head[0], zero.head[1], zero.head[2] = z, rack, 1.0
        newton.copy_pose(c, r, lam, zero.c, zero.r, zero.lam)
        if finish != kernel.SYMMETRIC:   # (the rates keep their own, at the equilibrium)
            newton.keep(w, kept)
    return ok


@bare
def load_point(model, r0, at_cp, out):
    """
    Write the load's point (3,) on the carrier (design position) into out.

    The wheel centre, or (at_cp) the contact patch: the lowest point of the wheel circle in
    the zero-load pose (rotation r0), taken as a carrier point.
    """
    center = model.consts[kernel.CENTER:kernel.CENTER + 3]
    for i in range(3):
        out[i] = center[i]
    if not at_cp:
        return
    spin = model.consts[kernel.SPIN:kernel.SPIN + 3]
    a0 = r0[0, 0] * spin[0] + r0[0, 1] * spin[1] + r0[0, 2] * spin[2]
    a1 = r0[1, 0] * spin[0] + r0[1, 1] * spin[1] + r0[1, 2] * spin[2]
    a2 = r0[2, 0] * spin[0] + r0[2, 1] * spin[1] + r0[2, 2] * spin[2]
    px, py, pz = patch_offset(a0, a1, a2, model.consts[kernel.RADIUS])
    for i in range(3):
        out[i] += r0[0, i] * px + r0[1, i] * py + r0[2, i] * pz


@jit
def solve(ints, reals, state, io, floats, integers):
    """
    Solve one loaded command (io's travel, rack and load); return and write its code.

    OK: the answer in io from ANSWER (forces.answer_offsets), the loaded state kept.
    ZERO_FAILED, LOADED_FAILED: no convergence from the start asked (residual in io);
    BEYOND: converged, but a bushing beyond the model (the answer's validity says which);
    COLD: asked to start WARM with no zero-load equilibrium near enough (none solved).
    floats, integers: the work (sizes()), kept by the caller, so that nothing is allocated.
    """
    model = kernel.model_of(ints, reals)
    bodies = len(model.b_kind)
    if io[LOADED_FROM] == WARM and not _near(views(state, bodies, model.m, 1).head, io[Z],
                                             io[RACK]):
        io[LOADED_FROM] = ZERO
    # the zero-load equilibrium: for the patch's place, or to start from; a load at the
    # wheel centre continued from the last loaded equilibrium needs none
    zero_load = io[AT_CP] != 0.0 or io[LOADED_FROM] != WARM
    if zero_load and io[ZERO_FROM] == WARM and not _near(views(state, bodies, model.m, 0).head,
                                                         io[Z], io[RACK]):
        io[CODE] = COLD
        return COLD
    w = newton.work_of(model, floats, integers)
    extra = extra_of(model, floats[newton.work_size(model)[0]:])
    io[CODE] = ZERO_FAILED
    if not zero_load:
        io[ZERO_ITERATIONS] = 0.0
    elif not _zero_load(model, state, io, w, extra, newton.POSE_ONLY):
        io[RESIDUAL] = io[ZERO_RESIDUAL]
        return ZERO_FAILED
    start = views(state, bodies, model.m, 0 if io[LOADED_FROM] != WARM else 1)
    c, r, lam = extra.c, extra.r, extra.lam
    newton.copy_pose(start.c, start.r, start.lam, c, r, lam)
    load_point(model, views(state, bodies, model.m, 0).r[0], io[AT_CP] != 0.0, extra.x_load)
    inputs = kernel.Inputs(io[Z], io[RACK], extra.x_load, io[FORCE:FORCE + 3],
                           io[MOMENT:MOMENT + 3])
    kept = factor_views(state, model, 1)
    w = newton.over(w, kept)   # (Newton factorises into the kept arrays: not kept till keep)
    last = 0.0
    if io[LOADED_FROM] == WARM and kept.head[0] == 1.0:   # the tangent, then Newton
        last = newton.chord(model, c, r, lam, inputs, kept, w)
    kept.head[0] = 0.0
    if io[LOADED_FROM] == WARM:
        ok, iterations, residual = newton.newton(model, c, r, lam, inputs, newton.MAX_ITER, w,
                                                 kernel.RESIDUAL, last)
    else:
        ok, iterations, residual = newton.loaded(model, c, r, lam, inputs, w, extra.c0,
                                                 extra.r0, extra.lam0, extra.force,
                                                 extra.moment)
    io[ITERATIONS], io[RESIDUAL] = iterations, residual
    if not ok:
        io[CODE] = LOADED_FAILED
        return LOADED_FAILED
    answer = io[ANSWER:]
    forces.pickups(model, c, r, lam, inputs, answer, w.scratch)
    answer[forces.RESIDUAL], answer[forces.ITERATIONS] = residual, iterations
    if answer[forces.VALIDITY] != forces.VALID:
        io[CODE] = BEYOND
        return BEYOND
    done = views(state, bodies, model.m, 1)
    done.head[0], done.head[1], done.head[2] = io[Z], io[RACK], 1.0
    newton.copy_pose(c, r, lam, done.c, done.r, done.lam)
    newton.keep(w, kept)
    io[CODE] = OK
    return OK


@bare
def angle_gradients(ax, ay, az, side_sign):
    """
    Return d camber / d w and d toe / d w (3 each) rad/rad of a spin axis a turned by w.

    camber = -atan2(a_z, |a_xy|), toe = atan2(a_x, s a_y) (so3.camber_toe); a moves by
    w x a, so d/dw = a x d/da.
    """
    flat = math.hypot(ax, ay)
    tilt, turn = az * az + flat * flat, ax * ax + ay * ay
    c0, c1, c2 = az * ax / flat / tilt, az * ay / flat / tilt, -flat / tilt
    t0, t1 = side_sign * ay / turn, side_sign * -ax / turn
    return ((ay * c2 - az * c1, az * c0 - ax * c2, ax * c1 - ay * c0),
            (-az * t1, az * t0, ax * t1 - ay * t0))


@jit
def rates(ints, reals, state, io, floats, integers):
    """
    Write the rates and the 6x6 compliance at io's travel and rack (from RATES); return code.

    First-order, by the implicit function theorem, at the zero-load equilibrium (which holds
    the springs' preload): the KKT system [[H, J^T], [J, 0]] (dq, dlambda) = (Q, 0) of each
    generalized load Q, one factorisation for all. Columns: Fx, Fy, Fz, Mx, My, Mz at the
    wheel centre (per N, per N mm), then Fy and Fx at the contact patch. The carrier's dq is
    its move dM (mm) and turn w (rad); the holding force changes by -dlambda of the travel.
    floats, integers: the work, as solve's.
    """
    model = kernel.model_of(ints, reals)
    zero = views(state, len(model.b_kind), model.m, 0)
    if io[ZERO_FROM] == WARM and not _near(zero.head, io[Z], io[RACK]):
        io[CODE] = COLD
        return COLD
    w = newton.work_of(model, floats, integers)
    extra = extra_of(model, floats[newton.work_size(model)[0]:])
    io[CODE] = ZERO_FAILED
    if not _zero_load(model, state, io, w, extra, kernel.SYMMETRIC):
        io[RESIDUAL] = io[ZERO_RESIDUAL]
        return ZERO_FAILED
    n, m = model.n, model.m
    center = model.consts[kernel.CENTER:kernel.CENTER + 3]
    if io[ZERO_ITERATIONS] == 0.0:   # kept as it was: its matrix again
        kernel.assemble(model, zero.c, zero.r, zero.lam, kernel.Inputs(
            io[Z], io[RACK], center, extra.zero, extra.zero), kernel.SYMMETRIC, w)
    kept = factor_views(state, model, 0)
    w = newton.over(w, kept)
    kept.head[0] = 0.0
    mode, dense = newton.factorise(model, w)
    if mode == kkt.FAILED:
        return ZERO_FAILED
    bounds = w.dense if dense else model.bounds
    newton.keep(w, kept)   # the next command's tangent
    rot, spin, rhs, sol = zero.r[0], model.consts[kernel.SPIN:kernel.SPIN + 3], w.rhs, w.sol
    ax = rot[0, 0] * spin[0] + rot[0, 1] * spin[1] + rot[0, 2] * spin[2]
    ay = rot[1, 0] * spin[0] + rot[1, 1] * spin[1] + rot[1, 2] * spin[2]
    az = rot[2, 0] * spin[0] + rot[2, 1] * spin[1] + rot[2, 2] * spin[2]
    d_camber, d_toe = angle_gradients(ax, ay, az, model.consts[kernel.SIDE])
    radius = model.consts[kernel.RADIUS]
    p0 = p1 = p2 = 0.0   # the patch less the wheel centre, turned: a carrier point's offset
    if radius > 0:
        x_cp = extra.x_load
        load_point(model, rot, True, x_cp)
        p0, p1, p2 = (rot[0, 0] * (x_cp[0] - center[0]) + rot[0, 1] * (x_cp[1] - center[1])
                      + rot[0, 2] * (x_cp[2] - center[2]),
                      rot[1, 0] * (x_cp[0] - center[0]) + rot[1, 1] * (x_cp[1] - center[1])
                      + rot[1, 2] * (x_cp[2] - center[2]),
                      rot[2, 0] * (x_cp[0] - center[0]) + rot[2, 1] * (x_cp[1] - center[1])
                      + rot[2, 2] * (x_cp[2] - center[2]))
    dm, turn = extra.rates[0:3], extra.rates[3:6]   # (the rows of extra.rates: views)
    held, toe, camber = extra.rates[6], extra.rates[7], extra.rates[8]
    for j in range(8):   # the loads as generalized forces (columns)
        for i in range(n + m):
            rhs[i] = 0.0
        if j < 6:
            rhs[j] = 1.0
        else:   # Fy (6) or Fx (7) at the patch: the force and its moment p x e
            e0, e1 = (0.0, 1.0) if j == 6 else (1.0, 0.0)
            rhs[0], rhs[1] = e0, e1
            rhs[3], rhs[4], rhs[5] = forces._cross(p0, p1, p2, e0, e1, 0.0)
        kkt.solve_full(w, model.perm, bounds, mode)
        for i in range(3):
            dm[i, j], turn[i, j] = sol[i], sol[3 + i]
        held[j] = -sol[n + m - 1]
        toe[j] = d_toe[0] * sol[3] + d_toe[1] * sol[4] + d_toe[2] * sol[5]
        camber[j] = d_camber[0] * sol[3] + d_camber[1] * sol[4] + d_camber[2] * sol[5]
    out = io[ANSWER:ANSWER + RATES_SIZE]
    for i in range(RATES_SIZE):
        out[i] = np.nan
    if radius > 0:
        _, patch_dy, _ = point_velocity((dm[0, 6], dm[1, 6], dm[2, 6]),   # a carrier point
                                        (turn[0, 6], turn[1, 6], turn[2, 6]), (p0, p1, p2))
        out[0] = toe[6] * DEG * PER_KN
        out[1] = camber[6] * DEG * PER_KN
        out[2] = dm[1, 6] * PER_KN
        out[3] = patch_dy * PER_KN
        out[4] = held[6]
        out[5] = toe[7] * DEG * PER_KN
        out[6] = camber[7] * DEG * PER_KN
        out[7] = dm[0, 7] * PER_KN
    out[8] = toe[0] * DEG * PER_KN
    out[9] = dm[0, 0] * PER_KN
    out[10] = toe[5] * DEG * PER_KNM
    out[11] = camber[5] * DEG * PER_KNM
    si = out[MATRIX_SI:RATES_SIZE].reshape((6, 6))
    table = out[MATRIX:MATRIX_SI].reshape((6, 6))
    for j in range(6):   # m and rad per N and per N mm, then per N m
        scale = 1e3 if j >= 3 else 1.0
        for i in range(3):
            si[i, j] = dm[i, j] * 1e-3 * scale
            si[3 + i, j] = turn[i, j] * scale
    for i in range(6):   # m/N -> mm/kN, rad/N -> deg/kN (per kN m likewise)
        for j in range(6):
            table[i, j] = si[i, j] * (1e3 * PER_KN if i < 3 else DEG * PER_KN)
    io[CODE] = OK
    return OK
