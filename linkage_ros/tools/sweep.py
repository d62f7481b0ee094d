# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-sweep: solve a scene over a travel range and write a CSV table (mm, deg).

The table goes to stdout (or to -o PATH), progress and errors to stderr. Travels default
to the scene's own travel block (for the bundled scenes -80 to +80 mm in 1 mm steps).
"""

import sys

import numpy as np

from ..cli import (check_table, counted, EXIT_STATUS, fail, Parser, program, SPAN, span,
                   table_status, warn)
from ..core.base import (check_position_count, LinkageError, lost_cells, positions_needed,
                         say_ranges)
from ..core.measure import columns
from ..core.model import load_scene
from ..core.solve import METHODS, sweep, travel_range
from ..core.warmup import compile_if_cold
from ..outputs import check_output, write_table

PROG = 'linkage-sweep'
# The columns, each declared once in the registry (core/measure/quantities.py), in the
# table's order: always COLUMNS; RACK_COLUMNS with --rack; ALIGNMENT_COLUMNS with
# --alignment.
COLUMNS = columns('travel', 'wheel', 'rotation', 'solver')
RACK_COLUMNS = columns('rack')
ALIGNMENT_COLUMNS = columns('alignment', 'kingpin')


def table(result, scene=None, with_rack=False, elements=None):
    """
    Return the values of a Sweep in mm and deg as an (n, columns) array.

    The columns are header(scene, with_rack, elements): COLUMNS, then rack_mm if with_rack,
    then the alignment columns if a scene is given, then the element columns of the scene
    elements. Built column-wise: linear in n.
    """
    n = len(result.travel)
    columns = [result.travel, np.degrees(result.camber), np.degrees(result.toe),
               result.wheel_center, result.quaternion, result.residual, result.iterations]
    if with_rack:
        columns.append(np.full(n, result.rack))
    if scene is not None:
        columns.append(alignment_table(scene, result))
    if elements is not None:
        from ..core.measure import element_table, element_values
        columns.append(element_table(elements, element_values(
            elements, result.wheel_center, result.rotation, result.rack)))
    # (n, width) each: -1 cannot be inferred from a table of no rows
    return np.column_stack([np.reshape(c, (n, int(np.prod(np.shape(c)[1:]))))
                            .astype(float) for c in columns])


def alignment_table(scene, result):
    """Return the ALIGNMENT_COLUMNS of a Sweep, shape (n, len(ALIGNMENT_COLUMNS))."""
    from ..core.measure import alignment, geometric_kingpin
    from ..core.solve import compile_scene
    a = alignment(scene, compile_scene(scene), result.wheel_center, result.rotation,
                  result.rack)
    k = geometric_kingpin(scene, result.joints, result.wheel_center, a.contact_patch,
                          result.rack)
    deg = np.degrees
    return np.column_stack((
        deg(a.camber_gain), deg(a.bump_steer), a.wheel_center_velocity[:, :2], deg(a.caster),
        deg(a.kingpin_inclination), a.scrub_radius, a.mechanical_trail, a.track_change,
        a.wheelbase_change, a.lateral_shift, a.longitudinal_shift, a.side_view_ic,
        a.front_view_ic, a.screw_axis, a.screw_pitch, deg(k.caster),
        deg(k.kingpin_inclination), k.scrub_radius, k.mechanical_trail,
        k.offset_wheel_centre))


def header(scene=None, with_rack=False, elements=None):
    """Return the column names of table(result, scene, with_rack, elements)."""
    from ..core.measure import element_columns
    return COLUMNS + (RACK_COLUMNS if with_rack else []) + (
        ALIGNMENT_COLUMNS if scene is not None else []) + (
        element_columns(elements) if elements is not None else [])


def write_sweeps(results, output, scene=None, with_rack=False, elements=None):
    """
    Write Sweeps (one or several, e.g. a rack grid) as one table to output (None: stdout).

    The table writer's format (outputs.write_table: CSV, or Parquet by the suffix); returns
    what it wrote (Written). The writers' rule (base.lost_cells): a value that is not finite
    is written as nan and told in Written.lost, unless the quantity is undefined there by its
    definition (an alignment quantity, NaN where the scene has no steer axis; an element's
    quantities where its ends crossed).
    """
    rows = [table(result, scene, with_rack, elements) for result in results]
    columns = header(scene, with_rack, elements)
    rows = np.concatenate(rows) if rows else np.empty((0, len(columns)))
    return write_table(output, columns, rows, lost=lost_cells(
        dict(zip(columns, rows.T)), undefined(columns, rows, scene, elements)))


def undefined(columns, rows, scene=None, elements=None):
    """Return where the sweep's quantities are NaN by definition: {column: mask or True}."""
    allowed = dict.fromkeys(ALIGNMENT_COLUMNS, True) if scene is not None else {}
    if elements is not None:
        from ..core.measure import columns_of_element
        for e in elements.elements:
            own = columns_of_element(e.name, e.has_rate)
            crossed = np.isnan(rows[:, columns.index(own[0])])   # its length: NaN once crossed
            allowed.update(dict.fromkeys(own, crossed))
    return allowed


