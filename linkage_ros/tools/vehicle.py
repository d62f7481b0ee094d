# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-vehicle: the setup sheet of a vehicle: rates, frequencies, roll, load transfer, pitch.

    linkage-vehicle VEHICLE [--csv FILE] [--plot FILE] [--tables DIR]

One table (CSV), a row per axle (front, rear) and one for the vehicle, the units in the column
names (doc/vehicle.md gives every formula and its source, doc/quantities.md every column). The
vehicle file needs `mass` and `tyre_rate` (config/vehicles/demo_vehicle.yaml); without them it
has no setup sheet, and says so in one line. --tables writes each axle's quantities over
heave, roll and rack (front_heave.csv, front_roll.csv, front_rack.csv, rear_heave.csv, ...).
"""

import math
import sys

import numpy as np

from ..cli import (check_plot, check_table, EXIT_STATUS, fail, Parser, program, table_status,
                   warn)
from ..core.base import LinkageError, lost_cells, say_ranges
from ..core.model import load_vehicle, Target
from ..core.warmup import compile_if_cold
from ..outputs import check_outputs, output_folder, write_table

PROG = 'linkage-vehicle'
TABLE_INPUTS = ('heave_mm', 'roll_deg', 'rack_mm')   # the columns a table is solved over

EPILOG = """examples:
  linkage-vehicle demo_vehicle
  linkage-vehicle demo_vehicle --csv sheet.csv --plot sheet.png
  linkage-vehicle demo_vehicle --tables sheet_tables

columns (the axle rows, then the vehicle's; empty where a column is not the row's): axle,
wheel_rate_N_per_mm, ride_rate_N_per_mm, ride_frequency_Hz, roll_stiffness_springs_Nm_per_deg,
roll_stiffness_bar_Nm_per_deg, roll_stiffness_Nm_per_deg, roll_stiffness_textbook_Nm_per_deg,
roll_centre_height_mm, the anti quantities, load_transfer_*_N (at 1 g), steering_ratio_*;
roll_axis_height_at_cg_mm, roll_moment_arm_mm, roll_gradient_deg_per_g, lltd_front_pct,
pitch_gradient_*_deg_per_g, pitch_centre_*_mm. Timing: linkage-bench vehicle.

