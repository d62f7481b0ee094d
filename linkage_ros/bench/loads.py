# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench loads: the time of a load case, beside one loaded solve per corner.

    linkage-bench loads VEHICLE [--case NAME ...] [--cases FILE] [--rounds N]

A load case finds each corner's loaded ride height (core/loads: the travels where the holding
forces are zero, each a loaded solve of the corner's Statics, which goes on from its last
equilibrium) and its forces. Timed at 1x, 10x and 100x the cases: the cases as given, then
each at 10 and 100 load levels (its accelerations and its corners' multiples times 0.55 to
1, a vertical load factor v as 1 + f (v - 1)). Beside each, one loaded solve of every corner
alone at the travel and load found (solve_corner: a Statics of its own, from the kinematic
pose). The median of N rounds of this process's CPU time, after a first solve of the cases
(compiling and preparing the vehicle's setup sheet are not timed).
"""

from dataclasses import replace
import sys
import time

import numpy as np

from ..cli import fail
from ..core.base import LinkageError
from ..tools.loads import parse_args, PROG, request

SCALES = (1, 10, 100)


def scaled_case(case, f):
    """
    Return a case at f (0 to 1) of its load, named NAME_F (F to three decimals).

    Its accelerations and its corners' multiples times f, a vertical load factor v as
    1 + f (v - 1): at f = 0 the car standing still, at 1 the case.
    """
    corners = {k: replace(c, g=(c.g[0] * f, c.g[1] * f, 1.0 + f * (c.g[2] - 1.0)))
               if c.g is not None else replace(
                   c, force_n=tuple(f * v for v in c.force_n),
                   moment_nm=tuple(f * v for v in c.moment_nm))
               for k, c in case.corners.items()}
    return replace(case, name=f'{case.name}_{f:.3f}', longitudinal_g=f * case.longitudinal_g,
                   lateral_g=f * case.lateral_g,
                   vertical_g=1.0 + f * (case.vertical_g - 1.0), corners=corners)


def scaled(cases, scale):
    """Return the cases at scale load levels each (scale 1: as given), as a list."""
    if scale == 1:
        return list(cases.values())
    return [scaled_case(case, f) for case in cases.values() for f in np.linspace(0.55, 1.0, scale)]


def corner_solves(answers):
    """Solve every solved corner once more, alone, at its travel and load; return how many."""
    from ..core.loads import solve_corner
    count = 0
    for answer in answers:
        for corner in answer.corners.values():
            if corner.loaded is not None:
                solve_corner(corner.scene, corner.travel_mm, corner.load)
                count += 1
    return count


def benchmark(loads, cases, rounds, scales=SCALES):
    """Print the table: scale, cases, ms per case, ms per corner solve; return 0 or 1."""
    answers = [loads.solve(c) for c in cases.values()]   # warm: compiled, caches filled
    print(f'load cases on {loads.vehicle.name}: median of {rounds} rounds of CPU time')
    print(f'{"scale":>6}{"cases":>7}{"case_ms":>10}{"corner_solve_ms":>17}{"ratio":>8}')
    failed = 0
    for scale in scales:
        chosen = scaled(cases, scale)
        case_times, solve_times = [], []
        for _ in range(rounds):
            start = time.process_time()
            answers = [loads.solve(c) for c in chosen]
            case_times.append((time.process_time() - start) / len(chosen))
            start = time.process_time()
            count = corner_solves(answers)
            solve_times.append((time.process_time() - start) / max(1, count))
        failed += sum(a.status != 0 for a in answers)
        case, solve = float(np.median(case_times)), float(np.median(solve_times))
        print(f'{scale:>6}{len(chosen):>7}{case * 1e3:>10.1f}{solve * 1e3:>17.2f}'
              f'{case / solve:>8.1f}', flush=True)
        print(f'linkage-bench loads: {scale}x done', file=sys.stderr, flush=True)
    if failed:
        print(f'linkage-bench loads: {failed} cases with a corner not solved', file=sys.stderr)
    return 1 if failed else 0


def main(argv: list[str], rounds: int) -> int:
    """Time the cases linkage-loads's arguments ask for over rounds: 0, 1 if one fails, 2."""
    args = parse_args(argv)
    try:
        loads, cases = request(args)
    except LinkageError as exc:
        return fail(PROG, exc)
    return benchmark(loads, cases, rounds)
