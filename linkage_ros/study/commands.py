# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The three commands of linkage-study, each taking the parsed arguments and a say(line).

They return the exit status (0 done, 1 done but something out of reach or unmet) and raise
LinkageError (SceneError) for a mistake, which the program turns into one line, status 2.
"""

from __future__ import annotations

import os
import sys

import numpy as np

from .executor import executor, Progress
from .tables import SENSITIVITY_COLUMNS, TOLERANCE_COLUMNS
from ..cli import counted, table_status
from ..core.base import LinkageError, Need, refuse_if_short
from ..core.model import read_yaml
from ..core.vary import load_design, SWEEP_COLUMNS
from ..outputs import check_outputs, write_table

PROG = 'linkage-study'
POOL_FROM = 16   # batches (of 4096 variants, about 0.3 s each) that repay starting processes
# Measured on five_link, 40,960 variants x 3 travels, one process: 32 B of memory per value
# kept (the batches' results, their concatenation, the deviations, a percentile's copy), and
# 13 us per variant at one travel (rounded up).
VALUE_BYTES = 32
SECONDS_PER_SOLVE = 15e-6


def run_sensitivity(args, say) -> int:
    """linkage-study sensitivity: the long table travel_mm, quantity, point, axis, derivative."""
    from ..core.vary import rows, sensitivities
    design = load_design(args.scene)
    scene = design.scene
    say('', scene.warnings)
    _finite(args.travel + [args.rack], '--travel')
    if args.rack and not scene.steered:
        raise LinkageError('--rack', f'{scene.name}: no constraint is marked steer: rack')
    result = sensitivities(scene, args.travel, rack=args.rack,
                           wanted=tuple(args.quantity) if args.quantity else None)
    written = write_table(args.out, SENSITIVITY_COLUMNS, rows(result), sys.stdout)
    count = len(result.travel)
    if not result.success:
        say(f'{result.message} ({counted(count, "position")} written)')
        return 1
    many = len(result.quantities)
    say(f'{scene.name}: {many} quantit{"y" if many == 1 else "ies"} x {len(result.points)} '
        f'points x 3 axes at {counted(count, "travel")}')
    return table_status(PROG, written)


def run_tolerance(args, say) -> int:
    """linkage-study tolerance: the stack-up table, a progress bar, and the picture."""
    from .tolerance import batches, length_sigmas, problem, rows, sigmas, tolerance
    design = load_design(args.scene)
    say('', design.scene.warnings)
    _finite(args.travel, '--travel')
    overrides = read_yaml(args.tolerances, 'tolerances') if args.tolerances else None
    if overrides is not None and not isinstance(overrides, dict):
        raise LinkageError(args.tolerances, 'expected a mapping POINT: SD or POINT: {x, y, z}')
    prob = problem(design, sigmas(design, args.sigma, overrides), args.samples, args.travel,
                   args.seed, length_sigmas(design, overrides))
    hours = _check_size(args.samples, len(prob.travels), args.workers)
    count = len(batches(prob))
    # without --workers, a pool of local processes only for work that repays their start
    with executor(args.scheduler, args.workers or None,
                  pool_from=2 if args.workers else POOL_FROM) as run:
        where = f' on {args.scheduler}' if args.scheduler else ''
        say(f'{design.scene.name}: {args.samples} variants x '
            f'{counted(len(prob.travels), "travel")} in {count} '
            f'batch{"es" if count != 1 else ""}{where}{hours}')
        result = tolerance(prob, run, Progress(PROG, count, 'batches'))
    status = table_status(PROG, write_table(args.out, TOLERANCE_COLUMNS, rows(result),
                                            sys.stdout))
    if args.plot:
        from .plots import plot_tolerance
        plot_tolerance(result, args.plot, f'{design.scene.name}: {args.samples} variants, '
                       f'sigma {args.sigma:g} mm')
    lost = int(result.out_of_reach.max(initial=0))
    if lost:
        say(f'{lost} of {args.samples} variants out of reach at some travel (counted in '
            'out_of_reach, left out of the statistics)')
        return 1
    return status


def _check_size(samples: int, travels: int, workers: int) -> str:
    """
    Refuse a Monte Carlo study whose values do not fit in memory (LinkageError, --samples).

    Returns what its time is estimated at, ' (about 3.2 h on 2 cores)', when it is a
    minute or more ('' otherwise): told before it starts, not found out after.
    """
    values = samples * travels * len(SWEEP_COLUMNS)
    refuse_if_short(Need(samples * travels, VALUE_BYTES * values, VALUE_BYTES * values),
                    '--samples', f'{samples:,} variants x {counted(travels, "travel")}',
                    'take fewer samples or travels')
    cores = workers or os.cpu_count() or 1
    seconds = samples * travels * SECONDS_PER_SOLVE / cores
    if seconds < 60:
        return ''
    took = f'{seconds / 3600:.1f} h' if seconds >= 3600 else f'{seconds / 60:.0f} min'
    return f' (about {took} on {counted(cores, "local core")}, by {SECONDS_PER_SOLVE:g} s a solve)'


def run_fit(args, say) -> int:
    """linkage-study fit: fit, write the scene, say before/after per target, the picture."""
    from .fit import fit
    from .fitted_scene import write_fitted
    from .targets import load_targets
    targets = load_targets(args.targets)
    say('', targets.design.scene.warnings)
    check_outputs([('-o', args.output)] + ([('--plot', args.plot)] if args.plot else []),
                  (args.targets, targets.design.scene.source))
    with executor(args.scheduler, args.workers or None) as run:
        result = fit(targets, args.starts, args.seed,
                     run if args.starts > 1 or args.scheduler else None)
    write_fitted(args.output, targets, result)
    unmet = report(targets, result, say)
    if args.plot:
        from .plots import plot_fit
        plot_fit(targets, result, args.plot)
    return 1 if unmet else 0


def report(targets, result, say) -> int:
    """Say the residuals per target before and after; return how many tolerances are unmet."""
    unmet = 0
    for t, before, after in zip(targets.targets, result.before.errors, result.after.errors):
        worst = float(np.max(np.abs(after)))
        judged = ''
        if np.isfinite(t.tolerance):
            met = worst <= t.tolerance
            unmet += not met
            judged = f'; tolerance {t.tolerance:g}: {"met" if met else "NOT met"}'
        say(f'{t.quantity} at {counted(len(t.travel), "travel")}: largest error '
            f'{np.max(np.abs(before)):.6g} -> {worst:.6g}, rms '
            f'{np.sqrt(np.mean(before ** 2)):.6g} -> {np.sqrt(np.mean(after ** 2)):.6g}{judged}')
    moved = ', '.join(f'{name} {offset:+.4g}' for name, offset in
                      zip(targets.names(), result.offsets))
    backed = (f', {counted(result.unassembled, "step")} backed off from designs that do not '
              'assemble' if result.unassembled else '')
    say(f'moved (mm): {moved}; {result.evaluations} evaluations, {result.jacobians} '
        f'Jacobians{backed}; {result.message}')
    if unmet:
        say(f'{counted(unmet, "target")} cannot be met within the bounds (the best design '
            'found is written)')
    return unmet


def _finite(values, option):
    for value in values:
        if not np.isfinite(value):
            raise LinkageError(option, f'must be finite, got {value}')
