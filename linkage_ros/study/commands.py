# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The three commands of linkage-study, each taking the parsed arguments and a say(line).

They return the exit status (0 done, 1 done but something out of reach or unmet) and raise
LinkageError (SceneError) for a mistake, which the program turns into one line, status 2.
"""

from __future__ import annotations

import itertools
import os
import sys

import numpy as np

from .executor import executor, Progress
from .tables import SENSITIVITY_COLUMNS, TOLERANCE_COLUMNS
from ..cli import counted, table_status
from ..core.base import LinkageError, Need, refuse_if_short
from ..core.model import read_yaml
from ..core.vary import bushing_names, load_design, SWEEP_COLUMNS
from ..outputs import check_outputs, write_table

PROG = 'linkage-study'
POOL_FROM = 16   # batches (of 4096 variants, about 0.3 s each) that repay starting processes
# Measured on five_link, 40,960 variants x 3 travels, one process: 32 B of memory per value
# kept (the batches' results, their concatenation, the deviations, a percentile's copy), and
# 13 us per variant at one travel (rounded up).
VALUE_BYTES = 32
SECONDS_PER_SOLVE = 15e-6
# A variant's compliance (five_link_bushings, batches of 4096, one process on the shared
# machine): 0.95 ms CPU for its scene, its Statics and its first travel, 50 us for each
# travel after (rounded up)
SECONDS_PER_STATICS = 1e-3
SECONDS_PER_RATES = 60e-6


def run_sensitivity(args, say) -> int:
    """linkage-study sensitivity: the long table travel_mm, quantity, point, axis, derivative."""
    from ..core.vary import rows, sensitivities
    design = load_design(args.scene)
    scene = design.scene
    say('', scene.warnings)
    _finite(args.travel + [args.rack], '--travel')
    if args.rack and not scene.steered:
        raise LinkageError('--rack', f'{scene.name}: no constraint is marked steer: rack')
    wanted, rates = _split_rates(scene, args)
    result = sensitivities(scene, args.travel, rack=args.rack, wanted=wanted)
    table = rows(result)
    if rates:
        table = itertools.chain(table, compliance_rows(scene, result.travel, rates, args.rack))
    written = write_table(args.out, SENSITIVITY_COLUMNS, table, sys.stdout)
    count = len(result.travel)
    if not result.success:
        say(f'{result.message} ({counted(count, "position")} written)')
        return 1
    many = len(result.quantities) + len(rates)
    bushings = f' and {counted(len(bushing_names(scene)), "bushing rate")}' if rates else ''
    say(f'{scene.name}: {many} quantit{"y" if many == 1 else "ies"} x {len(result.points)} '
        f'points x 3 axes{bushings} at {counted(count, "travel")}')
    return table_status(PROG, written)


def _split_rates(scene, args) -> tuple[tuple[str, ...] | None, tuple[str, ...]]:
    """
    Return the kinematic quantities asked for (None: all) and the compliance rates.

    The rates: those --quantity names, or with --compliance every one the scene has (a scene
    with bushings; LinkageError otherwise).
    """
    from ..core.statics import RATE_COLUMNS
    from ..core.vary import rate_names
    asked = tuple(args.quantity or ())
    rates = tuple(q for q in asked if q in RATE_COLUMNS)
    wanted = tuple(q for q in asked if q not in RATE_COLUMNS) if asked else None
    if not (rates or args.compliance):
        return wanted, ()
    if not scene.has_bushings:
        raise LinkageError(rates[0] if rates else '--compliance', f'the scene {scene.name} has '
                           'no bushings: its compliance rates are 0')
    have = rate_names(scene, args.travel, args.rack)
    for name in rates:
        if name not in have:
            raise LinkageError(name, f'not a compliance rate of the scene {scene.name} (its '
                               f'rates: {", ".join(have)})')
    if args.compliance:
        rates = have
    return wanted, rates


def compliance_rows(scene, travels, rates, rack):
    """
    Yield the sensitivity rows of the compliance rates (central differences of Statics).

    By hardpoint coordinate (per mm), then by bushing rate (point `<constraint>.bushing`,
    axis the field: per N/mm, or per N m/deg for torsion and conical).
    """
    from ..core.vary import bushing_names, compliance_rates
    by_point, by_rate = compliance_rates(scene, travels, rates, rack=rack)
    names = [name.rsplit('.', 1) for name in bushing_names(scene)]
    for t, travel in enumerate(travels):
        for q, quantity in enumerate(rates):
            for k, point in enumerate(scene.point_names):
                for a, axis in enumerate('xyz'):
                    yield travel, quantity, point, axis, by_point[t, q, k, a]
            for b, (point, axis) in enumerate(names):
                yield travel, quantity, point, axis, by_rate[t, q, b]


def run_tolerance(args, say) -> int:
    """linkage-study tolerance: the stack-up table, a progress bar, and the picture."""
    from .tolerance import (batches, bushing_sigmas, length_sigmas, problem, rows, sigmas,
                            tolerance)
    design = load_design(args.scene)
    say('', design.scene.warnings)
    _finite(args.travel, '--travel')
    overrides = read_yaml(args.tolerances, 'tolerances') if args.tolerances else None
    if overrides is not None and not isinstance(overrides, dict):
        raise LinkageError(args.tolerances, 'expected a mapping POINT: SD or POINT: {x, y, z}')
    spread = sigmas(design, args.sigma, overrides)
    lengths, bushings = length_sigmas(design, overrides), bushing_sigmas(design, overrides)
    prob = problem(design, spread, args.samples, args.travel, args.seed, lengths, bushings,
                   args.compliance)
    hours = _check_size(args.samples, len(prob.travels), args.workers,
                        len(SWEEP_COLUMNS) + len(prob.rates), bool(prob.rates))
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


def _check_size(samples: int, travels: int, workers: int, quantities: int = len(SWEEP_COLUMNS),
                compliance: bool = False) -> str:
    """
    Refuse a Monte Carlo study whose values do not fit in memory (LinkageError, --samples).

    Returns what its time is estimated at, ' (about 3.2 h on 2 cores)', when it is a
    minute or more ('' otherwise): told before it starts, not found out after. quantities:
    per variant and travel; compliance: each variant has a Statics of its own.
    """
    values = samples * travels * quantities
    refuse_if_short(Need(samples * travels, VALUE_BYTES * values, VALUE_BYTES * values),
                    '--samples', f'{samples:,} variants x {counted(travels, "travel")}',
                    'take fewer samples or travels')
    cores = workers or os.cpu_count() or 1
    each = SECONDS_PER_SOLVE + (SECONDS_PER_RATES if compliance else 0.0)
    seconds = samples * (travels * each + (SECONDS_PER_STATICS if compliance else 0.0)) / cores
    if seconds < 60:
        return ''
    took = f'{seconds / 3600:.1f} h' if seconds >= 3600 else f'{seconds / 60:.0f} min'
    return f' (about {took} on {counted(cores, "local core")}, by {each:g} s a solve)'


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
