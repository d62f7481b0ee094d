# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Bushing rates as design variables, and a scene's compliance rates as outputs (issue 39).

Variables are named `<constraint>.bushing.<field>`: axial and radial (N/mm) of every
constraint with a bushing, and torsion and conical (N m/deg) of an arm's where its file gives
them above 0 (a link's bushing has no angular rates). The kinematics ignores bushings, so
only the statics' outputs see them: the compliance rates (statics.RATE_COLUMNS, as the
quantity registry names them), from statics.Statics(scene).rates at each travel.

    names = bushing_names(scene)                    (b,) variable names, constraint order
    values = bushing_values(scene)                  (b,) their rates in the scene
    scene2 = with_bushings(scene, values)           the same Scene with other rates
    have = rate_names(scene, travels)               the rates the scene has (not NaN)
    table = compliance_of(scene, travels, have)     (T, R): NaN where a rate failed
    d = compliance_rates(scene, travels, have, points=..., bushings=...)
        d(rate)/d(variable) by central differences of Statics: (T, R, k, 3) per hardpoint
        coordinate (per mm) and (T, R, b) per bushing rate (per N/mm or N m/deg)

The statics is compiled and has no jets: its derivatives here are central differences
(Richardson-extrapolated, error O(h^4)), each variable moved alone and the scene solved
again, where the kinematic quantities have exact ones (sensitivity.py).
"""

from __future__ import annotations

from dataclasses import replace
import math
from typing import TYPE_CHECKING

import numpy as np

from ..model.scene_moves import with_points
from ..statics.compliance import RATE_COLUMNS
from ..statics.statics import Statics

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..model.scene import Scene

LINEAR = ('axial', 'radial')        # N/mm: every bushing
ANGULAR = ('torsion', 'conical')    # N m/deg: an arm's (circle) only
BUSHING = '.bushing.'
# central-difference steps: a bushing rate moves by this fraction of itself, a hardpoint
# coordinate by this many mm. Richardson's two steps (h and h / 2) leave an error of order
# h^4 (1e-8 of a derivative of a rate going as 1 / k at 1 %) against the statics' own
# scatter (a rate solved from other starts differs by 2e-13 of itself: 3 x that / h)
RELATIVE_STEP = 1e-2
POINT_STEP_MM = 0.01


def bushing_fields(scene: Scene) -> list[tuple[int, str]]:
    """
    Return (constraint index, field) of every bushing rate of a scene, in file order.

    An arm's torsion or conical rate of 0 (the default: no such part) is not one.
    """
    out = []
    for i, c in enumerate(scene.constraints):
        if c.bushing is not None:
            out += [(i, f) for f in LINEAR + (ANGULAR if c.type == 'circle' else ())
                    if f in LINEAR or getattr(c.bushing, f) > 0]
    return out


def bushing_names(scene: Scene) -> tuple[str, ...]:
    """Return the names `<constraint>.bushing.<field>` of a scene's bushing rates."""
    return tuple(f'{scene.constraints[i].name}{BUSHING}{f}' for i, f in bushing_fields(scene))


def bushing_values(scene: Scene) -> np.ndarray:
    """Return a scene's bushing rates (b,): N/mm (axial, radial), N m/deg (torsion, conical)."""
    return np.array([getattr(scene.constraints[i].bushing, f) for i, f in bushing_fields(scene)],
                    dtype=float)


def with_bushings(scene: Scene, values: ArrayLike) -> Scene:
    """Return the same scene with its bushing rates at values (b,), as bushing_values orders."""
    constraints = list(scene.constraints)
    changes: dict[int, dict] = {}
    for (i, f), value in zip(bushing_fields(scene), np.asarray(values, dtype=float)):
        changes.setdefault(i, {})[f] = float(value)
    for i, change in changes.items():
        constraints[i] = replace(constraints[i], bushing=replace(constraints[i].bushing,
                                                                 **change))
    return replace(scene, constraints=tuple(constraints))


def compliance_of(scene: Scene, travels: ArrayLike, names: tuple[str, ...],
                  rack: float = 0.0) -> np.ndarray:
    """Return the rates names (R,) at travels (T,) mm: (T, R), NaN where a rate failed."""
    statics = Statics(scene)
    travels = np.asarray(travels, dtype=float).ravel()
    out = np.full((len(travels), len(names)), math.nan)
    for t, travel in enumerate(travels):
        rates = statics.rates(float(travel), rack).rates
        out[t] = [rates.get(n, math.nan) for n in names]
    return out


def rate_names(scene: Scene, travels: ArrayLike, rack: float = 0.0) -> tuple[str, ...]:
    """Return the RATE_COLUMNS a scene has at every travel, in the registry's order."""
    values = compliance_of(scene, travels, RATE_COLUMNS, rack)
    return tuple(n for n, ok in zip(RATE_COLUMNS, np.isfinite(values).all(axis=0)) if ok)


def _central(evaluate, h: float) -> np.ndarray:
    """Return the Richardson-extrapolated central difference of evaluate(offset) at 0."""
    def diff(step):
        return (evaluate(step) - evaluate(-step)) / (2.0 * step)
    return (4.0 * diff(h / 2.0) - diff(h)) / 3.0


def compliance_rates(scene: Scene, travels: ArrayLike, names: tuple[str, ...],
                     points: ArrayLike | None = None, bushings: ArrayLike | None = None,
                     rack: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """
    Return d(rates)/d(hardpoint coordinate) (T, R, k, 3) and d(rates)/d(bushing rate) (T, R, b).

    points (k, 3), bushings (b,): which variables to differentiate by (True, or a standard
    deviation above 0; None: all); the others' derivatives are 0. Central differences of
    Statics on the scene with one variable moved (with_points, with_bushings), see above.
    """
    travels = np.asarray(travels, dtype=float).ravel()
    base, rates0 = scene.points, bushing_values(scene)
    wanted_points = np.ones(base.shape, bool) if points is None else np.asarray(points) != 0
    wanted_rates = np.ones(rates0.shape, bool) if bushings is None else \
        np.asarray(bushings) != 0
    by_point = np.zeros((len(travels), len(names)) + base.shape)
    by_rate = np.zeros((len(travels), len(names), len(rates0)))
    for k, a in zip(*np.nonzero(wanted_points)):
        def moved(offset, k=k, a=a):
            values = base.copy()
            values[k, a] += offset
            return compliance_of(with_points(scene, values), travels, names, rack)
        by_point[:, :, k, a] = _central(moved, POINT_STEP_MM)
    for b in np.flatnonzero(wanted_rates):
        def changed(offset, b=b):
            values = rates0.copy()
            values[b] += offset
            return compliance_of(with_bushings(scene, values), travels, names, rack)
        by_rate[:, :, b] = _central(changed, RELATIVE_STEP * rates0[b])
    return by_point, by_rate
