# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-loads: load cases on a vehicle, from the tyres to the force at every pickup.

Each case (the body's accelerations in g, and a corner's own load where given) gives the four
tyre loads (load transfer by the setup sheet's paths, brake and drive shares); each corner is
found at its loaded ride height (its springs, stops and anti-roll bar carrying the load, the
holding force zero) and solved with its bushings: travel, camber and toe under load, the force
at every pickup, every link's, spring's, stop's and bushing's load. Model, cases and sources:
doc/loads.md. The table goes to stdout (or -o), progress and notes to stderr.
"""

import sys

from ..cli import (check_plot, check_table, counted, EXIT_STATUS, fail, Parser, program,
                   table_status, warn)
from ..core.base import LinkageError
from ..core.model import load_vehicle, Target
from ..outputs import check_outputs, write_table

PROG = 'linkage-loads'
TABLES = ('corners', 'pickups', 'members', 'summary')

EPILOG = """tables (--table; units in the column names, signs in doc/quantities.md):
  pickups   (default) a row per case, corner, pickup and end: x_mm, y_mm, z_mm, fx_N, fy_N,
            fz_N, force_magnitude_N, mx_Nm, my_Nm, mz_Nm; end body: the force on the body at
            <link>_base, <arm>_axis0/_axis1/_centre, <strut>_top, <spring>_body; end carrier:
            the force on the carrier at <constraint>_carrier; end bar: on an anti-roll bar
  corners   a row per case and corner: status, travel_mm, camber_deg, toe_deg,
            wheel_center_x/y/z_mm, tyre_fx/fy/fz_N and tyre_mx/my/mz_Nm (the ground's wrench
            about the contact patch), holding_force_N (0 at the loaded ride height)
  members   a row per case, corner and member: kind (link, drop_link, spring, stop,
            bushing, bar), force_N (+ = tension for links, + = compressed for springs and
            stops), a bushing's deflection_mm and its x, y, z, a bar's torque_Nm, twist_deg
  summary   a row per corner, pickup and end: the largest force_magnitude_N over the cases,
            the case, its fx/fy/fz_N and where

cases (built in, config/loads/cases.yaml; doc/loads.md gives their sources): static (1 g),
  bump (3 g vertical), braking (1 g), cornering (1 g to the left), traction (0.5 g on the
  driven axle), pothole (3 g vertical and 1 g rearward at the front left), combined (0.7 g
  braking with 0.7 g cornering). --cases FILE: your own, as
    cases:
      hard_braking: {vertical_g: 1.0, longitudinal_g: -1.2}
      kerb: {corners: {front_left: {force_n: [0, -8000, 9000], at: cp}}}
  longitudinal_g and lateral_g -5 to 5, vertical_g above 0 to 10; a corner's multiples of its
  static load -20 to 20 (vertical 0 to 20), at cp or wc; force_n -1e6 to 1e6 N, moment_nm
  -1e5 to 1e5 N m; at most 1000 cases; names of ASCII letters, digits, _ and -.

examples:
  linkage-loads demo_vehicle_loads
  linkage-loads demo_vehicle_loads --table summary -o brackets.csv
  linkage-loads demo_vehicle_loads --case bump --case cornering --table corners
  linkage-loads demo_vehicle_loads --cases my_cases.yaml -o loads.parquet --plot loads.png

The vehicle needs the setup sheet's mass block and tyre rates, and a wheel_radius and a
spring with a rate in every corner. Timing: linkage-bench loads.

exit status: 0 every case solved; 1 a corner not solved: a wheel that lifts off, a load its
springs and stops cannot carry within its travel, a bushing beyond the statics' model (the
line names the case, the corner and why; the rest is written); """ + EXIT_STATUS


def parse_args(argv):
    """Read the command line; a mistake exits with one line and status 2."""
    parser = Parser(PROG, __doc__, EPILOG)
    parser.add_argument('vehicle', help='bundled vehicle name (e.g. demo_vehicle_loads) or '
                        'path to a vehicle YAML file with masses')
    parser.add_argument('--case', action='append', metavar='NAME',
                        help='solve this case only (repeat, or NAME,NAME); default: all')
    parser.add_argument('--cases', metavar='FILE',
                        help='your own cases (YAML) instead of the built-in ones')
    parser.add_argument('--table', choices=TABLES, default='pickups',
                        help='which table to write (default: pickups)')
    parser.add_argument('-o', '--output', metavar='FILE',
                        help='write the table here (.csv, or .parquet, which needs pyarrow); '
                        'default: stdout as CSV')
    parser.add_argument('--plot', metavar='FILE',
                        help='draw the largest force at each pickup by case, and the vehicle '
                        'under the heaviest case in front and side view (PNG)')
    return parser.parse_args(argv)


def chosen_cases(args):
    """Return the cases to solve, by name; LinkageError or SceneError names a mistake."""
    from ..core.loads import built_in_cases, read_cases
    cases = read_cases(args.cases) if args.cases else built_in_cases()
    if not args.case:
        return cases
    names = [n.strip() for given in args.case for n in given.split(',') if n.strip()]
    unknown = [n for n in names if n not in cases]
    if unknown or not names:
        raise LinkageError('--case', f'no case {unknown[0] if unknown else ""!r}: choose from '
                           f'{", ".join(cases)}')
    return {n: cases[n] for n in dict.fromkeys(names)}


def solve_all(loads, cases):
    """Solve every case in turn, saying each on stderr; return the CaseAnswers."""
    from ..core.loads import describe, tables
    answers = []
    for k, case in enumerate(cases.values(), start=1):
        print(f'{PROG}: {k}/{len(cases)} {describe(case)}', file=sys.stderr, flush=True)
        answer = loads.solve(case)
        for note in tables.case_notes(answer):
            print(f'{PROG}: {note}', file=sys.stderr)
        answers.append(answer)
    return answers


def table(answers, name):
    """Return (columns, rows) of the table asked for."""
    from ..core.loads import tables
    if name == 'summary':
        return tables.SUMMARY_COLUMNS, tables.summary_rows(answers)
    make = {'corners': tables.corner_rows, 'pickups': tables.pickup_rows,
            'members': tables.member_rows}[name]
    return tables.TABLES[name], [row for a in answers for row in make(a)]


def failures(answers):
    """Return one line per corner that is not solved: case, corner, status and why."""
    return [f'{a.case.name}: {c.corner}: {c.status.name}: {c.message}'
            for a in answers for c in a.corners.values() if c.status.name != 'OK']


def request(args):
    """
    Return what parsed arguments ask to solve: (Loads, {name: LoadCase}).

    Raises LinkageError (a SceneError is one) for a vehicle or cases file that does not load,
    a vehicle without a setup sheet, an output that cannot be written, or a case the vehicle
    cannot take (its corners and shares, checked for every case before any solving).
    """
    vehicle = load_vehicle(args.vehicle)
    cases = chosen_cases(args)
    inputs = Target(vehicle, vehicle.corners).files + ((args.cases,) if args.cases else ())
    check_outputs((('-o', args.output), ('--plot', args.plot)), inputs)
    check_plot(args.plot)
    check_table(args.output)
    from ..core.loads import sheet_problem
    problem = sheet_problem(vehicle)
    if problem:
        raise LinkageError(vehicle.source, problem)
    warn(PROG, vehicle.warnings)
    from ..core.warmup import compile_if_cold
    compile_if_cold(PROG, statics=True)   # every case is loaded solves
    from ..core.loads import Loads, tyre_loads
    loads = Loads(vehicle)
    for case in cases.values():   # every case's corners and shares, before any solving
        tyre_loads(loads.data, case, loads.corner_keys(case))
    return loads, cases


@program(PROG)
def main(argv: list[str] | None = None) -> int:
    """Run linkage-loads: 0 when every case is solved, 1 if a corner is not, 2 for a mistake."""
    args = parse_args(argv)
    try:
        loads, cases = request(args)
        answers = solve_all(loads, cases)
    except LinkageError as exc:
        return fail(PROG, exc)
    columns, rows = table(answers, args.table)
    status = table_status(PROG, write_table(args.output, columns, rows), 'row')
    if args.plot:
        from .loads_plot import plot_loads
        plot_loads(loads, answers, args.plot)
        print(f'{PROG}: wrote {args.plot}', file=sys.stderr)
    lost = failures(answers)
    for line in lost:
        print(f'{PROG}: {line}', file=sys.stderr)
    if lost:
        print(f'{PROG}: {counted(len(lost), "corner")} not solved', file=sys.stderr)
        return 1
    if status:
        return status
    print(f'{PROG}: done', file=sys.stderr)
    return 0


if __name__ == '__main__':
    sys.exit(main())
