# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-study: design studies of a suspension corner, on this machine or a Dask cluster.

Exact sensitivities to the hardpoints, tolerance stack-up (first order and Monte Carlo),
and fitting hardpoints to target curves.
"""

from __future__ import annotations

import argparse
import sys

from ..cli import (check_plot, check_table, counted, EXIT_STATUS, fail, INTERRUPTED,
                   millimetres, Parser, program, SPAN, span, warn)
from ..core.base import LENGTH_LIMIT_MM, LinkageError, positions_needed
from ..outputs import check_outputs

PROG = 'linkage-study'
COMMANDS = ('sensitivity', 'tolerance', 'fit')

EPILOG = """examples:
  linkage-study sensitivity five_link --travel -50:50:50 -o five_link_sensitivity.csv
  linkage-study tolerance five_link --sigma 0.05 --samples 10000 --travel -50 0 50
  linkage-study tolerance five_link_bushings --sigma 1 --samples 2000 --travel 0 \\
      --tolerances config/study/five_link_bushings_15_percent.yaml
  linkage-study fit targets.yaml -o fitted.yaml --plot fit.png
  linkage-study tolerance five_link --sigma 0.1 --samples 1000000 --travel -50:50:50 \\
      --scheduler tcp://127.0.0.1:8786 -o tolerance.parquet

Hardpoints are named <constraint>.base, <constraint>.axis0, <constraint>.axis1,
<constraint>.carrier, wheel_center and spin_axis_point; quantities as linkage-sweep's columns
(camber_deg, toe_deg, wheel_center_x_mm, ..., the alignment set, <element>_length_mm, ...);
bushing rates <constraint>.bushing.<field>, and with --compliance the compliance rates
(toe_per_fy_cp_deg_per_kN, ...) as linkage-kc names them.
Tables go to stdout as CSV, or to -o (CSV, or Parquet for a name ending in .parquet).
--travel takes travels and ranges FROM:TO:STEP (TO included), in any mix.

exit status: 0 done; 1 done, but a travel or a variant is out of reach, or a fit leaves a
target with a tolerance unmet (said on stderr); """ + EXIT_STATUS


def parser() -> Parser:
    """Return the parser of linkage-study and its three subcommands."""
    from .tolerance import BUSHING_SD_LIMIT
    top = Parser(PROG, __doc__, EPILOG)
    commands = top.add_subparsers(dest='command', metavar='{sensitivity,tolerance,fit}',
                                  parser_class=Parser)

    def sub(name, text):
        return commands.add_parser(name, help=text, description=text, epilog=EPILOG,
                                   prog=f'{PROG} {name}')

    one = sub('sensitivity', 'exact d(quantity)/d(hardpoint coordinate) at travels (IFT)')
    two = sub('tolerance', 'tolerance stack-up: first order and Monte Carlo')
    for p in (one, two):
        p.add_argument('scene', help='bundled scene name or path to a scene file')
        p.add_argument('--travel', nargs='+', required=True, metavar=SPAN,
                       help='travels, mm (+ = bump): values, ranges, or both')
        p.add_argument('-o', '--output', dest='out', metavar='FILE',
                       help='write the table here (.csv, or .parquet); default stdout')
    one.add_argument('--rack', type=millimetres, default=0.0,
                     help='steering rack travel, mm (default 0)')
    one.add_argument('--quantity', nargs='+', metavar='Q',
                     help='quantities (default: every one the scene has; a compliance rate, '
                     'toe_per_fy_cp_deg_per_kN, ..., by central differences of the statics)')
    two.add_argument('--sigma', type=float, required=True, metavar='MM',
                     help='standard deviation of every hardpoint coordinate, mm (> 0)')
    two.add_argument('--samples', type=int, required=True, metavar='N',
                     help='Monte Carlo variants (>= 2)')
    two.add_argument('--seed', type=int, default=0, help='random seed (default 0)')
    two.add_argument('--tolerances', metavar='FILE',
                     help='YAML of per-point standard deviations, mm: POINT: SD or '
                     'POINT: {x: SD, y: SD, z: SD}; of lengths (the design re-assembles): '
                     'CONSTRAINT.length: SD; of bushing rates: CONSTRAINT.bushing.FIELD: SD '
                     f'(axial, radial N/mm; torsion, conical N m/deg; or a percentage, 5%%; '
                     f'from 0 to {100 * BUSHING_SD_LIMIT:g}%% of the rate)')
    two.add_argument('--plot', metavar='PNG', help='draw the distributions here')
    for p in (one, two):
        p.add_argument('--compliance', action='store_true',
                       help='the compliance rates (toe_per_fy_cp_deg_per_kN, ...) are '
                       'quantities too (a scene with bushings; a tolerance study has them '
                       'whenever a bushing rate varies)')
    three = sub('fit', 'fit free hardpoints to target curves (bounded least squares)')
    three.add_argument('targets', help='targets file (YAML: scene, free, targets)')
    three.add_argument('-o', '--output', required=True, metavar='NEW_SCENE.yaml',
                       help='write the fitted scene here')
    three.add_argument('--starts', type=int, default=1,
                       help='starting points: the design, then random ones within the bounds')
    three.add_argument('--seed', type=int, default=0, help='seed of the random starts')
    three.add_argument('--plot', metavar='PNG', help='draw the curves before and after here')
    for p in (two, three):
        p.add_argument('--scheduler', metavar='ADDRESS',
                       help='a Dask scheduler (tcp://host:8786): run the batches there')
        p.add_argument('--workers', type=int, default=0, help=workers_help())
    return top


def workers_help() -> str:
    """Say what --workers does by default, from the numbers the studies use."""
    from .commands import POOL_FROM
    from .tolerance import BATCH
    return (f'local processes without --scheduler (default 0: every core once a tolerance '
            f'study has {POOL_FROM} batches of {BATCH} variants or more, a fit 2 starts or '
            'more; less work runs in this process, since a process takes seconds to start)')


def parse_args(argv):
    """Parse the command line; a mistake exits with one line and status 2."""
    top = parser()
    args, extra = top.parse_known_args(argv)
    if extra:
        top.error(f'unrecognized arguments: {" ".join(extra)}')
    if args.command is None:
        top.error(f'give a command: {", ".join(COMMANDS)}')
    if getattr(args, 'travel', None):
        args.travel = travels(args.travel)
    return args


def travels(texts) -> list[float]:
    """Return every travel, mm, of --travel's values and ranges, in the order given."""
    from ..core.solve import travel_range
    try:
        spans = [span(text) for text in texts]
        for given in spans:
            positions_needed(*given, '--travel')   # before a range too long is made
    except (argparse.ArgumentTypeError, LinkageError) as exc:
        sys.exit(fail(PROG, f'--travel: {exc}' if isinstance(exc, argparse.ArgumentTypeError)
                      else exc))
    return [float(t) for given in spans for t in travel_range(*given)]


