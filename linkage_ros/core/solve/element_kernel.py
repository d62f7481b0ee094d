# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Compiled kernels of the elements: the carrier's motion to second order, mount points, lengths.

Compiled (base/compiled.py's jit) like kernel.py, and like it calling so3.py's rotate and
jacobian_kernel.py's LU (factor, solve). The formulas are those of motion.py (the
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

import numpy as np

from .jacobian_kernel import factor, solve
from ..base.compiled import jit
from ..base.force_table import table_force
from ..base.so3 import rotate

CARRIER, ARM, LINK, ALONG = 0, 1, 2, 3      # MountTable.kind
# pack_rows columns: one row per guidance equation
R_LINE, R_OFFSET, R_BASE, R_STEER, R_LENGTH, R_NORMAL, ROW_COLUMNS = 0, 1, 4, 7, 8, 9, 12
# pack_elements columns: one row per element (a mount alone: body, rate, free length unused).
# E_CURVE: the number n of rows of a spring's force table (0: none, the rate holds), whose
# deflections (mm) then fill the n columns after it and its forces (N) the n after those.
(E_KIND, E_OFFSET, E_BASE, E_AXIS, E_COEFF, E_STEER, E_BODY, E_RATE, E_FREE, E_DIRECTION,
 E_CURVE, ELEMENT_COLUMNS) = 0, 1, 4, 7, 10, 13, 14, 17, 18, 19, 22, 23
# mm: an element is defined while its moving point stays more than this ahead of its body
# point along its design direction (body to moving point). At or below it the two ends have
# met or passed through each other, which no spring or damper can: its direction, ratio and
# wheel rate lose their meaning (1 / L runs away: -9e14 N/mm where the ends met), so every
# value is NaN there. Far above the round-off of the points (about 1e-13 mm at a suspension's
# size), far below any real element's length.
MIN_LENGTH = 1e-6

# Scratch rows of the kernels' workspace (WORK_ROWS, 5): 0-4 the LU factors, 5-6 right-hand
# side and solution, then ([:3]) 7-10 the carrier's motion, 11-13 a mount's point and rates.
# Allocated once per call of an entry point, not per pose.
WORK_ROWS = 14


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
    direction: np.ndarray     # (k, 3) unit: body point to moving point at design
    curves: tuple = ()        # per element None or its force table (n, 2): deflection mm, N


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
        springs = SpringTable(np.zeros((k, 3)), np.full(k, np.nan), np.full(k, np.nan),
                              np.zeros((k, 3)))
    curves = [c if c is not None else np.empty((0, 2))
              for c in (springs.curves or (None,) * k)]
    rows = max([len(c) for c in curves] + [0])
    packed = np.zeros((k, 2 * rows))
    for j, c in enumerate(curves):
        packed[j, :len(c)], packed[j, rows:rows + len(c)] = c[:, 0], c[:, 1]
    # deflections in the first half of the packed columns, forces in the second: each half
    # starts at the same column on every row; the kernel reads the first E_CURVE of each
    width = ELEMENT_COLUMNS + 2 * rows
    return np.ascontiguousarray(np.column_stack((
        mounts.kind.astype(float), mounts.offset, mounts.base, mounts.axis, mounts.coeff,
        mounts.steer, springs.body, springs.rate, springs.free_length,
        springs.direction, [len(c) for c in curves], packed)).reshape(k, width))


@jit
def cross(ax, ay, az, bx, by, bz):
    """Return a x b as three floats."""
    return ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx


@jit
def carrier_rates(rows, center, rotation, rack, jac, motion, lu, pivots, rhs, x):
    """
    Write the carrier's v, w, a, alpha per travel into motion (4, 3) (motion.py's formulas).

    NaN if the Jacobian is singular there. lu (5, 5), pivots (5,) int, rhs and x (5,):
    scratch, allocated once by the caller.
    """
    if not factor(jac, lu, pivots):
        motion[:] = np.nan
        return
    for i in range(5):
        rhs[i] = -jac[i, 2]
    solve(lu, pivots, rhs, x)
    vx, vy, vz, wx, wy, wz = x[0], x[1], 1.0, x[2], x[3], x[4]
    for i in range(5):
        row = rows[i]
        rx, ry, rz = rotate(rotation, row[R_OFFSET], row[R_OFFSET + 1], row[R_OFFSET + 2])
        wrx, wry, wrz = cross(wx, wy, wz, rx, ry, rz)
        cx, cy, cz = cross(wx, wy, wz, wrx, wry, wrz)          # w x (w x r)
        px, py, pz = vx + wrx, vy + wry, vz + wrz               # P' = C'
        dx = center[0] + rx - row[R_BASE]
        dy = center[1] + ry - row[R_BASE + 1] - rack * row[R_STEER]
        dz = center[2] + rz - row[R_BASE + 2]
        if row[R_LINE] == 0.0:
            rhs[i] = -(px * px + py * py + pz * pz + dx * cx + dy * cy + dz * cz) / row[R_LENGTH]
            continue
        nx, ny, nz = rotate(rotation, row[R_NORMAL], row[R_NORMAL + 1], row[R_NORMAL + 2])
        qx, qy, qz = cross(wx, wy, wz, nx, ny, nz)             # n' = w x n
        sx, sy, sz = cross(wx, wy, wz, qx, qy, qz)
        rhs[i] = (nx * cx + ny * cy + nz * cz + 2.0 * (px * qx + py * qy + pz * qz)
                  + dx * sx + dy * sy + dz * sz)
    solve(lu, pivots, rhs, x)
    motion[0, 0], motion[0, 1], motion[0, 2] = vx, vy, vz
    motion[1, 0], motion[1, 1], motion[1, 2] = wx, wy, wz
    motion[2, 0], motion[2, 1], motion[2, 2] = x[0], x[1], 0.0
    motion[3, 0], motion[3, 1], motion[3, 2] = x[2], x[3], x[4]


@jit
def mount_rates(table, j, motion, center, rotation, rack, out):
    """Write mount j's (pack_elements row j) position and its rates into out (3, 3)."""
    row = table[j]
    wx, wy, wz = motion[1, 0], motion[1, 1], motion[1, 2]
    rx, ry, rz = rotate(rotation, row[E_OFFSET], row[E_OFFSET + 1], row[E_OFFSET + 2])
    wrx, wry, wrz = cross(wx, wy, wz, rx, ry, rz)
    cx, cy, cz = cross(wx, wy, wz, wrx, wry, wrz)
    ax, ay, az = cross(motion[3, 0], motion[3, 1], motion[3, 2], rx, ry, rz)
    out[0, 0], out[0, 1], out[0, 2] = center[0] + rx, center[1] + ry, center[2] + rz
    out[1, 0], out[1, 1], out[1, 2] = motion[0, 0] + wrx, motion[0, 1] + wry, motion[0, 2] + wrz
    out[2, 0], out[2, 1], out[2, 2] = (motion[2, 0] + ax + cx, motion[2, 1] + ay + cy,
                                       motion[2, 2] + az + cz)
    kind = row[E_KIND]
    if kind == LINK:
        s = row[E_COEFF]
        for k in range(3):
            body = row[E_BASE + k] + (rack * row[E_STEER] if k == 1 else 0.0)
            out[0, k] = body + s * (out[0, k] - body)
            out[1, k] *= s
            out[2, k] *= s
    elif kind == ARM:
        arm_rates(row, out)


@jit
def arm_rates(row, out):
    """Turn out (3, 3), an arm's joint (position, rates), into its point's (mounts.py)."""
    ux, uy, uz = row[E_AXIS], row[E_AXIS + 1], row[E_AXIS + 2]
    hx, hy, hz = out[0, 0] - row[E_BASE], out[0, 1] - row[E_BASE + 1], out[0, 2] - row[E_BASE + 2]
    along = hx * ux + hy * uy + hz * uz
    ex, ey, ez = hx - along * ux, hy - along * uy, hz - along * uz
    size = math.sqrt(ex * ex + ey * ey + ez * ez)
    ex, ey, ez = ex / size, ey / size, ez / size
    fx, fy, fz = cross(ux, uy, uz, ex, ey, ez)
    lx, ly, lz = cross(ux, uy, uz, hx, hy, hz)                  # u x rho
    lever2 = lx * lx + ly * ly + lz * lz
    rate = (lx * out[1, 0] + ly * out[1, 1] + lz * out[1, 2]) / lever2
    rate2 = (lx * out[2, 0] + ly * out[2, 1] + lz * out[2, 2]) / lever2
    cu, c1, c2 = row[E_COEFF], row[E_COEFF + 1], row[E_COEFF + 2]
    qx = cu * ux + c1 * ex + c2 * fx
    qy = cu * uy + c1 * ey + c2 * fy
    qz = cu * uz + c1 * ez + c2 * fz
    gx, gy, gz = cross(ux, uy, uz, qx, qy, qz)                   # u x q
    kx, ky, kz = cross(ux, uy, uz, gx, gy, gz)
    out[0, 0], out[0, 1], out[0, 2] = row[E_BASE] + qx, row[E_BASE + 1] + qy, row[E_BASE + 2] + qz
    out[1, 0], out[1, 1], out[1, 2] = rate * gx, rate * gy, rate * gz
    rate_2 = rate * rate
    out[2, 0], out[2, 1], out[2, 2] = (rate2 * gx + rate_2 * kx, rate2 * gy + rate_2 * ky,
                                       rate2 * gz + rate_2 * kz)


@jit
def elements_one(rows, table, center, rotation, rack, jac, values):
    """
    Write the quantities of the elements of table at one pose into values (5, k).

    values[0] length (mm), [1] ratio dL/dz, [2] ratio rate d2L/dz2 (1/mm), [3] force
    k (L0 - L) (N, + = compressed), [4] wheel rate k ratio^2 - F ratio_rate (N/mm). rows:
    pack_rows; table: pack_elements; center (3,) mm, rotation (3, 3), rack mm, jac (5, 6).
    All five NaN for an element whose ends have met or passed through each other (MIN_LENGTH).
    """
    work, pivots = np.empty((WORK_ROWS, 5)), np.empty(5, np.int64)
    elements_at(rows, table, center, rotation, rack, jac, values, work, pivots)


@jit
def elements_at(rows, table, center, rotation, rack, jac, values, work, pivots):
    """Do elements_one's work in the given scratch (work (WORK_ROWS, 5), pivots (5,) int)."""
    motion, point = work[7:11, :3], work[11:14, :3]
    carrier_rates(rows, center, rotation, rack, jac, motion, work[:5], pivots, work[5], work[6])
    for j in range(table.shape[0]):
        mount_rates(table, j, motion, center, rotation, rack, point)
        dx = point[0, 0] - table[j, E_BODY]
        dy = point[0, 1] - table[j, E_BODY + 1]
        dz = point[0, 2] - table[j, E_BODY + 2]
        vx, vy, vz = point[1, 0], point[1, 1], point[1, 2]
        if not (dx * table[j, E_DIRECTION] + dy * table[j, E_DIRECTION + 1]
                + dz * table[j, E_DIRECTION + 2]) > MIN_LENGTH:
            values[:, j] = math.nan
            continue
        length = math.sqrt(dx * dx + dy * dy + dz * dz)
        ratio = (dx * vx + dy * vy + dz * vz) / length
        rate2 = (dx * point[2, 0] + dy * point[2, 1] + dz * point[2, 2]
                 + vx * vx + vy * vy + vz * vz - ratio * ratio) / length
        force, stiffness = spring_at(table[j], table.shape[1], length)
        values[0, j], values[1, j], values[2, j] = length, ratio, rate2
        values[3, j], values[4, j] = force, stiffness * ratio * ratio - force * rate2


@jit
def spring_at(row, width, length):
    """
    Return a spring's (force N, + = compressed; stiffness dF/d deflection N/mm) at length mm.

    The rate's k (L0 - L), k; or its force table (E_CURVE) at the deflection L0 - L
    (base.force_table.table_force: held outside the table, stiffness 0 there).
    """
    n = int(row[E_CURVE])
    deflection = row[E_FREE] - length
    if n == 0:
        return row[E_RATE] * deflection, row[E_RATE]
    d0 = E_CURVE + 1
    f0 = d0 + (width - d0) // 2
    return table_force(row[d0:d0 + n], row[f0:f0 + n], deflection)


@jit
def elements_many(rows, table, poses, values):
    """Write elements_one's values at n poses (tuple(Poses)) into values (5, n, k)."""
    center, rotation, rack, jac = poses
    work, pivots = np.empty((WORK_ROWS, 5)), np.empty(5, np.int64)
    for i in range(center.shape[0]):
        elements_at(rows, table, center[i], rotation[i], rack[i], jac[i], values[:, i], work,
                    pivots)


@jit
def mounts_many(rows, table, poses, points):
    """Write every mount's (position, rate, rate of rate) at n poses into points (n, k, 3, 3)."""
    center, rotation, rack, jac = poses
    work, pivots = np.empty((WORK_ROWS, 5)), np.empty(5, np.int64)
    motion = work[7:11, :3]
    for i in range(center.shape[0]):
        carrier_rates(rows, center[i], rotation[i], rack[i], jac[i], motion, work[:5], pivots,
                      work[5], work[6])
        for j in range(table.shape[0]):
            mount_rates(table, j, motion, center[i], rotation[i], rack[i], points[i, j])


@jit
def carrier_many(rows, poses, motions):
    """Write the carrier's (v, w, a, alpha) per travel at n poses into motions (n, 4, 3)."""
    center, rotation, rack, jac = poses
    work, pivots = np.empty((WORK_ROWS, 5)), np.empty(5, np.int64)
    for i in range(center.shape[0]):
        carrier_rates(rows, center[i], rotation[i], rack[i], jac[i], motions[i], work[:5],
                      pivots, work[5], work[6])
