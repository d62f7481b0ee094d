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

import sys

from .. import cli
from ..core.base import LinkageError

PROG = 'linkage-chrono'
EPILOG = """example:
  linkage-chrono import config/chrono/generic/DoubleWishbone.json -o dw.yaml
  linkage-chrono export five_link -o five_link.json
  linkage-chrono export dw.yaml -o dw.json --like config/chrono/generic/DoubleWishbone.json

exit status:
  0  written
""" + '  ' + cli.EXIT_STATUS + """
     (also a file Chrono would not read, or a template outside the list: nothing is written)"""


def main(argv=None):
    """Run linkage-chrono; returns the exit status."""
    return _main(argv)


@cli.program(PROG)
def _main(argv):
    parser = cli.Parser(PROG, cli.summary(__doc__), EPILOG)
    sub = parser.add_subparsers(dest='command', metavar='{import,export}', required=True,
                                parser_class=cli.Parser)
    one = sub.add_parser('import', help='a Chrono suspension or vehicle JSON file -> a scene '
                         'or vehicle YAML file', prog=f'{PROG} import', description='',
                         epilog=EPILOG)
    one.add_argument('source', metavar='CHRONO.json')
    one.add_argument('-o', '--output', metavar='FILE.yaml', required=True)
    one.add_argument('--wheel-radius', type=float, default=None, metavar='M',
                     help='tyre radius, m (a suspension file has none; default 0.33)')
    two = sub.add_parser('export', help='a scene -> a Chrono suspension JSON file',
                         prog=f'{PROG} export', description='', epilog=EPILOG)
    two.add_argument('scene', metavar='SCENE', help='bundled scene name or scene file')
    two.add_argument('-o', '--output', metavar='FILE.json', required=True)
    two.add_argument('--like', metavar='ORIGINAL.json', default=None,
                     help='keep every non-kinematic field of this Chrono file')
    args = parser.parse_args(argv)
    try:
        if args.command == 'import':
            return _import(args)
        return _export(args)
    except (cli.Mistake, LinkageError) as exc:
        return cli.fail(PROG, exc)


def _import(args):
    from ..chrono import import_file
    inputs = (args.source,)
    cli.check_output(args.output, '-o', inputs=inputs)
    texts, summary = import_file(args.source, args.output, args.wheel_radius)
    for path, text in texts.items():
        cli.check_output(path, '-o', inputs=inputs)
    for path, text in texts.items():
        with cli.whole_file(path, encoding='utf-8') as out:
            out.write(text)
    print(f'{PROG}: {summary}', file=sys.stderr)
    return cli.DONE


def _export(args):
    from ..chrono import export_file
    inputs = tuple(p for p in (args.like,) if p)
    cli.check_output(args.output, '-o', inputs=inputs)
    text, summary = export_file(args.scene, args.like)
    with cli.whole_file(args.output, encoding='utf-8') as out:
        out.write(text)
    print(f'{PROG}: {summary} -> {args.output}', file=sys.stderr)
    return cli.DONE


if __name__ == '__main__':
    sys.exit(main())