ranges (doc/scenes.md#ranges; outside them the file is refused in one line, status 2):
""" + \
    say_ranges('sprung_mass', 'unsprung_mass', 'front_share', 'height', 'tyre_rate',
               'bar_rate') + """

exit status: 0 the sheet written; 1 a table stopped at a corner's travel limits or out of
reach (the message names where; the sheet is of what was solved), or a value is not finite
(left empty, the message names the cells: a body its roll stiffness cannot hold has no roll
gradient); """ + EXIT_STATUS


def parse_args(argv):
    """Read the command line; a mistake exits with one line and status 2."""
    parser = Parser(PROG, __doc__, EPILOG)
    parser.add_argument('vehicle', help='bundled vehicle name or path to a vehicle YAML file '
                        'with mass and tyre_rate')
    parser.add_argument('-o', '--output', '--csv', dest='output', metavar='FILE',
                        help='write the sheet to this CSV file (default: stdout)')
    parser.add_argument('--plot', metavar='FILE', help='draw the sheet to this PNG file '
                        '(needs matplotlib)')
    parser.add_argument('--tables', metavar='DIR', help="write each axle's heave, roll and "
                        'rack tables into this folder (made if missing)')
    return parser.parse_args(argv)


def sheet_table(sheet):
    """Return (header, rows) of a SetupSheet: 'axle' first, every column once, in order."""
    header = ['axle'] + list(dict.fromkeys(k for row in sheet.rows.values() for k in row))
    rows = [[name] + [row.get(k) for k in header[1:]] for name, row in sheet.rows.items()]
    return header, rows


def table_names(vehicle):
    """Return the files --tables writes: <axle>_heave.csv, _roll.csv, _rack.csv if it steers."""
    from ..core.axle import axle_of
    return [f'{name}_{table}.csv' for name in ('front', 'rear') for table in
            ('heave', 'roll') + (('rack',) if axle_of(vehicle, name).steered else ())]


def lost(header, rows, inputs=()):
    """
    Return the cells of a table that are not finite where a number belongs (base.lost_cells).

    rows: lists under header, the first entry of a sheet's row its axle (text). A sheet's row
    has a number in each of its own columns ('' only where the column is not the row's); a
    table over heave, roll or rack (inputs: its input columns) may hold NaN where its quantity
    is undefined by definition (Ackermann near straight ahead, an element whose ends
    crossed), never an infinity.
    """
    columns = {name: [math.nan if v is None else v for v in values]
               for name, values in zip(header, zip(*rows)) if name != 'axle'}
    if 'axle' in header:   # a sheet: NaN only where the column is not the row's
        undefined = {name: [v is None for v in values]
                     for name, values in zip(header, zip(*rows)) if name != 'axle'}
    else:
        undefined = {name: name not in inputs for name in columns}
    return lost_cells(columns, undefined)


def request(args):
    """
    Return the vehicle parsed arguments name, loaded, once it is known to have a setup sheet.

    Raises SceneError for a file that does not load and LinkageError, in a few words, for a
    vehicle without a setup sheet: no mass block, or a corner without a spring with a rate.
    """
    vehicle = load_vehicle(args.vehicle)
    if vehicle.mass is None:
        raise LinkageError(f'{vehicle.name} ({vehicle.source}) has no setup sheet', 'its file '
                           'has no mass block (mass: sprung, front_share or cg_x, unsprung; '
                           'tyre_rate: doc/vehicle.md)')
    for name in ('front', 'rear'):
        spec = vehicle.axles.axles[name]
        for corner in (spec.left, spec.right):
            if not any(e.has_rate for e in vehicle.corners[corner].elements):
                raise LinkageError(f'{vehicle.source}: corners.{corner}', 'its scene has no '
                                   'spring with a rate and free_length: the wheel rate, ride '
                                   'rate and roll stiffness need one')
    return vehicle


@program(PROG)
def main(argv=None):
    """Run linkage-vehicle: 0 when done, 1 if a table stopped early, 2 for a mistake."""
    args = parse_args(argv)
    try:
        vehicle = request(args)   # SceneError is a LinkageError
        warn(PROG, vehicle.warnings)
        target = Target(vehicle, vehicle.corners)   # its files: the vehicle's and every scene's
        check_outputs((('-o', args.output), ('--plot', args.plot)), target.files)
        check_plot(args.plot)
        check_table(args.output)
        folder = args.tables and output_folder('--tables', args.tables, table_names(vehicle),
                                               target.files + tuple(p for p in (
                                                   args.output, args.plot) if p))
    except LinkageError as exc:
        return fail(PROG, exc)
    compile_if_cold(PROG)
    from ..core.vehicle import setup_sheet
    sheet = setup_sheet(vehicle)
    for note in sheet.notes:
        print(f'{PROG}: {note}', file=sys.stderr)
    header, rows = sheet_table(sheet)
    status = table_status(PROG, write_table(args.output, header, rows,
                                            lost=lost(header, rows)))
    if folder:
        for name, sheet_axle in sheet.axles.items():
            for table, columns in sheet_axle.tables.items():
                cells = np.column_stack([np.asarray(c, float) for c in columns.values()])
                written = write_table(folder / f'{name}_{table}.csv', list(columns), cells,
                                      lost=lost(list(columns), cells.tolist(), TABLE_INPUTS))
                status = max(status, table_status(PROG, written, 'position',
                                                  f'{name}_{table}.csv'))
    if args.plot:
        from .vehicle_plot import plot_sheet
        plot_sheet(sheet, args.plot)
        print(f'{PROG}: wrote {args.plot}', file=sys.stderr)
    for message in sheet.messages:
        print(f'{PROG}: {message}', file=sys.stderr)
    if sheet.messages or status:
        return 1
    print(f'{PROG}: done', file=sys.stderr)
    return 0


if __name__ == '__main__':
    sys.exit(main())
