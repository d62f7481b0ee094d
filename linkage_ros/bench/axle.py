# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench axle: an axle's positions against its corners' positions, side by side.

    linkage-bench axle [VEHICLE] [--axle front|rear] [--heave ...] [--roll ...] [--rack ...]
                       [--rounds N]

The options are linkage-axle's (its parse_args and request read them). One corner swept, both
corners swept, and the axle solved (solve_axle: both corners, then the roll centre, anti
quantities and the bar), each at 1x, 10x and 100x the positions, in alternating rounds.
"""

import sys
import time

import numpy as np

from .asked import asked
from ..core.axle import solve_axle, wheel_travels
from ..core.solve import sweep
from ..tools import axle as program


def benchmark(axle, heave, roll, rack, rounds):
    """
    Print the median time per position (us) of an axle and of its corners, side by side.

    At 1x, 10x and 100x the positions (the heaves repeated, each copy shifted by a small
    fraction of a millimetre so that no two positions are the same). The time is this
    process's CPU time: the work, which other processes on a shared machine disturb less
    than they disturb the wall-clock time.
    """
    print(f'{axle.name} axle of {axle.left.name} and {axle.right.name}: {len(heave)} '
          'positions (1x)')
    print(f'{"positions":>10}{"one_corner_us":>15}{"two_corners_us":>16}{"axle_us":>10}'
          f'{"axle/one_corner":>17}{"axle/two_corners":>18}')
    left, right = wheel_travels(axle, heave, np.radians(roll))
    for scale in (1, 10, 100):
        # each copy shifted towards the middle of the travel block, never past its limits
        # (solve_axle would stop there, and the time be of fewer positions)
        h = np.tile(heave, scale)
        shift = np.repeat(np.arange(scale) * 1e-3, len(heave)) * np.where(
            h > 0.5 * (axle.left.travel[0] + axle.left.travel[1]), -1.0, 1.0)
        h, r, k = h + shift, np.tile(roll, scale), np.tile(rack, scale)
        tl, tr = np.tile(left, scale) + shift, np.tile(right, scale) + shift
        runs = {'one': lambda: sweep(axle.left, tl, rack=k[0]),
                'two': lambda: (sweep(axle.left, tl, rack=k[0]),
                                sweep(axle.right, tr, rack=k[0])),
                'axle': lambda: solve_axle(axle, h, np.radians(r), k)}
        times = {name: [] for name in runs}
        for _ in range(rounds):
            for name, run in runs.items():
                start = time.process_time()
                run()
                times[name].append((time.process_time() - start) / len(h) * 1e6)
        one, two, both = (float(np.median(times[name])) for name in runs)
        print(f'{len(h):>10}{one:>15.2f}{two:>16.2f}{both:>10.2f}{both / one:>17.2f}'
              f'{both / two:>18.2f}', flush=True)
        print(f'{program.PROG}: benchmark {scale}x done', file=sys.stderr)


def main(argv: list[str], rounds: int) -> int:
    """Time the axle linkage-axle's arguments ask for over rounds: 0, or 2 for a mistake."""
    request = asked(program, program.parse_args(argv),
                    lambda request: request[0].vehicle.warnings)
    if isinstance(request, int):
        return request
    _, axle, (heave, roll, rack) = request
    benchmark(axle, heave, roll, rack, rounds)
    return 0
