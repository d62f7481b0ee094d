# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench accuracy: error against run time of the solvers, on every bundled scene.

    linkage-bench accuracy [-o bench-report] [--quick] [--scenes five_link ...] [--tols 1e-3 ...]
                           [--steps 0.1 ...] [--repeats 3] [--positions 40] [--no-stress]

Entries, each solving the same positions of a scene by continuation from the design pose:
    fast            Continuation(method='fast'), one position per call (the node's path)
    fast sweep      kinematics.sweep(method='fast'): knots, then one batched Newton solve
    paper           Continuation(method='paper'): 8 unknowns, Gauss-Jordan (Alexandru 2018)
    newton LU       the paper's 8 equations with np.linalg.solve (peers.LUNewton)
    scipy root      scipy.optimize.root, hybr, on the 5 pose equations (peers.RootHybr)
    scipy lsq 6dof  scipy.optimize.least_squares on the 6-DOF pose (peers.LeastSquares6Dof)
    exudyn          exudyn's static solver on a rigid body with distance constraints (optional
                    'bench' extra; left out with a note when not installed)
Error is measured against an extended-precision 6-DOF reference (reference.reference_poses).
For each (stopping tolerance, continuation step) the one-call-per-position entries solve a
window of at most --positions travels at that spacing next to each end of the scene's travel
range (where the mechanism is furthest from design), reached by an untimed walk; every call
is timed (median and p95 per position). The batched sweep solves the whole travel range at
that spacing, as a user asking for a table would, timed whole (per position = total / n,
median and p95 over the repeats). Entries run interleaved in the same process, --repeats
times, the order rotating.
Writes <out>/report.md, <out>/results.csv, <out>/bench_front.png; progress on stderr; the
summary table on stdout. Lengths in mm, angles in deg, times in microseconds.
"""

import math
import sys
import time

import numpy as np

from . import reference
from .peers import entries
from .report import level_table, plot_front, progress, report, write_csv
from .stress import stress_lines
from ..cli import EXIT_STATUS, fail, Parser, program
from ..core.base import LinkageError
from ..core.model import bundled_scenes, load_scene, SceneError
from ..core.solve import travel_range
from ..core.warmup import compile_if_cold
from ..outputs import output_folder, whole_file

PROG = 'linkage-bench accuracy'

TOLS = (1e-3, 1e-6, 1e-8, 1e-9, 1e-10, 1e-12)     # mm
STEPS = (0.1, 1.0, 5.0, 20.0)                           # mm
WARMUP_STEP = 2.0        # mm: untimed walk from design to a timing window
FILES = ('report.md', 'results.csv', 'bench_front.png')   # written into -o DIR


# --- measuring ----------------------------------------------------------------------------

def windows(scene, step, positions):
    """Return per end of the travel range a timing window (mm): (untimed walk, timed travels)."""
    out = []
    for end in (scene.travel[1], scene.travel[0]):
        if end == 0:
            continue
        count = max(1, min(positions, int(math.floor(abs(end) / step + 1e-9))))
        start = end - math.copysign(count * step, end)
        timed = start + math.copysign(step, end) * np.arange(1, count + 1)
        warmup = travel_range(0.0, start, WARMUP_STEP)[1:] if start != 0 else np.array([])
        out.append((warmup, timed))
    return out


def run_entry(entry, scene, tol, step, legs, table):
    """
    Solve with one entry.

    Per-call entries solve the legs (untimed walk, timed window), batch entries the whole
    table of travels. Returns (center, rotation, iterations, ok, times s).
    """
    if entry.kind == 'batch':
        run = entry.make(scene, tol, step)
        start = time.perf_counter()
        center, rotation, its, ok = run(table)
        elapsed = time.perf_counter() - start
        if len(center) < len(table):
            ok = False
        return center, rotation, np.asarray(its, float), bool(ok), [elapsed / len(table)]
    centers, rotations, iterations, times = [], [], [], []
    for warmup, timed in legs:
        solver = entry.make(scene, tol, step)
        for travel in warmup:
            if not solver.solve(float(travel))[3]:
                return None, None, None, False, []
        for travel in timed:
            start = time.perf_counter()
            center, rotation, its, good = solver.solve(float(travel))
            times.append(time.perf_counter() - start)
            if not good:
                return None, None, None, False, times
            centers.append(center)
            rotations.append(rotation)
            iterations.append(its)
    return np.array(centers), np.array(rotations), np.array(iterations, float), True, times


def measure(scene, tol, step, chosen, legs, table, refs, repeats):
    """
    Measure one grid point: every entry, interleaved repeats; return a list of result dicts.

    refs: {'call': reference at the windows' travels, 'batch': at the table's travels}.
    """
    times = {e.name: [] for e in chosen}
    last = {}
    for r in range(repeats):
        order = chosen[r % len(chosen):] + chosen[:r % len(chosen)]
        for entry in order:
            center, rotation, its, ok, t = run_entry(entry, scene, tol, step, legs, table)
            times[entry.name] += t
            last[entry.name] = (center, rotation, its, ok)
    rows = []
    for entry in chosen:
        center, rotation, its, ok = last[entry.name]
        ref = refs[entry.kind]
        t_us = np.array(times[entry.name]) * 1e6
        row = {'scene': scene.name, 'entry': entry.name, 'tol_mm': tol, 'step_mm': step,
               'positions': len(ref.travel), 'ok': bool(ok),
               'median_us': float(np.median(t_us)) if len(t_us) else math.nan,
               'p95_us': float(np.percentile(t_us, 95)) if len(t_us) else math.nan}
        if ok:
            err = reference.errors(ref, center, rotation)
            row.update(err, iterations_mean=float(np.mean(its)),
                       error_mm=max(err['residual_mm'], err['wheel_center_mm']))
        else:
            row.update(residual_mm=math.nan, wheel_center_mm=math.nan, camber_deg=math.nan,
                       toe_deg=math.nan, iterations_mean=math.nan, error_mm=math.inf)
        rows.append(row)
    fast = next((r for r in rows if r['entry'] == 'fast'), None)
    for row in rows:
        row['ratio_to_fast'] = row['median_us'] / fast['median_us'] if fast else math.nan
    return rows


def run_grid(scenes, chosen, tols, steps, repeats, positions):
    """Measure every scene x step x tol; return the result rows."""
    rows = []
    total = len(scenes) * len(steps) * len(tols)
    done = 0
    for scene in scenes:
        for step in steps:
            legs = windows(scene, step, positions)
            table = travel_range(scene.travel[0], scene.travel[1], step)
            refs = {'call': reference.reference_poses(scene, np.concatenate([t for _, t in legs])),
                    'batch': reference.reference_poses(scene, table)}
            if not all(ref.success.all() for ref in refs.values()):
                progress(f'{scene.name}: the reference walk failed at step {step} mm; skipped')
                continue
            for tol in tols:
                done += 1
                started = time.perf_counter()
                rows += measure(scene, tol, step, chosen, legs, table, refs, repeats)
                progress(f'[{done}/{total}] {scene.name} step {step:g} mm tol {tol:g} mm '
                         f'({time.perf_counter() - started:.1f} s)')
    return rows


EPILOG = f"""examples:
  linkage-bench accuracy --quick -o bench-report
  linkage-bench accuracy --scenes five_link macpherson --tols 1e-9 --steps 1 5

