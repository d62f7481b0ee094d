# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-map: kinematic maps of a corner, of every corner of a vehicle, or of an axle.

Every quantity of linkage-sweep's tables (pose, camber, toe, the alignment set, the scene's
elements) on a regular (travel, rack) grid, or an axle's roll centre, track, cambers and toes
over (left travel, right travel), written as lookup tables for simulators: CSV in long form,
NumPy .npz (grid axes and arrays) and, with the map extra, Parquet. Points out of reach are
NaN and listed in out_of_reach.csv, never extrapolated (doc/maps.md).
"""

import argparse
from functools import partial
import math
from pathlib import Path
import re
import sys
import time
from typing import Callable, NamedTuple

import numpy as np
import yaml

from .map_files import FORMATS, map_files, UNREACHED, write_map, write_unreached
from .map_grid import axle_grid_map, AXLE_QUANTITIES, corner_map, Grid, GridMap, quantities
from .map_memory import memory_needed, refuse_if_short
from ..cli import EXIT_STATUS, fail, output_folder, Parser, program, same_file, SPAN, span, warn
from ..core.axle import axle_of
from ..core.base import LinkageError
from ..core.model import load_scene, load_vehicle, vehicle_dir
from ..core.warmup import compile_if_cold

PROG = 'linkage-map'
GRID_OPTIONS = ('--travel', '--rack')
DEFAULT_RACK = Grid(-40.0, 40.0, 5.0)   # mm, steered corners when --rack is not given

EPILOG = """writes into DIR, per corner (the scene's name, or the vehicle's corner names):
  <corner>.csv      long form: corner,travel_mm,rack_mm,quantity,value (exact floats)
  <corner>.npz      travel_mm (nt,), rack_mm (nr,), one (nt, nr) array per quantity
  <corner>.parquet  with --format ...,parquet (pip install -e '.[map]'): a row per point
  out_of_reach.csv  corner,travel_mm,rack_mm,reason of every solve out of reach (NaN)
The quantities are linkage-sweep's columns with --alignment and --elements, in mm and deg.
With --axle NAME instead: <NAME>_axle.* over left_travel_mm x right_travel_mm (rack 0),
roll_centre_y_mm, roll_centre_z_mm, roll_centre_height_mm, track_mm and both wheels'
camber and toe (core/axle/axle.py). Loading a map into an interpolating lookup: doc/maps.md.

examples:
  linkage-map double_wishbone -o maps
  linkage-map demo_vehicle --travel -50:50:2 --rack -30:30:10 -o maps --format csv,npz,parquet
  linkage-map demo_vehicle --axle front -o maps

--travel and --rack take a range FROM:TO:STEP (TO included) or one value. Timing:
linkage-bench map. Old spellings kept for one release, each with a note: --out, --benchmark.

