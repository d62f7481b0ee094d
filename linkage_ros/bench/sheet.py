# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench vehicle: the time of a vehicle's setup sheet at 1x, 10x and 100x its table sizes.

    linkage-bench vehicle VEHICLE [--rounds N]

The options are linkage-vehicle's (its parse_args and request read them).

The setup sheet (core/vehicle/sheet.py) of a four-corner vehicle solves each axle at design
and over its heave, roll and (if it steers) rack tables, and computes every rate, stiffness
and balance quantity from them. Timed here with the tables' positions multiplied by 1, 10 and
100: the median of N rounds of this process's CPU time (the work, which other processes on a
shared machine disturb less than the wall-clock time), after the first compile.
"""

import sys
import time

import numpy as np

from .asked import asked
from ..core.vehicle import setup_sheet
from ..tools import vehicle as program

SCALES = (1, 10, 100)


def benchmark(vehicle, setup_sheet, rounds, scales=SCALES):
    """Print a table: scale, positions solved, the sheet's median time (ms) and per position."""
    print(f'setup sheet of {vehicle.name}: median of {rounds} rounds')
    print(f'{"scale":>6}{"positions":>11}{"sheet_ms":>11}{"per_position_us":>17}')
    for scale in scales:
        times = []
        for _ in range(rounds):
            start = time.process_time()
            sheet = setup_sheet(vehicle, scale)
            times.append(time.process_time() - start)
        positions = sum(len(r.heave) for s in sheet.axles.values()
                        for r in (s.design, s.heave, s.roll, s.rack) if r is not None)
        median = float(np.median(times))
        print(f'{scale:>6}{positions:>11}{median * 1e3:>11.1f}{median / positions * 1e6:>17.2f}',
              flush=True)
        print(f'linkage-bench vehicle: {scale}x done', file=sys.stderr)


def main(argv: list[str], rounds: int) -> int:
    """Time the sheet of the vehicle linkage-vehicle's arguments name: 0, or 2 for a mistake."""
    vehicle = asked(program, program.parse_args(argv),
                    lambda vehicle: vehicle.warnings)
    if isinstance(vehicle, int):
        return vehicle
    benchmark(vehicle, setup_sheet, rounds)
    return 0
