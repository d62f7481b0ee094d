# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
An independent reference for the kinematics core, in extended precision.

Reference: the plain 6-DOF pose formulation (wheel centre M and carrier rotation R, 6
unknowns; the 5 guidance equations as true lengths plus the travel equation Z_M - Z_M0 = t),
walked from the design position in steps of at most 1/1000 of the scene size (0.76 mm for
the bundled scenes) and polished in extended precision
(numpy longdouble, 64-bit mantissa on x86-64: eps 1.1e-19). Equations and residuals are
evaluated in longdouble; each Newton correction is solved in float64 (mixed-precision
iterative refinement), which converges to the longdouble solution because only the residual
needs the extra digits. It shares no code with the core solvers: only the Scene loader.
All lengths in mm, vehicle frame (ISO 8855: x forward, y left, z up); angles in rad.
"""

from dataclasses import dataclass
import math

import numpy as np
from scipy.optimize import least_squares

LD = np.longdouble
REF_STEP = 1e-3          # longest step of the reference walk, as a fraction of the scene size
REF_MAX_ITER = 40        # Newton iterations per reference step
# fraction of the scene size: a least-squares minimum below this is a solution (fold search);
# about 1e-8 mm in the bundled scenes
ZERO_RESIDUAL = 1e-11


@dataclass(frozen=True)
class PoseModel:
    """The 6-DOF formulation of a scene. Shapes: m carrier points, k distances, q line eqs."""

    m0: np.ndarray           # (3,) design wheel centre
    offsets: np.ndarray      # (m, 3) carrier points minus M0 at design
    dist_point: np.ndarray   # (k,) index into offsets
    dist_base: np.ndarray    # (k, 3) body-side point
    dist_length: np.ndarray  # (k,) link length
    line_point: np.ndarray   # (q,) index into offsets of the strut's carrier point
    line_base: np.ndarray    # (q, 3) top mount
    line_normal: np.ndarray  # (q, 3) carrier-fixed normals of the strut line at design
    spin_axis: np.ndarray    # (3,) outboard spin-axis unit vector at design
    side_sign: float         # +1 left wheel, -1 right wheel
    size: float              # mm, largest coordinate magnitude: scale of round-off


def build(scene):
    """Build the PoseModel of a Scene, in longdouble so extended-precision residuals are exact."""
    m0 = scene.wheel_center.astype(LD)
    offsets, dist_point, dist_base, dist_length = [], [], [], []
    line_point, line_base, line_normal = [], [], []
    for c in scene.constraints:
        index = len(offsets)
        offsets.append(c.carrier.astype(LD) - m0)
        if c.type == 'line':
            # Two normals of the strut line square to each other, built here (not taken from
            # the core) from the line and whichever vehicle axis is least parallel to it.
            d = _unit(c.base[0].astype(LD) - c.carrier.astype(LD))
            helper = np.eye(3, dtype=LD)[int(np.argmin(np.abs(d)))]
            n1 = _unit(np.cross(d, helper))
            for normal in (n1, np.cross(d, n1)):
                line_point.append(index)
                line_base.append(c.base[0].astype(LD))
                line_normal.append(normal)
        else:
            for base in c.base:
                dist_point.append(index)
                dist_base.append(base.astype(LD))
                dist_length.append(np.sqrt(np.sum((c.carrier.astype(LD) - base) ** 2)))
    return PoseModel(
        m0=m0, offsets=np.array(offsets, dtype=LD),
        dist_point=np.array(dist_point, dtype=int),
        dist_base=np.array(dist_base, dtype=LD).reshape(-1, 3),
        dist_length=np.array(dist_length, dtype=LD),
        line_point=np.array(line_point, dtype=int),
        line_base=np.array(line_base, dtype=LD).reshape(-1, 3),
        line_normal=np.array(line_normal, dtype=LD).reshape(-1, 3),
        spin_axis=_unit(scene.wheel_center.astype(LD) - scene.spin_axis_point),
        side_sign=scene.side_sign, size=scene.size)


def guidance(model, center, rotation):
    """
    Evaluate the 5 guidance equations (mm) of a pose: link length errors, strut offsets.

    Sphere and circle: |B - A| - l, a true length. Line: the top mount's offset from the
    carrier-fixed strut line along its two carrier-fixed normals. Works in the dtype given.
    """
    r = model.offsets @ rotation.T
    pts = center + r
    d = pts[model.dist_point] - model.dist_base
    dist = np.sqrt(np.sum(d * d, axis=1)) - model.dist_length
    to_top = model.line_base - pts[model.line_point]
    line = np.sum(to_top * (model.line_normal @ rotation.T), axis=1)
    return np.concatenate((dist, line))


def equations(model, center, rotation, travel):
    """Evaluate the 6 equations of the 6-DOF formulation: guidance (5), Z_M - Z_M0 - travel."""
    return np.concatenate((guidance(model, center, rotation),
                           [center[2] - model.m0[2] - travel]))


def jacobian(model, center, rotation):
    """d(equations)/d(M, omega) (6, 6) in float64; omega turns the carrier: R <- exp(omega) R."""
    center, rotation = np.asarray(center, float), np.asarray(rotation, float)
    r = np.asarray(model.offsets, float) @ rotation.T
    pts = center + r
    d = pts[model.dist_point] - np.asarray(model.dist_base, float)
    u = d / np.linalg.norm(d, axis=1)[:, None]
    rows = [np.hstack((u, np.cross(r[model.dist_point], u)))]
    normals = np.asarray(model.line_normal, float) @ rotation.T
    to_top = np.asarray(model.line_base, float) - pts[model.line_point]
    rows.append(np.hstack((-normals, np.cross(normals, to_top)
                           - np.cross(r[model.line_point], normals))))
    rows.append([[0.0, 0.0, 1.0, 0.0, 0.0, 0.0]])
    return np.vstack(rows)


def exp_so3(omega):
    """Rotation matrix of a rotation vector (Rodrigues), in omega's dtype (float or longdouble)."""
    omega = np.asarray(omega)
    t2 = omega @ omega
    one = omega.dtype.type(1)
    if t2 < 1e-30:
        a, b = one - t2 / 6, one / 2 - t2 / 24
    else:
        t = np.sqrt(t2)
        a, b = np.sin(t) / t, (one - np.cos(t)) / t2
    k = np.array([[0, -omega[2], omega[1]], [omega[2], 0, -omega[0]],
                  [-omega[1], omega[0], 0]], dtype=omega.dtype)
    return np.eye(3, dtype=omega.dtype) + a * k + b * (k @ k)


