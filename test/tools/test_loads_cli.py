# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-loads end to end: its tables are the core's answers, its files read back whole.

Tables are written as CSV with 17 significant digits (the same float64 back) or Parquet;
each is read back by an independent reader (csv, pyarrow) and compared with
linkage_ros.core.loads's answers, and a corner with linkage-kc's table of the same load.
"""

import csv
from pathlib import Path
import subprocess
import sys

from linkage_ros.bench.loads import benchmark, scaled
from linkage_ros.core.loads import built_in_cases, Loads, tables
from linkage_ros.core.model import load_vehicle
from linkage_ros.tools.loads import main
import numpy as np
import pytest
import yaml

VEHICLE = 'demo_vehicle_loads'
KC = str(Path(sys.executable).parent / 'linkage-kc')


@pytest.fixture(scope='module')
def loads():
    """Return the Loads of demo_vehicle_loads: its setup sheet, prepared once."""
    return Loads(load_vehicle(VEHICLE))


def read(path):
    """Return the rows of a CSV file as dicts (csv.DictReader)."""
    with open(path, newline='') as stream:
        return list(csv.DictReader(stream))


def test_the_corners_table_read_back_is_the_cores_answer(loads, tmp_path, capsys):
    out = tmp_path / 'corners.csv'
    assert main([VEHICLE, '--case', 'static,bump', '--table', 'corners', '-o', str(out)]) == 0
    err = capsys.readouterr().err
    assert 'linkage-loads: 1/2 static (1 g vertical)' in err and err.endswith('done\n')
    assert 'bump: front_left: bump_stop closed at travel' in err
    rows = read(out)
    assert list(rows[0]) == list(tables.CORNER_COLUMNS)
    expected = [r for c in ('static', 'bump')
                for r in tables.corner_rows(loads.solve(built_in_cases()[c]))]
    assert [(r['case'], r['corner'], r['status']) for r in rows] == [
        tuple(e[:3]) for e in expected]
    got = np.array([[float(r[k]) for k in tables.CORNER_COLUMNS[3:]] for r in rows])
    # a fresh process's solve against this one's: the same equilibria to their tolerance
    np.testing.assert_allclose(got, np.array([e[3:] for e in expected], dtype=float),
                               rtol=1e-9, atol=1e-6)
    assert np.abs(got[:, -1]).max() <= 1e-6   # the holding force, zero


def test_a_parquet_table_holds_what_the_csv_holds(tmp_path, capsys):
    pq = pytest.importorskip('pyarrow.parquet')
    csv_path, parquet_path = tmp_path / 'members.csv', tmp_path / 'members.parquet'
    for path in (csv_path, parquet_path):
        assert main([VEHICLE, '--case', 'cornering', '--table', 'members', '-o',
                     str(path)]) == 0
    capsys.readouterr()
    rows = read(csv_path)
    table = pq.read_table(parquet_path).to_pydict()
    assert list(table) == list(tables.MEMBER_COLUMNS)
    assert table['member'] == [r['member'] for r in rows]
    np.testing.assert_allclose(np.array(table['force_N'], dtype=float),
                               [float(r['force_N']) for r in rows], rtol=1e-9, atol=1e-6)
    kinds = dict(zip(table['member'], table['kind']))
    assert kinds['tie_rod'] == 'link' and kinds['bump_stop'] == 'stop'
    assert kinds['arb_drop_link'] == 'drop_link' and kinds['anti_roll_bar'] == 'bar'


def test_the_summary_is_the_largest_pickup_force_over_the_cases(tmp_path, capsys):
    pickups, summary = tmp_path / 'pickups.csv', tmp_path / 'summary.csv'
    for name, path in (('pickups', pickups), ('summary', summary)):
        assert main([VEHICLE, '--case', 'static,braking,pothole', '--table', name, '-o',
                     str(path)]) == 0
    capsys.readouterr()
    largest = {}
    for r in read(pickups):
        key, size = (r['corner'], r['pickup'], r['end']), float(r['force_magnitude_N'])
        if key not in largest or size > largest[key][0]:
            largest[key] = (size, r['case'])
    rows = read(summary)
    assert len(rows) == len(largest)
    for r in rows:
        size, case = largest[(r['corner'], r['pickup'], r['end'])]
        assert float(r['force_magnitude_N']) == pytest.approx(size, rel=1e-9)
        assert r['case'] == case


@pytest.mark.parametrize('case', ['braking', 'combined'])
def test_a_rear_corner_is_what_linkage_kc_gives_at_its_travel_under_its_load(loads, case):
    """
    Give linkage-kc's numbers for a rear corner at its travel under its load.

    linkage-kc on the corner's scene (the rear has no bar: nothing but its load acts) with
    the travel and the load linkage-loads found: the same camber, toe, holding force and
    forces to its 10 significant digits (the vehicle places the scene 1400 mm behind).
    """
    corner = loads.solve(built_in_cases()[case]).corners['rear_left']
    load = corner.load

    def text(values):
        return ','.join(repr(float(v)) for v in values)

    scene = Path(load_vehicle(VEHICLE).source).parent / VEHICLE / 'rear.yaml'
    done = subprocess.run([KC, str(scene), '--travel', repr(corner.travel_mm),
                           '--load', text(load.force_n), '--at', 'cp', '--moment',
                           text(load.moment_nm)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    lines = list(csv.reader(done.stdout.splitlines()))
    row = dict(zip(lines[0], (float(v) for v in lines[1])))
    got = corner.loaded
    scale = max(abs(f) for f in load.force_n)
    assert row['camber_deg'] == pytest.approx(got.camber_deg, rel=1e-9)
    assert row['toe_deg'] == pytest.approx(got.toe_deg, rel=1e-9)
    assert row['wheel_center_x_mm'] - 1400.0 == pytest.approx(got.wheel_center_mm[0],
                                                              abs=1e-6)
    assert abs(row['holding_force_N']) <= 1e-6 + 1e-9 * scale
    columns = {**{f'{name}_tension_N': f for name, f in got.link_forces_n.items()},
               **{f'{name}_force_N': f for name, f in got.spring_forces_n.items()}}
    for column, force in columns.items():
        assert row[column] == pytest.approx(force, rel=1e-9, abs=1e-9 * scale)


def test_a_wheel_that_lifts_off_is_status_1_naming_the_case_and_corner(tmp_path, capsys):
    out = tmp_path / 'corners.csv'
    assert main(['demo_vehicle', '--case', 'cornering', '--table', 'corners', '-o',
                 str(out)]) == 1
    err = capsys.readouterr().err
    assert ('linkage-loads: cornering: front_left: NOT_CARRIED: the front axle is not solved:'
            ' a wheel lifts off, its vertical tyre load not above 0: front_left (-15.9') in err
    assert err.endswith('linkage-loads: 3 corners not solved\n')
    rows = read(out)
    # demo_vehicle's soft rear springs: the outer rear wheel is beyond its travel; an axle
    # without a bar solves its corners apart, so the inner one is answered
    assert [r['status'] for r in rows] == ['NOT_CARRIED', 'NOT_CARRIED', 'OK', 'OUT_OF_REACH']


def mistakes(tmp_path):
    """Yield (argv, the one line said) of mistakes, each refused with status 2."""
    bad = tmp_path / 'bad.yaml'
    bad.write_text(yaml.safe_dump({'cases': {'kerb': {'corners': {
        'front_left': {'force_n': [0, 2e6, 0]}}}}}))
    nowhere = tmp_path / 'nowhere.yaml'
    nowhere.write_text(yaml.safe_dump({'cases': {'c': {'corners': {'middle': {}}}}}))
    vehicle = Path(load_vehicle(VEHICLE).source)
    no_mass = tmp_path / 'no_mass.yaml'
    data = yaml.safe_load(vehicle.read_text())
    data.pop('mass'), data.pop('tyre_rate')
    for corner in data['corners'].values():
        corner['scene'] = str(vehicle.parent / corner['scene'])   # beside the vehicle file
    no_mass.write_text(yaml.safe_dump(data))
    yield [VEHICLE, '--case', 'nope'], ("linkage-loads: --case: no case 'nope': choose from "
                                        'static, bump, braking, cornering, traction, pothole, '
                                        'combined')
    yield [VEHICLE, '--cases', str(bad)], (f'linkage-loads: {bad}: cases.kerb.corners.'
                                           'front_left.force_n: 2000000.0 is outside -1e+06 '
                                           'to 1e+06')
    yield [VEHICLE, '--cases', str(nowhere)], ('linkage-loads: case c: corners.middle: '
                                               'demo_vehicle_loads has no such corner')
    yield [VEHICLE, '-o', str(vehicle)], f'linkage-loads: -o: {vehicle} is the input'
    yield [str(no_mass)], f'linkage-loads: {no_mass}: no mass block'
    yield [VEHICLE, '--table', 'nope'], 'linkage-loads: error: argument --table: invalid choice'


def test_every_mistake_is_one_line_with_status_2_and_writes_nothing(tmp_path, capsys):
    for argv, said in mistakes(tmp_path):
        before = sorted(tmp_path.iterdir())
        try:
            status = main(argv)
        except SystemExit as exc:
            status = exc.code
        out, err = capsys.readouterr()
        assert status == 2 and out == '', (argv, err)
        assert err.count('\n') == 1 and err.startswith(said), (argv, err)
        assert sorted(tmp_path.iterdir()) == before


def test_the_plot_is_a_png_drawn_from_the_cases(tmp_path, capsys):
    path = tmp_path / 'loads.png'
    assert main([VEHICLE, '--case', 'static,cornering', '--table', 'summary',
                 '--plot', str(path)]) == 0
    assert f'linkage-loads: wrote {path}' in capsys.readouterr().err
    assert path.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n' and path.stat().st_size > 50_000


def test_the_benchmark_times_each_scale_of_cases_beside_a_solve_per_corner(loads, capsys):
    cases = {'static': built_in_cases()['static']}
    assert [c.vertical_g for c in scaled(cases, 2)] == [1.0, 1.0]
    bump = scaled({'bump': built_in_cases()['bump']}, 3)
    assert [c.vertical_g for c in bump] == pytest.approx([2.1, 2.55, 3.0])
    assert benchmark(loads, cases, 1, scales=(1, 2)) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[1].split() == ['scale', 'cases', 'case_ms', 'corner_solve_ms', 'ratio']
    assert [line.split()[:2] for line in lines[2:]] == [['1', '1'], ['2', '2']]
    assert all(float(v) > 0 for line in lines[2:] for v in line.split()[2:])
