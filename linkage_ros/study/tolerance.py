# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Tolerance stack-up: how hardpoint and length tolerances spread camber, toe and wheel centre.

Each hardpoint coordinate is an independent normal variable about its design value, with
standard deviation sigma (mm; per point and axis, sigmas()). Hardpoints are design
positions: a variant of them assembles at its own design position. A length tolerance
(length_sigmas(): `<constraint>.length`, a link's length or an arm's pivot-to-ball
distance) is another independent normal variable; the hardpoints then no longer assemble,
and the design re-assembles: it is solved at design travel (0) from the nominal pose, which
gives the static camber and toe spread (travel 0's rows). Two answers per travel and
quantity (SWEEP_COLUMNS):
  first order: rss_std = sqrt(sum over coordinates and lengths of (dq/dp sigma_p)^2), from
               the exact sensitivities (core/vary's sweep_column_rates, compiled; a
               length's is its body point's along the link, length_rates());
  Monte Carlo: samples variants, each solved at every travel from the design's pose there
               by the design's batched sweep kernel, batched over variants
               (core/vary/variants.py); mean, std, 1st and 99th percentiles of the variants
               solved, and how many were out of reach (a point variant is solved again by
               Continuation, arclength included, to be sure).

The variants come in batches of BATCH; batch i draws its perturbations from
SeedSequence(seed, spawn_key=(i,)), so the result depends on the seed alone, never on where
or in what order the batches run (executor.py).

Bushing rates (bushing_sigmas(): `<constraint>.bushing.<field>`, N/mm or N m/deg, or a
percentage of the rate) are independent normal variables too. They move no kinematic
quantity (the kinematics ignores bushings): a study with them, or with compliance=True, also
has the compliance rates (statics.RATE_COLUMNS) as quantities, each variant's from a Statics
of its own scene (the hardpoints moved, the rates changed) and their first order from
central differences of Statics (core/vary/bushings.py). A variant's rate drawn at or below 0
is no bushing: its rates count as out of reach. Lengths have no scene of their own and no
compliance rates.
"""

from __future__ import annotations

import math
from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from .executor import in_process, Items
from ..core.base import camber_toe, LENGTH_LIMIT_MM, LinkageError
from ..core.model import with_points
from ..core.solve import compile_scene, Continuation
from ..core.vary import (AXES, bushing_names, bushing_values, compliance_of, compliance_rates,
                         controls_of, Design, design_starts, length_rates, poses, rate_names,
                         solve_variants, sweep_column_rates, SWEEP_COLUMNS, with_bushings)

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

BATCH = 4096                # variants per batch: fixed, so that a seed means one sample
LENGTH = '.length'          # a constraint's length tolerance: `<constraint>.length`
BUSHING = '.bushing.'       # a bushing rate's tolerance: `<constraint>.bushing.<field>`
BUSHING_SD_LIMIT = 0.25     # a bushing rate's sd, at most this fraction of the rate: a draw
#                             at or below 0 is then a 4-sigma event (3e-5 of the variants)
DEG = 180.0 / np.pi
SCALES = np.array([DEG, DEG, 1.0, 1.0, 1.0])   # kernel outputs (rad, mm) -> table units


class Problem(NamedTuple):
    """What a batch of variants needs (sent to the workers): small and picklable."""

    design: Design
    sigma: np.ndarray       # (k, 3) mm
    travels: np.ndarray     # (T,) mm
    seed: int
    samples: int
    controls: tuple         # core/vary's variant kernel's Controls (controls_of)
    starts: np.ndarray      # (T, STATE_SIZE) the design's solved states at the travels
    lengths: np.ndarray     # (c,) mm: standard deviation of each constraint's length
    bushings: np.ndarray = np.zeros(0)   # (b,) standard deviation of each bushing rate
    rates: tuple = ()       # the compliance rates among the quantities (none: kinematics only)


class Tolerance(NamedTuple):
    """The stack-up at T travels of Q quantities (SWEEP_COLUMNS): arrays (T, Q)."""

    travel: np.ndarray
    quantities: tuple[str, ...]
    nominal: np.ndarray
    mean: np.ndarray
    std: np.ndarray
    rss_std: np.ndarray
    p01: np.ndarray
    p99: np.ndarray
    out_of_reach: np.ndarray   # (T, Q) int: variants not solved at the travel
    values: np.ndarray         # (samples, T, Q) every variant (NaN where out of reach)


def sigmas(design: Design, sigma: float, overrides: dict | None = None) -> np.ndarray:
    """
    Return the standard deviations (k, 3) mm: sigma everywhere, per point from overrides.

    overrides maps a point name to a number (every axis) or to {x, y, z} (axes not named
    keep sigma). Values >= 0; 0 fixes a coordinate. Raises LinkageError naming the mistake.
    Keys `<constraint>.length` are length_sigmas'.
    """
    if not (np.isfinite(sigma) and sigma > 0):
        raise LinkageError('--sigma', f'must be a number of mm above 0, got {sigma:g}')
    out = np.full(design.values.shape, float(sigma))
    for name, given in (overrides or {}).items():
        if str(name).endswith(LENGTH) or BUSHING in str(name):   # the others' to read
            continue
        i = design.index(str(name))
        if isinstance(given, dict):
            for axis, value in given.items():
                if axis not in AXES:
                    raise LinkageError(f'{name}.{axis}', 'not an axis (x, y or z)')
                out[i, AXES.index(axis)] = _sd(f'{name}.{axis}', value)
        else:
            out[i] = _sd(name, given)
    return out


def length_sigmas(design: Design, overrides: dict | None = None) -> np.ndarray:
    """
    Return the standard deviations (c,) mm of the constraints' lengths: 0 unless given.

    overrides' keys `<constraint>.length` (a number >= 0): a link's length (sphere) or an
    arm's pivot-to-ball distance (circle); a strut (line) has no length. Raises LinkageError
    naming the mistake.
    """
    constraints = design.scene.constraints
    out = np.zeros(len(constraints))
    names = [c.name for c in constraints]
    for name, given in (overrides or {}).items():
        name = str(name)
        if not name.endswith(LENGTH):
            continue
        owner = name[:-len(LENGTH)]
        if owner not in names or constraints[names.index(owner)].type == 'line':
            lengths = ', '.join(f'{c.name}{LENGTH}' for c in constraints if c.type != 'line')
            raise LinkageError(name, 'not a length of the scene '
                               f'{design.scene.name} (its lengths: {lengths})')
        out[names.index(owner)] = _sd(name, given)
    return out


def bushing_sigmas(design: Design, overrides: dict | None = None) -> np.ndarray:
    """
    Return the standard deviations (b,) of the bushing rates (bushing_names), 0 unless given.

    overrides' keys `<constraint>.bushing.<field>`: a number in the rate's unit (N/mm for
    axial and radial, N m/deg for torsion and conical) or a percentage of the rate ('5%'),
    from 0 to BUSHING_SD_LIMIT of the rate. Raises LinkageError naming the mistake.
    """
    scene = design.scene
    names, rates = bushing_names(scene), bushing_values(scene)
    out = np.zeros(len(names))
    for name, given in (overrides or {}).items():
        name = str(name)
        if BUSHING not in name:
            continue
        if name not in names:
            have = (f'its bushing rates: {", ".join(names)}' if names else
                    'it has no bushings')
            shown = name if name.isprintable() else repr(name)   # one line: \n escaped
            raise LinkageError(shown, f'not a bushing rate of the scene {scene.name} ({have})')
        i = names.index(name)
        out[i] = _bushing_sd(name, given, rates[i])
    return out


def _bushing_sd(where, value, rate):
    """Return a bushing rate's sd from a number (the rate's unit) or 'P%'; LinkageError."""
    unit = 'N m/deg' if where.endswith(('torsion', 'conical')) else 'N/mm'
    rate = float(rate)   # Python's arithmetic: 1e308% of a rate is inf, without a warning
    limit = BUSHING_SD_LIMIT * rate
    if isinstance(value, str) and value.strip().endswith('%'):
        try:
            number = float(value.strip()[:-1])
        except ValueError:
            number = math.nan
        sd = number / 100.0 * rate
    elif isinstance(value, bool) or not isinstance(value, (int, float)):
        sd = math.nan
    else:
        sd = float(value)
    if not (np.isfinite(sd) and 0.0 <= sd <= limit):
        raise LinkageError(where, f"a bushing rate's standard deviation is a number of {unit} "
                           f'from 0 to {limit:g} ({100 * BUSHING_SD_LIMIT:g}% of its rate '
                           f'{rate:g}) or a percentage (5%), got {value!r}')
    return sd


def _sd(where, value):
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not (np.isfinite(value) and 0 <= value <= LENGTH_LIMIT_MM):
        raise LinkageError(where, f'a standard deviation is a number of mm >= 0 and at most '
                           f'{LENGTH_LIMIT_MM:g}, got {value!r}')
    return float(value)


def problem(design: Design, sigma: np.ndarray, samples: int, travels: ArrayLike,
            seed: int = 0, lengths: ArrayLike | None = None,
            bushings: ArrayLike | None = None, compliance: bool = False) -> Problem:
    """
    Return the Problem of a study; the solver settings are the design's (Continuation).

    lengths (c,) mm: length_sigmas (None: none); bushings (b,): bushing_sigmas (None: none);
    compliance: the compliance rates are quantities too (they are whenever a bushing rate
    varies). Solves the design at the travels (its states start every variant's solve);
    LinkageError if it does not reach one of them, or for compliance rates of a scene
    without bushings or with length tolerances.
    """
    travels = np.asarray(travels, dtype=float).ravel()
    scene = design.scene
    lengths = np.zeros(len(scene.constraints)) if lengths is None else lengths
    lengths = np.asarray(lengths, dtype=float)
    bushings = np.zeros(len(bushing_names(scene))) if bushings is None else bushings
    bushings = np.asarray(bushings, dtype=float)
    rates: tuple = ()
    if compliance or bushings.any():
        if not scene.has_bushings:
            raise LinkageError('--compliance', f'the scene {scene.name} has no bushings: its '
                               'compliance rates are 0')
        if lengths.any():
            raise LinkageError('--compliance', 'compliance rates and length tolerances '
                               'cannot go together (a length variant has no scene to solve '
                               'the statics of)')
    starts, _ = design_starts(scene, travels)
    if compliance or bushings.any():
        rates = rate_names(scene, travels)
    return Problem(design, np.asarray(sigma, dtype=float), travels, int(seed), int(samples),
                   controls_of(scene), starts, lengths, bushings, rates)


def batches(prob: Problem) -> Items:
    """Return the work items: (problem, batch index), BATCH variants each (the last fewer)."""
    return Items(prob, (prob.samples + BATCH - 1) // BATCH)


def perturbed(prob: Problem, index: int) -> tuple[np.ndarray, np.ndarray | None]:
    """
    Return batch index's hardpoints (n, k, 3) and length changes (n, c) (None: none), mm.

    Hardpoints design + sigma x N(0, 1); then, if any length has a tolerance, lengths
    lengths x N(0, 1) from the same stream (a study without them draws what it always did).
    """
    return _drawn(prob, index)[:2]


def bushing_draws(prob: Problem, index: int) -> np.ndarray | None:
    """Return batch index's bushing rates (n, b) (None: none vary): rate + sd x N(0, 1)."""
    return _drawn(prob, index)[2]


def _drawn(prob: Problem, index: int):
    """Return a batch's hardpoints, length changes and bushing rates, in that order drawn."""
    n = min(BATCH, prob.samples - index * BATCH)
    rng = np.random.default_rng(np.random.SeedSequence(prob.seed, spawn_key=(index,)))
    points = prob.design.values + prob.sigma * rng.standard_normal((n,) + prob.sigma.shape)
    deltas = prob.lengths * rng.standard_normal((n, len(prob.lengths))) \
        if prob.lengths.any() else None
    rates = None
    if prob.bushings.any():   # after the others: a study without them draws what it did
        rates = bushing_values(prob.design.scene) + \
            prob.bushings * rng.standard_normal((n, len(prob.bushings)))
    return points, deltas, rates


def solve_batch(item: tuple[Problem, int]) -> np.ndarray:
    """Return the quantities (n, T, Q) of a batch's variants, NaN where out of reach."""
    prob, index = item
    points, deltas, rates = _drawn(prob, index)
    values, solved = solve_variants(prob.design.scene.layout, points, deltas, prob.starts,
                                    prob.travels, prob.controls)
    for v in np.flatnonzero(~solved.all(axis=1)):
        if deltas is None:   # a Continuation solves a scene: a moved design has one
            values[v] = _by_continuation(prob, points[v], solved[v], values[v])
    values = values * SCALES
    if not prob.rates:
        return values
    return np.concatenate([values, _compliance(prob, points, rates)], axis=2)


def _compliance(prob: Problem, points: np.ndarray, rates: np.ndarray | None) -> np.ndarray:
    """Return the compliance rates (n, T, R) of a batch's variants, NaN where not solved."""
    scene = prob.design.scene
    out = np.full((len(points), len(prob.travels), len(prob.rates)), np.nan)
    for v in range(len(points)):
        if rates is not None and not (rates[v] > 0).all():   # no bushing: out of reach
            continue
        varied = with_points(scene, points[v])
        if rates is not None:
            varied = with_bushings(varied, rates[v])
        with np.errstate(invalid='ignore', divide='ignore'):
            try:
                out[v] = compliance_of(varied, prob.travels, prob.rates)
            except LinkageError:   # the variant is not a mechanism
                pass
    return out


def _by_continuation(prob, points, solved, values):
    """Solve a variant's failed travels one by one by Continuation (arclength included)."""
    values = values.copy()
    with np.errstate(invalid='ignore', divide='ignore'):
        try:
            cont = Continuation(with_points(prob.design.scene, points))
        except LinkageError:   # the variant is not a mechanism (a zero-length link, say)
            values[:] = np.nan
            return values
    for t in np.flatnonzero(~solved):
        cont.reset()
        solution = cont.solve(float(prob.travels[t]))
        if solution.success:
            values[t] = (solution.camber, solution.toe, *solution.wheel_center)
    return values


def tolerance(prob: Problem, run=None, progress=None) -> Tolerance:
    """
    Return the stack-up of a Problem; run(function, items, progress) runs the batches.

    run: an executor (executor.py; None: this process).
    """
    scene = prob.design.scene
    center, rotation = poses(prob.starts)
    rates = sweep_column_rates(scene, center, rotation)
    spread = np.sum((rates * prob.sigma) ** 2, axis=(2, 3))
    if prob.lengths.any():
        spread += np.sum((length_rates(scene, center, rotation) * prob.lengths) ** 2, axis=2)
    camber, toe = camber_toe(rotation @ compile_scene(scene).spin_axis, scene.side_sign)
    table = np.column_stack([np.degrees(camber), np.degrees(toe), center])
    if prob.rates:   # the kinematic quantities' spread from the bushings is 0
        by_point, by_rate = compliance_rates(scene, prob.travels, prob.rates, prob.sigma,
                                             prob.bushings)
        spread = np.concatenate([spread, np.sum((by_point * prob.sigma) ** 2, axis=(2, 3))
                                 + np.sum((by_rate * prob.bushings) ** 2, axis=2)], axis=1)
        table = np.concatenate([table, compliance_of(scene, prob.travels, prob.rates)],
                               axis=1)
    rss = np.sqrt(spread)
    items = batches(prob)
    results = (run or in_process)(solve_batch, items, progress)
    values = np.concatenate(results) if results else np.empty((0,) + rss.shape)
    solved = np.isfinite(values)
    count = solved.sum(axis=0)
    with np.errstate(invalid='ignore', divide='ignore'):
        mean = np.nanmean(values, axis=0) if len(values) else np.full(rss.shape, np.nan)
        deviation = np.where(solved, values - mean, 0.0)
        std = np.sqrt(np.sum(deviation ** 2, axis=0) / (count - 1))
    low, high = (np.full(rss.shape, np.nan) for _ in range(2))
    if count.size and count.min() > 0:
        low, high = np.nanpercentile(values, [1, 99], axis=0)
    return Tolerance(prob.travels, SWEEP_COLUMNS + prob.rates, table, mean, std, rss, low,
                     high, len(values) - count, values)


def rows(result: Tolerance):
    """Yield the table rows: travel_mm, quantity, nominal, mean, std, rss_std, p01, p99, n."""
    for t, travel in enumerate(result.travel):
        for q, name in enumerate(result.quantities):
            yield (travel, name, result.nominal[t, q], result.mean[t, q], result.std[t, q],
                   result.rss_std[t, q], result.p01[t, q], result.p99[t, q],
                   int(result.out_of_reach[t, q]))
