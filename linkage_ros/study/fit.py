# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Fitting hardpoints to target curves: bounded least squares with the exact Jacobian.

    fit(targets, starts=1) -> Fit

The unknowns are the free coordinates' offsets from the design (mm, within their bounds);
the residuals are weight x (quantity - target value) at every travel of every target
(targets.py). Each evaluation solves the moved design's sweep (kinematics.sweep, the same
path as linkage-sweep) and its exact sensitivities (sensitivity.py): the residuals and their
Jacobian come together, and scipy.optimize.least_squares ('trf', made for bounds) takes
both. A design that does not assemble over the travels (a travel out of reach, a singular
position, links that cannot be built) gets residuals of PENALTY: the step that led there is
rejected and the trust region shrinks, so the fit backs off instead of failing.

Several starts (starts > 1: the design, then points drawn uniformly within the bounds from
SeedSequence(seed, spawn_key=(start,))) run as separate tasks of an executor (executor.py)
and the best is kept.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from scipy.optimize import least_squares

from .executor import in_process
from .targets import Targets
from ..core.base import LinkageError
from ..core.vary import scene_with, sensitivities

PENALTY = 1e6   # each residual of a design that does not assemble over the travels


class Evaluation(NamedTuple):
    """The residuals of one design: (R,), their Jacobian (R, m), errors per target."""

    residual: np.ndarray
    jacobian: np.ndarray
    errors: tuple[np.ndarray, ...]   # per target: quantity - value at its travels (NaN: none)
    values: tuple[np.ndarray, ...]   # per target: the quantity at its travels
    assembled: bool
    message: str


class Fit(NamedTuple):
    """The outcome of a fit: the best start's design and what it did."""

    offsets: np.ndarray           # (m,) mm, the free coordinates relative to the design
    hardpoints: np.ndarray        # (k, 3) mm, the fitted design
    before: Evaluation
    after: Evaluation
    evaluations: int              # residual evaluations (least_squares' nfev), every start
    jacobians: int                # Jacobian evaluations (njev), every start
    start: int                    # the start that gave the best fit
    message: str                  # least_squares' message of that start
    unassembled: int              # evaluations whose design did not assemble (backed off)


def hardpoints_of(targets: Targets, offsets: np.ndarray) -> np.ndarray:
    """Return the hardpoints (k, 3) mm with the free coordinates moved by offsets (m,) mm."""
    values = targets.design.values.copy()
    for (i, a), offset in zip(targets.free, offsets):
        values[i, a] += offset
    return values


def evaluate(targets: Targets, offsets: np.ndarray) -> Evaluation:
    """Solve the design moved by offsets (m,) mm; return its residuals and their Jacobian."""
    size = sum(len(t.travel) for t in targets.targets)
    points = hardpoints_of(targets, offsets)
    travels = np.unique(np.concatenate([t.travel for t in targets.targets]))
    quantities = tuple(dict.fromkeys(t.quantity for t in targets.targets))
    try:
        scene = scene_with(targets.design, points)
        exact = sensitivities(scene, travels, wanted=quantities)
        message = '' if exact.success else exact.message
    except LinkageError as exc:   # SceneError: the moved points do not make a mechanism
        message = str(exc)
    if message or not np.isfinite(exact.nominal).all():
        message = message or 'a position is singular (no derivative)'
        nan = tuple(np.full(len(t.travel), np.nan) for t in targets.targets)
        return Evaluation(np.full(size, PENALTY), np.zeros((size, len(offsets))), nan, nan,
                          False, message)
    residual, jacobian, errors, values = [], [], [], []
    free = np.array([3 * i + a for i, a in targets.free], dtype=int)
    for t in targets.targets:
        rows = np.searchsorted(travels, t.travel)
        q = quantities.index(t.quantity)
        value = exact.nominal[rows, q]
        values.append(value)
        errors.append(value - t.value)
        residual.append(t.weight * errors[-1])
        derivative = exact.derivative[rows, q].reshape(len(rows), -1)[:, free]
        jacobian.append(t.weight * derivative)
    return Evaluation(np.concatenate(residual), np.concatenate(jacobian), tuple(errors),
                      tuple(values), True, '')


def fit_start(item: tuple[Targets, int, int]) -> dict:
    """Run least squares from one start (targets, start index, seed); a task of fit()."""
    targets, start, seed = item
    lower, upper = targets.lower, targets.upper
    x0 = np.clip(np.zeros(len(lower)), lower, upper)
    if start:
        rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(start,)))
        x0 = rng.uniform(lower, upper)
    cache, failed = {}, []

    def evaluated(x):
        key = x.tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = evaluate(targets, x)
            if not cache[key].assembled:
                failed.append(x)
        return cache[key]

    first = evaluated(x0)
    if not first.assembled:
        return {'start': start, 'x': x0, 'cost': np.inf, 'nfev': 1, 'njev': 0, 'failed': 1,
                'message': f'the start does not assemble: {first.message}'}
    answer = least_squares(lambda x: evaluated(x).residual, x0,
                           jac=lambda x: evaluated(x).jacobian,
                           bounds=(lower, upper), method='trf', x_scale='jac')
    return {'start': start, 'x': answer.x, 'cost': float(answer.cost), 'nfev': answer.nfev,
            'njev': answer.njev or 0, 'failed': len(failed), 'message': answer.message}


def fit(targets: Targets, starts: int = 1, seed: int = 0, run=None, progress=None) -> Fit:
    """
    Fit the free coordinates to the targets; starts > 1 tries more starting points.

    run(function, items, progress): an executor (None: one after another here). Raises
    LinkageError when the design itself does not assemble over the target travels.
    """
    before = evaluate(targets, np.zeros(len(targets.lower)))
    if not before.assembled:
        raise LinkageError(targets.source, f'the design does not assemble over the target '
                           f'travels: {before.message}')
    items = [(targets, i, seed) for i in range(starts)]
    outcomes = (run or in_process)(fit_start, items, progress)
    best = min(outcomes, key=lambda o: (o['cost'], o['start']))
    after = evaluate(targets, best['x'])
    if not after.assembled:   # no start assembled: keep the design
        best = dict(best, x=np.zeros(len(targets.lower)))
        after = before
    return Fit(best['x'], hardpoints_of(targets, best['x']), before, after,
               sum(o['nfev'] for o in outcomes), sum(o['njev'] for o in outcomes),
               best['start'], best['message'], sum(o['failed'] for o in outcomes))
