"""
Compiled kernels of the elements: the carrier's motion to second order, mount points, lengths.

numba-compiled (njit, cache=True) like kernel.py, and self-contained for the same reason
(numba's on-disk cache is per source file). The formulas are those of motion.py (the
carrier's velocity and acceleration per travel by the implicit function theorem), mounts.py
(points on the carrier, an arm, a link, a strut) and elements.py (length, ratio, ratio rate,
force, wheel rate). mm, rad, N; vehicle frame.

The Python side describes the geometry with named tuples (Rows, MountTable, SpringTable,
Poses); the kernels take the two static ones packed as tables with named columns (pack_rows,
pack_elements), as kernel.py takes its equation table: numba types each array argument on
every call, and on the one-command path that typing, not the arithmetic, is the cost.
"""

import math
from typing import NamedTuple

from numba import njit
import numpy as np

CARRIER, ARM, LINK, ALONG = 0, 1, 2, 3      # MountTable.kind
FREE = (0, 1, 3, 4, 5)   # Jacobian columns of the unknowns (kernel.FREE); 2 is the travel
# pack_rows columns: one row per guidance equation
R_LINE, R_OFFSET, R_BASE, R_STEER, R_LENGTH, R_NORMAL, ROW_COLUMNS = 0, 1, 4, 7, 8, 9, 12
# pack_elements columns: one row per element (a mount alone: body, rate, free length unused)
(E_KIND, E_OFFSET, E_BASE, E_AXIS, E_COEFF, E_STEER, E_BODY, E_RATE, E_FREE,
 ELEMENT_COLUMNS) = 0, 1, 4, 7, 10, 13, 14, 17, 18, 19

jit = njit(cache=True, nogil=True, error_model='numpy')


class Rows(NamedTuple):
    """The guidance equations as geometry, in the row order of the mechanism's Jacobian."""

    line: np.ndarray      # (5,) bool: a strut line row (else a sphere row)
    offset: np.ndarray    # (5, 3) mm: the row's carrier point minus M0 (carrier frame)
    base: np.ndarray      # (5, 3) mm: body point A (sphere) or top mount T (line), rack 0
    steer: np.ndarray     # (5,) 1.0 where A moves with the rack along +y
    length: np.ndarray    # (5,) mm: link length (sphere rows; 1.0 on line rows)
    normal: np.ndarray    # (5, 3) carrier-fixed unit normal of the strut line at design


class MountTable(NamedTuple):
    """k mounts, design position: what moves each point (mounts.mount_table builds it)."""

    kind: np.ndarray     # (k,) int64: CARRIER, ARM, LINK or ALONG
    offset: np.ndarray   # (k, 3) mm: the carrier point that moves it, minus M0 (the mount
    #                      point itself on the carrier, else the constraint's joint)
    base: np.ndarray     # (k, 3) mm: arm axis point A0; link body end B (rack 0)
    axis: np.ndarray     # (k, 3): arm axis unit vector u
    coeff: np.ndarray    # (k, 3): arm: the point's design coordinates in (u, e1, e2) from A0;
    #                      link: (fraction s from B to the joint, 0, 0)
    steer: np.ndarray    # (k,) 1.0 where a link's body end moves with the rack along +y


class SpringTable(NamedTuple):
    """k elements' body points (mm) and springs (rate N/mm, free length mm; NaN if none)."""

    body: np.ndarray          # (k, 3)
    rate: np.ndarray          # (k,)
    free_length: np.ndarray   # (k,)


class Poses(NamedTuple):
    """n solved poses: wheel centre (n, 3) mm, rotation (n, 3, 3), rack (n,) mm, Jacobian."""

    center: np.ndarray
    rotation: np.ndarray
    rack: np.ndarray
    jacobian: np.ndarray   # (n, 5, 6) d(residuals)/d(M, omega) at each pose


def pack_rows(rows: Rows) -> np.ndarray:
    """Pack Rows into the kernels' (5, ROW_COLUMNS) table."""
    return np.ascontiguousarray(np.column_stack((
        rows.line.astype(float), rows.offset, rows.base, rows.steer, rows.length, rows.normal)))


def pack_elements(mounts: MountTable, springs: SpringTable | None = None) -> np.ndarray:
    """Pack k mounts (and their elements' springs) into the kernels' (k, ELEMENT_COLUMNS)."""
    k = len(mounts.kind)
    if springs is None:
        springs = SpringTable(np.zeros((k, 3)), np.full(k, np.nan), np.full(k, np.nan))
    return np.ascontiguousarray(np.column_stack((
        mounts.kind.astype(float), mounts.offset, mounts.base, mounts.axis, mounts.coeff,
        mounts.steer, springs.body, springs.rate, springs.free_length)).reshape(
            k, ELEMENT_COLUMNS))


