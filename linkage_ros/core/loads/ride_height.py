# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The loaded ride height: the travels at which an axle's holding forces are zero.

    find_travels(evaluate, z0, jacobian, low, high) -> Found

evaluate(z) gives the holding forces (n,) N of the corners held at travels z (n,) mm (the
force at each wheel centre that the springs, stops and bar leave to a rig: doc/kc.md), or
None and why when a corner cannot be solved there. Broyden's method (a secant update of the
Jacobian, which starts from the kinematic wheel rates) finds where they are all zero, each
travel within its corner's travel block; a step that does not lower the largest holding
force is halved. Where a corner reaches the end of its travel block with its holding force
still pushing beyond it, the load is out of reach there.
"""

from __future__ import annotations

from typing import Callable, NamedTuple

import numpy as np

from ..base.status import Status

# The holding force is solved to this (N): the statics' equilibrium is converged to a step
# of 1e-11 mm, which at the stiffest bushing's 1e4 N/mm leaves about 1e-7 N of noise in it.
TOLERANCE_N = 5e-7
MAX_STEPS = 60          # Broyden steps per axle
MAX_HALVINGS = 10       # of one step that does not lower the holding force


class Found(NamedTuple):
    """The travels found (mm), their holding forces (N), the last evaluation's payload."""

    status: Status
    message: str
    travel_mm: np.ndarray
    holding_n: np.ndarray
    payload: object
    evaluations: int


def find_travels(evaluate: Callable, z0: np.ndarray, jacobian: np.ndarray, low: np.ndarray,
                 high: np.ndarray, names: tuple = ()) -> Found:
    """Return where evaluate's holding forces are zero (module doc); names: the corners."""
    z = np.clip(np.asarray(z0, dtype=float), low, high)
    r, payload, why = evaluate(z)
    count = 1
    if r is None:
        return Found(Status.NOT_CARRIED, why, z, np.full(len(z), np.nan), None, count)
    jac = np.array(jacobian, dtype=float)
    for _ in range(MAX_STEPS):
        size = float(np.max(np.abs(r)))
        if size <= TOLERANCE_N:
            return Found(Status.OK, 'ok', z, r, payload, count)
        try:
            step = -np.linalg.solve(jac, r)
        except np.linalg.LinAlgError:
            step = r / np.abs(np.diag(jac)).clip(1e-9)
        fraction, accepted = 1.0, None
        for _ in range(MAX_HALVINGS + 1):
            trial = np.clip(z + fraction * step, low, high)
            stuck = _beyond(z, trial, step, r, low, high)
            if stuck is not None:
                return _out_of_reach(stuck, z, r, payload, count, low, high, names)
            rt, pt, why = evaluate(trial)
            count += 1
            if rt is not None and float(np.max(np.abs(rt))) < size:
                accepted = (trial, rt, pt)
                break
            fraction *= 0.5
        if accepted is None:
            return Found(Status.NOT_CARRIED, why or f'the holding force stays at {size:.3g} N: '
                         'no travel lowers it further', z, r, payload, count)
        trial, rt, pt = accepted
        s, y = trial - z, rt - r
        jac += np.outer(y - jac @ s, s) / (s @ s)
        z, r, payload = trial, rt, pt
    return Found(Status.NOT_CARRIED, f'the holding force is still {np.max(np.abs(r)):.3g} N '
                 f'after {MAX_STEPS} steps', z, r, payload, count)


def _beyond(z, trial, step, r, low, high):
    """Return the index of a corner held at a travel limit that its load pushes past; None."""
    for k in range(len(z)):
        at_limit = (trial[k] == high[k] and step[k] > 0) or (trial[k] == low[k] and step[k] < 0)
        if at_limit and trial[k] == z[k]:
            return k
    return None


def _out_of_reach(k, z, r, payload, count, low, high, names):
    limit = 'upper' if z[k] == high[k] else 'lower'
    name = names[k] if names else f'corner {k}'
    return Found(Status.OUT_OF_REACH, f'{name} reaches its {limit} travel limit '
                 f'({z[k]:g} mm) with {r[k]:.6g} N still to hold: its springs and stops '
                 'cannot carry the load within its travel', z, r, payload, count)
