"""
linkage-map: kinematic maps of a corner or of every corner of a vehicle, for simulators.

Every quantity of linkage-sweep's tables (pose, camber, toe, the alignment set, the scene's
elements) on a regular (travel, rack) grid, written as lookup tables: CSV in long form,
NumPy .npz (grid axes and arrays) and, with the map extra, Parquet (map_files.py). Points out
of reach are NaN and listed in out_of_reach.csv, never extrapolated (doc/maps.md).
"""

import os
from pathlib import Path
import re
import sys
import time

import numpy as np
import yaml

from .map_files import FORMATS, UNREACHED, write_map, write_unreached
from .map_grid import corner_map, Grid, quantities
from ..cli import EXIT_STATUS, fail, Parser, program
from ..core.errors import LinkageError
from ..core.scene import load_scene
from ..core.vehicle import load_vehicle, vehicle_dir

PROG = 'linkage-map'
GRID_OPTIONS = ('--travel', '--rack')
DEFAULT_RACK = Grid(-40.0, 40.0, 5.0)   # mm, steered corners when --rack is not given
# Bytes a grid point needs per quantity while its corner is solved and written: the map's
# array, the rows of one rack's sweep and the copy a writer makes (float64 each).
BYTES_PER_VALUE = 3 * 8

EPILOG = """writes into DIR, per corner (the scene's name, or the vehicle's corner names):
  <corner>.csv      long form: corner,travel_mm,rack_mm,quantity,value (exact floats)
  <corner>.npz      travel_mm (nt,), rack_mm (nr,), one (nt, nr) array per quantity
  <corner>.parquet  with --format ...,parquet (pip install -e '.[map]'): a row per point
  out_of_reach.csv  corner,travel_mm,rack_mm,reason of every point left NaN
The quantities are linkage-sweep's columns with --alignment and --elements, in mm and deg.
Loading a map into an interpolating lookup: doc/maps.md.

examples:
  linkage-map double_wishbone --out maps
  linkage-map demo_vehicle --travel -50:50:2 --rack -30:30:10 --out maps --format csv,npz,parquet

exit status: 0 every grid point solved; 1 done, but some points are out of reach (NaN, listed
in out_of_reach.csv); """ + EXIT_STATUS


def parse_args(argv):
    parser = Parser(PROG, __doc__, EPILOG)
    parser.add_argument('target', metavar='SCENE_OR_VEHICLE',
                        help='bundled scene or vehicle name, or the path of either file')
    parser.add_argument('--travel', metavar='FROM:TO:STEP',
                        help="wheel travel grid, mm (default: each scene's travel block)")
    parser.add_argument('--rack', metavar='FROM:TO:STEP',
                        help='steering rack grid, mm, + = rack to the left (default -40:40:5 '
                        'for a corner with a steer: rack link; 0 for the others)')
    parser.add_argument('--axle', metavar='NAME',
                        help="an axle's map over (left travel, right travel) (not yet)")
    parser.add_argument('--out', metavar='DIR', help='folder for the map files (made if '
                        'missing)')
    parser.add_argument('--format', default='csv,npz',
                        help=f'comma-separated, of {", ".join(FORMATS)} (default csv,npz)')
    parser.add_argument('--benchmark', type=int, metavar='ROUNDS', default=0,
                        help='instead of a map, time answers with and without the elements '
                        '(1x, 10x, 100x positions) over ROUNDS rounds; print the medians')
    args = parser.parse_args(joined_grids(sys.argv[1:] if argv is None else argv))
    if args.benchmark < 0:
        parser.error(f'--benchmark: expected a number of rounds >= 0, got {args.benchmark}')
    if not args.out and not args.benchmark:
        parser.error('--out DIR is required')
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
    """Read FROM:TO:STEP (mm) into a Grid; LinkageError naming the option if it is not one."""
    try:
        start, stop, step = (float(v) for v in text.split(':'))
    except ValueError:
        raise LinkageError(option, f'expected FROM:TO:STEP in mm, got {text!r}') from None
    if not (step > 0 and np.isfinite([start, stop, step]).all()):
        raise LinkageError(option, f'FROM, TO, STEP must be finite and STEP > 0, got {text!r}')
    return Grid(start, stop, step)


def load_corners(target):
    """Return {corner name: Scene} of a scene (its name) or a vehicle file (its corners)."""
    path = Path(target)
    bundled = vehicle_dir() / f'{target}.yaml'
    if (not path.suffix and not path.exists() and bundled.is_file()) or _is_vehicle(path):
        return load_vehicle(target).corners
    scene = load_scene(target)
    return {re.sub(r'[^A-Za-z0-9_.-]+', '_', scene.name).strip('._-') or 'scene': scene}


