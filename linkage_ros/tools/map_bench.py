"""
linkage-map --benchmark: the cost per answer of the elements' quantities, against without.

Two paths, each at 1x, 10x and 100x positions (161, 1 610, 16 100 over the scene's travel
block), timed side by side in alternating rounds: one command at a time (Continuation.solve,
the node's path; with elements, element_values of that pose from the Jacobian the solve
holds) and a sweep (sweep; with elements, element_values of the whole batch).
"""

import sys
import time

import numpy as np

from ..core.elements import element_values, prepare
from ..core.kinematics import Continuation, sweep

SIZES = (161, 1610, 16100)


def one_by_one(scene, travels, with_elements):
    """Solve travels one command at a time; with_elements: each answer's element values."""
    cont = Continuation(scene)
    model = prepare(scene, cont.mech)
    for travel in travels:
        solution = cont.solve(travel)
        if with_elements:
            element_values(scene, solution.wheel_center, solution.rotation, solution.rack,
                           jac=cont.jacobian, model=model)


def batch(scene, travels, with_elements):
    """Solve travels in one sweep; with_elements: the element values of the batch."""
    result = sweep(scene, travels)
    if with_elements:
        element_values(scene, result.wheel_center, result.rotation, result.rack)


def benchmark(corners, rounds):
    """Print the median µs per answer without and with elements, and their ratio."""
    scene = next((s for s in corners.values() if s.elements), next(iter(corners.values())))
    low, high, _ = scene.travel
    runs = {(path, n): [[], []] for path in ('one command', 'sweep') for n in SIZES}
    for r in range(rounds):
        for (path, n), times in runs.items():
            travels = np.linspace(low, high, n)
            run = one_by_one if path == 'one command' else batch
            for with_elements in (False, True):
                start = time.perf_counter()
                run(scene, travels, with_elements)
                times[with_elements].append((time.perf_counter() - start) / n * 1e6)
        print(f'linkage-map: benchmark round {r + 1}/{rounds}', file=sys.stderr)
    print(f'{scene.name}: {len(scene.elements)} elements '
          f'({", ".join(e.name for e in scene.elements)}), travels {low:g} to {high:g} mm')
    print(f'{"path":<14}{"scale":>6}{"positions":>10}{"without_us":>12}{"with_us":>10}'
          f'{"elements_us":>13}{"ratio":>7}')
    for (path, n), (without, with_) in runs.items():
        a, b = np.median(without), np.median(with_)
        print(f'{path:<14}{n // SIZES[0]:>5}x{n:>10}{a:>12.2f}{b:>10.2f}{b - a:>13.2f}'
              f'{b / a:>7.2f}')
