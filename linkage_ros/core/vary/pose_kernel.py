# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Compiled sensitivities of the sweep's columns to the hardpoints, by closed forms.

The same implicit function theorem as sensitivity.py (J_free dx/dH = -(dF/dH + J_z
dM0_z/dH)), with dF/dH written out per row at a solved pose instead of carried by jets, so
that all the hardpoints' derivatives of one position cost about one solve. Row notation of
kernel.py: r0 = b - M0 the carrier point b from the design wheel centre M0, C = M + R r0.

    sphere, d = C - A - rack e_y s, l = |b - A|:
        dF/dA = (b - A - d) / l      dF/db = R^T d / l - (b - A) / l      dF/dM0 = -R^T d / l
    strut, n = R n0, d0 = (T - b) / L0, L0 = |T - b|, lambda = (T - C) . R d0:
        dF/dT = n - (lambda / L0) n0     dF/db = -(1 - lambda / L0) n0     dF/dM0 = n0

(a strut's normals n0 turn with d0, but at a solution T - C lies along R d0, so only their
component along d0 counts: d0 . dn0 = -n0 . dd0, which gives the lambda terms; the spin axis
that helps choose them drops out). Then camber and toe follow the spin axis a = R a0,
a0 = (M0 - N0) / |M0 - N0|: da = omega x a + R da0. Columns SWEEP_COLUMNS, per mm.
"""

import numpy as np

from ..base.compiled import jit
from ..base.so3 import rotate
from ..solve import kernel
from ..solve.jacobian_kernel import factor, solve


@jit
def _add(out, column, x, y, z):
    out[column], out[column + 1], out[column + 2] = (out[column] + x, out[column + 1] + y,
                                                     out[column + 2] + z)


@jit
def moved_rows(eqs, carrier, base, center_index, center0, center, rotation, rack, f_h):
    """Write dF/dH (5, 3k) at a solved pose (the rows' closed forms above)."""
    f_h[:, :] = 0.0
    m0 = 3 * center_index
    for i in range(5):
        e = eqs[i]
        rx, ry, rz = rotate(rotation, e[kernel.POINT], e[kernel.POINT + 1], e[kernel.POINT + 2])
        # b - A or T - b, from the design: b = M0 + r0
        bx = center0[0] + e[kernel.POINT] - e[kernel.BASE]
        by = center0[1] + e[kernel.POINT + 1] - e[kernel.BASE + 1]
        bz = center0[2] + e[kernel.POINT + 2] - e[kernel.BASE + 2]
        jb, ja = 3 * carrier[i], 3 * base[i]
        if e[kernel.KIND] == kernel.SPHERE:
            length = e[kernel.LENGTH]
            dx = (center[0] + rx - e[kernel.BASE]) / length
            dy = (center[1] + ry - e[kernel.BASE + 1] - rack * e[kernel.STEER]) / length
            dz = (center[2] + rz - e[kernel.BASE + 2]) / length
            # R^T d / l
            tx = rotation[0, 0] * dx + rotation[1, 0] * dy + rotation[2, 0] * dz
            ty = rotation[0, 1] * dx + rotation[1, 1] * dy + rotation[2, 1] * dz
            tz = rotation[0, 2] * dx + rotation[1, 2] * dy + rotation[2, 2] * dz
            _add(f_h[i], ja, bx / length - dx, by / length - dy, bz / length - dz)
            _add(f_h[i], jb, tx - bx / length, ty - by / length, tz - bz / length)
            _add(f_h[i], m0, -tx, -ty, -tz)
        else:
            n0x, n0y, n0z = e[kernel.NORMAL], e[kernel.NORMAL + 1], e[kernel.NORMAL + 2]
            nx, ny, nz = rotate(rotation, n0x, n0y, n0z)
            run = np.sqrt(bx * bx + by * by + bz * bz)        # L0 = |T - b|, b - A = -(T - b)
            ux, uy, uz = rotate(rotation, -bx / run, -by / run, -bz / run)   # R d0
            reach = ((e[kernel.BASE] - center[0] - rx) * ux
                     + (e[kernel.BASE + 1] - center[1] - ry) * uy
                     + (e[kernel.BASE + 2] - center[2] - rz) * uz) / run      # lambda / L0
            _add(f_h[i], ja, nx - reach * n0x, ny - reach * n0y, nz - reach * n0z)
            _add(f_h[i], jb, (reach - 1.0) * n0x, (reach - 1.0) * n0y, (reach - 1.0) * n0z)
            _add(f_h[i], m0, n0x, n0y, n0z)


@jit
def column_rates(jac, f_h, center_index, spin_index, spin_axis, spin_length, rotation,
                 side_sign, out):
    """Write d(camber, toe (rad), M (mm))/dH into out (5, 3k) from dF/dH (5, 3k)."""
    size = f_h.shape[1]
    lift = 3 * center_index + 2
    for i in range(5):
        f_h[i, lift] += jac[i, 2]
    lu, pivots = np.empty((5, 5)), np.empty(5, np.int64)
    from_kernel = np.empty((5, 6))
    from_kernel[:, :] = jac
    rhs, x = np.empty(5), np.empty(5)
    ok = factor(from_kernel, lu, pivots)
    ax, ay, az = rotate(rotation, spin_axis[0], spin_axis[1], spin_axis[2])
    h2 = ax * ax + ay * ay
    h = np.sqrt(h2)
    for p in range(size):
        for i in range(5):
            rhs[i] = -f_h[i, p]
        if ok:
            solve(lu, pivots, rhs, x)
        else:
            x[:] = np.nan
        wx, wy, wz = x[2], x[3], x[4]
        # da = omega x a + R da0, da0 = (I - a0 a0^T)(dM0 - dN0) / |M0 - N0|
        dax, day, daz = wy * az - wz * ay, wz * ax - wx * az, wx * ay - wy * ax
        point, axis = p // 3, p % 3
        sign = 1.0 if point == center_index else (-1.0 if point == spin_index else 0.0)
        if sign != 0.0:
            gx, gy, gz = -spin_axis[axis] * spin_axis[0], -spin_axis[axis] * spin_axis[1], \
                -spin_axis[axis] * spin_axis[2]
            if axis == 0:
                gx += 1.0
            elif axis == 1:
                gy += 1.0
            else:
                gz += 1.0
            sx, sy, sz = rotate(rotation, gx, gy, gz)
            scale = sign / spin_length
            dax, day, daz = dax + scale * sx, day + scale * sy, daz + scale * sz
        dh = (ax * dax + ay * day) / h
        out[0, p] = -(h * daz - az * dh) / (h2 + az * az)
        out[1, p] = side_sign * (ay * dax - ax * day) / h2
        out[2, p], out[3, p] = x[0], x[1]
        out[4, p] = 1.0 if p == lift else 0.0


@jit
def sweep_rates_many(eqs, carrier, base, indices, center0, spin_axis, spin_length, side_sign,
                     centers, rotations, jacs, rack, out):
    """
    Write d(camber, toe, M)/dH at n solved poses into out (n, 5, 3k) (rad, mm per mm).

    indices: (wheel_center, spin_axis_point) hardpoint indices; carrier, base (5,) int the
    rows' hardpoints (equations.Layout); centers (n, 3), rotations (n, 3, 3), jacs (n, 5, 6).
    """
    f_h = np.empty((5, out.shape[2]))
    for n in range(centers.shape[0]):
        moved_rows(eqs, carrier, base, indices[0], center0, centers[n], rotations[n], rack,
                   f_h)
        column_rates(jacs[n], f_h, indices[0], indices[1], spin_axis, spin_length,
                     rotations[n], side_sign, out[n])
