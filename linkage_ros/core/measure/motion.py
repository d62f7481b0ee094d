# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The carrier's motion per unit of wheel travel, to second order, exact (beyond the paper).

Along the solution curve at a fixed rack the carrier pose is a function of the travel z. At a
solved pose (M, R) the implicit function theorem gives its first derivatives from the
Jacobian J of the guidance equations F (the pose's twist per mm of travel):

    J [v; w] = 0,  v_z = 1            v = dM/dz (mm/mm), w = angular velocity per mm (rad/mm)

and differentiating F(pose(z)) = 0 once more gives the second derivatives with the same J:

    J [a; alpha] = -c,  a_z = 0       a = d2M/dz2 (1/mm), alpha = dw/dz (rad/mm^2)

where c is each equation's second derivative along the curve with a = alpha = 0, written out
analytically for both kinds of guidance equation (mechanism.py), r = R b a carrier point
from M, P' = C' = v + w x r, d = P - A:

    sphere, F = (|d|^2 - l^2) / 2l:     c = (|P'|^2 + d . (w x (w x r))) / l
    line, F = (T - C) . n, n = R n0:    c = -n . (w x (w x r)) - 2 C' . (w x n)
                                            + (T - C) . (w x (w x n))

A carrier point then moves with P' = v + w x r and P'' = a + alpha x r + w x (w x r).
Nothing here is a finite difference: the only error is rounding (and the pose's own residual).
The arithmetic runs compiled (element_kernel.py), batched over n poses.
"""

from __future__ import annotations

from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from ..solve import element_kernel
from ..solve.element_kernel import Poses, Rows
from ..solve.mechanism import linearize

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..model.scene import Scene
    from ..solve.mechanism import Mechanism


class CarrierMotion(NamedTuple):
    """First and second derivatives of the carrier pose with respect to travel, (n, 3) each."""

    velocity: np.ndarray      # dM/dz, mm/mm (z component 1)
    omega: np.ndarray         # angular velocity per travel, rad/mm, vehicle frame
    acceleration: np.ndarray  # d2M/dz2, 1/mm (z component 0)
    alpha: np.ndarray         # d omega/dz, rad/mm^2


def guidance_rows(scene: Scene, mech: Mechanism) -> Rows:
    """
    Return the guidance equations of a compiled scene as geometry, row by row.

    Read from the scene's constraints through the mechanism's public row map: row i belongs
    to the constraint of carrier point mech.equation_point[i] (a circle gives a row per axis
    point, in order); strut rows take their normals from mech.line_rows().
    """
    lines = iter(mech.line_rows())
    seen: dict[int, int] = {}
    line, offset, base, steer, length, normal = [], [], [], [], [], []
    for point in mech.equation_point.tolist():
        c = scene.constraints[point]
        offset.append(mech.offsets[point])
        if c.type == 'line':
            _, top, n0 = next(lines)
            line.append(True), base.append(top), steer.append(0.0), length.append(1.0)
            normal.append(n0)
            continue
        k = seen.get(point, 0)
        seen[point] = k + 1
        line.append(False), base.append(c.base[k]), normal.append(np.zeros(3))
        steer.append(1.0 if c.steer == 'rack' else 0.0)
        length.append(float(np.linalg.norm(c.carrier - c.base[k])))
    return Rows(np.array(line), np.array(offset), np.array(base), np.array(steer),
                np.array(length), np.array(normal))


def pose_batch(mech: Mechanism, center: ArrayLike, rotation: ArrayLike, rack: ArrayLike = 0.0,
               jac: ArrayLike | None = None) -> Poses:
    """
    Pack n solved poses for the compiled kernels (element_kernel.Poses).

    center (n, 3) or (3,) mm, rotation (n, 3, 3) or (3, 3), rack mm (scalar or (n,)); jac
    (n, 5, 6) or (5, 6): the Jacobian at the poses if the solve has it (Continuation.jacobian),
    else linearized. One pose costs no copy (the node's path).
    """
    center, rotation = np.asarray(center, dtype=float), np.asarray(rotation, dtype=float)
    if center.ndim == 1:
        center, rotation = center[None], rotation[None]
        jac = None if jac is None else np.asarray(jac, dtype=float)[None]
    rack = (np.full(len(center), float(rack)) if np.ndim(rack) == 0
            else np.asarray(rack, dtype=float))
    if jac is None:
        jac = linearize(mech, center, rotation, rack)[1]
    return Poses(center, rotation, rack, np.asarray(jac, dtype=float))


def carrier_motion(rows: Rows, poses: Poses) -> CarrierMotion:
    """Return the carrier's velocity and acceleration per travel at n poses (pose_batch)."""
    out = np.empty((len(poses.center), 4, 3))
    element_kernel.carrier_many(element_kernel.pack_rows(rows), tuple(poses), out)
    return CarrierMotion(*(out[:, i] for i in range(4)))
