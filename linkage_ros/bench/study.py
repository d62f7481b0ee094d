# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Benchmark of the studies: python -m linkage_ros.bench.study [--sizes N ...] [--repeats R].

Prints, in CPU seconds of this process (time.process_time: the machine may be busy; every
figure is the minimum of --repeats runs, one core, no pool):
  tolerance: the batched variant solve at each size x 11 travels (-50..50 mm), its cost per
             (variant, position), against kinematics.sweep's cost per position in the same
             run, for the same 11 travels and for 161 (-80..80 mm);
  sensitivity: all points at one position (25 mm) against one solve of that position;
  fit: the bump-steer fit of double_wishbone's tie-rod body point (wall time, evaluations).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from ..core.model import scene_dir
from ..core.solve import Continuation, sweep
from ..core.vary import (load_design, pose_derivative, sensitivities, sweep_column_rates,
                         SWEEP_COLUMNS)
from ..study.fit import fit
from ..study.targets import load_targets
from ..study.tolerance import batches, problem, sigmas, solve_batch

TRAVELS = np.linspace(-50.0, 50.0, 11)
BUMP_STEER = """scene: double_wishbone
free:
  tie_rod.base: {x: [-30, 30], y: [-30, 30], z: [-30, 30]}
targets:
  - {quantity: toe_deg, travel: [-50, 50, 5], value: 0.0, weight: 1.0}
"""


def cpu(function, repeats: int) -> float:
    """Return the least CPU time (s) of repeats calls of function()."""
    best = float('inf')
    for _ in range(repeats):
        start = time.process_time()
        function()
        best = min(best, time.process_time() - start)
    return best


def bench_tolerance(sizes, repeats):
    """Print the variant solve's cost per (variant, position) beside the sweep's."""
    design = load_design('five_link')
    scene = design.scene
    short = cpu(lambda: sweep(scene, TRAVELS), 20 * repeats) / len(TRAVELS)
    long_travels = np.arange(-80.0, 81.0, 1.0)
    long = cpu(lambda: sweep(scene, long_travels), 5 * repeats) / len(long_travels)
    print(f'sweep five_link, 11 travels: {short * 1e6:.2f} us per position; 161 travels: '
          f'{long * 1e6:.2f} us per position')
    print(f'{"variants":>10}{"cpu_s":>10}{"us_per_variant_position":>26}'
          f'{"ratio_to_sweep_11":>19}{"ratio_to_sweep_161":>20}')
    for size in sizes:
        prob = problem(design, sigmas(design, 0.05), size, TRAVELS, seed=1)
        items = batches(prob)
        seconds = cpu(lambda: [solve_batch(item) for item in items], repeats)
        each = seconds / (size * len(TRAVELS))
        print(f'{size:>10}{seconds:>10.2f}{each * 1e6:>26.3f}{each / short:>19.3f}'
              f'{each / long:>20.3f}')


def bench_sensitivity(repeats):
    """Print the cost of all sensitivities at one position beside one solve."""
    scene = load_design('five_link').scene
    cont = Continuation(scene)

    def two_solves():   # design -> 25 mm -> design: two walks of 25 mm
        cont.solve(25.0)
        cont.solve(0.0)

    solve = cpu(lambda: [two_solves() for _ in range(100)], repeats) / 200
    table = sweep(scene, [25.0])
    points = load_design('five_link').values
    pose = cpu(lambda: pose_derivative(scene, points, table.wheel_center, table.rotation),
               20 * repeats)
    sweep_only = cpu(lambda: sensitivities(scene, [25.0], wanted=SWEEP_COLUMNS), 10 * repeats)
    compiled = cpu(lambda: [sweep_column_rates(scene, table.wheel_center, table.rotation)
                            for _ in range(100)], repeats) / 100
    everything = cpu(lambda: sensitivities(scene, [25.0]), 10 * repeats)
    print(f'one solve of five_link, a walk of 25 mm (Continuation.solve): '
          f'{solve * 1e6:.1f} us')
    for name, seconds in (('5 sweep columns, compiled (sweep_column_rates)', compiled),
                          ('pose derivative by jets, 36 coordinates', pose),
                          ('sensitivities of the 5 sweep columns (solve included)', sweep_only),
                          ('sensitivities of all 35 quantities (solve included)', everything)):
        print(f'{name:<58}{seconds * 1e6:>9.1f} us{seconds / solve:>10.2f} x one solve')


def bench_fit(tmp):
    """Print the wall time and evaluations of the bump-steer fit."""
    path = f'{tmp}/bump_steer_targets.yaml'
    with open(path, 'w') as stream:
        stream.write(BUMP_STEER.replace('double_wishbone',
                                        str(scene_dir() / 'double_wishbone.yaml')))
    targets = load_targets(path)
    start = time.perf_counter()
    result = fit(targets)
    wall = time.perf_counter() - start
    print(f'fit of tie_rod.base (3 coordinates) to toe 0 at 21 travels: {wall:.2f} s wall, '
          f'{result.evaluations} evaluations, {result.jacobians} Jacobians; largest |toe| '
          f'{np.abs(result.before.errors[0]).max():.4f} -> '
          f'{np.abs(result.after.errors[0]).max():.5f} deg')


def main(argv=None) -> int:
    """Run the benchmark sections and print their tables."""
    import tempfile
    parser = argparse.ArgumentParser(prog='python -m linkage_ros.bench.study',
                                     description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--sizes', type=int, nargs='+', default=[10_000, 100_000, 1_000_000])
    parser.add_argument('--repeats', type=int, default=3)
    args = parser.parse_args(argv)
    solve_batch(batches(problem(load_design('five_link'), np.full((12, 3), 0.05), 10,
                                TRAVELS))[0])   # compile (or load) the kernels first
    bench_tolerance(args.sizes, args.repeats)
    bench_sensitivity(args.repeats)
    with tempfile.TemporaryDirectory() as tmp:
        bench_fit(tmp)
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
