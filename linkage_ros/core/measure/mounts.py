# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The motion of mounts (model/mounts.py: points on the carrier, an arm, a link, a strut).

mount_motion gives the points' positions and their first and second derivatives with respect
to wheel travel, exact (motion.py), at n solved poses, compiled (element_kernel.py). mm,
vehicle frame.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..base.geometry import unit
from ..solve import element_kernel
from ..solve.element_kernel import ALONG, ARM, CARRIER, LINK, MountTable

if TYPE_CHECKING:
    from collections.abc import Sequence

    from .motion import Rows
    from ..model.mounts import Mount
    from ..model.scene import Scene
    from ..solve.element_kernel import Poses


def mount_table(scene: Scene, mounts: Sequence[Mount]) -> MountTable:
    """Build the compiled kernels' table (element_kernel.MountTable) of mounts in a scene."""
    k = len(mounts)
    kind = np.empty(k, dtype=np.int64)
    offset, base, axis, coeff = (np.zeros((k, 3)) for _ in range(4))
    steer = np.zeros(k)
    codes = {'carrier': CARRIER, 'arm': ARM, 'link': LINK, 'along': ALONG}
    for j, mount in enumerate(mounts):
        kind[j] = codes[mount.kind]
        if mount.kind == 'carrier':
            offset[j] = mount.point - scene.wheel_center
            continue
        c = scene.constraints[mount.constraint]
        offset[j] = c.carrier - scene.wheel_center      # the joint moves the point
        if mount.kind == 'link':
            base[j] = c.base[0]
            coeff[j, 0] = ((mount.point - c.base[0]) @ (c.carrier - c.base[0])
                           / ((c.carrier - c.base[0]) @ (c.carrier - c.base[0])))
            steer[j] = 1.0 if c.steer == 'rack' else 0.0
        elif mount.kind == 'arm':
            # The arm's frame follows its joint: e1 along the joint's offset from the axis,
            # square to it; e2 = u x e1. The point keeps its design coordinates in (u, e1, e2).
            u = unit(c.base[1] - c.base[0])
            rho = c.carrier - c.base[0]
            e1 = unit(rho - (rho @ u) * u)
            q = mount.point - c.base[0]
            base[j], axis[j] = c.base[0], u
            coeff[j] = (q @ u, q @ e1, q @ np.cross(u, e1))
    return MountTable(kind, offset, base, axis, coeff, steer)


def mount_motion(rows: Rows, table: MountTable,
                 poses: Poses) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """
    Return the mounts' positions (mm), d/dtravel (mm/mm), d2/dtravel2 (1/mm), (n, k, 3) each.

    rows: motion.guidance_rows; table: mount_table; poses: motion.pose_batch. Exact: the
    carrier's motion to second order (motion.py), then an arm's angle rates from its joint:
    theta' = (u x rho) . C' / |u x rho|^2, theta'' likewise with C''.
    """
    points = np.empty((len(poses.center), len(table.kind), 3, 3))
    element_kernel.mounts_many(element_kernel.pack_rows(rows), element_kernel.pack_elements(table),
                               tuple(poses), points)
    return points[:, :, 0], points[:, :, 1], points[:, :, 2]
