# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The loaded ride height: the travels at which an axle's holding forces are zero.

    find_travels(evaluate, z0, jacobian, low, high) -> Found

evaluate(z) gives the holding forces (n,) N of the corners held at travels z (n,) mm (the
force at each wheel centre that the springs, stops and bar leave to a rig: doc/kc.md), or
None and why when a corner cannot be solved there. The holding force grows with its own
corner's travel (by the wheel rate) and falls with the other's (the bar): it is piecewise
smooth, with a kink where a stop's force table starts to carry.

First Broyden's method (a secant update of the Jacobian, which starts from the kinematic
wheel rates) on all the travels at once, each within its corner's travel block; a step that
does not lower the largest holding force is halved. That is fast where the forces are smooth,
but at a stop's kink its Jacobian can be wrong enough that no fraction of its step lowers
them, or that its step pushes a corner against the end of its block. Then (and to confirm a
corner out of reach), from the best travels found, a safeguarded search that cannot stall:
corner by corner (the other's travel held), a root of its holding force is bracketed in its
travel block (where it changes sign) and closed in on by secant steps inside the bracket
(Illinois' rule), bisection when a step would leave it or does not halve the holding force;
sweeps over the corners until every holding force is within the tolerance (the bar couples
them more weakly than their springs hold them, so each sweep shrinks what is left). A corner
that reaches the end of its travel block with its holding force still pushing beyond it, the
others solved, is out of reach there.
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
MAX_EVALUATIONS = 400   # of the safeguarded search, per axle


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
            if _beyond(z, trial, step, r, low, high) is not None:   # the safe search says
                return _safeguarded(evaluate, z, r, payload, count, jac, low, high, names)
            rt, pt, why = evaluate(trial)
            count += 1
            if rt is not None and float(np.max(np.abs(rt))) < size:
                accepted = (trial, rt, pt)
                break
            fraction *= 0.5
        if accepted is None:   # Broyden's Jacobian is wrong here (a kink): the safe search
            return _safeguarded(evaluate, z, r, payload, count, jac, low, high, names)
        trial, rt, pt = accepted
        s, y = trial - z, rt - r
        jac += np.outer(y - jac @ s, s) / (s @ s)
        z, r, payload = trial, rt, pt
    return _safeguarded(evaluate, z, r, payload, count, jac, low, high, names)


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


class _Point:
    """The search's state: travels z (n,) mm, holding forces r (n,) N, payload, evaluations."""

    def __init__(self, evaluate, z, r, payload, count):
        self.evaluate, self.z, self.r, self.payload, self.count = evaluate, z, r, payload, count

    def at(self, k, travel):
        """Evaluate with corner k at travel (mm); return its holding force, or None and why."""
        z = self.z.copy()
        z[k] = travel
        r, payload, why = self.evaluate(z)
        self.count += 1
        if r is None:
            return None, why
        self.z, self.r, self.payload = z, r, payload
        return float(r[k]), ''


def _safeguarded(evaluate, z, r, payload, count, jac, low, high, names):
    """Return the Found of the corner-by-corner bracketed search (module doc) from z, r."""
    point = _Point(evaluate, np.array(z, dtype=float), np.array(r, dtype=float), payload,
                   count)
    slopes = np.abs(np.diag(jac)).clip(1e-3)   # N/mm: a step's size, then each bracket's
    while point.count < MAX_EVALUATIONS:
        pushing = [k for k in range(len(z)) if _pushes_beyond(point, k, low, high)]
        open_ = [k for k in range(len(z))
                 if abs(point.r[k]) > TOLERANCE_N and k not in pushing]
        if not open_:
            if pushing:
                return _out_of_reach(pushing[0], point.z, point.r, point.payload, point.count,
                                     low, high, names)
            return Found(Status.OK, 'ok', point.z, point.r, point.payload, point.count)
        for k in sorted(open_, key=lambda k: -abs(point.r[k])):
            why = _solve_corner(point, k, slopes, low[k], high[k])
            if why:
                return Found(Status.NOT_CARRIED, why, point.z, point.r, point.payload,
                             point.count)
    return Found(Status.NOT_CARRIED, f'the holding force is still {np.max(np.abs(point.r)):.3g} '
                 f'N after {point.count} evaluations', point.z, point.r, point.payload,
                 point.count)


def _pushes_beyond(point, k, low, high):
    """Return whether corner k is at an end of its travel block, its load pushing past it."""
    return ((point.z[k] == high[k] and point.r[k] < -TOLERANCE_N)
            or (point.z[k] == low[k] and point.r[k] > TOLERANCE_N))


def _solve_corner(point, k, slopes, low, high):
    """
    Bring corner k's holding force within the tolerance, the others held; return '' or why.

    It grows with the travel: a root lies above a travel where it is negative, below one
    where it is positive. Bracket it (steps of the wheel rate's size, growing), then close in
    (Illinois' secant steps, bisection when one would leave the bracket or did not halve the
    holding force). A corner whose block ends before a sign change stays at that end (pushing
    beyond it).
    slopes (n,) N/mm: each corner's last secant, the first step's size (1.5 times, to
    bracket the root at once), updated here.
    """
    t, g = float(point.z[k]), float(point.r[k])
    step = max(1.5 * abs(g) / slopes[k], 1e-9)
    a, ga = t, g    # the bracket's ends: ga < 0 < gb once both are found
    while True:   # bracket: walk the way the holding force says, growing the step
        if abs(g) <= TOLERANCE_N:
            return ''
        direction = 1.0 if g < 0 else -1.0
        end = high if direction > 0 else low
        if t == end:
            return ''   # pushing beyond the block's end: out of reach unless the others say
        trial = min(max(t + direction * step, low), high)
        gt, why = _at(point, k, t, trial)
        if gt is None:
            return why
        trial = float(point.z[k])
        if (gt < 0) != (g < 0) or gt == 0:
            a, ga, b, gb = t, g, trial, gt
            break
        if gt != g and (gt - g) / (trial - t) > 0:   # the secant's way to zero, overshot
            step = max(1.5 * abs(gt * (trial - t) / (gt - g)), 2 * step)
        else:
            step *= 2
        t, g = trial, gt
    if a > b:
        a, ga, b, gb = b, gb, a, ga
    if gb > ga:
        slopes[k] = (gb - ga) / (b - a)
    if min(abs(ga), abs(gb)) <= TOLERANCE_N:
        return _settle(point, k, a if abs(ga) < abs(gb) else b)
    fa, fb = ga, gb   # the ends' values as the secant weighs them (Illinois halves one)
    best, slow, kept = min(abs(ga), abs(gb)), False, 0
    while point.count < MAX_EVALUATIONS:
        if b - a <= 4 * np.finfo(float).eps * max(abs(a), abs(b), 1.0):
            return (f'the holding force jumps from {ga:.6g} N to {gb:.6g} N at travel '
                    f'{a:g} mm: no travel holds it there')
        trial = 0.5 * (a + b) if slow else (a * fb - b * fa) / (fb - fa)
        if not a < trial < b:
            trial = 0.5 * (a + b)
        g, why = _at(point, k, None, trial)
        if g is None:
            return why
        if abs(g) <= TOLERANCE_N:
            return ''
        slow, best = abs(g) > 0.5 * best, min(best, abs(g))   # not halved: bisect next
        if (g < 0) == (ga < 0):
            a, ga, fa = trial, g, g
            fb, kept = (0.5 * fb if kept == 1 else fb), 1   # b kept twice: weigh it half
        else:
            b, gb, fb = trial, g, g
            fa, kept = (0.5 * fa if kept == -1 else fa), -1
    return ''


def _at(point, k, t, trial):
    """Evaluate corner k at trial, halving toward t (the last solved travel) where it fails."""
    for _ in range(MAX_HALVINGS + 1):
        g, why = point.at(k, trial)
        if g is not None or t is None:
            return g, why
        trial = 0.5 * (t + trial)
    return None, why


def _settle(point, k, travel):
    """Leave the point (its travels, forces, payload) at corner k's travel; return '' or why."""
    if point.z[k] != travel:
        g, why = point.at(k, travel)
        if g is None:
            return why
    return ''
