# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The paper's method as written (Alexandru 2018): three points, Newton-Kantorovich, Gauss-Jordan.

The carrier ("rod") is located by M (wheel centre), N (inboard spin-axis point) and P (third
point). With Z_M imposed the unknowns are
    x = [X_M, Y_M, X_N, Y_N, Z_N, X_P, Y_P, Z_P].
Equations: the rigid-body distances F1-F3 (eq. 1) and 5 guidance equations in squared
form (eqs. 2-4, 13; a strut line gives two, see mechanism.py). The carrier joints enter
through eqs. 5-7 (trilateration from M, N, P) and the Jacobian (eq. 10) follows them by the
chain rule. Each Newton step is solved by Gauss-Jordan elimination and iteration stops by
the step test of eqs. 11-12.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..base.geometry import frame_from_points, local_coordinates, trilaterate

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from .mechanism import Mechanism
    from ..model.scene import Scene


@dataclass(frozen=True)
class PaperModel:
    """Design data of the paper's formulation, built once per scene (mm)."""

    m0: np.ndarray
    n0: np.ndarray
    p0: np.ndarray
    rigid: np.ndarray      # |PN|, |PM|, |NM| (eq. 1')
    radii: np.ndarray      # (j, 3): |BM|, |BN|, |BP| per carrier joint (eq. 5')
    signs: np.ndarray      # (j,): side of the M-N-P plane at design
    equations: tuple       # ('sphere', joint, base, length, steers) or ('line', joint, aux, top)
    frame0: np.ndarray     # design frame of M, N, P


def build(scene: Scene, mech: Mechanism) -> PaperModel:
    """Build the paper's model of a scene: joints, their eq. 5' distances, the equations."""
    m0, n0, p0 = scene.wheel_center, scene.spin_axis_point, scene.third_point
    joints, equations = [], []

    def add_joint(point):
        joints.append(point)
        return len(joints) - 1

    for c in scene.constraints:
        b = add_joint(c.carrier)
        if c.type in ('sphere', 'circle'):
            for base in c.base:
                equations.append(('sphere', b, base, np.linalg.norm(c.carrier - base),
                                  1.0 if c.steer == 'rack' else 0.0))
    for point, top, normal in mech.line_rows():
        # A strut line: T stays in the carrier plane through C spanned by the line and the
        # normal; the normal is carried by an auxiliary carrier point E = C + L n (a joint too).
        carrier = joints[point]   # joints 0..k-1 are the constraints' carrier points
        aux = add_joint(carrier + np.linalg.norm(top - carrier) * normal)
        equations.append(('line', point, aux, top))
    joints = np.array(joints)
    radii = np.linalg.norm(joints[:, None, :] - np.array([m0, n0, p0])[None], axis=2)
    signs = np.array([np.sign(local_coordinates(m0, n0, p0, j)[2]) for j in joints])
    return PaperModel(m0=m0, n0=n0, p0=p0,
                      rigid=np.array([np.linalg.norm(p0 - n0), np.linalg.norm(p0 - m0),
                                      np.linalg.norm(n0 - m0)]),
                      radii=radii, signs=signs, equations=tuple(equations),
                      frame0=frame_from_points(m0, n0, p0))


