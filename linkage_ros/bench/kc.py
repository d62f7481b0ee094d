# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench kc: the compliance rates and a loaded solve against a kinematic solve.

    linkage-bench kc SCENE --travel FROM[:TO:STEP] [--rack ...] [--load ... --at ...]
                     [--rounds N]

The options are linkage-kc's (its parse_args and request read them); the load timed is
--load and --moment, else 1 kN lateral at the contact patch.
Per position, side by side in one run: one kinematic solve (core.solve.sweep of that one
travel, from the design pose, as the statics start from it), all the compliance rates
(core.statics.compliance) and one loaded solve (core.statics.solve_loaded). At 1x, 10x and
100x the positions, each copy shifted by a small fraction of a millimetre so that no two are
the same. Times are this process's CPU time, median over rounds that alternate the three.
"""

import sys
import time

import numpy as np

from .asked import asked
from ..core.solve import sweep
from ..tools import kc

PROG = 'linkage-bench kc'
SCALES = (1, 10, 100)
SHIFT_MM = 1e-3   # between copies of the positions
DEFAULT_FORCE_N = (0.0, 1000.0, 0.0)   # a lateral kN (cornering), when no load is given


def default_load(scene):
    """Return the load timed when none is given: 1 kN lateral at the patch (else the centre)."""
    from ..core.statics import Load
    return Load(force_n=DEFAULT_FORCE_N, at='cp' if scene.wheel_radius > 0 else 'wc',
                moment_nm=(0.0, 0.0, 0.0))


def _per_position(run, positions):
    """Return the CPU time (us) per position of run(travel, rack) over every position."""
    start = time.process_time()
    for travel, rack in positions:
        run(travel, rack)
    return (time.process_time() - start) / len(positions) * 1e6


def benchmark(scene, travels, racks, load, rounds):
    """
    Print the times per position (us) and their ratios at 1x, 10x and 100x; return 0 or 1.

    1 (nothing timed, one line) when a position's kinematic solve, rates or loaded solve fails:
    a failure returns early and is no measure of a solve.
    """
    from ..core.base import Status
    from ..core.statics import compliance, solve_loaded
    load = load or default_load(scene)
    base = [(float(t), float(r)) for r in racks for t in travels]
    runs = {'kinematic': lambda t, r: sweep(scene, [t], rack=r),
            'rates': lambda t, r: compliance(scene, travel_mm=t, rack_mm=r),
            'loaded': lambda t, r: solve_loaded(scene, travel_mm=t, load=load, rack_mm=r)}
    for travel, rack in base:
        checks = (runs['kinematic'](travel, rack).success,
                  runs['rates'](travel, rack).status == Status.OK,
                  runs['loaded'](travel, rack).status == Status.OK)
        if not all(checks):
            what = ('kinematic solve', 'rates', 'loaded solve')[checks.index(False)]
            print(f'{PROG}: nothing to time: the {what} at travel {travel:g} mm, rack '
                  f'{rack:g} mm fails', file=sys.stderr)
            return 1
    print(f'{scene.name}: {len(base)} positions (1x); loaded by {load}')
    print(f'{"positions":>10}{"kinematic_us":>14}{"rates_us":>12}{"loaded_us":>12}'
          f'{"rates/kinematic":>17}{"loaded/kinematic":>18}')
    middle = 0.5 * (scene.travel[0] + scene.travel[1])
    for scale in SCALES:
        positions = [(t + k * SHIFT_MM * (-1.0 if t > middle else 1.0), r)
                     for k in range(scale) for t, r in base]
        times = {name: [] for name in runs}
        for _ in range(rounds):
            for name, run in runs.items():
                times[name].append(_per_position(run, positions))
        kinematic, rates, loaded = (float(np.median(times[name])) for name in runs)
        print(f'{len(positions):>10}{kinematic:>14.1f}{rates:>12.1f}{loaded:>12.1f}'
              f'{rates / kinematic:>17.2f}{loaded / kinematic:>18.2f}', flush=True)
        print(f'{PROG}: {scale}x done', file=sys.stderr)
    return 0


def main(argv: list[str], rounds: int) -> int:
    """Time the positions linkage-kc's arguments ask for over rounds: 0, 1 if one fails, 2."""
    args = kc.parse_args(argv)
    # every answer timed here is a statics solve
    request = asked(kc, args, lambda request: request[0].warnings, statics=True)
    if isinstance(request, int):
        return request
    scene, travels, racks = request
    return benchmark(scene, travels, racks, kc.load_of(args) if args.loaded else None, rounds)
