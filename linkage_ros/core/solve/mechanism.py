"""
The mechanism of a scene: its 5 guidance equations as a table, on the carrier pose (M, R).

The pose is the wheel-centre position M (mm, vehicle frame) and the carrier rotation R
relative to design: a carrier point at design position b0 is at M + R (b0 - M0).
Residuals are lengths in mm, so a tolerance reads the same in every scene:
  sphere (eq. 2, 13): |B - A| - l, written (|B - A|^2 - l^2) / 2l so it stays smooth;
  circle (eqs. 3-4): two spheres about the two axis points;
  line (strut):       distance of the top mount T from the carrier-fixed strut line,
                      as two components along carrier-fixed normals of the line.
The equations themselves are written once, compiled, in kernel.py; the functions here apply
them to one pose or to a batch (leading axes of center (..., 3) and rotation (..., 3, 3)).
"""

from __future__ import annotations

from dataclasses import dataclass
import math
from typing import TYPE_CHECKING

import numpy as np

from . import jacobian_kernel, kernel
from ..base import geometry
from ..base.geometry import unit

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..model.scene import Scene

# Beyond this scaled condition number (scaled_condition) a position counts as singular: the
# Jacobian then holds about 4 significant digits of 16, and its null direction (the motion
# it does not determine) is as good as exact; a duplicated link gives 1e16 and more.
SINGULAR_CONDITION = 1e12


@dataclass(frozen=True)
class Mechanism:
    """A scene compiled for the solvers. m carrier points (one per constraint)."""

    design_center: np.ndarray    # M0 (3,)
    offsets: np.ndarray          # (m, 3) carrier points minus M0, carrier frame = design frame
    point_names: tuple[str, ...]   # (m,) names of the carrier points
    equations: np.ndarray        # (5, kernel.COLUMNS) one row per guidance equation
    equation_point: np.ndarray   # (5,) index into offsets of each equation's carrier point
    spin_axis: np.ndarray        # (3,) design outboard spin-axis unit vector
    lever: float                 # mm: largest |offset|, turns a rotation step into mm

    @property
    def steered(self) -> bool:
        """Whether a base point moves with the steering rack (a steer: rack link)."""
        return bool(self.equations[:, kernel.STEER].any())

    def line_rows(self) -> list[tuple[int, np.ndarray, np.ndarray]]:
        """
        Return the strut line equations, at design.

        One tuple (carrier point index, top mount T (3,) mm, carrier-fixed unit normal (3,))
        per strut line equation.
        """
        return [(int(self.equation_point[i]), row[kernel.BASE:kernel.BASE + 3],
                 row[kernel.NORMAL:kernel.NORMAL + 3])
                for i, row in enumerate(self.equations) if row[kernel.KIND] == kernel.LINE]


def compile_scene(scene: Scene) -> Mechanism:
    """Build the Mechanism of a validated Scene: sphere rows first, then strut line rows."""
    m0 = scene.wheel_center
    offsets = np.array([c.carrier - m0 for c in scene.constraints])
    spheres, lines = [], []
    for index, c in enumerate(scene.constraints):
        if c.type in ('sphere', 'circle'):
            for base in c.base:
                row = np.zeros(kernel.COLUMNS)
                row[kernel.KIND] = kernel.SPHERE
                row[kernel.BASE:kernel.BASE + 3] = base
                row[kernel.LENGTH] = np.linalg.norm(c.carrier - base)
                row[kernel.STEER] = 1.0 if c.steer == 'rack' else 0.0
                spheres.append((index, row))
        else:
            for normal in line_normals(c.base[0] - c.carrier, m0 - scene.spin_axis_point):
                row = np.zeros(kernel.COLUMNS)
                row[kernel.KIND] = kernel.LINE
                row[kernel.BASE:kernel.BASE + 3] = c.base[0]
                row[kernel.NORMAL:kernel.NORMAL + 3] = normal
                lines.append((index, row))
    rows = spheres + lines
    equations = np.array([row for _, row in rows])
    points = np.array([index for index, _ in rows], dtype=np.int64)
    equations[:, kernel.POINT:kernel.POINT + 3] = offsets[points]
    return Mechanism(
        design_center=m0.copy(), offsets=offsets,
        point_names=tuple(c.name for c in scene.constraints),
        equations=np.ascontiguousarray(equations), equation_point=points,
        spin_axis=unit(scene.wheel_center - scene.spin_axis_point),
        lever=float(np.max(np.linalg.norm(offsets, axis=1))))


