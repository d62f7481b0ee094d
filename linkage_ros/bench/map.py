# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-bench map: the cost per answer of the elements' quantities, against without.

    linkage-bench map SCENE_OR_VEHICLE [--rounds N]

The options are linkage-map's (its parse_args and request read them; -o is not needed); the
first corner with elements is timed (else the first corner), over its travel block.

Two paths, each at 1x, 10x and 100x positions (161, 1 610, 16 100 over the scene's travel
block): one command at a time (Continuation.solve, the node's path; then values_at, the elements
of that pose from the Jacobian the solve holds) and a sweep (sweep; then element_values of the
whole batch). Solving and the elements are timed back to back, answer by answer or batch by
batch, so that both see the same load; the medians over the rounds are printed.
"""

import sys
import time

import numpy as np

from .asked import asked
from ..core.measure import element_values, prepare, values_at
from ..core.solve import Continuation, sweep
from ..tools import kinematic_map as program

SIZES = (161, 1610, 16100)


def one_by_one(scene, travels):
    """
    Solve travels one command at a time, each answer followed by its element values.

    Returns the seconds spent solving and the seconds spent on the elements, each answer's
    two parts timed back to back (so that both see the same load of a shared machine).
    """
    cont = Continuation(scene)
    model = prepare(scene, cont.mech)
    clock = time.perf_counter
    solving = elements = 0.0
    for travel in travels:
        start = clock()
        answer = cont.solve(travel)
        middle = clock()
        values_at(model, answer.wheel_center, answer.rotation, answer.rack, cont.jacobian)
        end = clock()
        solving += middle - start
        elements += end - middle
    return solving, elements


def batch(scene, travels):
    """Solve travels in one sweep, then the element values of the batch; seconds of each."""
    start = time.perf_counter()
    result = sweep(scene, travels)
    middle = time.perf_counter()
    element_values(scene, result.wheel_center, result.rotation, result.rack)
    return middle - start, time.perf_counter() - middle


def benchmark(corners, rounds):
    """
    Print the median µs per answer without and with elements, and their ratio; return 0.

    1, with the line, if the scene's travel block is out of reach in part: nothing is timed.
    """
    scene = next((s for s in corners.values() if s.elements), next(iter(corners.values())))
    low, high, _ = scene.travel
    solved = sweep(scene, np.linspace(low, high, SIZES[0]))
    if not solved.success:
        print(f'linkage-map: nothing to time: {scene.name}: {solved.message}', file=sys.stderr)
        return 1
    runs = {(path, n): [] for path in ('one command', 'sweep') for n in SIZES}
    for r in range(rounds):
        for (path, n), times in runs.items():
            run = one_by_one if path == 'one command' else batch
            times.append(np.array(run(scene, np.linspace(low, high, n))) / n * 1e6)
        print(f'linkage-map: benchmark round {r + 1}/{rounds}', file=sys.stderr)
    print(f'{scene.name}: {len(scene.elements)} elements '
          f'({", ".join(e.name for e in scene.elements)}), travels {low:g} to {high:g} mm, '
          f'median of {rounds} rounds')
    print(f'{"path":<14}{"scale":>6}{"positions":>10}{"without_us":>12}{"elements_us":>13}'
          f'{"with_us":>10}{"ratio":>7}')
    for (path, n), times in runs.items():
        without, extra = np.median(times, axis=0)
        print(f'{path:<14}{n // SIZES[0]:>5}x{n:>10}{without:>12.2f}{extra:>13.2f}'
              f'{without + extra:>10.2f}{(without + extra) / without:>7.2f}')
    return 0


def main(argv: list[str], rounds: int) -> int:
    """Time the corners linkage-map's arguments name over rounds: 0, 1 out of reach, 2."""
    # the grid and axle checked, as linkage-map does
    request = asked(program, program.parse_args(argv),
                    lambda request: request[0].warnings)
    if isinstance(request, int):
        return request
    return benchmark(request[1], rounds)
