# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The public entry points of the kinematics core: one command at a time, or a table.

    Continuation(scene, method='fast').solve(travel_mm) -> Solution   (stateful; the node)
    sweep(scene, travels_mm, method='fast') -> Sweep                   (a table of positions)

Continuation (continuation.py) solves each command from the last good pose, which keeps the
carrier on the assembly branch of the design position; sweep() solves a table the same way,
the fast method batched. Nothing here raises for numerics: a Solution or Sweep carries
success, a status (status.Status) and a message; a sweep whose first travel is out of reach
is a table of no rows.
"""

from __future__ import annotations

from dataclasses import dataclass, field
import math
from typing import Any, TYPE_CHECKING

import numpy as np

from . import kernel, state
from .continuation import Continuation, METHODS, Settings, Solution
from .mechanism import carrier_points, length_errors
from ..base.finite import all_finite
from ..base.geometry import camber_toe, quaternion_from_matrix
from ..base.status import Status

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..model.scene import Scene

__all__ = ['Continuation', 'METHODS', 'Settings', 'Solution', 'Sweep', 'sweep', 'travel_range']


@dataclass(frozen=True)
class Sweep:
    """A table of solved positions, in the order asked for. Arrays over n positions."""

    travel: np.ndarray           # (n,) mm
    wheel_center: np.ndarray     # (n, 3) mm
    rotation: np.ndarray         # (n, 3, 3)
    camber: np.ndarray           # (n,) rad
    toe: np.ndarray              # (n,) rad
    iterations: np.ndarray       # (n,)
    residual: np.ndarray         # (n,) mm
    success: bool = True
    message: str = ''
    joints: np.ndarray | None = field(default=None, repr=False)   # (n, m, 3) carrier points, mm
    rack: float = 0.0            # steering rack travel of the sweep (mm)
    quaternion: np.ndarray | None = field(default=None, repr=False)   # (n, 4) xyzw, w >= 0
    status: Status = Status.OK   # why the table ends early (success False)


def sweep(scene: Scene, travels: ArrayLike, method: str = 'fast', rack: float = 0.0,
          **settings: Any) -> Sweep:
    """
    Solve the travels (mm, in the given order) at a steering rack position (mm).

    By continuation; returns a Sweep. The paper method walks the positions one after
    another. The fast method solves knots every knot_step mm by continuation and then every
    position at once by batched Newton, each from the tangent at its nearest knot; a position
    that fails there is walked.
    """
    travels = np.asarray(travels, dtype=float).ravel()
    cont = Continuation(scene, method=method, **settings)
    if rack:
        first = cont.solve(0.0, rack)   # steer at design travel first, then sweep
        if not first.success:
            return _table(cont, [], rack, success=False, message=first.message,
                          status=first.status)
    if method == 'fast' and len(travels) > 2 and all_finite(travels):
        batch = _batched(cont, travels)
        if batch is not None:
            return batch
    return _sequential(cont, travels)


def _sequential(cont, travels):
    rows = []
    for travel in travels:
        sol = cont.solve(travel)
        if not sol.success:
            return _table(cont, rows, cont.rack, success=False, message=sol.message,
                          status=sol.status)
        rows.append(sol)
    return _table(cont, rows, cont.rack)


def _table(cont, rows, rack, success=True, message='ok', status=Status.OK):
    n = len(rows)
    center = np.array([r.wheel_center for r in rows]).reshape(n, 3)
    rotation = np.array([r.rotation for r in rows]).reshape(n, 3, 3)
    return _sweep_of(cont, np.array([r.travel for r in rows], dtype=float), center, rotation,
                     np.array([r.iterations for r in rows], dtype=int), rack, success, message,
                     status)


def _sweep_of(cont, travel, center, rotation, iterations, rack, success=True, message='ok',
              status=Status.OK):
    mech = cont.mech
    camber, toe = camber_toe(rotation @ mech.spin_axis, cont.scene.side_sign)
    return Sweep(travel=travel, wheel_center=center, rotation=rotation, camber=camber, toe=toe,
                 iterations=iterations, residual=length_errors(mech, center, rotation, rack),
                 success=success, message=message, rack=rack, status=status,
                 joints=carrier_points(mech, center, rotation),
                 quaternion=quaternion_from_matrix(rotation))


def _batched(cont, travels):
    """
    Sweep fast: knots by continuation, then every position in one compiled loop.

    The knots are walked from the state at travel 0; each position is a continuation step
    from its nearest knot. Returns None when a knot cannot be reached (the sequential walk
    then finds the limit).
    """
    cfg, rack = cont.settings, cont.rack
    knots = _knots(cont, min(travels.min(), 0.0), max(travels.max(), 0.0))
    if knots is None:
        return None
    nearest = np.argmin(np.abs(travels[:, None] - state.travels(knots)[None, :]), axis=1)
    n = len(travels)
    states = state.empty(n)
    iterations, good = np.empty(n, dtype=np.int64), np.empty(n, dtype=np.bool_)
    # Knots hold to knot_tol only, so a position at a knot may move by about that much.
    kernel.step_many(cont.setup._replace(slack=1e3 * cfg.knot_tol), nearest, knots, travels,
                     rack, states, iterations, good)
    center, rotation = state.centers(states), state.rotations(states)
    origin = cont.state
    for i in np.flatnonzero(~good):    # rare: walk it from travel 0
        cont._commit(origin)
        sol = cont.solve(travels[i])
        if not sol.success:
            return None
        center[i], rotation[i], iterations[i] = sol.wheel_center, sol.rotation, sol.iterations
    return _sweep_of(cont, travels, center, rotation, iterations, rack)


def _knots(cont, low, high):
    """
    Return states every knot_step mm from the current state (travel 0) to high and low (mm).

    These are the bump and rebound continuation chains, each step from its tangent prediction
    and checked for a branch change. Knots hold to knot_tol only (they start the batched
    solve). Returns states (k, STATE_SIZE) (state.py), or None if a step fails (the caller
    then walks, halving steps, and finds any limit).
    """
    cfg = cont.settings
    if high - low > cfg.knot_step * cfg.max_substeps:   # the walk would refuse it too
        return None
    setup = cont.setup._replace(tol=cfg.knot_tol, slack=1e3 * cfg.knot_tol)
    knots = [cont.state]
    for end in (high, low):
        last = knots[0]
        while state.travel(last) != end:
            travel = state.travel(last)
            target = end if abs(end - travel) <= cfg.knot_step else (
                travel + math.copysign(cfg.knot_step, end - travel))
            new = state.empty()
            _, ok = kernel.step(setup, last, target, cont.rack, new)
            if not ok:
                return None
            new.flags.writeable = False   # as committed states are: one kernel specialization
            last = new
            knots.append(last)
    return np.array(knots)


def travel_count(start: float, stop: float, step: float) -> float:
    """
    Return how many travels travel_range(start, stop, step) gives, counted, not built.

    math.inf for a range too long to count or to step exactly (more than 2**52 steps, or a
    span that overflows: 0 to 1e308 by 1e-308), which no caller can allocate anyway.
    """
    steps = abs(stop - start) / step + 1e-9
    if not steps < 2.0 ** 52:   # inf and NaN too
        return math.inf
    count = math.floor(steps)
    return count + 1 + (start + math.copysign(step * count, stop - start) != stop)


def travel_range(start: float, stop: float, step: float) -> np.ndarray:
    """Return the travels from start to stop (mm) inclusive at step, either direction."""
    count = int(math.floor(abs(stop - start) / step + 1e-9))
    values = start + math.copysign(step, stop - start) * np.arange(count + 1)
    return values if values[-1] == stop else np.append(values, stop)
