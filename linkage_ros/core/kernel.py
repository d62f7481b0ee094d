"""
Compiled kernels of the fast method.

The guidance equations on the carrier pose, Newton, the tangent predictor, the branch check,
the residual and the condition number.

Every function here is numba-compiled (njit, cache=True) and works on plain float64 arrays
and scalars, one pose at a time, without a numpy call per operation: a single command is a
handful of these calls, and the batched sweep is the same calls in a compiled loop. They
live in one module on purpose: numba's on-disk cache is invalidated per source file, so a
kernel that calls a kernel of another file could keep running stale code after an edit.

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

from numba import njit
import numpy as np

SPHERE, LINE = 0.0, 1.0   # equation table columns (see above)
KIND, POINT, BASE, LENGTH, STEER, NORMAL = 0, 1, 4, 7, 8, 9
COLUMNS = 12
N_EQUATIONS = 5
FREE = (0, 1, 3, 4, 5)   # Jacobian columns of the unknowns: x, y of M and omega
# A solved position packed in one array (one kernel argument instead of many): travel and
# rack (mm), M (3,), R (3, 3), Jacobian (5, 6), then what it reports (report()): residual
# (mm), condition number, camber and toe (rad), quaternion (x, y, z, w) of R.
TRAVEL, RACK, CENTER, ROTATION, JACOBIAN = 0, 1, 2, 5, 14
RESIDUAL, CONDITION, CAMBER, TOE, QUATERNION = 44, 45, 46, 47, 48
STATE_SIZE = 52

jit = njit(cache=True, nogil=True, error_model='numpy')


# --- rotations and angles ------------------------------------------------------------------

@jit
def rotate(rotation, x, y, z):
    """Return R v for v = (x, y, z), as three floats."""
    return (rotation[0, 0] * x + rotation[0, 1] * y + rotation[0, 2] * z,
            rotation[1, 0] * x + rotation[1, 1] * y + rotation[1, 2] * z,
            rotation[2, 0] * x + rotation[2, 1] * y + rotation[2, 2] * z)


@jit
def exp_so3(x, y, z, out):
    """
    Write into out (3, 3) the rotation matrix of the rotation vector (x, y, z) (Rodrigues).

    R = I + a K + b (w w^T - |w|^2 I), K = [w]x, a = sin t / t, b = (1 - cos t) / t^2.
    """
    t2 = x * x + y * y + z * z
    if t2 < 1e-16:
        a, b = 1.0 - t2 / 6.0, 0.5 - t2 / 24.0
    else:
        t = math.sqrt(t2)
        a, b = math.sin(t) / t, (1.0 - math.cos(t)) / t2
    out[0, 0], out[0, 1], out[0, 2] = (
        1.0 - b * (y * y + z * z), b * x * y - a * z, b * x * z + a * y)
    out[1, 0], out[1, 1], out[1, 2] = (
        b * x * y + a * z, 1.0 - b * (x * x + z * z), b * y * z - a * x)
    out[2, 0], out[2, 1], out[2, 2] = (
        b * x * z - a * y, b * y * z + a * x, 1.0 - b * (x * x + y * y))


@jit
def turn(x, y, z, rotation, out):
    """Write exp_so3(x, y, z) @ rotation into out (3, 3); out may be rotation itself."""
    step = np.empty((3, 3))
    exp_so3(x, y, z, step)
    for j in range(3):   # column by column, so that out may be rotation
        c0, c1, c2 = rotation[0, j], rotation[1, j], rotation[2, j]
        for i in range(3):
            out[i, j] = step[i, 0] * c0 + step[i, 1] * c1 + step[i, 2] * c2


@jit
def quaternion(rotation, out):
    """Write into out (4,) the unit quaternion of rotation as x, y, z, w; w >= 0 (Shepperd)."""
    m = rotation
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    if trace >= m[0, 0] and trace >= m[1, 1] and trace >= m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + trace)
        x, y, z, w = ((m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s,
                      (m[1, 0] - m[0, 1]) / s, s / 4)
    elif m[0, 0] >= m[1, 1] and m[0, 0] >= m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        x, y, z, w = (s / 4, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s,
                      (m[2, 1] - m[1, 2]) / s)
    elif m[1, 1] >= m[2, 2]:
        s = 2.0 * math.sqrt(1.0 - m[0, 0] + m[1, 1] - m[2, 2])
        x, y, z, w = ((m[0, 1] + m[1, 0]) / s, s / 4, (m[1, 2] + m[2, 1]) / s,
                      (m[0, 2] - m[2, 0]) / s)
    else:
        s = 2.0 * math.sqrt(1.0 - m[0, 0] - m[1, 1] + m[2, 2])
        x, y, z, w = ((m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, s / 4,
                      (m[1, 0] - m[0, 1]) / s)
    sign = 1.0 if w >= 0.0 else -1.0
    out[0], out[1], out[2], out[3] = sign * x, sign * y, sign * z, sign * w


@jit
def camber_toe(ax, ay, az, side_sign):
    """
    Return camber and toe (rad) of an outboard spin-axis vector a (any length).

    camber = -atan2(a_z, |a_xy|): + = top of the wheel outboard (eq. 14 made side-aware);
    toe = atan2(a_x, a_y_outboard): + = toe-in. side_sign: +1 left wheel, -1 right wheel.
    """
    return -math.atan2(az, math.hypot(ax, ay)), math.atan2(ax, side_sign * ay)


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


# --- linear algebra on the 5 unknowns ------------------------------------------------------

@jit
def solve_free(jac, rhs, x):
    """
    Solve J_free x = rhs into x (5,), J_free the FREE columns of jac (5, 6).

    By Gaussian elimination with partial pivoting. Returns False if J_free is singular or not
    finite, else True.
    """
    a = np.empty((5, 6))
    for i in range(5):
        for j in range(5):
            a[i, j] = jac[i, FREE[j]]
        a[i, 5] = rhs[i]
    for col in range(5):
        pivot = col
        for row in range(col + 1, 5):
            if abs(a[row, col]) > abs(a[pivot, col]):
                pivot = row
        if not abs(a[pivot, col]) > 0.0:   # zero or NaN
            return False
        if pivot != col:
            for j in range(col, 6):
                a[col, j], a[pivot, j] = a[pivot, j], a[col, j]
        for row in range(col + 1, 5):
            factor = a[row, col] / a[col, col]
            for j in range(col, 6):
                a[row, j] -= factor * a[col, j]
    for i in range(4, -1, -1):
        total = a[i, 5]
        for j in range(i + 1, 5):
            total -= a[i, j] * x[j]
        x[i] = total / a[i, i]
    return np.isfinite(x).all()


@jit
def condition(jac):
    """
    Return the 2-norm condition number of J_free (the FREE columns of jac (5, 6)).

    By one-sided Jacobi (Hestenes) SVD: accurate to rounding for the small singular values
    too. inf if singular.
    """
    a = np.empty((5, 5))
    for i in range(5):
        for j in range(5):
            a[i, j] = jac[i, FREE[j]]
    for _ in range(60):
        worst = 0.0   # largest cosine between two columns before this sweep
        for p in range(4):
            for q in range(p + 1, 5):
                alpha = beta = gamma = 0.0
                for i in range(5):
                    alpha += a[i, p] * a[i, p]
                    beta += a[i, q] * a[i, q]
                    gamma += a[i, p] * a[i, q]
                cosine = abs(gamma) / math.sqrt(alpha * beta)
                if not cosine > 1e-15:
                    continue
                worst = max(worst, cosine)
                zeta = (beta - alpha) / (2.0 * gamma)
                t = math.copysign(1.0, zeta) / (abs(zeta) + math.sqrt(1.0 + zeta * zeta))
                c = 1.0 / math.sqrt(1.0 + t * t)
                s = c * t
                for i in range(5):
                    ap, aq = a[i, p], a[i, q]
                    a[i, p], a[i, q] = c * ap - s * aq, s * ap + c * aq
        if worst < 1e-8:   # the column norms are the singular values to O(cosine^2)
            break
    largest, smallest = 0.0, np.inf
    for j in range(5):
        norm = math.sqrt(a[0, j] ** 2 + a[1, j] ** 2 + a[2, j] ** 2 + a[3, j] ** 2 + a[4, j] ** 2)
        largest, smallest = max(largest, norm), min(smallest, norm)
    if not np.isfinite(largest):
        return np.nan
    return largest / smallest if smallest > 0.0 else np.inf


# --- Newton, tangent, continuation step ----------------------------------------------------

@jit
def correct(eqs, z0, travel, rack, center, rotation, tol, max_iter, jac):
    """
    Correct the pose (center, rotation) in place by Newton to the pose at travel and rack.

    Travel and rack are in mm: Z_M = z0 + travel is imposed, x, y of M and the rotation are
    solved. Stops when every guidance equation holds to tol (mm). jac (5, 6) receives the
    Jacobian at the last pose (the converged one: it serves the next tangent and the
    condition number). Returns (iterations, converged).
    """
    f = np.empty(5)
    rhs = np.empty(5)
    dx = np.empty(5)
    center[2] = z0 + travel
    for iteration in range(max_iter + 1):
        linearize(eqs, center, rotation, rack, f, jac)
        worst = 0.0
        for i in range(5):
            if not abs(f[i]) <= worst:
                worst = abs(f[i])
        if worst <= tol:
            return iteration, True
        if iteration == max_iter or not np.isfinite(worst):
            return iteration, False
        for i in range(5):
            rhs[i] = -f[i]
        if not solve_free(jac, rhs, dx):
            return iteration, False
        center[0] += dx[0]
        center[1] += dx[1]
        turn(dx[2], dx[3], dx[4], rotation, rotation)
    return max_iter, False


@jit
def predict(eqs, center0, rotation0, jac0, rack0, h, h_rack, center, rotation):
    """
    Guess to first order (tangent) the pose h mm of travel and h_rack mm of rack further on.

    From the solved pose (center0, rotation0) with Jacobian jac0, by the implicit function
    theorem (J_free dx = -J_travel h - J_rack h_rack). Writes center (3,) and rotation (3, 3);
    returns False if the Jacobian is singular, else True.
    """
    column = np.empty(5)
    slope = np.empty(5)
    for i in range(5):
        column[i] = -jac0[i, 2]
    if not solve_free(jac0, column, slope):
        return False
    d = slope * h
    center[0], center[1], center[2] = center0[0] + d[0], center0[1] + d[1], center0[2] + h
    if h_rack != 0.0:
        rack_column(eqs, center0, rotation0, rack0, column)
        for i in range(5):
            column[i] = -column[i]
        if not solve_free(jac0, column, slope):
            return False
        d += slope * h_rack
        center[0], center[1] = center0[0] + d[0], center0[1] + d[1]
    turn(d[2], d[3], d[4], rotation0, rotation)
    return True


@jit
def views(state):
    """Return views of a packed state: center (3,), rotation (3, 3), jacobian (5, 6)."""
    return (state[CENTER:CENTER + 3], state[ROTATION:ROTATION + 9].reshape((3, 3)),
            state[JACOBIAN:JACOBIAN + 30].reshape((5, 6)))


@jit
def step(eqs, z0, tol, max_iter, slack, state0, travel, rack, state):
    """
    Take one continuation step from the solved state0 to (travel, rack) (mm).

    Tangent prediction, Newton correction to tol, branch check (on_branch, with slack mm).
    Writes the new position into state (not its report). Returns (iterations, accepted).
    """
    center0, rotation0, jac0 = views(state0)
    center, rotation, jac = views(state)
    guess_center, guess_rotation = np.empty(3), np.empty((3, 3))
    h, h_rack = travel - state0[TRAVEL], rack - state0[RACK]
    state[TRAVEL], state[RACK] = travel, rack
    if not predict(eqs, center0, rotation0, jac0, state0[RACK], h, h_rack, guess_center,
                   guess_rotation):
        return 0, False
    center[:] = guess_center
    rotation[:, :] = guess_rotation
    iterations, converged = correct(eqs, z0, travel, rack, center, rotation, tol, max_iter, jac)
    return iterations, converged and on_branch(eqs, guess_center, guess_rotation, center,
                                               rotation, max(abs(h), abs(h_rack)), slack)


@jit
def on_branch(eqs, guess_center, guess_rotation, center, rotation, step_length, slack):
    """
    Tell whether the converged pose is where continuation along the branch predicts it.

    A tangent prediction misses by O(step^2); a jump to another assembly branch moves the
    carrier by a link-length scale. Half the step (mm, plus a slack for the tolerance the
    poses hold to) separates the two.
    """
    shift = carrier_shift(eqs, guess_center, guess_rotation, center, rotation)
    return shift <= 0.5 * abs(step_length) + slack


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
def walk(eqs, spin_axis, side_sign, z0, tol, max_iter, slack, max_step, min_step, state0,
         target, rack, low, high):
    """
    Continue from the solved state0 to (target travel, rack) (mm) along a straight line.

    The steps are at most max_step long, halved on failure and doubled on success.

    Returns (state, steps, iterations of the last step, stalled, low, high): the last state
    reached (reported if the walk got to the target), the steps accepted, True if a step fell
    below min_step (the walk stopped there), and the travel range low..high (mm) extended by
    every travel reached.
    """
    start, start_rack = state0[TRAVEL], state0[RACK]
    length = max(abs(target - start), abs(rack - start_rack))
    done, step_length = 0.0, min(max_step, length)
    state, steps, iterations = state0.copy(), 0, 0   # a copy: state0 may be read-only
    while done < length:
        step_length, fraction = next_step(length, done, step_length)
        new = np.empty(STATE_SIZE)
        iterations, accepted = step(eqs, z0, tol, max_iter, slack, state,
                                    start + fraction * (target - start),
                                    start_rack + fraction * (rack - start_rack), new)
        if accepted:
            state, steps = new, steps + 1
            low, high = min(low, new[TRAVEL]), max(high, new[TRAVEL])
            if fraction == 1.0:
                report(eqs, spin_axis, side_sign, state)
        done, step_length = after_step(accepted, length, done, step_length, fraction, max_step)
        if not accepted and step_length < min_step:
            return state, steps, iterations, True, low, high
    return state, steps, iterations, False, low, high


@jit
def report(eqs, spin_axis, side_sign, state):
    """
    Fill in what a solved state reports.

    That is the residual (mm), the condition number of the Jacobian, camber and toe (rad) of
    the spin axis (spin_axis (3,) at design, side_sign +1 left, -1 right), and the carrier
    orientation as a quaternion (x, y, z, w).
    """
    center, rotation, jac = views(state)
    ax, ay, az = rotate(rotation, spin_axis[0], spin_axis[1], spin_axis[2])
    state[CAMBER], state[TOE] = camber_toe(ax, ay, az, side_sign)
    state[RESIDUAL] = residual(eqs, center, rotation, state[RACK])
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
def slope_many(jac, out):
    """
    Write d(free unknowns)/d(travel) of n solved poses into out (n, 5): J_free x = -J_travel.

    jac (n, 5, 6): the Jacobians there (the implicit function theorem; NaN where singular).
    """
    rhs = np.empty(5)
    for n in range(jac.shape[0]):
        for i in range(5):
            rhs[i] = -jac[n, i, 2]
        if not solve_free(jac[n], rhs, out[n]):
            out[n, :] = np.nan


@jit
def exp_so3_many(omegas, out):
    """Write the rotation matrices of n rotation vectors omegas (n, 3) into out (n, 3, 3)."""
    for n in range(omegas.shape[0]):
        exp_so3(omegas[n, 0], omegas[n, 1], omegas[n, 2], out[n])


@jit
def quaternion_many(rotations, out):
    """Write the quaternions (x, y, z, w) of rotations (n, 3, 3) into out (n, 4)."""
    for n in range(rotations.shape[0]):
        quaternion(rotations[n], out[n])


@jit
def camber_toe_many(axes, side_sign, camber, toe):
    """Write camber and toe (rad) of n spin-axis vectors axes (n, 3) into camber, toe (n,)."""
    for n in range(axes.shape[0]):
        camber[n], toe[n] = camber_toe(axes[n, 0], axes[n, 1], axes[n, 2], side_sign)


@jit
def step_many(eqs, z0, tol, max_iter, slack, start, start_states, travels, rack, states,
              iterations, accepted):
    """
    Take step() to each of n travels (n,) at one rack (mm).

    Position n starts from the solved state start_states[start[n]]; states (n, STATE_SIZE)
    receive the results, without report; iterations and accepted (n,) what step() returns.
    """
    for n in range(travels.shape[0]):
        iterations[n], accepted[n] = step(eqs, z0, tol, max_iter, slack, start_states[start[n]],
                                          travels[n], rack, states[n])