def points_of_pose(model: PaperModel, center: np.ndarray,
                   rotation: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return M, N, P of a pose (center, rotation relative to design)."""
    return (center, center + rotation @ (model.n0 - model.m0),
            center + rotation @ (model.p0 - model.m0))


def pose_of_points(model: PaperModel, m: np.ndarray, n: np.ndarray,
                   p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return the pose (center, rotation) of M, N, P: R carries the design frame onto theirs."""
    return m.copy(), frame_from_points(m, n, p) @ model.frame0.T


def unpack(x: np.ndarray, z_m: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return M, N, P from the unknown vector x and the imposed Z_M."""
    return np.array([x[0], x[1], z_m]), x[2:5], x[5:8]


def joints_of(model: PaperModel, m: np.ndarray, n: np.ndarray,
              p: np.ndarray) -> np.ndarray | None:
    """Return the joint positions by eqs. 5-7, or None where the spheres do not meet."""
    out = []
    for radii, sign in zip(model.radii, model.signs):
        point, _ = trilaterate(m, n, p, radii, sign)
        if point is None:
            return None
        out.append(point)
    return np.array(out)


def system(model: PaperModel, x: np.ndarray, z_m: float,
           rack: float = 0.0) -> tuple[np.ndarray, np.ndarray] | tuple[None, None]:
    """
    Return F (8,) and the Jacobian (8, 8) of eqs. 1-4 at x.

    rack (mm) moves the base points of steer: rack links along +y. Returns (None, None) if a
    joint cannot be placed, or cannot be differentiated (its arms to M, N, P coplanar).
    """
    m, n, p = unpack(x, z_m)
    joints = joints_of(model, m, n, p)
    if joints is None:
        return None, None
    f = np.empty(8)
    jac = np.zeros((8, 9))   # columns: M (3), N (3), P (3); Z_M dropped at the end
    # eq. 1: rigid-body distances
    f[0] = (p - n) @ (p - n) - model.rigid[0]**2
    jac[0, 6:9], jac[0, 3:6] = 2 * (p - n), -2 * (p - n)
    f[1] = (p - m) @ (p - m) - model.rigid[1]**2
    jac[1, 6:9], jac[1, 0:3] = 2 * (p - m), -2 * (p - m)
    f[2] = (n - m) @ (n - m) - model.rigid[2]**2
    jac[2, 3:6], jac[2, 0:3] = 2 * (n - m), -2 * (n - m)
    for row, eq in enumerate(model.equations, start=3):
        if eq[0] == 'sphere':   # eqs. 2-4, 13
            _, b, base, length, steers = eq
            d = joints[b] - base
            d[1] -= rack * steers
            f[row] = d @ d - length**2
            grads = {b: 2 * d}
        else:                   # strut line: (T - C) . (E - C) = 0
            _, c, e, top = eq
            to_top, normal = top - joints[c], joints[e] - joints[c]
            f[row] = to_top @ normal
            grads = {c: -(to_top + normal), e: to_top}
        for j, grad in grads.items():
            chained = _chain(joints[j], m, n, p, grad)
            if chained is None:
                return None, None
            jac[row] += chained
    return f, np.delete(jac, 2, axis=1)


def _chain(joint, m, n, p, grad):
    """
    Return d(F)/d(M, N, P) (9,) of an equation with gradient grad (3,) at a trilaterated joint.

    Differentiating |B - Q_i|^2 = r_i^2 (eq. 5) gives G dB = [(B - Q_i) . dQ_i] with rows
    G_i = (B - Q_i); so dF = sum_i lambda_i (B - Q_i) . dQ_i where G^T lambda = grad.
    None if G is singular (the joint in the plane of M, N, P).
    """
    arms = joint - np.array([m, n, p])
    try:
        lam = np.linalg.solve(arms.T, grad)
    except np.linalg.LinAlgError:
        return None
    return (lam[:, None] * arms).ravel()


def gauss_jordan(a: ArrayLike, b: ArrayLike) -> np.ndarray | None:
    """
    Solve a x = b by Gauss-Jordan elimination with partial pivoting (reduced row echelon).

    Returns None if a is singular (a zero pivot) or not finite.
    """
    aug = np.column_stack((np.array(a, dtype=float), np.array(b, dtype=float)))
    size = len(aug)
    for col in range(size):
        pivot = col + int(np.argmax(np.abs(aug[col:, col])))
        if not abs(aug[pivot, col]) > 0.0:   # zero or NaN
            return None
        aug[[col, pivot]] = aug[[pivot, col]]
        aug[col] /= aug[col, col]
        others = np.arange(size) != col
        aug[others] -= np.outer(aug[others, col], aug[col])
    return aug[:, -1]


def correct(model: PaperModel, travel: float, center: np.ndarray, rotation: np.ndarray,
            tol: float, max_iter: int,
            rack: float = 0.0) -> tuple[np.ndarray, np.ndarray, int, bool, None]:
    """
    Run Newton-Kantorovich from the pose (center, rotation) to the pose at travel (mm).

    Same contract as pose_newton.correct: returns (center, rotation, iterations, converged,
    jacobian); the jacobian is None (the paper's is not the pose Jacobian).
    """
    m, n, p = points_of_pose(model, center, rotation)
    x = np.concatenate((m[:2], n, p))
    z_m = model.m0[2] + travel
    for iteration in range(1, max_iter + 1):
        f, jac = system(model, x, z_m, rack)
        if f is None:
            return center, rotation, iteration, False, None
        dx = gauss_jordan(jac, -f)
        if dx is None:
            return center, rotation, iteration, False, None
        x = x + dx
        step = np.max(np.abs(dx))        # eqs. 11-12
        if not np.isfinite(step):
            return center, rotation, iteration, False, None
        if step <= tol:
            m, n, p = unpack(x, z_m)
            if joints_of(model, m, n, p) is None:
                return center, rotation, iteration, False, None
            new_center, new_rotation = pose_of_points(model, m, n, p)
            return new_center, new_rotation, iteration, True, None
    return center, rotation, max_iter, False, None
