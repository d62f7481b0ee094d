# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-axle: solve an axle of a vehicle in heave, roll and steer; write a CSV table (mm, deg).

The axle's two corners move together: in heave both wheels travel by the heave; in roll by
phi (+ = right side down) the right wheel goes to bump and the left to rebound by
(t / 2) tan(phi), t the design track. The table gives the roll centre, track, camber and toe
relative to the body and to the ground, the anti-dive, anti-lift or anti-squat the axle has,
and with a rack the steer angles and Ackermann (definitions and sources: doc/axle.md).
"""

import math
import sys

import numpy as np

from ..cli import (check_table, EXIT_STATUS, fail, Parser, program, SPAN, span, table_status,
                   warn)
from ..core.axle import ACKERMANN_MIN_STEER, axle_of, solve_axle
from ..core.base import LinkageError, positions_needed
from ..core.model import load_target
from ..core.solve import travel_range
from ..core.warmup import compile_if_cold
from ..outputs import check_output, write_table

PROG = 'linkage-axle'
MAX_ROLL_DEG = 45.0   # |roll| beyond this is a typo: tan(phi) runs away near 90 deg

EPILOG = """columns: heave_mm, roll_deg (+ = right side down), rack_mm (+ = rack to the left),
  left_travel_mm, right_travel_mm (+ = bump), roll_centre_y_mm (vehicle frame, + = left),
  roll_centre_height_mm (above the ground line through the contact patches), track_mm (at
  the contact patches), left_/right_camber_deg (+ = top outboard) and left_/right_toe_deg
  (+ = toe-in) relative to the body, the same relative to the ground (*_ground_deg); then
  anti_dive_pct, anti_lift_pct or anti_squat_pct as the axle's brake_share and drive_share
  ask; with --rack: left_/right_steer_deg (yaw, + = to the left),
  mean_steer_deg and ackermann_pct (NaN below MIN_STEER deg of mean steer); with an
  anti_roll_bar: arb_left_angle_deg, arb_right_angle_deg (each arm about the bar's axis,
  directed to the left), arb_twist_deg
  (left minus right), arb_ratio_deg_per_deg_roll, arb_ratio_left_deg_per_mm and
  arb_ratio_right_deg_per_mm (twist per mm of one wheel's travel, the other held), and with
  its rate arb_torque_Nm, arb_roll_moment_Nm and arb_roll_stiffness_Nm_per_deg. A corner
  without wheel_radius has no contact patch: the patch columns are left out, and stderr says
  so. Roll-centre, track and Ackermann columns need wheel_radius in both scenes, Ackermann
  also the wheelbase; anti quantities need cg_height (and the wheelbase) in the vehicle
  file.

examples:
  linkage-axle demo_vehicle --axle front --heave -40:40:10
  linkage-axle demo_vehicle --axle rear --roll -4:4:1 -o roll.csv
  linkage-axle demo_vehicle --axle front --rack -30:30:10 --heave 0

--heave, --roll and --rack take one value or a range FROM:TO:STEP (TO included). Timing:
linkage-bench axle.

exit status: 0 every position solved; 1 a position is out of reach of a wheel or beyond a
corner's travel limits (its scene's travel block; the rows solved before it are written, the
message names the limit) or out of reach of the anti-roll bar's drop links (its columns are
NaN there); """ + EXIT_STATUS


def parse_args(argv):
    """Read the command line; a mistake exits with one line and status 2."""
    parser = Parser(PROG, __doc__, EPILOG.replace(
        'MIN_STEER', f'{math.degrees(ACKERMANN_MIN_STEER):g}'))
    parser.add_argument('vehicle', nargs='?', default='demo_vehicle',
                        help='bundled vehicle name or path to a vehicle YAML file with axles '
                        '(default demo_vehicle)')
    parser.add_argument('--axle', default='front', help='front or rear (default front)')
    parser.add_argument('--heave', type=span, metavar=SPAN,
                        help="heave, mm, + = bump (default: the left corner's travel block "
                        'when --roll is not given, else 0)')
    parser.add_argument('--roll', type=span, metavar=SPAN,
                        help=f'body roll, deg, + = right side down, |roll| < {MAX_ROLL_DEG:g} '
                        '(default 0)')
    parser.add_argument('--rack', type=span, metavar=SPAN,
                        help='steering rack travel, mm, + = to the left; adds the steer and '
                        'Ackermann columns; a range solves every heave and roll at each rack')
    parser.add_argument('-o', '--output', metavar='FILE',
                        help='write the table to this file (default: stdout)')
    return parser.parse_args(argv)


def values(option, given):
    """Return the values of a Span (mm or deg), or raise LinkageError naming option."""
    positions_needed(*given, option)   # before a range too long is made
    return travel_range(*given)


def request(args):
    """
    Return what parsed arguments ask to solve: (target, axle, (heave mm, roll deg, rack mm)).

    Raises SceneError for a vehicle that does not load and LinkageError for a request that
    cannot be carried out (no such axle, a bad position, a rack on an axle that does not
    steer), before anything is solved.
    """
    target = load_target(args.vehicle, 'vehicle')
    axle = axle_of(target.vehicle, args.axle)
    heave, roll, rack = positions(args, axle)
    if args.rack is not None and not axle.steered:
        raise LinkageError(f'{target.vehicle.name} {axle.name} axle', 'no corner has a steer: '
                           'rack link, so a rack input moves nothing')
    return target, axle, (heave, roll, rack)


def positions(args, axle):
    """Return heave (mm), roll (deg) and rack (mm) of every position: rack, heave, roll order."""
    roll = np.zeros(1) if args.roll is None else values('--roll', args.roll)
    if np.abs(roll).max() >= MAX_ROLL_DEG:
        raise LinkageError('--roll', f'|roll| must stay below {MAX_ROLL_DEG:g} deg, got '
                           f'{np.abs(roll).max():g}')
    if args.heave is not None:
        heave = values('--heave', args.heave)
    elif args.roll is None:
        heave = travel_range(*axle.left.travel)
    else:
        heave = np.zeros(1)
    rack = np.zeros(1) if args.rack is None else values('--rack', args.rack)
    grid = np.meshgrid(rack, heave, roll, indexing='ij')
    return grid[1].ravel(), grid[2].ravel(), grid[0].ravel()


def table(axle, result, with_rack):
    """
    Return (header, rows) of an AxleResult: column names and an (n, columns) array, mm, deg.

    Contact-patch columns only when both corners have a wheel radius; steer columns with_rack.
    """
    deg = np.degrees
    columns = [('heave_mm', result.heave), ('roll_deg', deg(result.roll)),
               ('rack_mm', result.rack), ('left_travel_mm', result.travel[:, 0]),
               ('right_travel_mm', result.travel[:, 1])]
    if axle.has_patches:
        columns += [('roll_centre_y_mm', result.roll_centre[:, 0]),
                    ('roll_centre_height_mm', result.roll_centre_height),
                    ('track_mm', result.track)]
    for what in ('camber', 'toe', 'camber_ground', 'toe_ground'):
        for k, side in enumerate(('left', 'right')):
            columns.append((f'{side}_{what}_deg', deg(getattr(result, what)[:, k])))
    for name, point, _ in axle.anti_quantities():
        if point == 'centre' or axle.has_patches:
            columns.append((f'{name}_pct', result.anti[name]))
    if with_rack:
        columns += [('left_steer_deg', deg(result.steer[:, 0])),
                    ('right_steer_deg', deg(result.steer[:, 1])),
                    ('mean_steer_deg', deg(result.mean_steer))]
        if axle.has_patches and axle.wheelbase > 0:
            columns.append(('ackermann_pct', result.ackermann))
    if result.bar is not None:
        columns += bar_columns(axle.anti_roll_bar, result.bar)
    header = [name for name, _ in columns]
    rows = np.column_stack([np.asarray(c, dtype=float) for _, c in columns])
    return header, rows.reshape(len(result.heave), len(header))


def bar_columns(bar, values):
    """Return the anti-roll bar's (name, values) columns, deg and N m (anti_roll_bar.py)."""
    deg = np.degrees
    columns = [('arb_left_angle_deg', deg(values.angle[:, 0])),
               ('arb_right_angle_deg', deg(values.angle[:, 1])),
               ('arb_twist_deg', deg(values.twist)),
               ('arb_ratio_deg_per_deg_roll', values.ratio_roll),
               ('arb_ratio_left_deg_per_mm', deg(values.ratio_travel[:, 0])),
               ('arb_ratio_right_deg_per_mm', deg(values.ratio_travel[:, 1]))]
    if bar.has_rate:
        columns += [('arb_torque_Nm', values.torque), ('arb_roll_moment_Nm', values.roll_moment),
                    ('arb_roll_stiffness_Nm_per_deg', values.roll_stiffness)]
    return columns