def check(args) -> None:
    """Refuse values no study can use, and outputs that cannot be written (LinkageError)."""
    from ..core.model import resolve_scene_path
    outputs = [('-o', getattr(args, 'out', None)), ('--plot', getattr(args, 'plot', None)),
               ('-o', getattr(args, 'output', None))]
    scene = getattr(args, 'scene', None)   # its file: the name of a bundled scene is no path
    inputs = tuple(str(i) for i in (scene and resolve_scene_path(scene),
                                    getattr(args, 'targets', None),
                                    getattr(args, 'tolerances', None)) if i)
    check_outputs(outputs, inputs)
    if args.command == 'tolerance':
        if not args.sigma > 0:   # NaN too
            raise LinkageError('--sigma', f'must be a number of mm above 0, got {args.sigma:g}')
        if args.sigma > LENGTH_LIMIT_MM:   # the variants' arithmetic would overflow
            raise LinkageError('--sigma', f'must be at most {LENGTH_LIMIT_MM:g} mm (the length '
                               f'limit of a scene), got {args.sigma:g}')
        if args.samples < 2:
            raise LinkageError('--samples', f'must be at least 2, got {args.samples}')
    if getattr(args, 'workers', 0) < 0:
        raise LinkageError('--workers', f'must be 0 (every core) or more, got {args.workers}')
    if args.command == 'fit' and args.starts < 1:
        raise LinkageError('--starts', f'must be at least 1, got {args.starts}')
    check_table(getattr(args, 'out', None), '-o', 'study')
    check_plot(getattr(args, 'plot', None), '--plot', inputs)


@program(PROG)
def main(argv: list[str] | None = None) -> int:
    """Run linkage-study: 0 when done, 1 if something is out of reach, 2 for a mistake."""
    args = parse_args(argv)
    from .commands import run_fit, run_sensitivity, run_tolerance
    from ..core.model import SceneError
    try:
        check(args)
        command = {'sensitivity': run_sensitivity, 'tolerance': run_tolerance,
                   'fit': run_fit}[args.command]
        return command(args, say)
    except (LinkageError, SceneError) as exc:
        return fail(PROG, exc)
    except KeyboardInterrupt:   # Ctrl-C: the local workers are stopped already (executor)
        print(f'{PROG}: interrupted', file=sys.stderr)
        return INTERRUPTED
    except BrokenPipeError:
        raise   # stdout's reader went away: program() ends quietly
    except OSError as exc:   # an output that became unwritable on the way
        return fail(PROG, f'{exc.filename or "an output"}: cannot write ({exc.strerror or exc})')


def say(message: str, warnings: tuple = ()) -> None:
    """Print warnings, then one progress or result line, on stderr."""
    warn(PROG, warnings)
    if message:
        print(f'{PROG}: {message}', file=sys.stderr)


__all__ = ['main', 'counted']


if __name__ == '__main__':
    sys.exit(main())
