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

numba's disk cache follows each file alone: kernel.py, kkt.py, newton.py, forces.py, so3.py
and patch.py are compiled in here (their digests below; test_statics_kernel says the values).
"""

import math
from typing import NamedTuple

from numba import njit
from numba.extending import register_jitable
import numpy as np

from . import forces, kernel, kkt, newton
from ..base.patch import patch_offset

jit = njit(cache=True, nogil=True, error_model='numpy')

KERNEL_DIGEST = 'e5ff0fb8efa959ef2e3b5f2009faf1931c9ded81016bac2d633c81d6a85e84f0'
KKT_DIGEST = 'd3d12e75f6d1f2b5c080b7cec2ca788eb028cbb9006dbf7774ffd86a948fcd9b'
NEWTON_DIGEST = '7475adadbbd683ecf60f04ca7716b59bc04f32c11487c90f9cd2d4604a815712'
FORCES_DIGEST = 'fa6bd2f179484c36a1db6b6f0a541d6ad6b8670137660327a6745fa9f3207336'
PATCH_DIGEST = '7617b861f96a597dfc1031314dfdee925963b63a94e3df13fe24e73a28863499'
# io: the command, then what it gives
Z, RACK, AT_CP, FORCE, MOMENT, ZERO_FROM, LOADED_FROM = 0, 1, 2, 3, 6, 9, 10
CODE, ITERATIONS, RESIDUAL, ZERO_ITERATIONS, ZERO_RESIDUAL, ANSWER = 11, 12, 13, 14, 15, 16
# where a solve starts: WARM the last equilibrium (zero-load: the same one if at the same
# travel and rack), KINEMATIC the pose written into the zero-load state (statics.py), ZERO
# the zero-load equilibrium of this command, the load in increments
WARM, KINEMATIC, ZERO = 0, 1, 2
# what a command gives (io[CODE])
OK, ZERO_FAILED, LOADED_FAILED, BEYOND = 0, 1, 2, 3
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


@register_jitable
def state_offset(bodies, m, which):
    """Return where equilibrium which (0 zero-load, 1 loaded; 2: the state's size) starts."""
    return which * (3 + 12 * bodies + m)


@jit
def views(state, bodies, m, which):
    """Return the Equilibrium views of a state: which 0 the zero-load one, 1 the loaded one."""
    o = state_offset(bodies, m, which)
    c = state[o + 3:o + 3 + 3 * bodies].reshape((bodies, 3))
    r = state[o + 3 + 3 * bodies:o + 3 + 12 * bodies].reshape((bodies, 3, 3))
    return Equilibrium(state[o:o + 3], c, r, state[o + 3 + 12 * bodies:o + 3 + 12 * bodies + m])


@jit
def _zero_load(model, state, io, w):
    """
    Make the zero-load state the equilibrium at io's travel and rack; return ok.

    Taken as it is at the same travel and rack (WARM), else solved from it (WARM: the last
    one; KINEMATIC: the pose statics.py wrote there) and kept if it converges.
    """
    z, rack = io[Z], io[RACK]
    zero = views(state, len(model.b_kind), model.m, 0)
    same = zero.head[2] == 1.0 and zero.head[0] == z and zero.head[1] == rack
    if same and io[ZERO_FROM] == WARM:
        io[ZERO_ITERATIONS] = 0.0
        return True
    c, r, lam = zero.c.copy(), zero.r.copy(), zero.lam.copy()
    center = model.consts[kernel.CENTER:kernel.CENTER + 3]
    ok, iterations, residual = newton.newton(
        model, c, r, lam, kernel.Inputs(z, rack, center, np.zeros(3), np.zeros(3)),
        newton.MAX_ITER, w)
    io[ZERO_ITERATIONS], io[ZERO_RESIDUAL] = iterations, residual
    if ok:
        zero.head[0], zero.head[1], zero.head[2] = z, rack, 1.0
        zero.c[:], zero.r[:], zero.lam[:] = c, r, lam
    return ok


@jit
def load_point(model, r0, at_cp, out):
    """
    Write the load's point (3,) on the carrier (design position) into out.

    The wheel centre, or (at_cp) the contact patch: the lowest point of the wheel circle in
    the zero-load pose (rotation r0), taken as a carrier point.
    """
    center = model.consts[kernel.CENTER:kernel.CENTER + 3]
    out[:] = center
    if not at_cp:
        return
    spin = model.consts[kernel.SPIN:kernel.SPIN + 3]
    a = r0 @ spin
    px, py, pz = patch_offset(a[0], a[1], a[2], model.consts[kernel.RADIUS])
    for i in range(3):
        out[i] += r0[0, i] * px + r0[1, i] * py + r0[2, i] * pz


@jit
def solve(ints, reals, state, io):
    """
    Solve one loaded command (io's travel, rack and load); return and write its code.

    OK: the answer in io from ANSWER (forces.answer_offsets), the loaded state kept.
    ZERO_FAILED, LOADED_FAILED: no convergence from the start asked (residual in io);
    BEYOND: converged, but a bushing beyond the model (the answer's validity says which).
    """
    model = kernel.unpack(ints, reals)
    w = newton.work(model)
    io[CODE] = ZERO_FAILED
    if (io[AT_CP] != 0.0 or io[LOADED_FROM] != WARM) and not _zero_load(model, state, io, w):
        io[RESIDUAL] = io[ZERO_RESIDUAL]
        return ZERO_FAILED
    bodies = len(model.b_kind)
    start = views(state, bodies, model.m, 0 if io[LOADED_FROM] != WARM else 1)
    c, r, lam = start.c.copy(), start.r.copy(), start.lam.copy()
    x_load = np.empty(3)
    load_point(model, views(state, bodies, model.m, 0).r[0], io[AT_CP] != 0.0, x_load)
    inputs = kernel.Inputs(io[Z], io[RACK], x_load, io[FORCE:FORCE + 3].copy(),
                           io[MOMENT:MOMENT + 3].copy())
    if io[LOADED_FROM] == WARM:
        ok, iterations, residual = newton.newton(model, c, r, lam, inputs, newton.MAX_ITER, w)
    else:
        ok, iterations, residual = newton.loaded(model, c, r, lam, inputs, w)
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
    done.c[:], done.r[:], done.lam[:] = c, r, lam
    io[CODE] = OK
    return OK


@jit
def angle_gradients(spin, side_sign):
    """
    Return d camber / d w and d toe / d w (3,) rad/rad of a spin axis a turned by w.

    camber = -atan2(a_z, |a_xy|), toe = atan2(a_x, s a_y) (so3.camber_toe); a moves by
    w x a, so d/dw = a x d/da.
    """
    ax, ay, az = spin[0], spin[1], spin[2]
    flat = math.hypot(ax, ay)
    tilt, turn = az * az + flat * flat, ax * ax + ay * ay
    cam = np.array([az * ax / flat / tilt, az * ay / flat / tilt, -flat / tilt])
    toe = np.array([side_sign * ay / turn, side_sign * -ax / turn, 0.0])
    return np.cross(spin, cam), np.cross(spin, toe)


@jit
def rates(ints, reals, state, io):
    """
    Write the rates and the 6x6 compliance at io's travel and rack (from RATES); return code.

    First-order, by the implicit function theorem, at the zero-load equilibrium (which holds
    the springs' preload): the KKT system [[H, J^T], [J, 0]] (dq, dlambda) = (Q, 0) of each
    generalized load Q, one factorisation for all. Columns: Fx, Fy, Fz, Mx, My, Mz at the
    wheel centre (per N, per N mm), then Fy and Fx at the contact patch. The carrier's dq is
    its move dM (mm) and turn w (rad); the holding force changes by -dlambda of the travel.
    """
    model = kernel.unpack(ints, reals)
    w = newton.work(model)
    io[CODE] = ZERO_FAILED
    zero = views(state, len(model.b_kind), model.m, 0)
    if not _zero_load(model, state, io, w):
        io[RESIDUAL] = io[ZERO_RESIDUAL]
        return ZERO_FAILED
    n, m = model.n, model.m
    center = model.consts[kernel.CENTER:kernel.CENTER + 3]
    if io[ZERO_ITERATIONS] == 0.0:   # kept as it was: its matrix again
        kernel.assemble(model, zero.c, zero.r, zero.lam, kernel.Inputs(
            io[Z], io[RACK], center, np.zeros(3), np.zeros(3)), False, w.grad, w.hess,
            w.values, w.rows, w.scratch)
    mode, bounds = newton.factorise(w.hess, w.rows, model.perm, model.bounds, w.a, w.piv,
                                    w.dense)
    if mode == kkt.FAILED:
        return ZERO_FAILED
    rot = zero.r[0]
    d_camber, d_toe = angle_gradients(rot @ model.consts[kernel.SPIN:kernel.SPIN + 3],
                                      model.consts[kernel.SIDE])
    radius = model.consts[kernel.RADIUS]
    patch = np.zeros(3)
    if radius > 0:
        x_cp = np.empty(3)
        load_point(model, rot, True, x_cp)
        patch = rot @ (x_cp - center)
    dm, turn, held = np.empty((3, 8)), np.empty((3, 8)), np.empty(8)
    for j in range(8):   # the loads as generalized forces (columns)
        w.rhs[:] = 0.0
        if j < 6:
            w.rhs[j] = 1.0
        else:
            e = np.zeros(3)
            e[1 if j == 6 else 0] = 1.0
            w.rhs[0:3] = e
            w.rhs[3:6] = np.cross(patch, e)
        kkt.solve_full(w.a, w.piv, bounds, mode, model.perm, w.hess, w.rows, w.rhs, w.sol,
                       w.b)
        dm[:, j], turn[:, j], held[j] = w.sol[0:3], w.sol[3:6], -w.sol[n + m - 1]
    out = io[ANSWER:ANSWER + RATES_SIZE]
    toe, camber = d_toe @ turn, d_camber @ turn
    out[:] = np.nan
    if radius > 0:
        patch_move = dm[:, 6] + np.cross(turn[:, 6], patch)   # the patch as a carrier point
        out[0] = toe[6] * DEG * PER_KN
        out[1] = camber[6] * DEG * PER_KN
        out[2] = dm[1, 6] * PER_KN
        out[3] = patch_move[1] * PER_KN
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
