"""
The carrier's motion per unit of wheel travel, to second order, exact (beyond the paper).

Along the solution curve at a fixed rack the carrier pose is a function of the travel z. At a
solved pose (M, R) the implicit function theorem gives its first derivatives from the
Jacobian J of the guidance equations F (the pose's twist per mm of travel):

    J [v; w] = 0,  v_z = 1            v = dM/dz (mm/mm), w = angular velocity per mm (rad/mm)

and differentiating F(pose(z)) = 0 once more gives the second derivatives with the same J:

    J [a; alpha] = -c,  a_z = 0       a = d2M/dz2 (1/mm), alpha = dw/dz (rad/mm^2)

where c is each equation's second derivative along the curve with a = alpha = 0, written out
analytically below for both kinds of guidance equation (mechanism.py). A carrier point
r = R b from M then moves with

    P'  = v + w x r                   P'' = a + alpha x r + w x (w x r)

Nothing here is a finite difference: the only error is rounding (and the pose's own residual).
Batched over n poses: center (n, 3), rotation (n, 3, 3), rack scalar or (n,).
"""

from __future__ import annotations

from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from .geometry import cross
from .mechanism import linearize
from .pose_newton import FREE

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from .mechanism import Mechanism
    from .scene import Scene


class Rows(NamedTuple):
    """The guidance equations as geometry, in the row order of the mechanism's Jacobian."""

    line: np.ndarray      # (5,) bool: a strut line row (else a sphere row)
    offset: np.ndarray    # (5, 3) mm: the row's carrier point minus M0 (carrier frame)
    base: np.ndarray      # (5, 3) mm: body point A (sphere) or top mount T (line), rack 0
    steer: np.ndarray     # (5,) 1.0 where A moves with the rack along +y
    length: np.ndarray    # (5,) mm: link length (sphere rows; 1.0 on line rows)
    normal: np.ndarray    # (5, 3) carrier-fixed unit normal of the strut line at design


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


def carrier_motion(rows: Rows, mech: Mechanism, center: ArrayLike, rotation: ArrayLike,
                   rack: ArrayLike = 0.0, jac: np.ndarray | None = None) -> CarrierMotion:
    """
    Return the carrier's velocity and acceleration per travel at n solved poses.

    rows: guidance_rows(scene, mech). jac (n, 5, 6): the Jacobian at the poses if the solve
    has it (Continuation.jacobian), else it is linearized here.
    """
    center = np.asarray(center, dtype=float).reshape(-1, 3)
    rotation = np.asarray(rotation, dtype=float).reshape(-1, 3, 3)
    n = len(center)
    if jac is None:
        jac = linearize(mech, center, rotation, rack)[1]
    jac = np.asarray(jac).reshape(n, 5, 6)
    inverse = np.linalg.inv(jac[:, :, FREE])                    # (n, 5, 5), once for both
    first = -inverse @ jac[:, :, 2:3]
    velocity = np.concatenate((first[:, :2, 0], np.ones((n, 1))), axis=1)
    omega = first[:, 2:, 0]
    quadratic = second_order_terms(rows, center, rotation, np.broadcast_to(rack, (n,)),
                                   velocity, omega)
    second = -(inverse @ quadratic[:, :, None])[:, :, 0]
    acceleration = np.concatenate((second[:, :2], np.zeros((n, 1))), axis=1)
    return CarrierMotion(velocity, omega, acceleration, second[:, 2:])


def second_order_terms(rows: Rows, center: np.ndarray, rotation: np.ndarray, rack: np.ndarray,
                       velocity: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """
    Return c (n, 5): each equation's second derivative along (v, w) with a = alpha = 0.

    sphere, F = (|d|^2 - l^2) / 2l, d = P - A:     c = (|P'|^2 + d . (w x (w x r))) / l
    line, F = (T - C) . n, n = R n0 (n' = w x n):  c = -n . (w x (w x r)) - 2 C' . (w x n)
                                                       + (T - C) . (w x (w x n))
    with r = R b the carrier point from M and P' = C' = v + w x r.
    """
    r = np.einsum('nij,kj->nki', rotation, rows.offset)       # (n, 5, 3)
    w = np.broadcast_to(omega[:, None, :], r.shape)
    point_velocity = velocity[:, None, :] + cross(w, r)
    centripetal = cross(w, cross(w, r))
    point = center[:, None, :] + r
    base = rows.base + (rack[:, None] * rows.steer)[:, :, None] * np.array([0.0, 1.0, 0.0])
    d = point - base
    sphere = (np.einsum('nki,nki->nk', point_velocity, point_velocity)
              + np.einsum('nki,nki->nk', d, centripetal)) / rows.length
    if not rows.line.any():
        return sphere
    normal = np.einsum('nij,kj->nki', rotation, rows.normal)
    normal_rate = cross(w, normal)
    line = (-np.einsum('nki,nki->nk', normal, centripetal)
            - 2 * np.einsum('nki,nki->nk', point_velocity, normal_rate)
            - np.einsum('nki,nki->nk', d, cross(w, normal_rate)))   # T - C = -d
    return np.where(rows.line, line, sphere)


def point_motion(motion: CarrierMotion, center: np.ndarray, rotation: np.ndarray,
                 offset: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """
    Return position, velocity and acceleration per travel (n, 3) of a carrier point.

    offset (3,): the point's design position minus M0, mm. Units mm, mm/mm, 1/mm.
    """
    r = np.asarray(rotation).reshape(-1, 3, 3) @ np.asarray(offset, dtype=float)
    w, alpha = motion.omega, motion.alpha
    return (np.asarray(center).reshape(-1, 3) + r, motion.velocity + cross(w, r),
            motion.acceleration + cross(alpha, r) + cross(w, cross(w, r)))