@dataclass(frozen=True)
class ReferencePoses:
    """Reference poses at the travels asked for (mm); NaN where the walk could not reach."""

    travel: np.ndarray        # (n,) mm
    success: np.ndarray       # (n,) bool
    center: np.ndarray        # (n, 3) longdouble, mm
    rotation: np.ndarray      # (n, 3, 3) longdouble, relative to design
    residual: np.ndarray      # (n,) float, mm: largest |equation| in longdouble
    model: PoseModel


def reference_poses(scene, travels, step=None):
    """
    Extended-precision poses at travels (mm) by a 6-DOF walk from the design position.

    Each leg (bump, rebound) walks from travel 0 in steps of at most `step` mm (default
    REF_STEP times the scene size), each Newton solve starting from the last pose, so the
    branch is the design assembly branch.
    """
    model = build(scene)
    step = step or REF_STEP * model.size
    travels = np.asarray(travels, dtype=float).ravel()
    n = len(travels)
    center = np.full((n, 3), np.nan, dtype=LD)
    rotation = np.full((n, 3, 3), np.nan, dtype=LD)
    residual = np.full(n, np.nan)
    success = np.zeros(n, dtype=bool)
    for leg in (np.flatnonzero(travels >= 0), np.flatnonzero(travels < 0)):
        order = leg[np.argsort(np.abs(travels[leg]), kind='stable')]
        pose = (model.m0.copy(), np.eye(3, dtype=LD))
        here = 0.0
        for i in order:
            pose, ok = walk(model, pose, here, travels[i], step)
            if not ok:
                break
            here = travels[i]
            center[i], rotation[i] = pose
            residual[i] = float(np.max(np.abs(equations(model, *pose, LD(here)))))
            success[i] = True
    return ReferencePoses(travel=travels, success=success, center=center, rotation=rotation,
                          residual=residual, model=model)


def walk(model, pose, start, target, step):
    """Walk a pose from travel start to target (mm) in steps <= step; returns (pose, ok)."""
    count = max(1, math.ceil(abs(target - start) / step - 1e-12))
    for k in range(1, count + 1):
        pose, ok = refine(model, pose, start + (target - start) * k / count)
        if not ok:
            return pose, False
    return pose, True


