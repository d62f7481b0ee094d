# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A batch of design variants of one scene, solved at once (variant_kernel.py, compiled).

    starts, nominal = design_starts(scene, travels)   the design solved at the travels (T,)
                                                      mm: its states (T, STATE_SIZE), where
                                                      every variant's solve starts, and the
                                                      Sweep; LinkageError if one is missed
    center, rotation = poses(starts)                   (T, 3) mm, (T, 3, 3)
    controls = controls_of(scene)                      the solver settings (its Continuation's)
    values, solved = solve_variants(layout, points, deltas, starts, travels, controls)
        points (V, k, 3) mm the variants' hardpoints; deltas (V, c) mm length changes or None;
        values (V, T, len(QUANTITIES)): camber, toe (rad), wheel centre x, y, z (mm), NaN
        rows for a degenerate variant; solved (V, T) bool

What solve_variants leaves unsolved is the caller's to solve by Continuation (arclength
included), to tell a travel out of reach from a hard step.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from . import variant_kernel
from ..base.errors import LinkageError
from ..solve import state
from ..solve.continuation import Continuation
from ..solve.kinematics import sweep
from ..solve.mechanism import compile_scene, equation_table, geometry_of, lengthened, linearize

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..model.scene import Scene
    from ..solve.kinematics import Sweep

QUANTITIES = variant_kernel.QUANTITIES


def controls_of(scene: Scene) -> tuple:
    """Return the variant kernel's Controls: the scene's Continuation settings."""
    cfg = Continuation(scene).settings
    # a variant whose pose is within one continuation substep of the design's is on its
    # branch: another branch is a link's length away
    return tuple(variant_kernel.Controls(scene.side_sign, cfg.tol, cfg.max_iter, cfg.max_step,
                                         cfg.min_step, cfg.max_substeps, cfg.max_step))


def design_starts(scene: Scene, travels: ArrayLike) -> tuple[np.ndarray, Sweep]:
    """Return the design's solved states (T, STATE_SIZE) at travels (T,) mm, and its Sweep."""
    travels = np.asarray(travels, dtype=float).ravel()
    nominal = sweep(scene, travels)
    if not nominal.success or len(nominal.travel) != len(travels):
        raise LinkageError('--travel', f'the design does not reach every travel: '
                           f'{nominal.message}')
    jac = linearize(compile_scene(scene), nominal.wheel_center, nominal.rotation)[1]
    starts = np.array([state.pack(t, 0.0, c, r, j) for t, c, r, j in
                       zip(travels, nominal.wheel_center, nominal.rotation, jac)])
    return starts.reshape(len(travels), -1), nominal


def poses(starts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return the wheel centres (T, 3) mm and rotations (T, 3, 3) of states (T, STATE_SIZE)."""
    return state.centers(starts), state.rotations(starts)


def solve_variants(layout, points: np.ndarray, deltas: np.ndarray | None, starts: np.ndarray,
                   travels: np.ndarray, controls: tuple) -> tuple[np.ndarray, np.ndarray]:
    """Solve V variants at T travels from the design's states: (values, solved), see above."""
    with np.errstate(invalid='ignore', divide='ignore'):   # a degenerate variant: NaN rows
        geom = geometry_of(layout, points)
        equations = equation_table(layout, geom)
        if deltas is not None:
            equations = lengthened(layout, equations, geom.center0, deltas)
    variants = variant_kernel.Variants(np.ascontiguousarray(equations),
                                       np.ascontiguousarray(geom.spin_axis),
                                       np.ascontiguousarray(geom.center0))
    n, count = len(points), len(travels)
    values = np.empty((n, count, variant_kernel.OUTPUTS))
    status = np.empty((n, count), dtype=np.int64)
    variant_kernel.solve_variants(tuple(variants), starts, travels, controls, values, status)
    return values, status == variant_kernel.SOLVED