def _is_vehicle(path):
    """Tell whether path is a YAML file of a vehicle (a top-level corners mapping)."""
    try:
        data = yaml.safe_load(path.read_text()) if path.is_file() else None
    except (OSError, UnicodeDecodeError, yaml.YAMLError, ValueError, RecursionError):
        return False   # load_scene then says what is wrong with it
    return isinstance(data, dict) and isinstance(data.get('corners'), dict)


def steered(scene):
    """Tell whether a rack moves something in the scene (a steer: rack link)."""
    return any(c.steer == 'rack' for c in scene.constraints)


def grids(corners, args):
    """Return {corner: (travel Grid, rack Grid or None for rack 0 only)}; LinkageError if bad."""
    travel = args.travel and grid_option(args.travel, '--travel')
    rack = args.rack and grid_option(args.rack, '--rack')
    if rack and not any(steered(s) for s in corners.values()):
        raise LinkageError('--rack', 'no corner has a steer: rack link, so a rack moves '
                           'nothing')
    return {name: (travel or Grid(*scene.travel),
                   (rack or DEFAULT_RACK) if steered(scene) else None)
            for name, scene in corners.items()}


def memory_needed(corners, axes):
    """Return (grid points, bytes) the maps need; counted, nothing allocated."""
    points = total = 0
    for name, scene in corners.items():
        travel, rack = axes[name]
        count = travel.count * (rack.count if rack else 1)
        points += count
        total = max(total, count * len(quantities(scene)) * BYTES_PER_VALUE)
    return points, total


def memory_available():
    """Return the bytes of memory available (MemAvailable), or None if unknown."""
    try:
        with open('/proc/meminfo') as stream:
            for line in stream:
                if line.startswith('MemAvailable:'):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    try:
        return os.sysconf('SC_AVPHYS_PAGES') * os.sysconf('SC_PAGE_SIZE')
    except (ValueError, OSError):
        return None


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


def output_folder(text):
    """Make the --out folder if missing; LinkageError if it cannot be written into."""
    folder = Path(text)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise LinkageError('--out', f'cannot make the folder {text} '
                           f'({exc.strerror or exc})') from None
    if not os.access(folder, os.W_OK):
        raise LinkageError('--out', f'cannot write into the folder {text}')
    return folder


def _gb(value):
    return f'{value / 1e9:,.1f} GB'


@program(PROG)
def main(argv: list[str] | None = None) -> int:
    """Run linkage-map: 0 when done, 1 if points are out of reach, 2 for a mistake."""
    args = parse_args(argv)
    try:
        corners = load_corners(args.target)
        axes = grids(corners, args)
        if args.benchmark:
            from .map_bench import benchmark
            benchmark(corners, args.benchmark)
            return 0
        if args.axle is not None:
            raise LinkageError('--axle', "an axle's map (roll centre, track, both wheels' "
                               'camber and toe over left x right travel) is not built yet: it '
                               'needs the axle module (core/axle.py)')
        points, need = memory_needed(corners, axes)
        available = memory_available()
        if available is not None and need > available:
            raise LinkageError('grid', f'{points:,} points need about {_gb(need)} of memory '
                               f'and {_gb(available)} is available: take a larger --travel '
                               'or --rack step, or a shorter range')
        formats = formats_option(args.format)
        folder = output_folder(args.out)
    except LinkageError as exc:
        return fail(PROG, exc)
    maps = []
    for name, scene in corners.items():
        travel, rack = axes[name]
        started = time.perf_counter()
        maps.append(corner_map(scene, travel.values(), rack.values() if rack else np.zeros(1),
                               name))
        written = write_map(folder, maps[-1], formats)
        print(f'{PROG}: {name}: {travel.count} x {rack.count if rack else 1} (travel x rack) '
              f'grid points, {len(maps[-1].quantities)} quantities, solved in '
              f'{time.perf_counter() - started:.2f} s -> '
              f'{", ".join(str(p) for p in written)}', file=sys.stderr)
        if maps[-1].undefined:
            print(f'{PROG}: {name}: left out, not defined for this corner: '
                  f'{", ".join(maps[-1].undefined)}', file=sys.stderr)
    lost = write_unreached(folder / UNREACHED, maps)
    if lost:
        print(f'{PROG}: {lost} grid points are out of reach: NaN in the map, listed in '
              f'{folder / UNREACHED}', file=sys.stderr)
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
