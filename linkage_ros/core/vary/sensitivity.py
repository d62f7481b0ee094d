# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Exact sensitivities of a suspension's quantities to its hardpoints (implicit function theorem).

At a solved position the guidance equations F(x, H) = 0 hold, x = (M_x, M_y, omega) the
unknowns and H the hardpoints (k, 3) mm. Travel is measured from the design wheel centre,
M_z = M0_z(H) + travel, so moving a hardpoint moves the solution by

    J_free dx/dH = -(dF/dH + J_z dM0_z/dH)

with dF/dH taken at the fixed pose (M, R) (mechanism.geometry_of's rows on jets.Jet,
equations.py), J the Jacobian of the solve, omega applied as R <- exp(omega) R. The pose
then carries its derivative into every quantity (quantities.py), which also depends on H
directly: the spin axis unit(M0 - N0), the carrier points relative to M0, the body points,
the design contact patch.
Exact to rounding (the only error is the pose's residual, 1e-10 mm): no finite differences.

    sensitivities(scene, travels) -> Sensitivity: derivative (n, q, k, 3), unit per mm
"""

from __future__ import annotations

import difflib
from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from .equations import free, residuals
from .outputs import ALIGNMENT_COLUMNS, element_names, quantities, SWEEP_COLUMNS
from ..base import jets as jt
from ..base.errors import LinkageError
from ..base.status import Status
from ..solve import kernel
from ..solve.kinematics import sweep
from ..solve.mechanism import compile_scene, geometry_of, is_singular, linearize, radii

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..model.scene import Scene


class Sensitivity(NamedTuple):
    """d(quantity)/d(hardpoint coordinate) at n positions; quantity unit per mm."""

    travel: np.ndarray            # (n,) mm
    quantities: tuple[str, ...]   # (q,) names, as linkage-sweep's columns
    points: tuple[str, ...]       # (k,) hardpoint names
    derivative: np.ndarray        # (n, q, k, 3): axes x, y, z
    nominal: np.ndarray           # (n, q) the quantities themselves
    success: bool = True
    message: str = 'ok'
    status: Status = Status.OK


def available(scene: Scene) -> tuple[str, ...]:
    """Return the quantities a scene has: NaN columns (no steer axis, no radius) left out."""
    names = SWEEP_COLUMNS + tuple(ALIGNMENT_COLUMNS) + tuple(element_names(scene))
    values = quantities(scene, scene.points, compile_scene(scene).design_center[None],
                        np.eye(3)[None])
    return tuple(n for n in names if np.isfinite(np.asarray(jt.value(values[n]))).all())


def check_quantities(scene: Scene, wanted) -> tuple[str, ...]:
    """Return the quantities asked for (None: all available); LinkageError for one it lacks."""
    have = available(scene)
    if wanted is None:
        return have
    for name in wanted:
        if name not in have:
            raise LinkageError(name, f'not a quantity of the scene {scene.name}'
                               f'{did_you_mean(name, have)} (its quantities: '
                               f'{", ".join(have)})')
    return tuple(wanted)


def did_you_mean(name: object, have: tuple[str, ...]) -> str:
    """Return ' (did you mean camber_deg?)' for a quantity named without its unit or misspelt."""
    text = str(name)
    close = [h for h in have if h.startswith(f'{text}_')][:1] or \
        difflib.get_close_matches(text, have, n=1)
    return f' (did you mean {close[0]}?)' if close else ''


def pose_derivative(scene: Scene, points: np.ndarray, center: np.ndarray,
                    rotation: np.ndarray, rack: float = 0.0) -> tuple[jt.Jet, jt.Jet]:
    """
    Return the solved poses as Jets of the hardpoints: M (n, 3) and R (n, 3, 3).

    center (n, 3), rotation (n, 3, 3): the poses solved for the design whose hardpoints are
    points (k, 3) mm. NaN derivatives where the Jacobian is singular.
    """
    layout = scene.layout
    params = jt.seed(points)
    size = params.g.shape[-1]
    moved = residuals(layout, geometry_of(layout, params), center, rotation, rack)   # dF/dH
    jac = linearize(compile_scene(scene), center, rotation, rack)[1]
    lift = np.zeros(size)   # dM0_z / dH: travel is counted from the design wheel centre
    lift[3 * layout.center + 2] = 1.0
    rhs = -(moved.g + jac[..., 2, None] * lift)
    return _pose_jets(center, rotation, jac, rhs, lift)


def _pose_jets(center, rotation, jac, rhs, lift):
    """Return M, R as Jets: J_free dx/dp = rhs (n, 5, P); dM_z/dp = lift (P,)."""
    a = free(jac)
    singular = is_singular(a)
    dx = np.linalg.solve(np.where(singular[..., None, None], np.eye(5), a), rhs)
    dx[singular] = np.nan
    d_center = np.stack([dx[:, 0], dx[:, 1], np.broadcast_to(lift, dx[:, 0].shape)], axis=1)
    omega = dx[:, 2:]                                      # (n, 3, P)
    d_rotation = np.cross(omega[:, :, None, :], rotation[:, :, :, None], axis=1)
    return jt.Jet(center, d_center), jt.Jet(rotation, d_rotation)


def length_rates(scene: Scene, center: np.ndarray, rotation: np.ndarray,
                 rack: float = 0.0) -> np.ndarray:
    """
    Return d(SWEEP_COLUMNS)/d(length) (n, 5, c) per constraint, at n solved poses.

    A constraint's length: a link's, an arm's pivot-to-ball distance (mechanism.radii and
    lengthened), with the hardpoints kept. Its rows' lengths l change by rho / l per mm,
    and dF/dl = -1 at a solution (F = (|d|^2 - l^2) / 2l), so J_free dx/dlength = rho / l
    on its rows; travel is imposed (M_z fixed). A strut's column is 0. Units per mm.
    """
    mech, layout = compile_scene(scene), scene.layout
    center = np.reshape(center, (-1, 3))
    rotation = np.reshape(rotation, (-1, 3, 3))
    jac = linearize(mech, center, rotation, rack)[1]
    lengths = np.where(layout.line, 1.0, mech.equations[:, kernel.LENGTH])
    gain = radii(layout, mech.equations, mech.design_center) / lengths   # (5,)
    count = len(scene.constraints)
    rhs = np.zeros((5, count))
    rhs[np.arange(5), layout.constraint] = gain
    pose = _pose_jets(center, rotation, jac, np.broadcast_to(rhs, (len(center), 5, count)),
                      np.zeros(count))
    values = quantities(scene, scene.points, *pose, rack, SWEEP_COLUMNS)
    return np.stack([np.asarray(values[name].g) for name in SWEEP_COLUMNS], axis=1)


def sensitivities(scene: Scene, travels: ArrayLike, rack: float = 0.0,
                  wanted: tuple[str, ...] | None = None, **settings) -> Sensitivity:
    """
    Return the exact sensitivities of the quantities (wanted: None = all) at the travels.

    The travels (mm) are solved by kinematics.sweep (settings go to it); a sweep that ends
    early gives the positions solved before it, success False and its message.
    """
    names = check_quantities(scene, wanted)
    travels = np.asarray(travels, dtype=float).ravel()
    table = sweep(scene, travels, rack=rack, **settings)
    points = scene.points
    n = len(table.travel)
    derivative = np.empty((n, len(names), len(points), 3))
    nominal = np.empty((n, len(names)))
    if n:
        center, rotation = pose_derivative(scene, points, table.wheel_center, table.rotation,
                                           rack)
        values = quantities(scene, jt.seed(points), center, rotation, rack, names)
        for j, name in enumerate(names):
            value = values[name]
            derivative[:, j] = value.g.reshape(n, len(points), 3)
            nominal[:, j] = value.v
    return Sensitivity(table.travel, names, scene.point_names, derivative, nominal,
                       table.success, table.message, table.status)


def sweep_column_rates(scene: Scene, center: np.ndarray, rotation: np.ndarray,
                       rack: float = 0.0) -> np.ndarray:
    """
    Return d(SWEEP_COLUMNS)/dH (n, 5, k, 3) at n solved poses, compiled (pose_kernel.py).

    The same derivatives as sensitivities() for those five columns (deg or mm per mm), by
    closed forms instead of jets: about a solve's cost per position.
    """
    from . import pose_kernel
    mech = compile_scene(scene)
    layout = scene.layout
    center = np.ascontiguousarray(np.reshape(center, (-1, 3)), dtype=float)
    rotation = np.ascontiguousarray(np.reshape(rotation, (-1, 3, 3)), dtype=float)
    jac = np.ascontiguousarray(linearize(mech, center, rotation, rack)[1])
    points = scene.points
    out = np.empty((len(center), 5, points.size))
    pose_kernel.sweep_rates_many(
        mech.equations, layout.carrier, layout.base, np.array([layout.center, layout.spin]),
        mech.design_center, mech.spin_axis,
        float(np.linalg.norm(scene.wheel_center - scene.spin_axis_point)),
        float(scene.side_sign), center, rotation, jac, float(rack), out)
    out[:, :2] = np.degrees(out[:, :2])
    return out.reshape(len(center), 5, len(points), 3)


def rows(result: Sensitivity):
    """Yield (travel_mm, quantity, point, axis, derivative): the long table of a Sensitivity."""
    for i, travel in enumerate(result.travel):
        for j, quantity in enumerate(result.quantities):
            for k, point in enumerate(result.points):
                for a, axis in enumerate('xyz'):
                    yield travel, quantity, point, axis, result.derivative[i, j, k, a]
