# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Compiled kernels of the fast method: guidance equations, Newton, tangent, branch check, walk.

Every function here is compiled (base/compiled.py's jit) and works on plain float64 arrays
and scalars, one pose at a time, without a numpy call per operation: a single command is a
handful of these calls, and the batched sweep is the same calls in a compiled loop. They
call so3.py's rotations and jacobian_kernel.py's linear algebra on the unknowns (solve,
determinant, condition number; FREE, read here as kernel.FREE), compiled in.

The mechanism is a table of its 5 guidance equations, one row each (mechanism.compile_scene
builds it; lengths in mm, vehicle frame, design position):

    sphere row (eq. 2, 13): KIND = SPHERE, POINT = carrier point minus M0, BASE = body point,
                            LENGTH = link length, STEER = 1 where BASE moves with the rack
    line row (strut):       KIND = LINE, POINT = carrier point minus M0, BASE = top mount T,
                            NORMAL = carrier-fixed unit normal of the strut line

A pose is the wheel centre M (3,) and the carrier rotation R (3, 3) relative to design: a
carrier point at design position b0 is at M + R (b0 - M0). Residuals are lengths in mm:
    sphere: (|B - A|^2 - l^2) / 2l   (smooth; equals |B - A| - l to first order)
    line:   (T - C) . n              (distance of T from the strut line along n = R n0)
The Jacobian (5, 6) is d/d(M, omega), omega a small rotation applied in the vehicle frame
(R <- exp(omega) R). Column 2 (dZ_M) is the travel direction; FREE are the unknowns.
"""

import math
from typing import NamedTuple

import numpy as np

from .jacobian_kernel import condition, determinant, FREE, solve_free  # noqa: F401 FREE
from ..base.compiled import jit
from ..base.so3 import camber_toe, quaternion, rotate, turn

SPHERE, LINE = 0.0, 1.0   # equation table columns (see above)
KIND, POINT, BASE, LENGTH, STEER, NORMAL = 0, 1, 4, 7, 8, 9
COLUMNS = 12
N_EQUATIONS = 5
# A solved position packed in one array (one kernel argument instead of many): travel and
# rack (mm), M (3,), R (3, 3), Jacobian (5, 6), then what it reports (report()): residual
# (mm), condition number, camber and toe (rad), quaternion (x, y, z, w) of R. Compiled code
# reads it here (views()); Python code through state.py only.
TRAVEL, RACK, CENTER, ROTATION, JACOBIAN = 0, 1, 2, 5, 14
RESIDUAL, CONDITION, CAMBER, TOE, QUATERNION = 44, 45, 46, 47, 48
STATE_SIZE = 52
# How a walk ended (Walked.outcome)
REACHED, STALLED, SUBSTEP_LIMIT = 0, 1, 2


class Setup(NamedTuple):
    """
    What the compiled solver needs of a mechanism and its settings. Lengths in mm.

    walk() takes it as tuple(setup), and names it again: numba types a plain tuple in C, a
    named one in Python, 2 us more a call (a fifth of a command).
    """

    equations: np.ndarray    # (5, COLUMNS) the guidance equations (mechanism.compile_scene)
    spin_axis: np.ndarray    # (3,) design outboard spin-axis unit vector
    side_sign: float         # +1 left wheel, -1 right wheel
    z0: float                # design wheel-centre z; travel = Z_M - z0
    tol: float               # Newton stops when every guidance equation holds to tol
    max_iter: int            # Newton iterations per step
    slack: float             # branch check: what a converged pose may add to half the step
    max_step: float          # longest substep of a walk
    min_step: float          # a failing substep shorter than this stops the walk (stalled)
    max_substeps: int        # substeps a walk may try, accepted or not


class Walked(NamedTuple):
    """What walk() returns."""

    state: np.ndarray   # (STATE_SIZE,) the last state reached; reported if outcome is REACHED
    steps: int          # substeps accepted
    iterations: int     # Newton iterations of the last substep
    outcome: int        # REACHED, STALLED (a substep failed below min_step), SUBSTEP_LIMIT
    low: float          # the travel range (mm) given, extended by every travel reached
    high: float


# --- the guidance equations ----------------------------------------------------------------

@jit
def linearize(eqs, center, rotation, rack, f, jac):
    """Write residuals f (5,) and Jacobian jac (5, 6) at pose (center, rotation), rack (mm)."""
    for i in range(eqs.shape[0]):
        e = eqs[i]
        rx, ry, rz = rotate(rotation, e[POINT], e[POINT + 1], e[POINT + 2])
        if e[KIND] == SPHERE:
            # F = (|d|^2 - l^2) / 2l, dF = (d / l) . (dM + omega x r)
            length = e[LENGTH]
            dx = rx + center[0] - e[BASE]
            dy = ry + center[1] - e[BASE + 1] - rack * e[STEER]
            dz = rz + center[2] - e[BASE + 2]
            f[i] = (dx * dx + dy * dy + dz * dz - length * length) * (0.5 / length)
            dx, dy, dz = dx / length, dy / length, dz / length
            jac[i, 0], jac[i, 1], jac[i, 2] = dx, dy, dz
            jac[i, 3], jac[i, 4], jac[i, 5] = (
                ry * dz - rz * dy, rz * dx - rx * dz, rx * dy - ry * dx)
        else:
            # F = (T - C) . n, n = R n0; dF = -n . dM + omega . (n x (T - C) - r x n)
            nx, ny, nz = rotate(rotation, e[NORMAL], e[NORMAL + 1], e[NORMAL + 2])
            tx = e[BASE] - center[0] - rx
            ty = e[BASE + 1] - center[1] - ry
            tz = e[BASE + 2] - center[2] - rz
            f[i] = tx * nx + ty * ny + tz * nz
            jac[i, 0], jac[i, 1], jac[i, 2] = -nx, -ny, -nz
            jac[i, 3] = (ny * tz - nz * ty) - (ry * nz - rz * ny)
            jac[i, 4] = (nz * tx - nx * tz) - (rz * nx - rx * nz)
            jac[i, 5] = (nx * ty - ny * tx) - (rx * ny - ry * nx)


@jit
def residual(eqs, center, rotation, rack):
    """
    Return the largest constraint violation (mm) as a true length.

    The violation is a link's length error or the strut line's distance from its top mount.
    NaN if any is NaN.
    """
    worst = 0.0
    for i in range(eqs.shape[0]):
        e = eqs[i]
        rx, ry, rz = rotate(rotation, e[POINT], e[POINT + 1], e[POINT + 2])
        if e[KIND] == SPHERE:
            dx = rx + center[0] - e[BASE]
            dy = ry + center[1] - e[BASE + 1] - rack * e[STEER]
            dz = rz + center[2] - e[BASE + 2]
            error = abs(math.sqrt(dx * dx + dy * dy + dz * dz) - e[LENGTH])
        else:
            nx, ny, nz = rotate(rotation, e[NORMAL], e[NORMAL + 1], e[NORMAL + 2])
            error = abs((e[BASE] - center[0] - rx) * nx + (e[BASE + 1] - center[1] - ry) * ny
                        + (e[BASE + 2] - center[2] - rz) * nz)
        if not error <= worst:   # NaN propagates
            worst = error
    return worst


@jit
def rack_column(eqs, center, rotation, rack, out):
    """Write d(residuals)/d(rack) into out (5,): the steer rows' base points move along +y."""
    for i in range(eqs.shape[0]):
        e = eqs[i]
        out[i] = 0.0
        if e[KIND] == SPHERE and e[STEER] != 0.0:
            ry = rotate(rotation, e[POINT], e[POINT + 1], e[POINT + 2])[1]
            d_y = ry + center[1] - e[BASE + 1] - rack * e[STEER]
            out[i] = -d_y / e[LENGTH] * e[STEER]


@jit
def carrier_shift(eqs, center, rotation, other_center, other_rotation):
    """Return the largest displacement (mm, along any axis) of a carrier point between poses."""
    worst = 0.0
    for i in range(eqs.shape[0]):
        e = eqs[i]
        a = rotate(rotation, e[POINT], e[POINT + 1], e[POINT + 2])
        b = rotate(other_rotation, e[POINT], e[POINT + 1], e[POINT + 2])
        for k in range(3):
            moved = abs(center[k] + a[k] - other_center[k] - b[k])
            if not moved <= worst:
                worst = moved
    return worst


# --- Newton, tangent, continuation step ----------------------------------------------------

@jit
def correct(eqs, z0, travel, rack, center, rotation, tol, max_iter, jac):
    """
    Correct the pose (center, rotation) in place by Newton to the pose at travel and rack.

    Travel and rack are in mm: Z_M = z0 + travel is imposed, x, y of M and the rotation are
    solved. Stops when every guidance equation holds to tol (mm). jac (5, 6) receives the
    Jacobian at the last pose (it serves the next tangent and the condition number). Returns
    (iterations, converged, det J_free one Newton step before the answer, 0.0 if none was
    taken: its sign is the answer's but within that last, smallest step of a fold).
    """
    f = np.empty(5)
    rhs = np.empty(5)
    dx = np.empty(5)
    center[2] = z0 + travel
    last = 0.0
    for iteration in range(max_iter + 1):
        linearize(eqs, center, rotation, rack, f, jac)
        worst = 0.0
        for i in range(5):
            if not abs(f[i]) <= worst:
                worst = abs(f[i])
        if worst <= tol:
            return iteration, True, last
        if iteration == max_iter or not np.isfinite(worst):
            return iteration, False, last
        for i in range(5):
            rhs[i] = -f[i]
        last = solve_free(jac, rhs, dx)
        if last == 0.0:
            return iteration, False, last
        center[0] += dx[0]
        center[1] += dx[1]
        turn(dx[2], dx[3], dx[4], rotation, rotation)
    return max_iter, False, last


@jit
def predict(eqs, center0, rotation0, jac0, rack0, h, h_rack, center, rotation):
    """
    Guess to first order (tangent) the pose h mm of travel and h_rack mm of rack further on.

    From the solved pose (center0, rotation0) with Jacobian jac0, by the implicit function
    theorem (J_free dx = -J_travel h - J_rack h_rack). Writes center (3,) and rotation (3, 3);
    returns the determinant of J_free at the solved pose, 0.0 if it is singular (no guess).
    """
    column = np.empty(5)
    slope = np.empty(5)
    for i in range(5):
        column[i] = -jac0[i, 2]
    determinant0 = solve_free(jac0, column, slope)
    if determinant0 == 0.0:
        return 0.0
    d = slope * h
    center[0], center[1], center[2] = center0[0] + d[0], center0[1] + d[1], center0[2] + h
    if h_rack != 0.0:
        rack_column(eqs, center0, rotation0, rack0, column)
        for i in range(5):
            column[i] = -column[i]
        if solve_free(jac0, column, slope) == 0.0:
            return 0.0
        d += slope * h_rack
        center[0], center[1] = center0[0] + d[0], center0[1] + d[1]
    turn(d[2], d[3], d[4], rotation0, rotation)
    return determinant0


@jit
def views(state):
    """Return views of a packed state: center (3,), rotation (3, 3), jacobian (5, 6)."""
    return (state[CENTER:CENTER + 3], state[ROTATION:ROTATION + 9].reshape((3, 3)),
            state[JACOBIAN:JACOBIAN + 30].reshape((5, 6)))


@jit
def step(setup, state0, travel, rack, state):
    """
    Take one continuation step from the solved state0 to (travel, rack) (mm).

    Tangent prediction, Newton correction to setup.tol, branch check (on_branch). Writes the
    new position into state (not its report). Returns (iterations, accepted).
    """
    eqs = setup.equations
    center0, rotation0, jac0 = views(state0)
    center, rotation, jac = views(state)
    guess_center, guess_rotation = np.empty(3), np.empty((3, 3))
    h, h_rack = travel - state0[TRAVEL], rack - state0[RACK]
    state[TRAVEL], state[RACK] = travel, rack
    determinant0 = predict(eqs, center0, rotation0, jac0, state0[RACK], h, h_rack,
                           guess_center, guess_rotation)
    if determinant0 == 0.0:
        return 0, False
    center[:] = guess_center
    rotation[:, :] = guess_rotation
    iterations, converged, determinant1 = correct(eqs, setup.z0, travel, rack, center,
                                                  rotation, setup.tol, setup.max_iter, jac)
    if not converged:
        return iterations, False
    if determinant1 == 0.0:   # the guess held: no Newton step factored a Jacobian
        determinant1 = determinant(jac)
    return iterations, on_branch(eqs, guess_center, guess_rotation, center, rotation,
                                 max(abs(h), abs(h_rack)), setup.slack,
                                 determinant0 * determinant1)


@jit
def on_branch(eqs, guess_center, guess_rotation, center, rotation, step_length, slack,
              orientation):
    """
    Tell whether the converged pose is where continuation along the branch predicts it.

    A tangent prediction misses by O(step^2); a jump to another assembly branch moves the
    carrier by a link-length scale. Half the step (mm, plus a slack for the tolerance the
    poses hold to) separates the two. Near a turning point, where the prediction is poor and
    the other branch close, orientation tells them apart: det J_free before times after the
    step, > 0 on the same side of every fold, < 0 across one, 0 at one.
    """
    shift = carrier_shift(eqs, guess_center, guess_rotation, center, rotation)
    return orientation > 0.0 and shift <= 0.5 * abs(step_length) + slack


@jit
def next_step(length, done, step_length):
    """
    Return the next substep of a walk along a line of length mm with done mm walked.

    Returns (its length, the fraction of the line reached at its end; exactly 1.0 at the end).
    """
    step_length = min(step_length, length - done)
    return step_length, 1.0 if step_length == length - done else (done + step_length) / length


@jit
def after_step(accepted, length, done, step_length, fraction, max_step):
    """
    Return (done, next step length) (mm) after a substep.

    An accepted step advances and doubles the step (up to max_step); a rejected one halves it.
    """
    if accepted:
        return length if fraction == 1.0 else done + step_length, min(2 * step_length, max_step)
    return done, step_length / 2


@jit
def walk(setup, state0, target, rack, low, high):
    """
    Continue from the solved state0 to (target travel, rack) (mm) along a straight line.

    setup: a Setup or the plain tuple of its fields. The substeps are at most max_step long,
    halved on failure and doubled on success; a walk tries at most max_substeps of them (a
    walk that needs more at max_step is not started). Returns a Walked: the last state
    reached (reported if it is the target), the substeps accepted, the iterations of the
    last, the outcome, and the travel range low..high (mm) extended by every travel reached.
    """
    setup = Setup(*setup)
    start, start_rack = state0[TRAVEL], state0[RACK]
    length = max(abs(target - start), abs(rack - start_rack))
    done, step_length = 0.0, min(setup.max_step, length)
    state, steps, iterations = state0.copy(), 0, 0   # a copy: state0 may be read-only
    if length > setup.max_step * setup.max_substeps:   # more substeps than allowed
        return Walked(state, 0, 0, SUBSTEP_LIMIT, low, high)
    for _ in range(setup.max_substeps):
        if done >= length:
            break
        step_length, fraction = next_step(length, done, step_length)
        new = np.empty(STATE_SIZE)
        iterations, accepted = step(setup, state, start + fraction * (target - start),
                                    start_rack + fraction * (rack - start_rack), new)
        if accepted:
            state, steps = new, steps + 1
            low, high = min(low, new[TRAVEL]), max(high, new[TRAVEL])
            if fraction == 1.0:
                report(setup, state)
        done, step_length = after_step(accepted, length, done, step_length, fraction,
                                       setup.max_step)
        if not accepted and step_length < setup.min_step:
            return Walked(state, steps, iterations, STALLED, low, high)
    outcome = REACHED if done >= length else SUBSTEP_LIMIT
    return Walked(state, steps, iterations, outcome, low, high)


@jit
def report(setup, state):
    """
    Fill in what a solved state reports.

    That is the residual (mm), the condition number of the Jacobian, camber and toe (rad) of
    the spin axis (setup.spin_axis at design, setup.side_sign +1 left, -1 right), and the
    carrier orientation as a quaternion (x, y, z, w).
    """
    center, rotation, jac = views(state)
    axis = setup.spin_axis
    ax, ay, az = rotate(rotation, axis[0], axis[1], axis[2])
    state[CAMBER], state[TOE] = camber_toe(ax, ay, az, setup.side_sign)
    state[RESIDUAL] = residual(setup.equations, center, rotation, state[RACK])
    state[CONDITION] = condition(jac)
    quaternion(rotation, state[QUATERNION:QUATERNION + 4])


# --- batches: the same kernels in a compiled loop ------------------------------------------

@jit
def linearize_many(eqs, centers, rotations, racks, f, jac):
    """Run linearize at n poses: centers (n, 3), rotations (n, 3, 3), racks (n,) (mm)."""
    for n in range(centers.shape[0]):
        linearize(eqs, centers[n], rotations[n], racks[n], f[n], jac[n])


@jit
def rack_column_many(eqs, centers, rotations, racks, out):
    """Run rack_column at n poses: centers (n, 3), rotations (n, 3, 3), racks (n,), out (n, 5)."""
    for n in range(centers.shape[0]):
        rack_column(eqs, centers[n], rotations[n], racks[n], out[n])


@jit
def residual_many(eqs, centers, rotations, racks, out):
    """Write the residual (mm) of n poses into out (n,): centers (n, 3), rotations (n, 3, 3)."""
    for n in range(centers.shape[0]):
        out[n] = residual(eqs, centers[n], rotations[n], racks[n])


@jit
def step_many(setup, start, start_states, travels, rack, states, iterations, accepted):
    """
    Take step() to each of n travels (n,) at one rack (mm).

    Position n starts from the solved state start_states[start[n]]; states (n, STATE_SIZE)
    receive the results, without report; iterations and accepted (n,) what step() returns.
    """
    for n in range(travels.shape[0]):
        iterations[n], accepted[n] = step(setup, start_states[start[n]], travels[n], rack,
                                          states[n])
