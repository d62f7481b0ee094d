# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench sweep: the paper's sweep, the fast sweep and one command at a time, side by side.

    linkage-bench sweep SCENE [--travel FROM:TO:STEP] [--rounds N]

The options are linkage-sweep's (its parse_args and request read them); the scene solved over
the travels it asks for, by each way of solving in turn, round after round; the median and
95th percentile of the wall-clock time per position, and each way's ratio to the fast sweep.
"""

import sys
import time

import numpy as np

from .asked import asked
from ..cli import counted
from ..core.solve import Continuation, METHODS, sweep
from ..tools import sweep as program


def benchmark(scene, travels, rounds):
    """
    Return the median time per solved position (us) of each way of solving.

    Timed side by side: paper and fast sweeps, and the fast method one command at a time (the
    node's path). Returns the exit status: 1, with the line, if a travel is out of reach
    (nothing is timed: a sweep that stops early is no measure of one that does not).
    """
    solved = sweep(scene, travels)
    if not solved.success:
        print(f'linkage-sweep: nothing to time: {solved.message}', file=sys.stderr)
        return 1

    def one_by_one():
        cont = Continuation(scene)
        for travel in travels:
            cont.solve(travel)

    entries = {'paper sweep': lambda: sweep(scene, travels, method='paper'),
               'fast sweep': lambda: sweep(scene, travels, method='fast'),
               'fast, one command at a time': one_by_one}
    repeats = {'paper sweep': 1, 'fast sweep': 20, 'fast, one command at a time': 2}
    times = {name: [] for name in entries}
    for r in range(rounds):
        for name, run in entries.items():
            for _ in range(repeats[name]):
                start = time.perf_counter()
                run()
                times[name].append((time.perf_counter() - start) / len(travels) * 1e6)
        print(f'linkage-sweep: benchmark round {r + 1}/{rounds}', file=sys.stderr)
    worst = max(sweep(scene, travels, method=m).residual.max() for m in METHODS)
    fast = np.median(times['fast sweep'])
    print(f'{scene.name}: {counted(len(travels), "position")} from {travels[0]:g} to '
          f'{travels[-1]:g} mm, '
          f'largest residual {worst:.2g} mm')
    print(f'{"method":<30}{"median_us_per_position":>24}{"p95_us":>10}{"ratio_to_fast":>15}')
    for name, values in times.items():
        print(f'{name:<30}{np.median(values):>24.1f}{np.percentile(values, 95):>10.1f}'
              f'{np.median(values) / fast:>15.1f}')
    return 0


def main(argv: list[str], rounds: int) -> int:
    """Time the sweep linkage-sweep's arguments ask for over rounds: 0, 1 out of reach, 2."""
    request = asked(program, program.parse_args(argv),
                    lambda request: request[0].warnings)
    if isinstance(request, int):
        return request
    scene, travels, _ = request
    return benchmark(scene, travels, rounds)
