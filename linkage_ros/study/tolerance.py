"""
Tolerance stack-up: how hardpoint tolerances spread camber, toe and the wheel centre.

Each hardpoint coordinate is an independent normal variable about its design value, with
standard deviation sigma (mm; per point and axis, sigmas()). Two answers per travel and
quantity (SWEEP_COLUMNS):
  first order: rss_std = sqrt(sum over coordinates of (dq/dp sigma_p)^2), from the exact
               sensitivities (sensitivity.sweep_column_rates, compiled);
  Monte Carlo: samples variants, each solved from its own design position to every travel
               by a compiled kernel batched over variants (variant_kernel.py); mean, std,
               1st and 99th percentiles of the variants solved, and how many were out of
               reach (solved again by Continuation, arclength included, to be sure).

The variants come in batches of BATCH; batch i draws its perturbations from
SeedSequence(seed, spawn_key=(i,)), so the result depends on the seed alone, never on where
or in what order the batches run (executor.py).
"""

from __future__ import annotations

from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from . import variant_kernel
from .equations import geometry, layout_of, table
from .executor import in_process, Items
from .hardpoints import AXES, Design, scene_with
from .quantities import SWEEP_COLUMNS
from .sensitivity import sweep_column_rates
from ..core.continuation import Continuation
from ..core.errors import LinkageError
from ..core.kinematics import sweep
from ..core.limits import LENGTH_LIMIT_MM
from ..core.scene import SceneError

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

BATCH = 4096                # variants per batch: fixed, so that a seed means one sample
DEG = 180.0 / np.pi
SCALES = np.array([DEG, DEG, 1.0, 1.0, 1.0])   # kernel outputs (rad, mm) -> table units


class Problem(NamedTuple):
    """What a batch of variants needs (sent to the workers): small and picklable."""

    design: Design
    sigma: np.ndarray       # (k, 3) mm
    travels: np.ndarray     # (T,) mm
    seed: int
    samples: int
    controls: tuple         # variant_kernel.Controls


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
    """
    if not (np.isfinite(sigma) and sigma > 0):
        raise LinkageError('--sigma', f'must be a number of mm above 0, got {sigma:g}')
    out = np.full(design.values.shape, float(sigma))
    for name, given in (overrides or {}).items():
        i = design.index(str(name))
        if isinstance(given, dict):
            for axis, value in given.items():
                if axis not in AXES:
                    raise LinkageError(f'{name}.{axis}', 'not an axis (x, y or z)')
                out[i, AXES.index(axis)] = _sd(f'{name}.{axis}', value)
        else:
            out[i] = _sd(name, given)
    return out


def _sd(where, value):
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not (np.isfinite(value) and 0 <= value <= LENGTH_LIMIT_MM):
        raise LinkageError(where, f'a standard deviation is a number of mm >= 0 and at most '
                           f'{LENGTH_LIMIT_MM:g}, got {value!r}')
    return float(value)


def problem(design: Design, sigma: np.ndarray, samples: int, travels: ArrayLike,
            seed: int = 0) -> Problem:
    """Return the Problem of a study; the solver settings are the design's (Continuation)."""
    cfg = Continuation(design.scene).settings
    controls = variant_kernel.Controls(design.scene.side_sign, cfg.tol, cfg.max_iter,
                                       cfg.max_step, cfg.min_step, cfg.max_substeps,
                                       cfg.knot_step, cfg.knot_tol)
    return Problem(design, np.asarray(sigma, dtype=float),
                   np.asarray(travels, dtype=float).ravel(), int(seed), int(samples),
                   tuple(controls))


def batches(prob: Problem) -> Items:
    """Return the work items: (problem, batch index), BATCH variants each (the last fewer)."""
    return Items(prob, (prob.samples + BATCH - 1) // BATCH)


def perturbed(prob: Problem, index: int) -> np.ndarray:
    """Return the hardpoints (n, k, 3) mm of batch index: design + sigma x N(0, 1)."""
    n = min(BATCH, prob.samples - index * BATCH)
    rng = np.random.default_rng(np.random.SeedSequence(prob.seed, spawn_key=(index,)))
    return prob.design.values + prob.sigma * rng.standard_normal((n,) + prob.sigma.shape)


def solve_batch(item: tuple[Problem, int]) -> np.ndarray:
    """Return the quantities (n, T, Q) of a batch's variants, NaN where out of reach."""
    prob, index = item
    points = perturbed(prob, index)
    layout = layout_of(prob.design.scene)
    with np.errstate(invalid='ignore', divide='ignore'):   # a degenerate variant: NaN rows
        geom = geometry(layout, points)
        variants = variant_kernel.Variants(np.ascontiguousarray(table(layout, geom)),
                                           np.ascontiguousarray(geom.spin_axis),
                                           np.ascontiguousarray(geom.center0))
    n, count = len(points), len(prob.travels)
    values = np.empty((n, count, variant_kernel.OUTPUTS))
    status = np.empty((n, count), dtype=np.int64)
    variant_kernel.solve_variants(tuple(variants), prob.travels, prob.controls, values, status)
    for v in np.flatnonzero((status != variant_kernel.SOLVED).any(axis=1)):
        values[v] = _by_continuation(prob, points[v], status[v], values[v])
    return values * SCALES


def _by_continuation(prob, points, status, values):
    """Solve a variant's failed travels one by one by Continuation (arclength included)."""
    values = values.copy()
    try:
        cont = Continuation(scene_with(prob.design, points))
    except SceneError:   # the variant is not a mechanism (a zero-length link, say)
        values[:] = np.nan
        return values
    for t in np.flatnonzero(status != variant_kernel.SOLVED):
        cont.reset()
        solution = cont.solve(float(prob.travels[t]))
        if solution.success:
            values[t] = (solution.camber, solution.toe, *solution.wheel_center)
    return values


def tolerance(prob: Problem, run=None, progress=None) -> Tolerance:
    """
    Return the stack-up of a Problem; run(function, items, progress) runs the batches.

    run: an executor (executor.py; None: this process). Raises LinkageError if the design
    itself does not reach a travel.
    """
    scene = prob.design.scene
    nominal = sweep(scene, prob.travels)
    if not nominal.success or len(nominal.travel) != len(prob.travels):
        raise LinkageError('--travel', f'the design does not reach every travel: '
                           f'{nominal.message}')
    rates = sweep_column_rates(scene, nominal.wheel_center, nominal.rotation)
    rss = np.sqrt(np.sum((rates * prob.sigma) ** 2, axis=(2, 3)))
    table = np.column_stack([np.degrees(nominal.camber), np.degrees(nominal.toe),
                             nominal.wheel_center])
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
    return Tolerance(prob.travels, SWEEP_COLUMNS, table, mean, std, rss, low, high,
                     len(values) - count, values)


def rows(result: Tolerance):
    """Yield the table rows: travel_mm, quantity, nominal, mean, std, rss_std, p01, p99, n."""
    for t, travel in enumerate(result.travel):
        for q, name in enumerate(result.quantities):
            yield (travel, name, result.nominal[t, q], result.mean[t, q], result.std[t, q],
                   result.rss_std[t, q], result.p01[t, q], result.p99[t, q],
                   int(result.out_of_reach[t, q]))
