# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

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
The table is compiled once, from the scene's hardpoint table (Scene.points rowed by
Scene.layout: geometry_of, equation_table), for one design (compile_scene, kept on the
Scene), a batch of variants (leading axes), or on jets.Jet points (exact d/dH).
"""

from __future__ import annotations

from dataclasses import dataclass
import math
from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from . import jacobian_kernel, kernel
from ..base import geometry, jets as jt
from ..model.layout import Layout, layout_of  # noqa: F401 (also read from here)
from ..model.scene import CHECKS

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..model.scene import Scene

# Beyond this scaled condition number (scaled_condition) a position counts as singular: the
# Jacobian then holds about 4 significant digits of 16, and its null direction (the motion
# it does not determine) is as good as exact; a duplicated link gives 1e16 and more.
SINGULAR_CONDITION = 1e12
# line_normals: the spin axis helps build a strut's normals unless nearly parallel to it
HELPER_SINE = 0.1
# where a Scene keeps its Mechanism (compile_scene)
COMPILED = '_mechanism'


class Geometry(NamedTuple):
    """The equation rows of one design or of many (leading axes), arrays or jets.Jet, mm."""

    center0: object     # (..., 3) design wheel centre M0
    spin_axis: object   # (..., 3) design outboard spin-axis unit vector
    offset: object      # (..., 5, 3) carrier point minus M0
    base: object        # (..., 5, 3) body point
    length: object      # (..., 5) link length (1.0 on line rows)
    normal: object      # (..., 5, 3) carrier-fixed unit normal (0 on sphere rows)


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


def geometry_of(layout: Layout, points) -> Geometry:
    """
    Return the rows of the design(s) whose hardpoints are points (..., k, 3) mm.

    The one compile of a mechanism: compile_scene packs it for one design, the tolerance
    study for a batch of variants (leading axes), and the sensitivities run it on jets.Jet
    points (d/dH), since jets' functions take plain arrays and Jets alike.
    """
    center0 = points[..., layout.center, :]
    spin = center0 - points[..., layout.spin, :]
    joints = points[..., layout.carrier, :]
    bases = points[..., layout.base, :]
    offset = joints - center0[..., None, :]
    length = jt.where(layout.line, 1.0, jt.norm(joints - bases))
    n1, n2 = line_normals(bases - joints, spin[..., None, :])
    normal = jt.where(layout.line[:, None], jt.where((layout.normal == 0)[:, None], n1, n2), 0.0)
    return Geometry(center0, jt.unit(spin), offset, bases, length, normal)


def line_normals(direction, helper):
    """
    Return a strut line's two unit normals (..., 3), square to each other and to the line.

    helper (the spin axis M0 - N0) builds the first unless nearly parallel to the line
    (sine below HELPER_SINE); then the x axis does. Arrays or jets.Jet.
    """
    d = jt.unit(direction)
    sine = jt.value(jt.norm(jt.cross(d, jt.unit(helper))))
    helper = jt.where((sine > HELPER_SINE)[..., None], helper, np.array([1.0, 0.0, 0.0]))
    n1 = jt.unit(jt.cross(d, helper))
    return n1, jt.cross(d, n1)


def equation_table(layout: Layout, geom: Geometry) -> np.ndarray:
    """Pack plain-array geometry into kernel equation tables (..., 5, kernel.COLUMNS)."""
    offset = np.asarray(geom.offset)
    out = np.zeros(offset.shape[:-1] + (kernel.COLUMNS,))
    out[..., kernel.KIND] = np.where(layout.line, kernel.LINE, kernel.SPHERE)
    out[..., kernel.POINT:kernel.POINT + 3] = offset
    out[..., kernel.BASE:kernel.BASE + 3] = geom.base
    out[..., kernel.LENGTH] = np.where(layout.line, 0.0, geom.length)
    out[..., kernel.STEER] = layout.steer
    out[..., kernel.NORMAL:kernel.NORMAL + 3] = geom.normal
    return out


def radii(layout: Layout, equations: np.ndarray, center0: ArrayLike) -> np.ndarray:
    """
    Return each row's radius (..., 5) mm: what a length tolerance of its constraint changes.

    A link's row: its length l. An arm's two rows: the ball's distance rho from the arm's
    axis (its pivot-to-ball distance), the same for both. A strut's rows: 0 (no length).
    A link is an arm whose radius is its length: a row's length l changes with the radius
    as l^2 - rho^2 (the ball's place along the axis) stays, dl/drho = rho / l.
    equations (..., 5, COLUMNS), center0 (..., 3) the design wheel centre M0 of each table.
    """
    eqs = np.asarray(equations, dtype=float)
    out = np.where(layout.line, 0.0, eqs[..., kernel.LENGTH])
    ball = eqs[..., kernel.POINT:kernel.POINT + 3] + np.asarray(center0)[..., None, :]
    for c in np.unique(layout.constraint):
        rows = np.flatnonzero(layout.constraint == c)
        if len(rows) == 2 and not layout.line[rows[0]]:   # an arm: axis A0-A1
            a0, a1 = (eqs[..., r, kernel.BASE:kernel.BASE + 3] for r in rows)
            arm = ball[..., rows[0], :] - a0
            along = geometry.unit(a1 - a0)
            rho = np.linalg.norm(arm - np.sum(arm * along, axis=-1)[..., None] * along, axis=-1)
            out[..., rows] = rho[..., None]
    return out


def lengthened(layout: Layout, equations: np.ndarray, center0: ArrayLike,
               delta: ArrayLike) -> np.ndarray:
    """
    Return equation tables (..., 5, COLUMNS) with each constraint's length changed by delta.

    delta (..., c) mm, one per constraint: a link's length, an arm's pivot-to-ball distance
    (radii: l^2 - rho^2 kept); a strut has none (its delta is ignored). center0 (..., 3): the
    design wheel centre of each table. The hardpoints are unchanged, so the design pose no
    longer assembles: the solvers re-assemble it (from the nominal pose).
    """
    out = np.array(equations, dtype=float)
    rho = radii(layout, out, center0)
    grown = rho + np.asarray(delta, dtype=float)[..., layout.constraint]
    length = out[..., kernel.LENGTH]
    out[..., kernel.LENGTH] = np.where(layout.line, length,
                                       np.sqrt(length * length - rho * rho + grown * grown))
    return out


def compile_scene(scene: Scene) -> Mechanism:
    """
    Return the Mechanism of a Scene, compiled from its hardpoint table once.

    The Scene (frozen) keeps it beside its other derived values (its instance dict, as
    functools.cached_property does): every solver of one scene shares one Mechanism, whose
    arrays nobody writes. A moved design (model.with_points) is another Scene, compiled anew.
    """
    mech = scene.__dict__.get(COMPILED)
    if mech is None:
        mech = scene.__dict__[COMPILED] = compile_points(scene)
    return mech


def compile_points(scene: Scene) -> Mechanism:
    """Build the Mechanism of a Scene from its hardpoint table (Scene.points, Scene.layout)."""
    layout = scene.layout
    geom = geometry_of(layout, scene.points)
    equations = equation_table(layout, geom)
    first = np.array([list(layout.constraint).index(i) for i in range(len(scene.constraints))])
    offsets = geom.offset[first]   # each constraint's carrier point, from a row of it
    return Mechanism(
        design_center=geom.center0.copy(), offsets=offsets,
        point_names=tuple(c.name for c in scene.constraints),
        equations=np.ascontiguousarray(equations), equation_point=layout.constraint.copy(),
        spin_axis=geom.spin_axis, lever=float(np.max(np.linalg.norm(offsets, axis=1))))


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


def singular_design_warnings(scene: Scene) -> tuple[str, ...]:
    """
    Return a warning if the design position itself is singular, else ().

    Singular: the scaled condition number of the guidance equations there
    (mechanism.design_condition, numpy only: no kernel is compiled or loaded) is beyond
    mechanism.SINGULAR_CONDITION, or not finite. Such a scene loads, and every travel but 0
    is then out of reach with Status.SINGULAR.
    """
    condition = design_condition(scene)
    if condition <= SINGULAR_CONDITION:   # False for NaN
        return ()
    return (f'{scene.source}: the design position is singular (scaled condition number '
            f'{condition:.3g}, beyond {SINGULAR_CONDITION:g}): the links do not determine the '
            "carrier's motion (two links alike?); only travel 0 can be solved",)


CHECKS.append(singular_design_warnings)   # every scene load asks it (model/scene.py)