@jit
def cross(a, b, out):
    """Write a x b (3,) into out (3,)."""
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


@jit
def rotate(rotation, v, out):
    """Write R v (3,) into out (3,)."""
    for k in range(3):
        out[k] = rotation[k, 0] * v[0] + rotation[k, 1] * v[1] + rotation[k, 2] * v[2]


@jit
def dot(a, b):
    """Return a . b of two (3,) arrays."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@jit
def factor(jac, lu, pivots):
    """LU-factor J_free (the FREE columns of jac (5, 6)) into lu (5, 5); False if singular."""
    for i in range(5):
        for j in range(5):
            lu[i, j] = jac[i, FREE[j]]
        pivots[i] = i
    for col in range(5):
        best = col
        for row in range(col + 1, 5):
            if abs(lu[row, col]) > abs(lu[best, col]):
                best = row
        if not abs(lu[best, col]) > 0.0:   # zero or NaN
            return False
        if best != col:
            for j in range(5):
                lu[col, j], lu[best, j] = lu[best, j], lu[col, j]
            pivots[col], pivots[best] = pivots[best], pivots[col]
        for row in range(col + 1, 5):
            lu[row, col] /= lu[col, col]
            for j in range(col + 1, 5):
                lu[row, j] -= lu[row, col] * lu[col, j]
    return True


@jit
def solve(lu, pivots, rhs, x):
    """Solve J_free x = rhs (5,) into x (5,) from factor()'s lu and pivots."""
    for i in range(5):
        total = rhs[pivots[i]]
        for j in range(i):
            total -= lu[i, j] * x[j]
        x[i] = total
    for i in range(4, -1, -1):
        total = x[i]
        for j in range(i + 1, 5):
            total -= lu[i, j] * x[j]
        x[i] = total / lu[i, i]


@jit
def carrier_rates(rows, center, rotation, rack, jac, motion):
    """
    Write the carrier's v, w, a, alpha per travel into motion (4, 3) (motion.py's formulas).

    NaN if the Jacobian is singular there.
    """
    lu, pivots = np.empty((5, 5)), np.empty(5, np.int64)
    rhs, x = np.empty(5), np.empty(5)
    if not factor(jac, lu, pivots):
        motion[:] = np.nan
        return
    for i in range(5):
        rhs[i] = -jac[i, 2]
    solve(lu, pivots, rhs, x)
    v, w = motion[0], motion[1]
    v[0], v[1], v[2], w[0], w[1], w[2] = x[0], x[1], 1.0, x[2], x[3], x[4]
    scratch = np.empty((8, 3))
    r, pv, wr, cen, d, n, nr, wnr = (scratch[0], scratch[1], scratch[2], scratch[3], scratch[4],
                                     scratch[5], scratch[6], scratch[7])
    for i in range(5):
        row = rows[i]
        rotate(rotation, row[R_OFFSET:R_OFFSET + 3], r)
        cross(w, r, wr)
        cross(w, wr, cen)                                # w x (w x r)
        for k in range(3):
            pv[k] = v[k] + wr[k]
            d[k] = center[k] + r[k] - row[R_BASE + k]
        d[1] -= rack * row[R_STEER]
        if row[R_LINE] == 0.0:
            rhs[i] = -(dot(pv, pv) + dot(d, cen)) / row[R_LENGTH]
            continue
        rotate(rotation, row[R_NORMAL:R_NORMAL + 3], n)
        cross(w, n, nr)
        cross(w, nr, wnr)
        rhs[i] = dot(n, cen) + 2.0 * dot(pv, nr) + dot(d, wnr)
    solve(lu, pivots, rhs, x)
    a, alpha = motion[2], motion[3]
    a[0], a[1], a[2], alpha[0], alpha[1], alpha[2] = x[0], x[1], 0.0, x[2], x[3], x[4]