def stop_lines(axle, result) -> tuple[str, ...]:
    """Say over which wheel travel each corner's stops carry a force (measure.stop_notes)."""
    from ..core.measure import element_values, stop_notes
    lines = ()
    for k, scene in enumerate(axle.scenes):
        if len(result.heave) and any(e.is_stop for e in scene.elements):
            forces = element_values(scene, result.wheel_center[:, k], result.rotation[:, k],
                                    result.rack).force
            lines += stop_notes(scene, result.travel[:, k], forces)
    return lines


@program(PROG)
def main(argv: list[str] | None = None) -> int:
    """Run linkage-axle: 0 when done, 1 if a position is out of reach, 2 for a mistake."""
    args = parse_args(argv)
    try:
        target, axle, (heave, roll, rack) = request(args)   # SceneError is a LinkageError
        vehicle = target.vehicle
        warn(PROG, vehicle.warnings)
        check_output(args.output, '-o', target.files)
        check_table(args.output)
    except LinkageError as exc:
        return fail(PROG, exc)
    with_rack = args.rack is not None
    compile_if_cold(PROG)
    print(f'{PROG}: {vehicle.name} {axle.name} axle ({axle.left.name}, {axle.right.name}): '
          f"{len(heave)} position{'' if len(heave) == 1 else 's'}", file=sys.stderr)
    result = solve_axle(axle, heave, np.radians(roll), rack)
    for note in result.notes + stop_lines(axle, result):
        print(f'{PROG}: {note}', file=sys.stderr)
    if with_rack and not axle.wheelbase > 0:
        print(f'{PROG}: {vehicle.source} has no wheelbase (and not two axles to derive it '
              'from): no Ackermann', file=sys.stderr)
    header, rows = table(axle, result, with_rack)
    try:
        written = write_table(args.output, header, rows)
    except BrokenPipeError:
        raise                      # stdout's reader went away: program() ends quietly
    except OSError as exc:         # a full disk; -o was writable when checked
        return fail(PROG, f'{args.output or "stdout"}: cannot write the table '
                          f'({exc.strerror or exc})')
    if not result.success:
        print(f'{PROG}: {result.message} ({len(rows)} positions written)', file=sys.stderr)
        return 1
    if result.bar is not None and np.isnan(result.bar.twist).any():
        return 1      # the note above said where
    print(f'{PROG}: done', file=sys.stderr)
    return table_status(PROG, written, 'position')


if __name__ == '__main__':
    sys.exit(main())
