# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-kc: the compliance (the C of K&C) of a scene with bushings, or its loaded pose and forces.

Without a load, the table gives the compliance rates at each travel (and rack), the travel
held at the wheel centre as a K&C rig's wheel pad holds it: toe, camber and displacement per
kN of lateral and longitudinal force at the contact patch and at the wheel centre, per kN m
of aligning torque, and the jacking force per lateral force. With --load (and --moment), the
table gives the loaded pose and what every link, pivot and spring carries. Model, signs and
units: doc/kc.md. The table goes to stdout (or to -o FILE), progress and errors to stderr.
"""

import math
import sys

import numpy as np

from ..cli import (check_plot, check_table, counted, EXIT_STATUS, fail, Parser, program, SPAN,
                   span, table_status, warn)
from ..core.base import check_position_count, FORCE_LIMIT_N, LinkageError, MOMENT_LIMIT_NM, \
    positions_needed, say_ranges, wrench_problem
from ..core.model import load_scene
from ..core.solve import travel_range
from ..outputs import check_outputs, write_table

PROG = 'linkage-kc'
# The 6x6 matrix's rows (the wheel centre's response) and columns (the load at the wheel
# centre), units in the labels: entry [i, j] is response i per unit of load j.
MATRIX_ROWS = ('dx_mm', 'dy_mm', 'dz_mm', 'rx_deg', 'ry_deg', 'rz_deg')
MATRIX_COLUMNS = ('fx_kN', 'fy_kN', 'fz_kN', 'mx_kNm', 'my_kNm', 'mz_kNm')
MATRIX_CORNER = 'response_per_load'
ZERO = (0.0, 0.0, 0.0)

EPILOG = """columns, without a load: travel_mm (+ = bump), rack_mm with --rack, then the
  compliance rates (doc/kc.md): toe_ and camber_per_fy_cp_deg_per_kN, wc_dy_ and
  cp_dy_per_fy_cp_mm_per_kN, jacking_per_fy_cp (N/N), toe_ and camber_per_fx_cp_deg_per_kN,
  wc_dx_per_fx_cp_mm_per_kN, toe_per_fx_wc_deg_per_kN, wc_dx_per_fx_wc_mm_per_kN, toe_ and
  camber_per_mz_deg_per_kNm. Toe + = toe-in, camber + = top outboard, forces and moments in
  the vehicle frame (x forward, y left, z up); cp the contact patch, wc the wheel centre.