exit status: 0 the report was written; {EXIT_STATUS}"""


def parse_args(argv):
    parser = Parser(PROG, __doc__, EPILOG)
    parser.add_argument('-o', '--output', dest='out', default='bench-report', metavar='DIR',
                        help='report folder (created; default bench-report)')
    parser.add_argument('--scenes', nargs='+', help='scene names or paths (default: bundled)')
    parser.add_argument('--tols', nargs='+', type=float, default=list(TOLS), help='mm')
    parser.add_argument('--steps', nargs='+', type=float, default=list(STEPS), help='mm')
    parser.add_argument('--repeats', type=int, default=3)
    parser.add_argument('--positions', type=int, default=20,
                        help='timed positions next to each end of the travel range')
    parser.add_argument('--entries', nargs='+', help='entry names to run (default: all)')
    parser.add_argument('--no-stress', action='store_true', help='leave out the stress section')
    parser.add_argument('--reversals', type=int, default=100_000,
                        help='random commands of the stress section')
    parser.add_argument('--quick', action='store_true',
                        help='small grid (1e-3, 1e-6, 1e-9, 1e-12 mm; 1 and 20 mm; 1 repeat; '
                             '10 positions; 2000 reversals): a smoke run')
    args = parser.parse_args(argv)
    if args.quick:
        args.tols, args.steps, args.repeats, args.positions = [1e-3, 1e-6, 1e-9, 1e-12], \
            [1.0, 20.0], 1, 10
        args.reversals = 2000
    if (args.repeats < 1 or args.positions < 1 or min(args.tols) <= 0
            or min(args.steps) <= 0):
        parser.error('--repeats, --positions, --tols and --steps must be positive')
    return args


@program('linkage-bench')
def main(argv: list[str] | None = None) -> int:
    """Run linkage-bench accuracy: 0 when the report is written, 2 for a bad scene or entry."""
    args = parse_args(argv)
    try:
        scenes = [load_scene(s) for s in (args.scenes or bundled_scenes())]
    except SceneError as exc:
        return fail(PROG, exc)
    chosen = entries()
    if args.entries:
        unknown = set(args.entries) - {e.name for e in chosen}
        if unknown:
            return fail(PROG, f'--entries: unknown {sorted(unknown)} (known: '
                        f'{[e.name for e in chosen]})')
        chosen = [e for e in chosen if e.name in args.entries]
    try:
        out = output_folder('-o', args.out, FILES, [s.source for s in scenes])
    except LinkageError as exc:
        return fail(PROG, exc)
    compile_if_cold('linkage-bench')
    started = time.perf_counter()
    progress(f'{len(scenes)} scenes x {len(args.steps)} steps x {len(args.tols)} tolerances, '
             f'{len(chosen)} entries, {args.repeats} repeats -> {out}/')
    rows = run_grid(scenes, chosen, args.tols, args.steps, args.repeats, args.positions)
    write_csv(rows, out / 'results.csv')
    names = [s.name for s in scenes]
    plot_front(rows, names, [e.name for e in chosen], out / 'bench_front.png')
    stress = [] if args.no_stress else stress_lines(args.reversals)
    text = report(rows, names, chosen, args, stress, time.perf_counter() - started)
    with whole_file(out / 'report.md') as stream:
        stream.write(text)
    print('\n'.join(level_table(rows, names, [e.name for e in chosen])))
    progress(f'wrote {out / "report.md"}, {out / "results.csv"}, {out / "bench_front.png"}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
