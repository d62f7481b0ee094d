# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Sections core and sweep of linkage-bench node: the solver alone, no ROS."""

import contextlib
import io
from pathlib import Path
import tempfile
import time

import numpy as np

from .tables import progress, table, us


def bench_core(args):
    """One command at a time: Continuation.solve beside exudyn, alternating rounds."""
    from .. import peers
    from ...core.model import load_scene
    from ...core.solve import Continuation
    scene = load_scene(args.scene)
    count = args.count * args.scale
    travels = 60.0 * np.sin(np.arange(count) * 0.0125)      # mm, steps of up to 0.75 mm
    entries = {'linkage_ros': Continuation(scene)}
    if peers.exudyn_version():
        entries['exudyn'] = peers.ExudynSolver(scene, 1e-10)
    else:
        progress('exudyn is not installed (pip install -e .[bench]): core alone')
    times = {name: [] for name in entries}
    centers = {name: [] for name in entries}
    residual = 0.0
    rounds = 4
    for r, chunk in enumerate(np.array_split(travels, rounds)):
        for name, solver in entries.items():
            for travel in chunk:
                start = time.perf_counter()
                answer = solver.solve(travel)
                times[name].append(time.perf_counter() - start)
                if name == 'linkage_ros':
                    residual = max(residual, answer.residual)
                    centers[name].append(answer.wheel_center)
                else:
                    centers[name].append(answer[0])
        progress(f'core: round {r + 1}/{rounds}')
    base = np.median(times['linkage_ros'])
    rows = []
    for name, values in times.items():
        diff = np.abs(np.array(centers[name]) - np.array(centers['linkage_ros'])).max()
        rows.append((name, count, us(values), us(values, 99), float(np.median(values) / base),
                     residual if name == 'linkage_ros' else '', float(diff)))
    table(['core', 'commands', 'median_us', 'p99_us', 'ratio_to_linkage_ros',
           'residual_max_mm', 'wheel_center_diff_mm'], rows)


def bench_sweep(args):
    """linkage-sweep to a CSV file over the scene's travel block in steps of 1, 0.1, 0.01 mm."""
    from ...core.model import load_scene
    from ...tools import sweep
    low, high, _ = load_scene(args.scene).travel   # -80, 80 mm: 161, 1601, 16001 positions
    rows, base = [], None
    with tempfile.TemporaryDirectory() as folder:
        with contextlib.redirect_stderr(io.StringIO()):   # untimed: loads the kernels
            sweep.main([args.scene, '-o', str(Path(folder) / 'warmup.csv')])
        for step in (1.0, 0.1, 0.01):
            step /= args.scale
            positions = int(round((high - low) / step)) + 1
            out = Path(folder) / 'sweep.csv'
            with contextlib.redirect_stderr(io.StringIO()):
                start = time.perf_counter()
                sweep.main([args.scene, f'--travel={low!r}:{high!r}:{step!r}', '-o', str(out)])
                seconds = time.perf_counter() - start
            base = base or (positions, seconds)
            over = ((seconds - base[1]) / (positions - base[0]) * 1e6
                    if positions > base[0] else '')
            rows.append((positions, seconds, seconds / positions * 1e6, over))
            progress(f'sweep: {positions} positions in {seconds:.2f} s')
    table(['sweep', 'seconds', 'us_per_position', 'us_per_position_over_the_first'], rows)
