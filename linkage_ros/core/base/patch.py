# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A wheel's contact patch and a carrier point's velocity: one formula each, for all callers.

Plain Python functions (floats or arrays (n,), as measure.alignment and the roll centre call
them) that numba also compiles into the statics kernels (compiled.jitable).
"""

from .compiled import jitable


@jitable
def patch_offset(axis_x, axis_y, axis_z, radius):
    """
    Return the contact patch less the wheel centre, (x, y, z) mm: the one contact-patch formula.

    The lowest point of a wheel of radius (mm) with the unit spin axis (axis_x, axis_y,
    axis_z): radius along minus the up direction made square to the axis. Each component a
    float or an array (n,): contact_patch gives arrays of positions, and suspension_node's
    roll centre (core.axle.roll_centre.roll_centre_of_states, compiled) floats.
    """
    up_x, up_y, up_z = -axis_z * axis_x, -axis_z * axis_y, 1.0 - axis_z * axis_z
    norm = (up_x * up_x + up_y * up_y + up_z * up_z) ** 0.5
    return -(radius * up_x / norm), -(radius * up_y / norm), -(radius * up_z / norm)


@jitable
def point_velocity(v_center, omega, offset):
    """
    Return the velocity (x, y, z) of a carrier point: v_center + omega x offset.

    v_center: the wheel centre's velocity, omega: the carrier's angular velocity, offset: the
    point less the wheel centre (mm), each a triple of floats or of arrays (n,).
    """
    (vx, vy, vz), (wx, wy, wz), (dx, dy, dz) = v_center, omega, offset
    return vx + (wy * dz - wz * dy), vy + (wz * dx - wx * dz), vz + (wx * dy - wy * dx)
