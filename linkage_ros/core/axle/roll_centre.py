# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The roll centre of an axle: one formula for the axle table, suspension_node and the maps.

    patch_motion(center, axis, radius, v_center, omega) -> patch, velocity     (n, 3) each
    roll_centre(patch, velocity) -> (n, 2)            (y, z) of n positions of both wheels
    roll_centre_of_poses(radius, spin_axis, center, rotation, jac) -> (3,)    one pose each
    height_above_ground(point, patch) -> (n,)

The roll centre is the front-view intersection of the two lines through the contact patches
square to the patches' velocities under their own wheel's travel (the patch taken as a point
of the carrier; doc/axle.md). Three pieces, each written once and each taking floats or
arrays alike: the contact patch (measure.alignment.patch_offset), the velocity of a carrier
point (point_velocity) and the front-view intersection (meet). The array functions serve the
axle table (axle.axle_quantities) and the maps (tools/map_grid.py), roll_centre_of_poses
serves the node per answer with Python floats (ros/roll_centres.py): numpy costs several
microseconds per call on arrays of two, a float operation tens of nanoseconds.
Units: mm, vehicle frame (x forward, y left, z up); column 0 the left wheel, 1 the right.
"""

from __future__ import annotations

import math

import numpy as np

from ..base.geometry import point_velocity
from ..measure.alignment import contact_patch, patch_offset
from ..solve import jacobian_kernel


def meet(left, right):
    """
    Return (y, z) mm where the two wheels' front-view lines meet: the roll centre.

    left, right: (velocity_y, velocity_z, patch_y, patch_z) of each wheel's contact patch,
    floats or arrays (n,). Each line runs square to its patch's velocity,
    v_y (y - p_y) + v_z (z - p_z) = 0. Parallel lines meet at NaN for floats, at an infinity
    or NaN for arrays.
    """
    (ay, az, apy, apz), (by, bz, bpy, bpz) = left, right
    ar, br = ay * apy + az * apz, by * bpy + bz * bpz
    det = ay * bz - by * az
    y, z = ar * bz - br * az, ay * br - by * ar
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
    Return the roll centre (3,) mm of one pose of each wheel: suspension_node's, per answer.

    x midway between the two contact patches, (y, z) as roll_centre gives them (NaN for
    parallel lines); the patches' velocities from the Jacobians (jacobian_kernel.slope_many), as
    axle_quantities has them. radius (2,) mm; spin_axis (2, 3): the design unit spin axes
    (Mechanism.spin_axis); center (2, 3) mm, rotation (2, 3, 3) (or each a pair of arrays),
    jac (2, 5, 6) C-contiguous: the wheels' poses and Jacobians (Continuation.jacobian), left
    then right. The same formulas as roll_centre, in floats.
    """
    free = np.empty((2, 5))
    jacobian_kernel.slope_many(jac, free)
    x, lines = 0.0, []
    for k in range(2):
        cx, cy, cz = center[k].tolist()
        (r0, r1, r2), s = rotation[k].tolist(), spin_axis[k].tolist()
        offset = patch_offset(r0[0] * s[0] + r0[1] * s[1] + r0[2] * s[2],
                              r1[0] * s[0] + r1[1] * s[1] + r1[2] * s[2],
                              r2[0] * s[0] + r2[1] * s[1] + r2[2] * s[2], radius[k])
        vx, vy, wx, wy, wz = free[k].tolist()                     # v_z = 1 per mm of travel
        _, velocity_y, velocity_z = point_velocity((vx, vy, 1.0), (wx, wy, wz), offset)
        x += 0.5 * (cx + offset[0])
        lines.append((velocity_y, velocity_z, cy + offset[1], cz + offset[2]))
    y, z = meet(*lines)
    return np.array([x, y, z])


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
