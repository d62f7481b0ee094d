# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage-axle and the axles of vehicle files: columns, units, statuses, one-line mistakes."""

import csv
import io
from pathlib import Path
import subprocess
import sys

from linkage_ros.core import warmup
from linkage_ros.core.axle import axle_of, solve_axle
from linkage_ros.core.model import load_vehicle, SceneError
from linkage_ros.tools.axle import main
import numpy as np
import pytest

DEMO = Path(load_vehicle('demo_vehicle').source)
SCENES = DEMO.parent.parent / 'scenes'
FRONT = ('heave_mm,roll_deg,rack_mm,left_travel_mm,right_travel_mm,roll_centre_y_mm,'
         'roll_centre_height_mm,track_mm,left_camber_deg,right_camber_deg,left_toe_deg,'
         'right_toe_deg,left_camber_ground_deg,right_camber_ground_deg,left_toe_ground_deg,'
         'right_toe_ground_deg,anti_dive_pct')
STEER = ',left_steer_deg,right_steer_deg,mean_steer_deg,ackermann_pct'
BAR = (',arb_left_angle_deg,arb_right_angle_deg,arb_twist_deg,arb_ratio_deg_per_deg_roll,'
       'arb_ratio_left_deg_per_mm,arb_ratio_right_deg_per_mm,arb_torque_Nm,arb_roll_moment_Nm,'
       'arb_roll_stiffness_Nm_per_deg')   # demo_vehicle's front axle has an anti-roll bar


def run(capsys, *argv):
    try:
        code = main(list(argv))
    except SystemExit as exited:   # a mistake argparse finds
        code = exited.code
    out, err = capsys.readouterr()
    # without the line a cold numba cache adds once (warmup.MESSAGE: after an edit of a kernel)
    err = ''.join(line for line in err.splitlines(True) if warmup.MESSAGE not in line)
    return code, list(csv.DictReader(io.StringIO(out))), out, err


def vehicle_file(tmp_path, axles, extra='cg_height: 550\n', scene='double_wishbone'):
    """Write a two-corner vehicle file with the given axles block; return its path."""
    path = tmp_path / 'car.yaml'
    path.write_text(f'name: car\nunits: mm\n{extra}corners:\n'
                    f'  fl: {{scene: {scene}, offset: [1400, 0, 0]}}\n'
                    f'  fr: {{scene: {scene}, offset: [1400, 0, 0], mirror: true}}\n'
                    f'axles:\n{axles}')
    return path


def test_the_default_is_the_demo_front_axle_over_the_travel_block_in_mm_and_deg(capsys):
    code, rows, out, err = run(capsys)
    assert code == 0 and out.splitlines()[0] == FRONT + BAR
    assert len(rows) == 161 and float(rows[0]['heave_mm']) == -80.0
    design = rows[80]
    assert float(design['track_mm']) == pytest.approx(1520.0)   # double_wishbone y = +-760
    # on the centre line by symmetry: to the round-off of an intersection of mm-scale lines
    assert float(design['roll_centre_y_mm']) == pytest.approx(0.0, abs=1e-9)
    assert err.startswith('linkage-axle: demo_vehicle front axle (front_left, front_right): '
                          '161 positions\n')


def test_the_table_holds_what_solve_axle_returns(capsys):
    _, rows, _, _ = run(capsys, '--heave', '-20:20:20', '--roll', '1.5')
    axle = axle_of(load_vehicle('demo_vehicle'), 'front')
    result = solve_axle(axle, [-20.0, 0.0, 20.0], np.radians(1.5))
    got = np.array([[float(r['roll_centre_y_mm']), float(r['roll_centre_height_mm']),
                     float(r['left_camber_ground_deg']), float(r['anti_dive_pct'])]
                    for r in rows])
    expected = np.column_stack((result.roll_centre[:, 0], result.roll_centre_height,
                                np.degrees(result.camber_ground[:, 0]), result.anti['anti_dive']))
    assert got == pytest.approx(expected, rel=1e-9, abs=1e-9)   # 10 significant digits