EPILOG = """columns: travel_mm, camber_deg (+ = top outboard), toe_deg (+ = toe-in), wheel centre
  x, y, z in mm (vehicle frame: x forward, y left, z up), the carrier rotation relative to
  design as a quaternion qx, qy, qz, qw, residual_mm, iterations; then rack_mm with --rack,
  the alignment set with --alignment, and with --elements each element's
  <name>_length_mm and <name>_ratio (d length / d travel), and for a spring with a rate
  <name>_force_N (+ = compressed) and <name>_wheel_rate_N_per_mm (doc/elements.md).

examples:
  linkage-sweep five_link -o five_link_sweep.csv
  linkage-sweep double_wishbone --travel -40:40:10 --rack 5 --alignment
  linkage-sweep my_corner.yaml --rack -20:20:10 > grid.csv

Travels and racks are plain numbers of mm (--travel -80:80:1, not -80mm); one value is one
position, FROM:TO:STEP a range (TO included). A request is refused before it runs when it
would solve more than 1,000,000 positions (travels x racks). Timing: linkage-bench sweep.

ranges (doc/scenes.md#ranges; outside them a scene is refused in one line, status 2):
""" + \
    say_ranges('coordinate', 'spring_rate', 'force_table_force', 'force_table_slope') + """

exit status: 0 every travel solved; 1 a travel is out of reach (the rows solved before it
are written, the message names the limit), or a value is not finite where its quantity is
defined (written as nan, the message names the columns); """ + EXIT_STATUS


def parse_args(argv):
    """Read the command line; a mistake exits with one line and status 2."""
    parser = Parser('linkage-sweep', __doc__, EPILOG)
    parser.add_argument('scene', help='bundled scene name (e.g. five_link) or path to a YAML file')
    parser.add_argument('--travel', type=span, metavar=SPAN,
                        help='wheel travel, mm, + = bump: one value or a range (default: the '
                        "scene's travel block)")
    parser.add_argument('--method', choices=METHODS, default='fast',
                        help='fast (pose Newton, compiled) or paper (Alexandru 2018); '
                        'default fast')
    parser.add_argument('-o', '--output', metavar='FILE',
                        help='write the table to this file (default: stdout)')
    parser.add_argument('--rack', type=span, metavar=SPAN,
                        help='steering rack travel, mm (+ = rack to the left); adds rack_mm; '
                        'a range solves a travel x rack grid')
    parser.add_argument('--alignment', action='store_true',
                        help='add the alignment columns (gains, steer axis, scrub, trail, '
                        'instant centres, screw axis)')
    parser.add_argument('--elements', action='store_true',
                        help="add the columns of the scene's springs, dampers and lengths")
    return parser.parse_args(argv)


def request(args):
    """
    Return what parsed arguments ask to solve: (scene, travels, racks), mm.

    Raises SceneError for a scene that does not load and LinkageError for a request that
    cannot be carried out (too many positions, a rack on a scene that does not steer,
    --elements of a scene without elements), before anything is solved.
    """
    scene = load_scene(args.scene)
    start, stop, step = args.travel or scene.travel
    count = positions_needed(start, stop, step, '--travel')
    racks = [0.0]
    if args.rack is not None:
        positions_needed(*args.rack, '--rack')   # before a range too long is made
        racks = list(travel_range(*args.rack))
    check_position_count(count * len(racks), '--rack', f'{counted(count, "travel")} x '
                         f'{counted(len(racks), "rack")}')
    if racks != [0.0] and not scene.steered:
        raise LinkageError(scene.name, 'no constraint is marked steer: rack, so a rack input '
                           'moves nothing')
    if args.elements and not scene.elements:
        raise LinkageError('--elements', f'{scene.name} lists no elements (doc/elements.md)')
    return scene, travel_range(start, stop, step), racks


@program(PROG)
def main(argv: list[str] | None = None) -> int:
    """Run linkage-sweep: 0 when done, 1 if a travel is out of reach, 2 for a mistake."""
    args = parse_args(argv)
    try:
        scene, travels, racks = request(args)   # SceneError is a LinkageError
        warn(PROG, scene.warnings)
        check_output(args.output, '-o', [scene.source])
        check_table(args.output)
    except LinkageError as exc:
        return fail(PROG, exc)
    start, stop, _ = args.travel or scene.travel
    compile_if_cold(PROG)
    print(f'linkage-sweep: {scene.name}: {counted(len(travels), "position")} from {start:g} to '
          f'{stop:g} mm, method {args.method}', file=sys.stderr)
    results = []
    for i, rack in enumerate(racks):
        results.append(sweep(scene, travels, method=args.method, rack=rack))
        if len(racks) > 1:
            print(f'linkage-sweep: rack {rack:g} mm ({i + 1}/{len(racks)})', file=sys.stderr)
        if not results[-1].success:
            break
    table = {'scene': scene if args.alignment else None,
             'with_rack': args.rack is not None,
             'elements': scene if args.elements else None}
    try:
        written = write_sweeps(results, args.output, **table)
    except BrokenPipeError:
        raise                      # stdout's reader went away: program() ends quietly
    except OSError as exc:         # a full disk; -o was writable when checked
        return fail(PROG, f'{args.output or "stdout"}: cannot write the table '
                          f'({exc.strerror or exc})')
    if args.elements:
        from ..core.measure import crossing_notes, element_values, stop_notes
        travel = np.concatenate([r.travel for r in results])
        values = [element_values(scene, r.wheel_center, r.rotation, r.rack) for r in results]
        warn(PROG, crossing_notes(scene, travel, np.concatenate([v.length for v in values])))
        for line in stop_notes(scene, travel, np.concatenate([v.force for v in values])):
            print(f'{PROG}: {line}', file=sys.stderr)
    failed = [r for r in results if not r.success]
    if failed:
        print(f'linkage-sweep: {failed[0].message} ({counted(written.rows, "position")} '
              'written)', file=sys.stderr)
    lost = table_status(PROG, written, 'position')
    if failed or lost:
        return 1
    worst = max(r.residual.max() for r in results if len(r.travel))
    print(f'linkage-sweep: done, largest residual {worst:.2g} mm', file=sys.stderr)
    return 0


if __name__ == '__main__':
    sys.exit(main())