def line_normals(direction: ArrayLike, spin_axis: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Return two unit normals of a strut line, chosen square to each other and to the line."""
    d = unit(direction)
    helper = spin_axis if np.linalg.norm(np.cross(d, unit(spin_axis))) > 0.1 else [1.0, 0, 0]
    n1 = unit(np.cross(d, helper))
    return n1, np.cross(d, n1)


def carrier_points(mech: Mechanism, center: ArrayLike, rotation: ArrayLike) -> np.ndarray:
    """Return carrier points (m, 3) mm of a pose; batched: center (n, 3), rotation (n, 3, 3)."""
    return geometry.carrier_points(mech.offsets, center, rotation)


def poses(center: ArrayLike, rotation: ArrayLike,
          rack: ArrayLike = 0.0) -> tuple[tuple[int, ...], np.ndarray, np.ndarray, np.ndarray]:
    """
    Flatten a pose or a batch of poses into contiguous float64 arrays for the kernels.

    The leading axes of center, rotation and rack are broadcast together. Returns (leading
    shape, centers (n, 3), rotations (n, 3, 3), racks (n,)).
    """
    center, rotation = np.asarray(center, dtype=float), np.asarray(rotation, dtype=float)
    rack = np.asarray(rack, dtype=float)
    shape = np.broadcast_shapes(center.shape[:-1], rotation.shape[:-2], rack.shape)
    n = int(np.prod(shape))
    return (shape,
            np.ascontiguousarray(np.broadcast_to(center, shape + (3,)).reshape(n, 3)),
            np.ascontiguousarray(np.broadcast_to(rotation, shape + (3, 3)).reshape(n, 3, 3)),
            np.ascontiguousarray(np.broadcast_to(rack, shape).reshape(n)))


def linearize(mech: Mechanism, center: ArrayLike, rotation: ArrayLike,
              rack: ArrayLike = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """
    Return residuals (..., 5) and their Jacobian d/d(M, omega) (..., 5, 6) at a pose or batch.

    omega is a small rotation applied in the vehicle frame (R <- exp(omega) R); Jacobian
    column 2 (dZ_M) is the travel direction, kernel.FREE the unknowns. rack (mm, scalar or
    (...,)): steering rack travel, + = to the left, moving the base points of steer: rack
    constraints along y.
    """
    shape, centers, rotations, racks = poses(center, rotation, rack)
    f = np.empty((len(centers), kernel.N_EQUATIONS))
    jac = np.empty((len(centers), kernel.N_EQUATIONS, 6))
    kernel.linearize_many(mech.equations, centers, rotations, racks, f, jac)
    return f.reshape(shape + (kernel.N_EQUATIONS,)), jac.reshape(shape + (kernel.N_EQUATIONS, 6))


def length_errors(mech: Mechanism, center: ArrayLike, rotation: ArrayLike,
                  rack: ArrayLike = 0.0) -> np.ndarray | float:
    """Return the largest constraint violation (mm) as a length: link error or strut offset."""
    shape, centers, rotations, racks = poses(center, rotation, rack)
    out = np.empty(len(centers))
    kernel.residual_many(mech.equations, centers, rotations, racks, out)
    return out.reshape(shape) if shape else float(out[0])


def rack_derivative(mech: Mechanism, center: ArrayLike, rotation: ArrayLike,
                    rack: ArrayLike = 0.0) -> np.ndarray:
    """Return d(residuals)/d(rack) (..., 5): the steer rows' base points move along +y."""
    shape, centers, rotations, racks = poses(center, rotation, rack)
    out = np.empty((len(centers), kernel.N_EQUATIONS))
    kernel.rack_column_many(mech.equations, centers, rotations, racks, out)
    return out.reshape(shape + (kernel.N_EQUATIONS,))


def scaled_condition(mech: Mechanism, jacobian: ArrayLike) -> float:
    """
    Return the 2-norm condition number of J_free with its rotation columns made lengths.

    jacobian (5, 6) at a pose; the rotation columns are divided by the mechanism's lever
    (mm/rad -> mm/mm), so that the number is dimensionless and the same for a scene at any
    scale (five_link about 5 at design, however it is scaled). inf (or beyond
    SINGULAR_CONDITION) when rank-deficient; NaN if the Jacobian is not finite.
    """
    scaled = np.array(jacobian, dtype=float)
    scaled[:, 3:] /= mech.lever
    return float(jacobian_kernel.condition(scaled))


def is_singular(matrix: ArrayLike) -> np.ndarray | bool:
    """
    Tell whether square matrices (..., k, k) are singular, as a numerical answer needs it.

    Singular: the condition number with every column scaled to unit length (so that it does
    not depend on the columns' units) is beyond SINGULAR_CONDITION, or not finite. LAPACK's
    solve alone answers a rank-deficient system that happens to be consistent.
    """
    a = np.asarray(matrix, dtype=float)
    with np.errstate(divide='ignore', invalid='ignore'):   # a zero column: singular
        scaled = a / np.linalg.norm(a, axis=-2, keepdims=True)
        return ~(np.linalg.cond(np.nan_to_num(scaled, posinf=0.0, neginf=0.0))
                 <= SINGULAR_CONDITION)


def design_condition(scene: Scene) -> float:
    """
    Return the scaled condition number (scaled_condition) at a scene's design position.

    Beyond SINGULAR_CONDITION the design position is singular: the links do not determine
    the carrier's motion there (two alike, say), and no travel but 0 can be solved. numpy
    only (design_jacobian, LAPACK's SVD): every scene load asks it (scene.py warns), and must
    neither compile a kernel on a cold cache (5 s) nor load one (0.7 s).
    """
    mech = compile_scene(scene)
    jac = design_jacobian(mech)
    scaled = np.column_stack((jac[:, :2], jac[:, 3:] / mech.lever))   # kernel.FREE columns
    with np.errstate(divide='ignore', invalid='ignore'):
        return float(np.linalg.cond(scaled)) if np.isfinite(scaled).all() else math.nan


def design_jacobian(mech: Mechanism) -> np.ndarray:
    """
    Return the Jacobian d/d(M, omega) (5, 6) at the design position (R = I, rack 0), by numpy.

    kernel.linearize at that pose, where a carrier point's offset r is its design offset:
    sphere row d / l and r x d / l with d = B - A; line row -n and n x (T - C) - r x n.
    test_singular checks it against the kernel on every bundled scene.
    """
    eqs = mech.equations
    r = eqs[:, kernel.POINT:kernel.POINT + 3]
    base = eqs[:, kernel.BASE:kernel.BASE + 3]
    normal = eqs[:, kernel.NORMAL:kernel.NORMAL + 3]
    sphere = (eqs[:, kernel.KIND] == kernel.SPHERE)[:, None]
    length = np.where(sphere, eqs[:, kernel.LENGTH:kernel.LENGTH + 1], 1.0)   # lines: none
    d = (r + mech.design_center - base) / length
    to_top = base - mech.design_center - r
    return np.where(sphere, np.hstack((d, np.cross(r, d))),
                    np.hstack((-normal, np.cross(normal, to_top) - np.cross(r, normal))))