def test_a_rack_adds_steer_and_ackermann_and_a_grid_walks_every_rack(capsys):
    code, rows, out, _ = run(capsys, '--rack', '-20:20:20', '--heave', '0')
    assert code == 0 and out.splitlines()[0] == FRONT + STEER + BAR
    assert [float(r['rack_mm']) for r in rows] == [-20.0, 0.0, 20.0]
    assert rows[1]['ackermann_pct'] == 'nan'   # straight ahead
    assert float(rows[0]['mean_steer_deg']) == pytest.approx(-float(rows[2]['mean_steer_deg']))


def test_the_rear_axle_has_anti_lift_under_braking_and_anti_squat_under_drive(capsys):
    code, rows, out, _ = run(capsys, '--axle', 'rear', '--heave', '0')
    assert code == 0
    assert out.splitlines()[0].endswith('right_toe_ground_deg,anti_lift_pct,anti_squat_pct')


def test_a_roll_beyond_the_travel_limits_writes_the_rows_before_it_with_status_1(capsys):
    # issue 27 item 21: roll 15 deg asks -203.6 mm of a corner whose travel block is +-80 mm
    code, rows, _, err = run(capsys, '--heave', '0', '--roll', '0:15:5')
    assert code == 1 and [float(r['roll_deg']) for r in rows] == [0.0, 5.0]
    assert err.splitlines()[-1] == (
        'linkage-axle: heave 0 mm, roll 10 deg, rack 0 mm: the left wheel (front_left) would '
        "travel -134.009 mm, beyond its travel limits -80 to 80 mm (the scene's travel block) "
        '(2 positions written)')


def test_a_roll_out_of_reach_writes_the_rows_before_it_and_names_the_limit(capsys, tmp_path):
    # double_wishbone's rebound limit is -276.781 mm: roll 20 deg asks -276.617 mm of the
    # left wheel, 30 deg -438.786 mm (a travel block of +-500 mm lets the wheel get there).
    scene = (SCENES / 'double_wishbone.yaml').read_text()
    wide = scene.replace('travel: {min: -80, max: 80, step: 1}',
                         'travel: {min: -500, max: 500, step: 1}')
    assert wide != scene
    (tmp_path / 'wide.yaml').write_text(wide)
    path = vehicle_file(tmp_path, '  front: {left: fl, right: fr}\n',
                        scene=str(tmp_path / 'wide.yaml'))
    code, rows, _, err = run(capsys, str(path), '--heave', '0', '--roll', '0:40:10')
    assert code == 1 and [float(r['roll_deg']) for r in rows] == [0.0, 10.0, 20.0]
    assert err.splitlines()[-1] == (
        'linkage-axle: heave 0 mm, roll 30 deg, rack 0 mm: the left wheel (fl): '
        'travel -438.786 mm is out of reach: continuation from -276.617 mm ends at the rebound '
        'limit -276.781 mm (a turning point, located to 0.01 mm); reachable range found: '
        '[-276.781, 0.000] mm (3 positions written)')


@pytest.mark.parametrize('axles, extra, key, says', [
    ('  front: {left: fl, right: rr}\n', 'cg_height: 550\n', 'axles.front.right',
     "'rr' is not a corner of the vehicle (corners: fl, fr)"),
    ('  front: {left: fr, right: fl}\n', '', 'axles.front.left',
     'corner fr is a right wheel'),
    ('  front: {left: fl, right: fr, brake_share: 0.7}\n', 'wheelbase: 2800\n', 'cg_height',
     'missing: axles.front.brake_share asks for anti-dive'),
    ('  front: {left: fl, right: fr, brake_share: 0.7}\n', 'cg_height: 550\n', 'wheelbase',
     'missing: axles.front.brake_share asks for anti-dive'),
    ('  middle: {left: fl, right: fr}\n', '', 'axles.middle', 'unknown axle'),
    ('  front: {left: fl, right: fr, brakes: drum}\n', '', 'axles.front.brakes',
     "unknown value 'drum'"),
    ('  front: {left: fl, right: fr, brake_share: 1.5}\n', 'cg_height: 550\n',
     'axles.front.brake_share', 'expected a share from 0 to 1'),
    ('  front: {left: fl, right: fr, toe: 1}\n', '', 'axles.front.toe', 'unknown key'),
])
def test_a_bad_axle_is_one_line_naming_the_file_and_the_key_with_status_2(
        capsys, tmp_path, axles, extra, key, says):
    path = vehicle_file(tmp_path, axles, extra)
    with pytest.raises(SceneError) as error:
        load_vehicle(path)
    assert error.value.field == key and says in error.value.problem
    code, _, out, err = run(capsys, str(path))
    assert (code, out) == (2, '')
    assert err == f'linkage-axle: {path}: {key}: {error.value.problem}\n'