@jit
def mount_rates(table, j, motion, center, rotation, rack, out):
    """Write mount j's (pack_elements row j) position and its rates into out (3, 3)."""
    v, w, a, alpha = motion[0], motion[1], motion[2], motion[3]
    row = table[j]
    scratch = np.empty((3, 3))
    r, wr, tmp = scratch[0], scratch[1], scratch[2]
    rotate(rotation, row[E_OFFSET:E_OFFSET + 3], r)
    cross(w, r, wr)
    for k in range(3):
        out[0, k], out[1, k] = center[k] + r[k], v[k] + wr[k]
    cross(w, wr, tmp)
    for k in range(3):
        out[2, k] = a[k] + tmp[k]
    cross(alpha, r, tmp)
    for k in range(3):
        out[2, k] += tmp[k]
    kind = row[E_KIND]
    if kind == LINK:
        s = row[E_COEFF]
        for k in range(3):
            body = row[E_BASE + k] + (rack * row[E_STEER] if k == 1 else 0.0)
            out[0, k] = body + s * (out[0, k] - body)
            out[1, k] *= s
            out[2, k] *= s
    elif kind == ARM:
        arm_rates(row[E_BASE:E_BASE + 3], row[E_AXIS:E_AXIS + 3], row[E_COEFF:E_COEFF + 3], out)


@jit
def arm_rates(axis0, u, coeff, out):
    """Turn out (3, 3), the arm's joint (position, rates), into its point's (mounts.py)."""
    scratch = np.empty((7, 3))
    rho, e1, e2, lever, q, uq, uuq = (scratch[0], scratch[1], scratch[2], scratch[3],
                                      scratch[4], scratch[5], scratch[6])
    for k in range(3):
        rho[k] = out[0, k] - axis0[k]
    along = dot(rho, u)
    for k in range(3):
        e1[k] = rho[k] - along * u[k]
    size = math.sqrt(dot(e1, e1))
    for k in range(3):
        e1[k] /= size
    cross(u, e1, e2)
    cross(u, rho, lever)
    lever2 = dot(lever, lever)
    rate, rate2 = dot(lever, out[1]) / lever2, dot(lever, out[2]) / lever2
    for k in range(3):
        q[k] = coeff[0] * u[k] + coeff[1] * e1[k] + coeff[2] * e2[k]
    cross(u, q, uq)
    cross(u, uq, uuq)
    for k in range(3):
        out[0, k] = axis0[k] + q[k]
        out[1, k] = rate * uq[k]
        out[2, k] = rate2 * uq[k] + rate * rate * uuq[k]


@jit
def elements_one(rows, table, center, rotation, rack, jac, values):
    """
    Write the quantities of the elements of table at one pose into values (5, k).

    values[0] length (mm), [1] ratio dL/dz, [2] ratio rate d2L/dz2 (1/mm), [3] force
    k (L0 - L) (N, + = compressed), [4] wheel rate k ratio^2 - F ratio_rate (N/mm). rows:
    pack_rows; table: pack_elements; center (3,) mm, rotation (3, 3), rack mm, jac (5, 6).
    """
    scratch = np.empty((8, 3))
    motion, point, d = scratch[:4], scratch[4:7], scratch[7]
    carrier_rates(rows, center, rotation, rack, jac, motion)
    for j in range(table.shape[0]):
        mount_rates(table, j, motion, center, rotation, rack, point)
        for k in range(3):
            d[k] = point[0, k] - table[j, E_BODY + k]
        length = math.sqrt(dot(d, d))
        ratio = dot(d, point[1]) / length
        rate2 = (dot(d, point[2]) + dot(point[1], point[1]) - ratio * ratio) / length
        force = table[j, E_RATE] * (table[j, E_FREE] - length)
        values[0, j], values[1, j], values[2, j] = length, ratio, rate2
        values[3, j], values[4, j] = force, table[j, E_RATE] * ratio * ratio - force * rate2


@jit
def elements_many(rows, table, poses, values):
    """Write elements_one's values at n poses (tuple(Poses)) into values (5, n, k)."""
    center, rotation, rack, jac = poses
    for i in range(center.shape[0]):
        elements_one(rows, table, center[i], rotation[i], rack[i], jac[i], values[:, i])


@jit
def mounts_many(rows, table, poses, points):
    """Write every mount's (position, rate, rate of rate) at n poses into points (n, k, 3, 3)."""
    center, rotation, rack, jac = poses
    motion = np.empty((4, 3))
    for i in range(center.shape[0]):
        carrier_rates(rows, center[i], rotation[i], rack[i], jac[i], motion)
        for j in range(table.shape[0]):
            mount_rates(table, j, motion, center[i], rotation[i], rack[i], points[i, j])


@jit
def carrier_many(rows, poses, motions):
    """Write the carrier's (v, w, a, alpha) per travel at n poses into motions (n, 4, 3)."""
    center, rotation, rack, jac = poses
    for i in range(center.shape[0]):
        carrier_rates(rows, center[i], rotation[i], rack[i], jac[i], motions[i])
