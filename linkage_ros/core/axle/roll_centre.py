# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The roll centre of an axle: one formula for the axle table, suspension_node and the maps.

    patch_motion(center, axis, radius, v_center, omega) -> patch, velocity     (n, 3) each
    roll_centre(patch, velocity) -> (n, 2)            (y, z) of n positions of both wheels
    roll_centre_of_poses(radius, spin_axis, center, rotation, jac) -> (3,)    one pose each
    roll_centre_of_states(radius, spin_axis, left, right, out)       the same, of two kernel
                                                                      states, compiled
    height_above_ground(point, patch) -> (n,)

The roll centre is the front-view intersection of the two lines through the contact patches
square to the patches' velocities under their own wheel's travel (the patch taken as a point
of the carrier; doc/axle.md). Three pieces, each written once and each taking floats or
arrays alike: the contact patch (measure.alignment.patch_offset), the velocity of a carrier
point (point_velocity) and the front-view intersection (meet). The array functions serve the
axle table (axle.axle_quantities) and the maps (tools/map_grid.py); the node's, per answer
(ros/roll_centres.py), is one compiled call on the two corners' kinematic states
(roll_centre_of_states, which compiles the same three pieces in): numpy costs several
microseconds per call on arrays of two, and the same formulas in Python floats cost about 15
us an axle in the node's step, against about 2 compiled.
Units: mm, vehicle frame (x forward, y left, z up); column 0 the left wheel, 1 the right.
"""

from __future__ import annotations

import math

import numpy as np

from ..base.compiled import jit, jitable
from ..base.geometry import point_velocity
from ..measure.alignment import contact_patch, patch_offset
from ..solve import jacobian_kernel, state
from ..solve.kernel import CENTER, JACOBIAN, N_EQUATIONS, ROTATION


@jitable
def meet_terms(left, right):
    """
    Return (y det, z det, det) of the two wheels' front-view lines (meet divides them).

    left, right as meet takes them; floats, arrays (n,), or in a compiled kernel floats.
    """
    (ay, az, apy, apz), (by, bz, bpy, bpz) = left, right
    ar, br = ay * apy + az * apz, by * bpy + bz * bpz
    return ar * bz - br * az, ay * br - by * ar, ay * bz - by * az


def meet(left, right):
    """
    Return (y, z) mm where the two wheels' front-view lines meet: the roll centre.

    left, right: (velocity_y, velocity_z, patch_y, patch_z) of each wheel's contact patch,
    floats or arrays (n,). Each line runs square to its patch's velocity,
    v_y (y - p_y) + v_z (z - p_z) = 0. Parallel lines meet at NaN for floats, at an infinity
    or NaN for arrays.
    """
    y, z, det = meet_terms(left, right)
    if isinstance(det, float):
        return (math.nan, math.nan) if det == 0.0 else (y / det, z / det)
    with np.errstate(divide='ignore', invalid='ignore'):
        return y / det, z / det


def patch_motion(center: np.ndarray, axis: np.ndarray, radius: float, v_center: np.ndarray,
                 omega: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """
    Return one wheel's contact patches (n, 3) mm and their velocities (n, 3) per mm of travel.

    center (n, 3) mm, axis (n, 3) the unit spin axes, radius mm; v_center, omega (n, 3): the
    wheel centre's velocity and the carrier's angular velocity under the wheel's travel.
    """
    patch = contact_patch(center, axis, radius)
    velocity = point_velocity(v_center.T, omega.T, (patch - center).T)
    return patch, np.column_stack(velocity)


def roll_centre(patch: np.ndarray, velocity: np.ndarray) -> np.ndarray:
    """
    Return the roll centre (n, 2): its (y, z) in the vehicle frame, mm.

    patch (n, 2, 3): left and right contact patches; velocity (n, 2, 3): their velocities
    under their own wheel's travel (patch_motion). NaN or infinite for parallel lines.
    """
    y, z = meet(*((velocity[:, k, 1], velocity[:, k, 2], patch[:, k, 1], patch[:, k, 2])
                  for k in range(2)))
    return np.column_stack((y, z))


def roll_centre_of_poses(radius, spin_axis, center, rotation, jac: np.ndarray) -> np.ndarray:
    """
    Return the roll centre (3,) mm of one pose of each wheel.

    x midway between the two contact patches, (y, z) as roll_centre gives them (NaN for
    parallel lines); the patches' velocities from the Jacobians (jacobian_kernel.slope_many), as
    axle_quantities has them. radius (2,) mm; spin_axis (2, 3): the design unit spin axes
    (Mechanism.spin_axis); center (2, 3) mm, rotation (2, 3, 3) (or each a pair of arrays),
    jac (2, 5, 6): the wheels' poses and Jacobians (Continuation.jacobian), left then right.
    Packed into kernel states for roll_centre_of_states, suspension_node's.
    """
    out = np.empty(3)
    roll_centre_of_states(np.asarray(radius, dtype=float),
                          np.ascontiguousarray(spin_axis, dtype=float),
                          *(state.pack(0.0, 0.0, center[k], rotation[k], jac[k])
                            for k in range(2)), out)
    return out


@jit
def roll_centre_of_states(radius, spin_axis, left, right, out):
    """
    Write the roll centre (3,) mm of two wheels' solved kernel states into out.

    As roll_centre_of_poses: suspension_node's, per answer (ros/roll_centres.py), one
    compiled call on the two Continuations' states (left, right: (STATE_SIZE,), the pose and
    its Jacobian). radius (2,) mm; spin_axis (2, 3) C-contiguous, left then right.
    """
    jac = np.empty((2, N_EQUATIONS, 6))
    for i in range(N_EQUATIONS):
        for j in range(6):
            jac[0, i, j] = left[JACOBIAN + 6 * i + j]
            jac[1, i, j] = right[JACOBIAN + 6 * i + j]
    free = np.empty((2, N_EQUATIONS))
    jacobian_kernel.slope_many(jac, free)
    x0, line0 = _patch_line(radius[0], spin_axis[0], left, free[0])
    x1, line1 = _patch_line(radius[1], spin_axis[1], right, free[1])
    out[0] = 0.0 + x0 + x1
    y, z, det = meet_terms(line0, line1)
    if det == 0.0:
        out[1], out[2] = np.nan, np.nan
    else:
        out[1], out[2] = y / det, z / det


@jitable
def _patch_line(radius, s, one, free):
    """Return half the contact patch's x, and its front-view line (meet's), of one wheel."""
    r = ROTATION
    offset = patch_offset(one[r] * s[0] + one[r + 1] * s[1] + one[r + 2] * s[2],
                          one[r + 3] * s[0] + one[r + 4] * s[1] + one[r + 5] * s[2],
                          one[r + 6] * s[0] + one[r + 7] * s[1] + one[r + 8] * s[2], radius)
    # v_z = 1 per mm of travel; free: (v_x, v_y, omega) of the wheel centre per mm
    _, velocity_y, velocity_z = point_velocity((free[0], free[1], 1.0),
                                               (free[2], free[3], free[4]), offset)
    c = CENTER
    return 0.5 * (one[c] + offset[0]), (velocity_y, velocity_z, one[c + 1] + offset[1],
                                        one[c + 2] + offset[2])


def height_above_ground(point: np.ndarray, patch: np.ndarray) -> np.ndarray:
    """
    Return the heights (n,) mm of front-view points (n, 2) (y, z) above the ground.

    The ground is the line through the two contact patches (n, 2, 3) (the body rolls and
    heaves over it); the height is the distance from that line, + above.
    """
    ground = patch[:, 0, 1:] - patch[:, 1, 1:]            # right patch to left patch
    ground = ground / np.linalg.norm(ground, axis=1, keepdims=True)
    offset = point - patch[:, 1, 1:]
    return ground[:, 0] * offset[:, 1] - ground[:, 1] * offset[:, 0]
