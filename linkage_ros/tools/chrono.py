# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-chrono: import Chrono::Vehicle suspension and vehicle JSON files, export scenes to them.

import SUSPENSION.json -o SCENE.yaml writes a scene (units m, left side) that loads and
solves; import VEHICLE.json -o VEHICLE.yaml writes each axle's scene beside it and a vehicle
file with left and mirrored right corners. export SCENE -o SUSPENSION.json writes the Chrono
template of the scene's topology (GenericWheeledSuspension where no named template fits);
--like ORIGINAL.json keeps every other field of an original file. doc/chrono.md.
"""

import math
import sys

from .target import write_text
from .. import cli
from ..core.base import LENGTH_LIMIT_MM, LinkageError, MM_PER_M
from ..outputs import check_outputs, whole_file

PROG = 'linkage-chrono'
MAX_RADIUS_M = LENGTH_LIMIT_MM / MM_PER_M   # the length limit of every scene
# Every example runs as written from a checkout (test/chrono/test_chrono_program.py).
EXAMPLES = (
    'import config/chrono/generic/suspension/DoubleWishbone.json -o dw.yaml',
    'export dw.yaml -o dw.json --like config/chrono/generic/suspension/DoubleWishbone.json',
    'export five_link -o five_link.json',
    'import config/chrono/hmmwv/vehicle/HMMWV_Vehicle.json -o hmmwv.yaml',
)
EPILOG = 'examples (from a checkout, in this order):\n' + ''.join(
    f'  {PROG} {e}\n' for e in EXAMPLES) + """
exit status:
  0  written
""" + '  ' + cli.EXIT_STATUS + """
     (also a file Chrono would not read, or a template outside the list: nothing is written)"""


def main(argv=None):
    """Run linkage-chrono; returns the exit status."""
    return _main(argv)


def radius(text: str) -> float:
    """Return a tyre radius, m, from an option's text: a number in (0, MAX_RADIUS_M]."""
    try:
        value = float(text)
    except ValueError:
        raise cli.Mistake(f'--wheel-radius: expected a number of metres, got {text!r}') from None
    if not (math.isfinite(value) and 0.0 < value <= MAX_RADIUS_M):
        raise cli.Mistake(f'--wheel-radius: must be in (0, {MAX_RADIUS_M:g}] m, got {text}')
    return value


@cli.program(PROG)
def _main(argv):
    parser = cli.Parser(PROG, cli.summary(__doc__), EPILOG)
    sub = parser.add_subparsers(dest='command', metavar='{import,export}', required=True,
                                parser_class=cli.Parser)
    one = sub.add_parser('import', help='a Chrono suspension or vehicle JSON file -> a scene '
                         'or vehicle YAML file', prog=f'{PROG} import',
                         description='Read a Chrono::Vehicle suspension file (a scene out) or '
                         'vehicle file (a vehicle and one scene per axle out).', epilog=EPILOG)
    one.add_argument('source', metavar='CHRONO.json',
                     help='a Chrono::Vehicle suspension or vehicle JSON file (a regular file '
                     "of at most 10 MB; a vehicle's suspension files are found under its "
                     'data folder, as Chrono finds them)')
    one.add_argument('-o', '--output', metavar='FILE.yaml', required=True,
                     help='the scene (or vehicle) file to write, whole or not at all; a '
                     "vehicle's axle scenes go beside it as FILE_front.yaml, FILE_rear.yaml "
                     '(or FILE_axle0.yaml, ...). Required')
    one.add_argument('--wheel-radius', type=str, default=None, metavar='M',
                     help=f'tyre radius, m, in (0, {MAX_RADIUS_M:g}] (a suspension file has '
                     "none, it is the tyre's); default 0.33")
    two = sub.add_parser('export', help='a scene -> a Chrono suspension JSON file',
                         prog=f'{PROG} export', description='Write a scene as a '
                         'Chrono::Vehicle suspension file of the template its topology has.',
                         epilog=EPILOG)
    two.add_argument('scene', metavar='SCENE',
                     help='a bundled scene name (five_link, ...) or a scene YAML file')
    two.add_argument('-o', '--output', metavar='FILE.json', required=True,
                     help="the Chrono JSON file to write, whole or not at all ('-': "
                     'stdout). Required')
    two.add_argument('--like', metavar='ORIGINAL.json', default=None,
                     help='a Chrono suspension file of the same template whose every other '
                     'field (masses, inertias, radii, curves) is kept; default: the bundled '
                     'generic file of the template')
    args = parser.parse_args(argv)
    try:
        if args.command == 'import':
            return _import(args)
        return _export(args)
    except (cli.Mistake, LinkageError) as exc:
        return cli.fail(PROG, exc)


def _import(args):
    from ..chrono import import_file, inputs_of
    wheel_radius = radius(args.wheel_radius) if args.wheel_radius is not None else None
    inputs = inputs_of(args.source)   # the file and, for a vehicle, its suspension files
    if args.output == '-':
        raise cli.Mistake('-o -: import writes a scene file (a vehicle: several), not '
                          'stdout; give a FILE.yaml')
    check_outputs([('-o', args.output)], inputs)
    texts, summary = import_file(args.source, args.output, wheel_radius)
    check_outputs([('-o', path) for path in texts], inputs)
    for path, text in texts.items():
        with whole_file(path, encoding='utf-8') as out:
            out.write(text)
    print(f'{PROG}: {summary}', file=sys.stderr)
    return cli.DONE


def _export(args):
    from ..chrono import export_file
    from ..core.model import resolve_scene_path
    inputs = [str(resolve_scene_path(args.scene))] + [p for p in (args.like,) if p]
    if args.output != '-':
        check_outputs([('-o', args.output)], inputs)
    text, summary = export_file(args.scene, args.like)
    write_text(args.output, text)
    print(f'{PROG}: {summary} -> {args.output}', file=sys.stderr)
    return cli.DONE


if __name__ == '__main__':
    sys.exit(main())
