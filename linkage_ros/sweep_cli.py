"""linkage-sweep: solve a scene over a travel range and print a CSV table (mm, deg).

Data goes to stdout (or --csv PATH), progress and errors to stderr.
"""

import argparse
import csv
import sys

import numpy as np

from .kinematics import METHODS, sweep, travel_range
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
    return parser.parse_args(argv)


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