exit status: 0 every grid point solved; 1 done, but some points are out of reach (NaN, listed
in out_of_reach.csv); """ + EXIT_STATUS


def parse_args(argv, rounds=0):
    parser = Parser(PROG, __doc__, EPILOG)
    parser.add_argument('target', metavar='SCENE_OR_VEHICLE',
                        help='bundled scene or vehicle name, or the path of either file')
    parser.add_argument('--travel', metavar=SPAN,
                        help="wheel travel grid, mm (default: each scene's travel block)")
    parser.add_argument('--rack', metavar=SPAN,
                        help='steering rack grid, mm, + = rack to the left (default -40:40:5 '
                        'for a corner with a steer: rack link; 0 for the others)')
    parser.add_argument('--axle', metavar='NAME',
                        help="instead of the corners' maps, the map of the vehicle's axle NAME "
                        'over (left travel, right travel) at rack 0: roll centre, track, both '
                        "wheels' camber and toe")
    parser.add_argument('-o', '--output', dest='out', metavar='DIR',
                        help='folder for the map files (made if missing)')
    parser.old('--out', dest='out', metavar='DIR', new='-o/--output')
    parser.add_argument('--format', default='csv,npz',
                        help=f'comma-separated, of {", ".join(FORMATS)} (default csv,npz)')
    parser.old('--benchmark', type=int, metavar='ROUNDS', default=0,
               new='linkage-bench map --rounds ROUNDS')
    args = parser.parse_args(joined_grids(sys.argv[1:] if argv is None else argv))
    args.benchmark = rounds or args.benchmark
    if args.benchmark < 0:
        parser.error(f'--benchmark: expected a number of rounds >= 0, got {args.benchmark}')
    if not args.out and not args.benchmark:
        parser.error('-o/--output DIR is required')
    return args


def joined_grids(argv):
    """Join '--travel -80:80:1' into '--travel=-80:80:1': argparse takes -80:... for an option."""
    joined = []
    for arg in argv:
        if joined and joined[-1] in GRID_OPTIONS and re.match(r'-[0-9.]', arg):
            joined[-1] = f'{joined[-1]}={arg}'
        else:
            joined.append(arg)
    return joined


def grid_option(text, option):
    """Read FROM[:TO:STEP] (mm) into a Grid; LinkageError naming the option if it is not one."""
    try:
        grid = Grid(*span(text))
    except argparse.ArgumentTypeError as exc:
        raise LinkageError(option, str(exc)) from None
    if grid.count == math.inf:
        raise LinkageError(option, f'{text}: more than 2**52 points, too many to make; take '
                           'a larger STEP or a shorter range')
    return grid


def load_target(target):
    """Return (Vehicle or None, {corner name: Scene}) of a scene file or a vehicle file."""
    path = Path(target)
    bundled = vehicle_dir() / f'{target}.yaml'
    if (not path.suffix and not path.exists() and bundled.is_file()) or _is_vehicle(path):
        vehicle = load_vehicle(target)
        return vehicle, vehicle.corners
    scene = load_scene(target)
    return None, {re.sub(r'[^A-Za-z0-9_.-]+', '_', scene.name).strip('._-') or 'scene': scene}


def _is_vehicle(path):
    """Tell whether path is a YAML file of a vehicle (a top-level corners mapping)."""
    try:
        data = yaml.safe_load(path.read_text()) if path.is_file() else None
    except (OSError, UnicodeDecodeError, yaml.YAMLError, ValueError, RecursionError):
        return False   # load_scene then says what is wrong with it
    return isinstance(data, dict) and isinstance(data.get('corners'), dict)


class Job(NamedTuple):
    """One map to make: its kind and name, grid size, quantities and how to solve it."""

    kind: str          # 'corner' or 'axle'
    name: str          # the corner's or the axle's
    shape: tuple[int, int]
    quantities: int
    solve: Callable[[], GridMap]


def corner_jobs(corners, args):
    """Return a Job per corner over (travel, rack); LinkageError for a bad grid."""
    travel = args.travel and grid_option(args.travel, '--travel')
    rack = args.rack and grid_option(args.rack, '--rack')
    if rack and not any(s.steered for s in corners.values()):
        raise LinkageError('--rack', 'no corner has a steer: rack link, so a rack moves '
                           'nothing')
    jobs = []
    for name, scene in corners.items():
        travels = travel or Grid(*scene.travel)
        racks = (rack or DEFAULT_RACK) if scene.steered else None
        jobs.append(Job('corner', name, (travels.count, racks.count if racks else 1),
                        len(quantities(scene)),
                        partial(solve_corner, scene, travels, racks, name)))
    return jobs


def axle_job(vehicle, args):
    """Return the Job of the axle --axle names over (left travel, right travel), rack 0."""
    if vehicle is None:
        raise LinkageError('--axle', f'{args.target} is a scene; an axle is in a vehicle file '
                           '(e.g. demo_vehicle)')
    if args.rack:
        raise LinkageError('--rack', "an axle's map is over both wheels' travels at rack 0; "
                           'map its steered corners without --axle for the rack')
    axle = axle_of(vehicle, args.axle)
    travel = grid_option(args.travel, '--travel') if args.travel else Grid(*axle.left.travel)
    return Job('axle', axle.name, (travel.count, travel.count), len(AXLE_QUANTITIES),
               partial(solve_axle, axle, travel))


def solve_corner(scene, travel, rack, name):
    """Solve a corner's map over the Grids travel and rack (None: rack 0 only)."""
    return corner_map(scene, travel.values(), rack.values() if rack else np.zeros(1), name)


def solve_axle(axle, travel):
    """Solve an axle's map, both wheels over the Grid travel."""
    return axle_grid_map(axle, travel.values())


