# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The summaries of linkage-bench.

The best setting of each entry per accuracy level, the fastest setting that meets the goal,
the default setting, the CSV, the error-against-time front (PNG) and report.md.
"""

import math
import os
from pathlib import Path
import platform
import sys

import numpy as np
import scipy

from .peers import exudyn_version
from ..core.solve import Settings
from ..outputs import save_figure, write_table

LEVELS = (1e-3, 1e-6, 1e-9, 1e-12)                      # mm: accuracy levels of the summary
GOAL_US, GOAL_ERROR = 20.0, 1e-9    # the goal: 1e-9 mm in at most 20 us per position
COLUMNS = ['scene', 'entry', 'tol_mm', 'step_mm', 'positions', 'median_us', 'p95_us',
           'ratio_to_fast', 'iterations_mean', 'residual_mm', 'wheel_center_mm', 'camber_deg',
           'toe_deg', 'error_mm', 'ok']


def progress(text):
    print(f'linkage-bench: {text}', file=sys.stderr, flush=True)


def best_at_level(rows, scene, entry, level):
    """Return the fastest row of an entry on a scene whose error is at most level (mm), or None."""
    good = [r for r in rows if r['scene'] == scene and r['entry'] == entry and r['ok']
            and r['error_mm'] <= level]
    return min(good, key=lambda r: r['median_us']) if good else None


def pareto(points):
    """Return the (time, error) points not beaten in both, sorted by time."""
    front, best = [], math.inf
    for t, e in sorted(points):
        if e < best:
            front.append((t, e))
            best = e
    return front


def level_table(rows, scenes, names):
    """Markdown rows: per scene and accuracy level, each entry's fastest setting reaching it."""
    lines = ['| scene | error <= (mm) | entry | tol (mm) | step (mm) | median (us) | p95 (us) '
             '| x fast | iterations | error (mm) |', '|' + '---|' * 10]
    for scene in scenes:
        for level in LEVELS:
            fast = best_at_level(rows, scene, 'fast', level)
            for name in names:
                r = best_at_level(rows, scene, name, level)
                if r is None:
                    lines.append(f'| {scene} | {level:.0e} | {name} | - | - | not reached | '
                                 '| | | |')
                    continue
                ratio = f'{r["median_us"] / fast["median_us"]:.2f}' if fast else '-'
                lines.append(f'| {scene} | {level:.0e} | {name} | {r["tol_mm"]:.0e} | '
                             f'{r["step_mm"]:g} | {r["median_us"]:.1f} | {r["p95_us"]:.1f} | '
                             f'{ratio} | {r["iterations_mean"]:.2f} | {r["error_mm"]:.1e} |')
    return lines


def goal_lines(rows, scenes, names):
    """Tell whether the fast variant is the fastest entry at every level; 1e-9 mm within 20 us."""
    lines = []
    for scene in scenes:
        for level in LEVELS:
            best = {n: best_at_level(rows, scene, n, level) for n in names}
            reached = {n: r for n, r in best.items() if r is not None}
            if not reached:
                continue
            winner = min(reached, key=lambda n: reached[n]['median_us'])
            calls = {n: r for n, r in reached.items() if n != 'fast sweep'}
            call_winner = min(calls, key=lambda n: calls[n]['median_us']) if calls else '-'
            lines.append(f'- {scene}, error <= {level:.0e} mm: fastest entry **{winner}** '
                         f'({reached[winner]["median_us"]:.1f} us); fastest one-call-per-'
                         f'position entry **{call_winner}**.')
        for name in ('fast sweep', 'fast'):
            r = best_at_level(rows, scene, name, GOAL_ERROR)
            verdict = ('not reached' if r is None else
                       f'{r["median_us"]:.1f} us median, {r["p95_us"]:.1f} us p95 '
                       f'({"meets" if r["median_us"] <= GOAL_US else "misses"} the '
                       f'{GOAL_US:g} us goal)')
            lines.append(f'- {scene}, {name} at error <= {GOAL_ERROR:.0e} mm: {verdict}.')
    return lines


def default_setting_lines(rows, scenes):
    """Why the node's default (Settings(): tol 1e-10 mm, max_step 5 mm) is what it is."""
    d = Settings()
    lines = [f"The node solves each command with `Continuation(scene, method='fast')` and the "
             f'default `Settings()`: tol {d.tol:g} mm (largest residual of a guidance '
             f'equation, a length), max_step {d.max_step:g} mm (longest continuation substep), '
             f'max_iter {d.max_iter}. Measured here, fast at step {d.max_step:g} mm:', '',
             '| scene | tol (mm) | median (us) | p95 (us) | iterations | error (mm) |',
             '|---|---|---|---|---|---|']
    for scene in scenes:
        for r in rows:
            if (r['scene'] == scene and r['entry'] == 'fast' and r['step_mm'] == d.max_step
                    and r['tol_mm'] in (1e-6, d.tol, 1e-12)):
                lines.append(f'| {scene} | {r["tol_mm"]:.0e} | {r["median_us"]:.1f} | '
                             f'{r["p95_us"]:.1f} | {r["iterations_mean"]:.2f} | '
                             f'{r["error_mm"]:.1e} |')
    lines += ['', f'Why: {d.tol:g} mm sits just above the float64 round-off of the residual '
              '(about 1e-13 mm at 1 m coordinates), so the node publishes poses as exact as '
              'double precision allows, for at most one Newton iteration more than 1e-6 mm '
              'would take (quadratic convergence: one more iteration squares the error). '
              'Tighter values (1e-12) sit at the round-off floor and may stall on scenes with '
              f'larger coordinates. {d.max_step:g} mm steps keep the tangent predictor within '
              'the quadratic basin (2 iterations) while a 20 mm step needs more iterations; '
              'commands closer than that take one step.']
    return lines


