# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage-vehicle: the setup sheet as a table and pictures; bad input one line, status 2."""

import csv
import io
from pathlib import Path

from linkage_ros.core.measure import quantities as registry
from linkage_ros.core.model import vehicle_dir
from linkage_ros.tools import vehicle as vehicle_tool
import pytest

DEMO = vehicle_dir() / 'demo_vehicle.yaml'
AXLE_COLUMNS = ('wheel_rate_N_per_mm', 'ride_rate_N_per_mm', 'ride_frequency_Hz',
                'roll_stiffness_springs_Nm_per_deg', 'roll_stiffness_bar_Nm_per_deg',
                'roll_stiffness_Nm_per_deg', 'roll_centre_height_mm')
VEHICLE_COLUMNS = ('roll_stiffness_Nm_per_deg', 'roll_axis_height_at_cg_mm',
                   'roll_gradient_deg_per_g', 'lltd_front_pct')


def run(argv, capsys):
    try:
        status = vehicle_tool.main(argv)
    except SystemExit as exited:
        status = exited.code
    out, err = capsys.readouterr()
    return status, out, err


def edited(tmp_path, old, new):
    """Write demo_vehicle with one piece of text replaced; return its path."""
    text = DEMO.read_text()
    assert old in text
    path = tmp_path / 'car.yaml'
    path.write_text(text.replace(old, new))
    return str(path)


def test_the_sheet_has_a_row_per_axle_and_one_for_the_vehicle(capsys):
    status, out, err = run(['demo_vehicle'], capsys)
    assert status == 0, err
    rows = {r['axle']: r for r in csv.DictReader(io.StringIO(out))}
    assert list(rows) == ['front', 'rear', 'vehicle']
    for axle in ('front', 'rear'):
        assert all(float(rows[axle][c]) >= 0 for c in AXLE_COLUMNS)
    assert all(rows['vehicle'][c] != '' for c in VEHICLE_COLUMNS)
    total = float(rows['front']['roll_stiffness_Nm_per_deg']) + float(
        rows['rear']['roll_stiffness_Nm_per_deg'])
    assert float(rows['vehicle']['roll_stiffness_Nm_per_deg']) == pytest.approx(total, rel=1e-9)
    assert 0.0 < float(rows['vehicle']['lltd_front_pct']) < 100.0


def test_tables_are_written_per_axle_and_every_column_is_a_registered_quantity(tmp_path,
                                                                               capsys):
    status, out, err = run(['demo_vehicle', '--tables', str(tmp_path / 'tables')], capsys)
    assert status == 0, err
    header = next(csv.reader(io.StringIO(out)))
    assert [n for n in header if not registry.known(n)] == []
    written = sorted(p.name for p in (tmp_path / 'tables').iterdir())
    assert written == ['front_heave.csv', 'front_rack.csv', 'front_roll.csv', 'rear_heave.csv',
                       'rear_roll.csv']
    for name in written:
        with open(tmp_path / 'tables' / name, newline='') as f:
            rows = list(csv.reader(f))
        assert [n for n in rows[0] if not registry.known(n)] == []
        assert len(rows) - 1 == {'heave': 31, 'roll': 25, 'rack': 61}[name[:-4].split('_')[1]]


def test_csv_and_plot_write_their_files(tmp_path, capsys):
    table, picture = tmp_path / 'sheet.csv', tmp_path / 'sheet.png'
    status, out, err = run(['demo_vehicle', '--csv', str(table), '--plot', str(picture)], capsys)
    assert status == 0, err
    assert out == ''
    with open(table, newline='') as f:
        assert [r['axle'] for r in csv.DictReader(f)] == ['front', 'rear', 'vehicle']
    assert picture.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'


@pytest.mark.parametrize('old, new, named', [
    ('sprung: 1280.0', 'sprung: -1280.0', 'mass.sprung'),
    ('sprung: 1280.0', 'sprung: .nan', 'mass.sprung'),
    ('front: 70.0, rear: 90.0}', 'front: -70.0, rear: 90.0}', 'mass.unsprung.front'),
    ('front_share: 0.54', 'cg_x: 1500.0', 'mass.cg_x'),
    ('front_share: 0.54', 'front_share: 1.2', 'mass.front_share'),
    ('tyre_rate: {front: 250.0', 'tyre_rate: {front: 0.0', 'tyre_rate.front'),
    ('tyre_rate: {front: 250.0', 'tyre_rate: {front: -5.0', 'tyre_rate.front'),
    ('tyre_rate: {front: 250.0, rear: 260.0}', '', 'tyre_rate'),
    ('  sprung: 1280.0                 # kg\n', '', 'mass.sprung'),
    ('  unsprung: {front: 70.0, rear: 90.0}', '', 'mass.unsprung'),
    ('front_share: 0.54', 'front_share: 0.54\n  cg_height: 600.0', 'mass.cg_height'),
    ('front_share: 0.54', 'front_share: 0.54\n  cg_x: 0.0', 'mass.front_share'),
])
def test_bad_mass_data_is_one_line_naming_the_key_and_status_2(
        tmp_path, capsys, old, new, named):
    status, out, err = run([edited(tmp_path, old, new)], capsys)
    assert status == 2
    assert out == ''
    assert len(err.strip().splitlines()) == 1, err
    assert named in err


def test_a_vehicle_without_mass_says_in_one_line_it_has_no_setup_sheet(tmp_path, capsys):
    text = DEMO.read_text()
    path = tmp_path / 'bare.yaml'
    path.write_text(text[:text.index('mass:')])
    status, out, err = run([str(path)], capsys)
    assert status == 2
    assert out == ''
    assert len(err.strip().splitlines()) == 1
    assert 'has no setup sheet' in err


def test_a_missing_cg_height_is_named_as_the_key_the_roll_quantities_need(tmp_path, capsys):
    text = DEMO.read_text().replace('cg_height: 550.0', '')
    text = text.replace('brake_share: 0.6', 'brake_share: 0.0').replace(
        'brake_share: 0.4, drive_share: 1.0', 'brake_share: 0.0, drive_share: 0.0')
    path = Path(tmp_path / 'car.yaml')
    path.write_text(text)
    status, _, err = run([str(path)], capsys)
    assert status == 2
    assert 'mass.cg_height' in err and 'missing' in err


def test_a_table_beyond_a_corners_travel_limits_stops_there_with_status_1(tmp_path, capsys):
    # the front scene's travel block at +-30 mm: the roll table's +-3 deg asks the wheels for
    # (t / 2) tan(3 deg) = 39.8 mm, so it stops at the first roll past 30 mm
    scene = (vehicle_dir().parent / 'scenes' / 'double_wishbone.yaml').read_text()
    assert 'travel: {min: -80, max: 80, step: 1}' in scene
    (tmp_path / 'short.yaml').write_text(scene.replace('travel: {min: -80, max: 80, step: 1}',
                                                       'travel: {min: -30, max: 30, step: 1}'))
    car = DEMO.read_text().replace('scene: double_wishbone,', 'scene: short.yaml,')
    (tmp_path / 'car.yaml').write_text(car)
    status, out, err = run([str(tmp_path / 'car.yaml')], capsys)
    assert status == 1
    assert [r['axle'] for r in csv.DictReader(io.StringIO(out))] == ['front', 'rear', 'vehicle']
    assert 'beyond its travel limits -30 to 30 mm' in err