def refine(model, pose, travel, max_iter=REF_MAX_ITER):
    """
    Newton on the 6 equations in longdouble with float64 solves; returns (pose, converged).

    Stops when a correction no longer shrinks and is below 1e-15 of the scene size, i.e.
    at the longdouble round-off floor (about 1e-19 of the size).
    """
    center, rotation = (np.array(p, dtype=LD) for p in pose)
    travel = LD(travel)
    floor = 1e-15 * model.size
    last = math.inf
    lever = float(np.max(np.sqrt(np.sum(model.offsets.astype(float) ** 2, axis=1))))
    for _ in range(max_iter):
        f = equations(model, center, rotation, travel)
        try:
            dx = np.linalg.solve(jacobian(model, center, rotation), -f.astype(float))
        except np.linalg.LinAlgError:
            return pose, False
        size = max(np.max(np.abs(dx[:3])), lever * np.linalg.norm(dx[3:]))
        if not np.isfinite(size) or size > 0.5 * model.size:
            return pose, False
        center = center + dx[:3].astype(LD)
        rotation = exp_so3(dx[3:].astype(LD)) @ rotation
        if size <= floor and size >= 0.5 * last:
            break
        last = size
    else:
        if last > floor:
            return pose, False
    rotation = 1.5 * rotation - 0.5 * rotation @ rotation.T @ rotation  # back onto SO(3)
    return (center, rotation), True


def wheel_angles(model, rotation):
    """Camber and toe (rad, longdouble) of rotations (..., 3, 3) relative to design."""
    a = rotation @ model.spin_axis
    camber = -np.arctan2(a[..., 2], np.hypot(a[..., 0], a[..., 1]))
    toe = np.arctan2(a[..., 0], model.side_sign * a[..., 1])
    return camber, toe


def errors(ref, center, rotation, where=None):
    """
    Deviation of poses (float64, (n, 3) and (n, 3, 3)) from the reference.

    Returns a dict of the largest values over the positions (where: bool mask, default all
    positions the reference reached): 'residual_mm' (largest guidance-equation violation of
    the given poses, evaluated in longdouble), 'wheel_center_mm', 'camber_deg', 'toe_deg'.
    """
    mask = ref.success if where is None else (ref.success & where)
    center = np.asarray(center, dtype=float)[mask].astype(LD)
    rotation = np.asarray(rotation, dtype=float)[mask].astype(LD)
    if not len(center):
        return {'residual_mm': math.nan, 'wheel_center_mm': math.nan, 'camber_deg': math.nan,
                'toe_deg': math.nan}
    residual = max(float(np.max(np.abs(guidance(ref.model, c, r))))
                   for c, r in zip(center, rotation))
    dev = np.sqrt(np.sum((center - ref.center[mask]) ** 2, axis=1))
    camber, toe = wheel_angles(ref.model, rotation)
    camber_ref, toe_ref = wheel_angles(ref.model, ref.rotation[mask])
    return {'residual_mm': residual, 'wheel_center_mm': float(np.max(dev)),
            'camber_deg': float(np.degrees(np.max(np.abs(camber - camber_ref)))),
            'toe_deg': float(np.degrees(np.max(np.abs(toe - toe_ref))))}


def has_solution(model, pose, travel):
    """
    Smallest guidance violation (mm) over poses with Z_M at travel, by least squares.

    Starts from pose (a nearby pose on the branch); zero (ZERO_RESIDUAL * size) means the
    travel is reachable there. Unknowns: x_M, y_M and a rotation vector applied to pose.
    """
    center0 = np.asarray(pose[0], dtype=float)
    rotation0 = np.asarray(pose[1], dtype=float)
    z = float(model.m0[2]) + travel

    def fun(u):
        center = np.array([u[0], u[1], z])
        return guidance(model, center.astype(LD),
                        exp_so3(u[2:].astype(LD)) @ rotation0.astype(LD)).astype(float)

    fit = least_squares(fun, np.concatenate((center0[:2], np.zeros(3))), jac='3-point',
                        xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=400)
    return float(np.max(np.abs(fit.fun)))


def reachable_limit(scene, direction, resolution=1e-4, step=None, far=1e4):
    """
    Travel limit (mm) in direction (+1 bump, -1 rebound) found independently of the core.

    Walks the 6-DOF reference until a step fails (or `far` mm), then bisects on whether a
    least-squares pose with zero guidance violation exists (has_solution) near the last
    pose, to `resolution` mm. Returns (limit, pose at the last good travel); inf if none.
    """
    model = build(scene)
    step = step or REF_STEP * model.size
    pose, here = (model.m0.copy(), np.eye(3, dtype=LD)), 0.0
    while abs(here) < far:
        nxt = here + direction * step
        new, ok = refine(model, pose, nxt)
        if not ok:
            break
        pose, here = new, nxt
    else:
        return math.copysign(math.inf, direction), pose
    good, bad = here, here + direction * step
    while abs(bad - good) > resolution:
        mid = 0.5 * (good + bad)
        if has_solution(model, pose, mid) <= ZERO_RESIDUAL * model.size:
            good = mid
        else:
            bad = mid
    return 0.5 * (good + bad), pose


def _unit(v):
    return v / np.sqrt(np.sum(v * v))
