# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Compiled kernel of the bodies' frames at a pose (bodies.py: what each frame is).

Compiled (base/compiled.py's jit) like kernel.py, and like it calling so3.py (quaternion).
The bodies come as one table, a
row per body with named columns (bodies.Bodies.table), as kernel.py takes its equation table:
numba types each array argument on every call, and on the node's one-command path that
typing, not the arithmetic, is the cost. mm, vehicle frame.
"""

import math

import numpy as np

from ..base.compiled import jit
from ..base.so3 import quaternion as so3_quaternion

CARRIER, LINK, ARM, STRUT = 0, 1, 2, 3      # KIND
# table columns: the body's kind, its carrier joint (index into the carrier offsets), 1 for a
# link whose body end moves with the rack, its design origin (3) and frame (3 x 3, row-major:
# its columns are the frame's x, y, z axes)
KIND, JOINT, STEER, ORIGIN, AXES, COLUMNS = 0, 1, 2, 3, 6, 15


@jit
def frames(table, offsets, center, rotation, quaternion, rack, scale, out):
    """
    Write every body's frame at the pose (center (3,) mm, rotation (3, 3) relative to design).

    table (k, COLUMNS); offsets (m, 3): the carrier joints minus the design wheel centre;
    quaternion (4,): the carrier's (of rotation), written as it is; rack: mm. Writes out
    (k, 7): each body's origin times scale (1e-3: in m), then its quaternion (x, y, z, w;
    w >= 0).
    """
    frame = np.empty((3, 3))
    joint = np.empty(3)
    for i in range(table.shape[0]):
        row = table[i]
        kind = int(row[KIND])
        ox, oy, oz = row[ORIGIN], row[ORIGIN + 1], row[ORIGIN + 2]
        if kind == CARRIER:
            ox, oy, oz = center[0], center[1], center[2]
            for r in range(3):
                for c in range(3):
                    frame[r, c] = rotation[r, c]
        elif kind == STRUT:     # R times the design frame, about the fixed top mount
            for r in range(3):
                for c in range(3):
                    frame[r, c] = (rotation[r, 0] * row[AXES + c]
                                   + rotation[r, 1] * row[AXES + 3 + c]
                                   + rotation[r, 2] * row[AXES + 6 + c])
        else:
            j = int(row[JOINT])
            for r in range(3):
                joint[r] = (center[r] + rotation[r, 0] * offsets[j, 0]
                            + rotation[r, 1] * offsets[j, 1] + rotation[r, 2] * offsets[j, 2])
            if kind == LINK:
                oy += rack * row[STEER]
                _link(row, joint[0] - ox, joint[1] - oy, joint[2] - oz, frame)
            else:
                _arm(row, joint[0] - ox, joint[1] - oy, joint[2] - oz, frame)
        out[i, 0], out[i, 1], out[i, 2] = ox * scale, oy * scale, oz * scale
        if kind == CARRIER:
            for c in range(4):
                out[i, 3 + c] = quaternion[c]
        else:
            so3_quaternion(frame, out[i, 3:])


@jit
def _link(row, ux, uy, uz, frame):
    """Write the smallest rotation from the design direction (frame z) to u, times the frame."""
    n = math.sqrt(ux * ux + uy * uy + uz * uz)
    ux, uy, uz = ux / n, uy / n, uz / n
    ax, ay, az = row[AXES + 2], row[AXES + 5], row[AXES + 8]
    vx, vy, vz = ay * uz - az * uy, az * ux - ax * uz, ax * uy - ay * ux
    k = 1.0 / (1.0 + ax * ux + ay * uy + az * uz)
    # I + [v]x + [v]x^2 / (1 + c)
    s00, s01, s02 = 1.0 - k * (vy * vy + vz * vz), -vz + k * vx * vy, vy + k * vx * vz
    s10, s11, s12 = vz + k * vx * vy, 1.0 - k * (vx * vx + vz * vz), -vx + k * vy * vz
    s20, s21, s22 = -vy + k * vx * vz, vx + k * vy * vz, 1.0 - k * (vx * vx + vy * vy)
    for c in range(3):
        a0, a1, a2 = row[AXES + c], row[AXES + 3 + c], row[AXES + 6 + c]
        frame[0, c] = s00 * a0 + s01 * a1 + s02 * a2
        frame[1, c] = s10 * a0 + s11 * a1 + s12 * a2
        frame[2, c] = s20 * a0 + s21 * a1 + s22 * a2


@jit
def _arm(row, wx, wy, wz, frame):
    """Write the arm frame: z the fixed axis, x towards the joint w square to z, y = z x x."""
    zx, zy, zz = row[AXES + 2], row[AXES + 5], row[AXES + 8]
    d = wx * zx + wy * zy + wz * zz
    xx, xy, xz = wx - d * zx, wy - d * zy, wz - d * zz
    n = math.sqrt(xx * xx + xy * xy + xz * xz)
    xx, xy, xz = xx / n, xy / n, xz / n
    yx, yy, yz = zy * xz - zz * xy, zz * xx - zx * xz, zx * xy - zy * xx
    frame[0, 0], frame[0, 1], frame[0, 2] = xx, yx, zx
    frame[1, 0], frame[1, 1], frame[1, 2] = xy, yy, zy
    frame[2, 0], frame[2, 1], frame[2, 2] = xz, yz, zz