def check_memory(jobs, formats):
    """Refuse maps that need more memory than this process may take (LinkageError)."""
    need = memory_needed(jobs, 'parquet' in formats)
    refuse_if_short(need, 'grid', f'{need.points:,} points',
                    'take a larger --travel or --rack step, or a shorter range')


def check_names(folder, jobs, formats, inputs):
    """
    Refuse outputs that would replace an input or each other (LinkageError naming both).

    inputs: the files read (the scene or vehicle file and the corners' scene files).
    """
    unreached = folder / UNREACHED
    written = {}
    for job in jobs:
        for path in map_files(folder, job.kind, job.name, formats):
            if path == unreached or path in written:
                other = 'the list of points out of reach' if path == unreached else \
                    f'the map of {written[path]}'
                what = 'axle' if job.kind == 'axle' else 'scene or corner'
                raise LinkageError('-o', f'the map of {job.name} would be {path}, which '
                                   f'is {other}: rename the {what}')
            written[path] = job.name
    for path in [*written, unreached]:
        for source in inputs:
            if same_file(str(path), source):
                raise LinkageError('-o', f'writing {path} would replace the input '
                                   f'{source}: give another -o folder')


def formats_option(text):
    """Return the formats asked for; LinkageError for an unknown one or a missing pyarrow."""
    kinds = tuple(dict.fromkeys(k.strip() for k in text.split(',') if k.strip()))
    unknown = [k for k in kinds if k not in FORMATS]
    if unknown or not kinds:
        raise LinkageError('--format', f'unknown format {", ".join(unknown) or repr(text)} '
                           f'(expected a comma-separated list of: {", ".join(FORMATS)})')
    if 'parquet' in kinds:
        try:
            import pyarrow.parquet  # noqa: F401 (only whether it is there)
        except ImportError:
            raise LinkageError('--format parquet', 'needs the Python package pyarrow, which '
                               "is not installed: pip install -e '.[map]' (in a linkage_ros "
                               'checkout) or pip install pyarrow') from None
    return kinds


@program(PROG)
def main(argv: list[str] | None = None, rounds: int = 0) -> int:
    """
    Run linkage-map: 0 when done, 1 if points are out of reach, 2 for a mistake.

    rounds > 0 times the answers instead (linkage-bench map) over that many rounds.
    """
    args = parse_args(argv, rounds)
    try:
        vehicle, corners = load_target(args.target)
        warn(PROG, [w for scene in corners.values() for w in scene.warnings])
        jobs = [axle_job(vehicle, args)] if args.axle is not None else corner_jobs(corners, args)
        if args.benchmark:
            from .map_bench import benchmark
            compile_if_cold(PROG)
            return benchmark(corners, args.benchmark)
        formats = formats_option(args.format)   # pyarrow first: its memory is then in use
        check_memory(jobs, formats)
        folder = output_folder(args.out, '-o')
        check_names(folder, jobs, formats, [args.target, *(
            [vehicle.source] if vehicle else []), *(s.source for s in corners.values())])
    except LinkageError as exc:
        return fail(PROG, exc)
    compile_if_cold(PROG)
    maps = []
    for job in jobs:
        started = time.perf_counter()
        maps.append(job.solve())
        written = write_map(folder, maps[-1], formats)
        first, second = (n.replace('_mm', '').replace('_', ' ') for n in maps[-1].axis_names)
        label = job.name if job.kind == 'corner' else f'{job.name} axle'
        print(f'{PROG}: {label}: {job.shape[0]} x {job.shape[1]} ({first} x {second}) '
              f'grid points, {len(maps[-1].quantities)} quantities, solved in '
              f'{time.perf_counter() - started:.2f} s -> '
              f'{", ".join(str(p) for p in written)}', file=sys.stderr)
        if maps[-1].undefined:
            print(f'{PROG}: {label}: left out, not defined here: '
                  f'{", ".join(maps[-1].undefined)}', file=sys.stderr)
    lost = write_unreached(folder / UNREACHED, maps)
    if lost:
        print(f'{PROG}: {lost} solves are out of reach: NaN in the map, listed in '
              f'{folder / UNREACHED}', file=sys.stderr)
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