def write_csv(rows, path):
    """results.csv: a row per (scene, entry, tolerance, step), COLUMNS (the table writer's)."""
    write_table(path, COLUMNS, [[r.get(k) for k in COLUMNS] for r in rows])


def plot_front(rows, scenes, names, path):
    """bench_front.png: error (mm) against median time per position (us), one panel per scene."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    cols = min(4, len(scenes))
    rows_ = math.ceil(len(scenes) / cols)
    fig, axes = plt.subplots(rows_, cols, figsize=(4.4 * cols, 3.7 * rows_ + 0.6),
                             squeeze=False, sharex=True, sharey=True)
    colours = dict(zip(names, plt.rcParams['axes.prop_cycle'].by_key()['color'] * 2))
    for ax in axes.flat[len(scenes):]:
        ax.set_visible(False)
    for ax, scene in zip(axes.flat, scenes):
        for name in names:
            pts = [(r['median_us'], max(r['error_mm'], 1e-16)) for r in rows
                   if r['scene'] == scene and r['entry'] == name and r['ok']]
            if not pts:
                continue
            t, e = zip(*pts)
            ax.scatter(t, e, s=10, alpha=0.35, color=colours[name])
            ft, fe = zip(*pareto(pts))
            ax.step(ft, fe, where='post', color=colours[name], label=name, lw=1.6)
        ax.axhline(GOAL_ERROR, color='grey', ls=':', lw=1)
        ax.axvline(GOAL_US, color='grey', ls=':', lw=1)
        ax.set(xscale='log', yscale='log')
        ax.set_title(scene, fontsize=9)
        ax.grid(True, which='major', alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel('median time per position (us)')
    for ax in axes[:, 0]:
        ax.set_ylabel('error (mm)')
    handles, labels = axes.flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc='lower center', ncol=len(labels), fontsize=9)
    fig.suptitle('Error = max(residual, wheel-centre deviation from the reference) against run '
                 'time. Dots: every tol x step; lines: Pareto fronts. Dotted: '
                 f'{GOAL_ERROR:g} mm, {GOAL_US:g} us', fontsize=10)
    fig.tight_layout(rect=(0, 0.04, 1, 0.97))
    save_figure(fig, path, dpi=110)
    plt.close(fig)


def cpu_name():
    """Return the CPU model (Linux /proc/cpuinfo) and core count, else the platform's name."""
    try:
        for line in Path('/proc/cpuinfo').read_text().splitlines():
            if line.startswith('model name'):
                return f'{line.split(":", 1)[1].strip()} ({os.cpu_count()} cores)'
    except OSError:
        pass
    return platform.processor() or platform.machine()


def report(rows, scenes, chosen, args, stress, elapsed):
    names = [e.name for e in chosen]
    version = exudyn_version()
    lines = ['# linkage-bench: error against run time', '',
             f'Machine: {cpu_name()}, Python '
             f'{platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}, '
             f'exudyn {version or "not installed (optional bench extra)"}. '
             f'Run time {elapsed:.0f} s.', '',
             f'Grid: tolerances {", ".join(f"{t:g}" for t in args.tols)} mm; continuation steps '
             f'{", ".join(f"{s:g}" for s in args.steps)} mm; one-call entries: up to '
             f"{args.positions} positions next to each end of each scene's travel range; fast "
             f'sweep: the whole range at each step; {args.repeats} interleaved repeats. Error: '
             'the larger of the largest guidance-equation residual (evaluated in extended '
             'precision) and the largest wheel-centre deviation from the 6-DOF '
             'extended-precision reference; camber and toe deviations are in results.csv.', '',
             '## Entries', '']
    lines += [f'- **{e.name}** ({e.kind}): {e.about}' for e in chosen]
    if not version:
        lines.append('- exudyn: not installed here, so not compared (pip install exudyn).')
    lines += ['', 'Stopping tolerance: for fast it bounds the residual; for paper and newton LU '
              'the last Newton step (eqs. 11-12); for the scipy entries it is mapped to their '
              'relative xtol (tol / |x|); for exudyn to its Newton tolerances. The measured '
              'error, not the tolerance, is what the table and the plot compare.', '',
              '## Error against run time', '', '![front](bench_front.png)', '',
              'Fastest setting of each entry reaching each accuracy level (x fast: median time '
              "over the fast entry's fastest setting at that level):", '']
    lines += level_table(rows, scenes, names)
    lines += ['', '## Goal check', '']
    lines += goal_lines(rows, scenes, names)
    lines += ['', '## Default setting of the node', '']
    lines += default_setting_lines(rows, scenes)
    if stress:
        lines += ['', '## Stiff and extreme cases', '']
        lines += stress
    return '\n'.join(lines) + '\n'
