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

from .map_files import FORMATS, map_files, UNREACHED, write_map, write_unreached
from .map_grid import axle_grid_map, AXLE_QUANTITIES, corner_map, Grid, GridMap, quantities
from ..cli import check_table, EXIT_STATUS, fail, Parser, program, SPAN, span, warn
from ..core.axle import axle_of
from ..core.base import LinkageError, Need, refuse_if_short
from ..core.model import load_target
from ..core.warmup import compile_if_cold
from ..outputs import output_folder

PROG = 'linkage-map'
GRID_OPTIONS = ('--travel', '--rack')
DEFAULT_RACK = Grid(-40.0, 40.0, 5.0)   # mm, steered corners when --rack is not given
# Measured with linkage-map demo_vehicle (4 corners, 41 quantities) on grids of 2,020 and
# 164,164 points: loading the compiled kernels and solving took 141 MB of address space and
# 48 MB resident on top of what the program held when it checked; each value of the maps
# (a grid point's quantity: the map's array, the rows of one rack's sweep, a writer's copy)
# took 15 B at the peak with CSV and NPZ, 23 B with Parquet too. Rounded up. Every corner's
# map is kept until the last is written (their points out of reach are listed at the end),
# so the need is the sum over the corners, not the largest.
BASE_BYTES = 160e6
BYTES_PER_VALUE = 24
# pyarrow's first Parquet file reserved 1.3 GB of address space (its allocator and threads),
# of which about 100 MB became resident.
PARQUET_ADDRESS_BYTES = 1.4e9
PARQUET_RESIDENT_BYTES = 100e6

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
linkage-bench map.

exit status: 0 every grid point solved; 1 done, but some points are out of reach (NaN, listed
in out_of_reach.csv); """ + EXIT_STATUS


def parse_args(argv):
    """Read the command line (-o is checked by main); a mistake exits with status 2."""
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
    parser.add_argument('--format', default='csv,npz',
                        help=f'comma-separated, of {", ".join(FORMATS)} (default csv,npz)')
    return parser.parse_args(joined_grids(sys.argv[1:] if argv is None else argv))


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


def map_corners(target):
    """Return {corner name: Scene} of a Target: a vehicle's corners, a scene under its name."""
    if target.vehicle is not None:
        return target.corners
    name = re.sub(r'[^A-Za-z0-9_.-]+', '_', target.scene.name).strip('._-') or 'scene'
    return {name: target.scene}


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


def memory_needed(jobs, parquet: bool = False) -> Need:
    """Return the Need of jobs (each with shape (n0, n1) and quantities); nothing allocated."""
    points = sum(job.shape[0] * job.shape[1] for job in jobs)
    values = sum(job.shape[0] * job.shape[1] * job.quantities for job in jobs)
    data = BASE_BYTES + BYTES_PER_VALUE * values
    return Need(points, data + parquet * PARQUET_RESIDENT_BYTES,
                data + parquet * PARQUET_ADDRESS_BYTES)


def check_memory(jobs, formats):
    """Refuse maps that need more memory than this process may take (LinkageError)."""
    need = memory_needed(jobs, 'parquet' in formats)
    refuse_if_short(need, 'grid', f'{need.points:,} points',
                    'take a larger --travel or --rack step, or a shorter range')


def file_names(folder, jobs, formats):
    """
    Return the names of the files the jobs write into folder, the list out of reach last.

    Raises LinkageError for two maps (or a map and that list) that would be one file.
    """
    written = {}
    for job in jobs:
        for path in map_files(Path(folder), job.kind, job.name, formats):
            if path.name == UNREACHED or path.name in written:
                other = 'the list of points out of reach' if path.name == UNREACHED else \
                    f'the map of {written[path.name]}'
                what = 'axle' if job.kind == 'axle' else 'scene or corner'
                raise LinkageError('-o', f'the map of {job.name} would be {path}, which '
                                   f'is {other}: rename the {what}')
            written[path.name] = job.name
    return [*written, UNREACHED]


def formats_option(text):
    """Return the formats asked for; LinkageError for an unknown one or a missing pyarrow."""
    kinds = tuple(dict.fromkeys(k.strip() for k in text.split(',') if k.strip()))
    unknown = [k for k in kinds if k not in FORMATS]
    if unknown or not kinds:
        raise LinkageError('--format', f'unknown format {", ".join(unknown) or repr(text)} '
                           f'(expected a comma-separated list of: {", ".join(FORMATS)})')
    if 'parquet' in kinds:
        check_table('maps.parquet', '--format parquet')
    return kinds


def request(args):
    """
    Return what parsed arguments ask to map: (target, {corner name: Scene}, [Job]).

    Raises SceneError for a file that does not load and LinkageError for a grid or an axle
    that cannot be mapped, before anything is solved.
    """
    target = load_target(args.target)
    vehicle, corners = target.vehicle, map_corners(target)
    jobs = [axle_job(vehicle, args)] if args.axle is not None else corner_jobs(corners, args)
    return target, corners, jobs


@program(PROG)
def main(argv: list[str] | None = None) -> int:
    """Run linkage-map: 0 when done, 1 if points are out of reach, 2 for a mistake."""
    args = parse_args(argv)
    if not args.out:
        return fail(PROG, f'error: -o/--output DIR is required (see {PROG} --help)')
    try:
        target, _, jobs = request(args)   # SceneError is a LinkageError
        warn(PROG, target.warnings)
        formats = formats_option(args.format)   # pyarrow first: its memory is then in use
        check_memory(jobs, formats)
        folder = output_folder('-o', args.out, file_names(args.out, jobs, formats),
                               target.files)
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
