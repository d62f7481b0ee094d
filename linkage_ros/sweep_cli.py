"""linkage-sweep: solve a scene over a travel range and print a CSV table (mm, deg).

Data goes to stdout (or --csv PATH), progress and errors to stderr.
"""

import argparse
import csv
import sys
import time

import numpy as np

from .kinematics import Continuation, METHODS, sweep, travel_range
from .scene import load_scene, SceneError

COLUMNS = ['travel_mm', 'camber_deg', 'toe_deg', 'wheel_center_x_mm', 'wheel_center_y_mm',
           'wheel_center_z_mm', 'qx', 'qy', 'qz', 'qw', 'residual_mm', 'iterations']


def table_rows(result):
    """CSV rows (mm, deg) of a Sweep, in COLUMNS order."""
    for i in range(len(result.travel)):
        yield ([result.travel[i], np.degrees(result.camber[i]), np.degrees(result.toe[i]),
                *result.wheel_center[i], *result.quaternion[i], result.residual[i],
                int(result.iterations[i])])


def write_csv(result, stream):
    writer = csv.writer(stream, lineterminator='\n')
    writer.writerow(COLUMNS)
    for row in table_rows(result):
        writer.writerow([f'{v:.10g}' if isinstance(v, float) else v for v in row])


def parse_args(argv):
    parser = argparse.ArgumentParser(prog='linkage-sweep', description=__doc__)
    parser.add_argument('scene', help='bundled scene name (e.g. five_link) or path to a YAML file')
    parser.add_argument('--from', dest='start', type=float, help='first travel, mm')
    parser.add_argument('--to', dest='stop', type=float, help='last travel, mm')
    parser.add_argument('--step', type=float, help='travel step, mm (> 0)')
    parser.add_argument('--method', choices=METHODS, default='fast')
    parser.add_argument('--csv', help='write the table here instead of stdout')
    parser.add_argument('--benchmark', type=int, metavar='ROUNDS', default=0,
                        help='instead of a table, time paper and fast sweeps side by side '
                        'over ROUNDS interleaved rounds and print the median per position')
    return parser.parse_args(argv)


def benchmark(scene, travels, rounds):
    """Median time per solved position (us) of each way of solving, timed side by side:
    paper and fast sweeps, and the fast method one command at a time (the node's path)."""
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
    print(f'{scene.name}: {len(travels)} positions from {travels[0]:g} to {travels[-1]:g} mm, '
          f'largest residual {worst:.2g} mm')
    print(f'{"method":<30}{"median_us_per_position":>24}{"p95_us":>10}{"ratio_to_fast":>15}')
    for name, values in times.items():
        print(f'{name:<30}{np.median(values):>24.1f}{np.percentile(values, 95):>10.1f}'
              f'{np.median(values) / fast:>15.1f}')


def main(argv=None):
    args = parse_args(argv)
    try:
        scene = load_scene(args.scene)
    except SceneError as exc:
        print(f'linkage-sweep: {exc}', file=sys.stderr)
        return 2
    low, high, step = scene.travel
    start = low if args.start is None else args.start
    stop = high if args.stop is None else args.stop
    step = step if args.step is None else args.step
    if not (step > 0 and np.isfinite([start, stop, step]).all()):
        print(f'linkage-sweep: --from, --to and --step must be finite and --step > 0 '
              f'(got {start}, {stop}, {step})', file=sys.stderr)
        return 2
    travels = travel_range(start, stop, step)
    if args.benchmark:
        benchmark(scene, travels, args.benchmark)
        return 0
    print(f'linkage-sweep: {scene.name}: {len(travels)} positions from {start:g} to '
          f'{stop:g} mm, method {args.method}', file=sys.stderr)
    result = sweep(scene, travels, method=args.method)
    if args.csv:
        with open(args.csv, 'w') as stream:
            write_csv(result, stream)
    else:
        write_csv(result, sys.stdout)
    if not result.success:
        print(f'linkage-sweep: {result.message} ({len(result.travel)} positions written)',
              file=sys.stderr)
        return 1
    print(f'linkage-sweep: done, largest residual {result.residual.max():.2g} mm',
          file=sys.stderr)
    return 0


if __name__ == '__main__':
    sys.exit(main())