@pytest.mark.parametrize('argv, says', [
    (['--axle', 'middle'], "axles: no axle 'middle' (axles: front, rear)"),
    (['--roll', '50'], '--roll: |roll| must stay below 45 deg, got 50'),
    (['--heave', '1:2'], 'argument --heave: expected FROM[:TO:STEP], finite numbers with '
     "STEP > 0, got '1:2'"),
    (['--roll', '-1:1:0'], 'argument --roll: expected FROM[:TO:STEP]'),
    (['--rack', 'x'], 'argument --rack: expected FROM[:TO:STEP]'),
    (['--axle', 'rear', '--rack', '5'], 'demo_vehicle rear axle: no corner has a steer: rack'),
    (['-o', '/no/such/folder/a.csv'], '-o: cannot write /no/such/folder/a.csv'),
])
def test_a_mistake_in_the_command_is_one_line_with_status_2(capsys, argv, says):
    code, _, out, err = run(capsys, *argv)
    assert (code, out) == (2, '')
    assert err.count('\n') == 1 and err.startswith('linkage-axle: ') and says in err, err


def test_a_corner_without_wheel_radius_drops_the_patch_columns_and_says_so_once(
        capsys, tmp_path):
    scene = (SCENES / 'five_link.yaml').read_text().replace('wheel_radius: 330\n', '')
    (tmp_path / 'bare.yaml').write_text(scene)
    path = vehicle_file(tmp_path, '  rear: {left: fl, right: fr, drive_share: 1.0}\n',
                        'cg_height: 550\nwheelbase: 2800\n', scene='bare.yaml')
    code, rows, out, err = run(capsys, str(path), '--axle', 'rear', '--heave', '0')
    assert code == 0
    header = out.splitlines()[0]
    assert 'roll_centre' not in header and 'track_mm' not in header
    assert header.endswith('anti_squat_pct')   # from the wheel centre: no patch needed
    notes = [line for line in err.splitlines() if 'no wheel_radius' in line]
    assert len(notes) == 2 and notes[0].startswith('linkage-axle: fl (')


def test_a_vehicle_without_axles_loads_and_imports_no_axle_code(tmp_path):
    path = tmp_path / 'car.yaml'
    path.write_text('name: car\ncorners:\n  fl: {scene: double_wishbone}\n'
                    '  fr: {scene: double_wishbone, mirror: true}\n')
    code = ('import sys\nfrom linkage_ros.core.model.vehicle import load_vehicle\n'
            f'vehicle = load_vehicle({str(path)!r})\n'
            'print(vehicle.axles, sorted(m for m in ("linkage_ros.core.model.vehicle_axles", '
            '"linkage_ros.core.axle.axle") if m in sys.modules))\n')
    done = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True)
    assert (done.returncode, done.stdout) == (0, 'None []\n'), done.stderr
    assert load_vehicle('demo_vehicle').axles.wheelbase == 2800.0


def test_a_single_axle_without_wheelbase_steers_but_says_it_has_no_ackermann(capsys, tmp_path):
    path = vehicle_file(tmp_path, '  front: {left: fl, right: fr}\n', '')
    code, rows, out, err = run(capsys, str(path), '--rack', '10', '--heave', '0')
    assert code == 0 and out.splitlines()[0].endswith('mean_steer_deg')
    assert f'linkage-axle: {path} has no wheelbase (and not two axles to derive it from): ' \
           'no Ackermann\n' in err