columns, with --load or --moment: travel_mm, rack_mm with --rack, camber_deg, toe_deg,
  wheel_center_x/y/z_mm, holding_force_N (the vertical force at the wheel centre that holds
  the travel, + = up), <link>_tension_N (+ = tension; a link that carries a spring has
  <link>_body_end_ and <link>_carrier_end_tension_N), <spring>_force_N (+ = compressed),
  <pickup>_fx/fy/fz_N (the force on the body at each pickup: <arm>_axis0, _axis1 or
  _centre, <link>_base, <spring>_body, <strut>_top) and <bushing>_mx/my/mz_Nm (each
  bushing's couple on the body at its pickup). The pickups' forces and couples balance the
  load and the holding force (doc/kc.md).

examples:
  linkage-kc double_wishbone_bushings --travel -40:40:20
  linkage-kc double_wishbone_bushings --travel 0 --matrix double_wishbone_compliance.csv
  linkage-kc double_wishbone_bushings --travel 0 --load 0,4000,0 --at cp -o cornering.csv
  linkage-kc double_wishbone_bushings --travel 0 --moment 0,0,100 --plot aligning.png

Travels and racks are plain numbers of mm; one value is one position, FROM:TO:STEP a range
(TO included). --matrix and the picture of a loaded solve are of one position. Timing:
linkage-bench kc.

ranges (doc/scenes.md#ranges; outside them a scene is refused in one line, status 2):
""" + \
    say_ranges('bushing_rate', 'bushing_angular_rate', 'spring_rate') + """

exit status: 0 every position solved; 1 a position is out of reach, or a load the linkage
cannot carry (a bushing beyond the model's validity, or no equilibrium: the line names the
load and the last residual; the rows solved before it are written); """ + EXIT_STATUS


def vector(text: str) -> tuple:
    """Read X,Y,Z (three finite numbers) into a tuple: an argparse type."""
    import argparse
    try:
        values = tuple(float(v) for v in text.split(','))
    except ValueError:
        values = ()
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f'expected X,Y,Z, three finite numbers, got {text!r}')
    return values


def parse_args(argv):
    """Read the command line; a mistake exits with one line and status 2."""
    parser = Parser(PROG, __doc__, EPILOG)
    parser.add_argument('scene', help='bundled scene name (e.g. double_wishbone_bushings) or '
                        'path to a YAML file')
    parser.add_argument('--travel', type=span, metavar=SPAN, required=True,
                        help='wheel travel, mm, + = bump: one value or a range')
    parser.add_argument('--rack', type=span, metavar=SPAN,
                        help='steering rack travel, mm (+ = rack to the left); adds rack_mm; '
                        'a range solves a travel x rack grid')
    parser.add_argument('--load', type=vector, metavar='FX,FY,FZ',
                        help='force on the wheel, N, vehicle frame (needs --at); each '
                        f'component within +-{FORCE_LIMIT_N:g} N')
    parser.add_argument('--at', choices=('cp', 'wc'),
                        help="where the force acts: cp the contact patch (needs the scene's "
                        'wheel_radius), wc the wheel centre')
    parser.add_argument('--moment', type=vector, metavar='MX,MY,MZ',
                        help='moment on the wheel, N m, vehicle frame; each component within '
                        f'+-{MOMENT_LIMIT_NM:g} N m')
    parser.add_argument('--columns', metavar='NAME,...',
                        help='write only these columns (after travel_mm and rack_mm)')
    parser.add_argument('-o', '--output', '--csv', dest='output', metavar='FILE',
                        help='write the table to this file (default: stdout)')
    parser.add_argument('--matrix', metavar='FILE',
                        help='write the 6x6 compliance matrix of the wheel centre (csv, mm and '
                        'deg per kN and kN m) at the one position given')
    parser.add_argument('--plot', metavar='FILE',
                        help='draw the rates against travel, or with a load the loaded '
                        'mechanism in front and side views with its forces (PNG)')
    args = parser.parse_args(argv)
    if args.load is not None and args.at is None:
        parser.error('--load needs --at cp or --at wc (where the force acts)')
    if args.at is not None and args.load is None:
        parser.error('--at says where the force of --load acts: give --load FX,FY,FZ')
    for option, given, force, moment in (('--load', args.load, args.load, ZERO),
                                         ('--moment', args.moment, ZERO, args.moment)):
        problem = given is not None and wrench_problem(force, moment)
        if problem:   # the node's bound on a wheel's wrench (core.base.limits)
            parser.error(f'{option}: {problem}')
    args.loaded = args.load is not None or args.moment is not None
    if args.loaded and args.matrix:
        parser.error('--matrix is the compliance at zero load: leave out --load and --moment')
    return args


def request(args):
    """
    Return what parsed arguments ask to solve: (scene, travels, racks), mm.

    Raises SceneError for a scene that does not load and LinkageError for a request that
    cannot be carried out (positions(), check_request()), before anything is solved.
    """
    scene = load_scene(args.scene)
    travels, racks = positions(args)
    check_request(scene, args)
    return scene, travels, racks


def positions(args):
    """Return (travels, racks) of the request (mm), or raise LinkageError naming the option."""
    count = positions_needed(*args.travel, '--travel')
    racks = np.zeros(1)
    if args.rack is not None:
        positions_needed(*args.rack, '--rack')   # before a range too long is made
        racks = travel_range(*args.rack)
    check_position_count(count * len(racks), '--rack',
                         f'{counted(count, "travel")} x {counted(len(racks), "rack")}')
    travels = travel_range(*args.travel)
    one = len(travels) * len(racks) == 1
    for option in ('matrix', 'plot'):
        if getattr(args, option) and not one and (option == 'matrix' or args.loaded):
            what = 'the matrix' if option == 'matrix' else 'the loaded mechanism'
            many = counted(len(travels) * len(racks), 'position')
            raise LinkageError(f'--{option}', f'{what} is of one position: give one --travel '
                               f'(and one --rack), not {many}')
    return travels, racks


def check_request(scene, args):
    """Raise LinkageError for what the scene cannot do: a contact patch, a rack, a column."""
    if args.at == 'cp' and not scene.wheel_radius > 0:
        raise LinkageError('--at cp', f'{scene.name} has no wheel_radius, so no contact patch: '
                           'give wheel_radius in the scene, or load at the wheel centre (--at wc)')
    if args.rack is not None and not scene.steered:
        raise LinkageError('--rack', f'{scene.name}: no constraint is marked steer: rack, so a '
                           'rack input moves nothing')


def loaded_header(scene, result):
    """
    Return the columns of a loaded solve after travel and rack, from the registry's templates.

    The wheel's columns, the holding force, each link's tension (both ends of a link that
    carries a spring), each spring's force, each pickup's force on the body (x, y, z: pivots,
    link bases, spring body ends, strut tops) and each bushing's couple on the body (x, y,
    z): the Loaded's names. With the pickups' points (doc/kc.md) they balance the load.
    """
    from ..core.measure import quantities
    wheel = [n for n in quantities.columns('wheel') if n.startswith(('camber', 'toe', 'wheel'))]
    loaded = quantities.names('kc_loaded')
    holding = next(n for n in loaded if n.startswith('holding'))
    tension = next(n for n in loaded if n.startswith('{link}_tension'))   # the ends: its form
    force = [n for n in loaded if n.startswith('{pickup}')]
    couple = [n for n in loaded if n.startswith('{bushing}')]
    spring = next(n for n in quantities.names('element') if n.endswith('_force_N'))
    return (wheel + [holding] + [tension.format(link=n) for n in result.link_forces_n]
            + [spring.format(element=n) for n in result.spring_forces_n]
            + [t.format(pickup=p) for p in result.body_forces_n for t in force]
            + [t.format(bushing=b) for b in result.body_moments_nm for t in couple])


def loaded_row(result):
    """Return the values of loaded_header of a Loaded (mm, deg, N, N m)."""
    row = [result.camber_deg, result.toe_deg, *result.wheel_center_mm, result.holding_force_n]
    row += list(result.link_forces_n.values())
    row += list(result.spring_forces_n.values())
    row += [v for force in result.body_forces_n.values() for v in force]
    row += [v for couple in result.body_moments_nm.values() for v in couple]
    return row


def select(header, wanted):
    """Return the indices of the wanted columns in header; LinkageError names an unknown one."""
    if wanted is None:
        return list(range(len(header)))
    names = [w.strip() for w in wanted.split(',') if w.strip()]
    unknown = [n for n in names if n not in header]
    if unknown or not names:
        problem = f'unknown column {unknown[0]!r}' if unknown else 'no column named'
        raise LinkageError('--columns', f'{problem}: choose from {", ".join(header)}')
    return [header.index(n) for n in names]


def write_matrix(matrix, output):
    """Write the 6x6 wheel-centre compliance as a table with labelled rows and columns."""
    rows = [[label, *row] for label, row in zip(MATRIX_ROWS, np.asarray(matrix, float).tolist())]
    return write_table(output, (MATRIX_CORNER,) + MATRIX_COLUMNS, rows)


def load_of(args):
    """Return the statics Load of the request (a moment alone acts at the wheel centre)."""
    from ..core.statics import Load
    return Load(force_n=args.load or (0.0, 0.0, 0.0), at=args.at or 'wc',
                moment_nm=args.moment or (0.0, 0.0, 0.0))


def solve(scene, args, travels, racks):
    """
    Solve every position: (header, rows, results, failure); failure '' when all solved.

    Rack by rack, travel by travel; the first position that fails ends the table there (its
    message is the failure). header and rows hold the columns --columns keeps; results: the
    Compliance or Loaded of each solved position. An unknown column raises LinkageError once
    the first position has named the columns, before anything is said or written.
    """
    from ..core.base import Status
    from ..core.statics import Statics
    lead = ['travel_mm'] + (['rack_mm'] if args.rack is not None else [])
    header, chosen, rows, results = None, None, [], []
    load = load_of(args) if args.loaded else None
    # one Statics across the positions: each goes on from the last equilibrium (one compiled
    # call), or the long way where that is too far; either gives the same answer to round-off
    statics = None
    for rack in racks:
        for travel in travels:
            try:
                statics = statics or Statics(scene)
                if load is None:
                    result = statics.rates(float(travel), float(rack))
                else:
                    result = statics.solve(float(travel), load, float(rack))
            except (ArithmeticError, ValueError, np.linalg.LinAlgError) as exc:
                # a statics solve that raises: not carried, said in one line, as the node says
                text = ' '.join(str(exc).split())[:300]
                failure = (f'ERROR {Status.NOT_CARRIED.name}: at travel {float(travel):g} mm: '
                           f'the statics solve failed ({type(exc).__name__}: {text})')
                return header or lead, rows, results, failure
            if result.status != Status.OK:   # the message names the travel (and the load)
                failure = f'ERROR {result.status.name}: {result.message}'
                return header or lead, rows, results, failure
            values = list(result.rates.values()) if load is None else loaded_row(result)
            if header is None:
                names = list(result.rates) if load is None else loaded_header(scene, result)
                chosen = list(range(len(lead))) + [
                    len(lead) + i for i in select(names, args.columns)]
                header = [(lead + names)[i] for i in chosen]
                announce(scene, args, len(travels) * len(racks))
            row = [travel] + ([rack] if len(lead) > 1 else []) + values
            rows.append([row[i] for i in chosen])
            results.append(result)
    return header, rows, results, ''


def announce(scene, args, count):
    """Say on stderr what is being solved (once the request is known to be sound)."""
    what = f'loaded by {load_of(args)}' if args.loaded else 'compliance rates'
    print(f'{PROG}: {scene.name}: {what}, {counted(count, "position")}', file=sys.stderr)


@program(PROG)
def main(argv: list[str] | None = None) -> int:
    """Run linkage-kc: 0 done, 1 if a position fails (out of reach, not carried), 2 a mistake."""
    args = parse_args(argv)
    try:
        scene, travels, racks = request(args)   # SceneError is a LinkageError
        check_outputs((('-o', args.output), ('--matrix', args.matrix), ('--plot', args.plot)),
                      [scene.source])
        check_plot(args.plot)
        check_table(args.output)
        check_table(args.matrix, '--matrix')
    except LinkageError as exc:
        return fail(PROG, exc)
    warn(PROG, scene.warnings)
    from ..core.warmup import compile_if_cold
    compile_if_cold(PROG, statics=True)   # every answer here is a statics solve
    try:
        header, rows, results, failure = solve(scene, args, travels, racks)
    except LinkageError as exc:   # an unknown column
        return fail(PROG, exc)
    status = table_status(PROG, write_table(args.output, header, rows), 'position')
    if args.matrix and results:
        status = max(status, table_status(PROG, write_matrix(results[0].matrix, args.matrix),
                                          'row', args.matrix))
    if args.plot and results:
        from .kc_plot import plot_loaded, plot_rates
        if args.loaded:
            plot_loaded(scene, results[0], load_of(args), args.plot)
        else:
            plot_rates(scene, header, rows, args.plot)
        print(f'{PROG}: wrote {args.plot}', file=sys.stderr)
    if failure:
        print(f'{PROG}: {failure} ({counted(len(rows), "position")} written)', file=sys.stderr)
        return 1
    print(f'{PROG}: done', file=sys.stderr)
    return status


if __name__ == '__main__':
    sys.exit(main())
