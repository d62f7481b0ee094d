# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-kc end to end: its tables are the statics API's numbers, its files read back whole.

Run as a user runs it (the installed console script, in a subprocess) on the bundled
double_wishbone_bushings, which declares bushings. Values are written to 10 significant digits,
so a table agrees with the API to 1e-9 relative (plus an absolute floor for values near zero).
"""

import csv
from pathlib import Path
import subprocess
import sys

from linkage_ros.core.measure import quantities
from linkage_ros.core.model import load_scene
from linkage_ros.core.statics import compliance, Load, RATE_COLUMNS, solve_loaded
import numpy as np
import pytest

KC = str(Path(sys.executable).parent / 'linkage-kc')
BENCH = str(Path(sys.executable).parent / 'linkage-bench')
SCENE = 'double_wishbone_bushings'
DIGITS = 1e-9   # relative round-off of %.10g


def run(*args, cwd=None, program=KC):
    """Run linkage-kc to its end; return (status, stdout, stderr)."""
    done = subprocess.run([program, *args], capture_output=True, text=True, timeout=300,
                          cwd=cwd)
    return done.returncode, done.stdout, done.stderr


def table(text):
    """Return (header, rows (n, columns) float) of a CSV table."""
    lines = list(csv.reader(text.splitlines()))
    return lines[0], np.array(lines[1:], dtype=float).reshape(-1, len(lines[0]))


def close(written, computed):
    """Assert written values equal computed ones to the table's 10 significant digits."""
    computed = np.asarray(computed, dtype=float)
    np.testing.assert_allclose(written, computed, rtol=DIGITS,
                               atol=DIGITS * max(1.0, float(np.abs(computed).max())))


@pytest.fixture(scope='module')
def scene():
    loaded = load_scene(SCENE)
    assert loaded.has_bushings
    return loaded


def test_the_rates_table_is_the_apis_rates_at_each_travel(scene):
    status, out, err = run(SCENE, '--travel', '-20:20:20')
    header, rows = table(out)
    assert status == 0, err
    assert header == ['travel_mm', *RATE_COLUMNS]
    assert all(quantities.known(name) for name in header)
    assert rows[:, 0].tolist() == [-20.0, 0.0, 20.0]
    for row in rows:
        rates = compliance(scene, travel_mm=row[0]).rates
        close(row[1:], [rates[name] for name in RATE_COLUMNS])


def test_a_rack_range_adds_rack_mm_and_solves_the_grid(scene):
    status, out, err = run(SCENE, '--travel', '0:10:10', '--rack', '-5:5:5',
                           '--columns', 'toe_per_fy_cp_deg_per_kN')
    header, rows = table(out)
    assert status == 0, err
    assert header == ['travel_mm', 'rack_mm', 'toe_per_fy_cp_deg_per_kN']
    assert rows[:, :2].tolist() == [[t, r] for r in (-5.0, 0.0, 5.0) for t in (0.0, 10.0)]
    for travel, rack, toe in rows:
        expected = compliance(scene, travel_mm=travel, rack_mm=rack)
        close([toe], [expected.rates['toe_per_fy_cp_deg_per_kN']])


def test_the_loaded_table_written_to_a_file_is_the_apis_loaded_solve(scene, tmp_path):
    path = tmp_path / 'cornering.csv'
    status, out, err = run(SCENE, '--travel', '10', '--load', '300,2000,-100', '--at', 'cp',
                           '--moment', '0,0,50', '-o', str(path))
    assert (status, out) == (0, ''), err
    header, rows = table(path.read_text())
    res = solve_loaded(scene, travel_mm=10.0, load=Load(force_n=(300.0, 2000.0, -100.0),
                                                        at='cp', moment_nm=(0.0, 0.0, 50.0)))
    expected = {'travel_mm': 10.0, 'camber_deg': res.camber_deg, 'toe_deg': res.toe_deg,
                'holding_force_N': res.holding_force_n}
    expected.update({f'wheel_center_{a}_mm': v for a, v in zip('xyz', res.wheel_center_mm)})
    expected.update({f'{n}_tension_N': f for n, f in res.link_forces_n.items()})
    expected.update({f'{p}_f{a}_N': v for p, f in res.body_forces_n.items()
                     for a, v in zip('xyz', f)})
    expected.update({f'{b}_m{a}_Nm': v for b, f in res.body_moments_nm.items()
                     for a, v in zip('xyz', f)})
    expected.update({f'{n}_force_N': f for n, f in res.spring_forces_n.items()})
    assert header[:7] == ['travel_mm', 'camber_deg', 'toe_deg', 'wheel_center_x_mm',
                          'wheel_center_y_mm', 'wheel_center_z_mm', 'holding_force_N']
    assert sorted(header) == sorted(expected)
    assert {'tie_rod_tension_N', 'lower_arm_axis0_fy_N', 'lower_arm_axis0_mz_Nm',
            'spring_force_N', 'spring_body_fz_N'} <= set(header)
    assert all(quantities.known(name) for name in header)
    close(rows[0], [expected[name] for name in header])


@pytest.mark.parametrize('name', ['double_wishbone_bushings', 'five_link_bushings',
                                  'chrono_sedan_doublewishbone_bushings'])
def test_the_loaded_table_s_forces_and_couples_balance_the_load(name):
    """
    The table's pickup forces and bushing couples balance load and holding force (doc/kc.md).

    Forces from the CSV (10 digits) at the pickups' points (Loaded.body_points_mm); moments
    about the origin, N mm. Before issue 36 the couples were not in the table: 2 to 25 N m
    short on these scenes. Bound: 1e-9 of the largest force times 1 m (the table's
    digits, 5e-11 relative, over a dozen terms).
    """
    force, moment = np.array([300.0, 2000.0, -100.0]), np.array([20.0, -30.0, 50.0])
    status, out, err = run(name, '--travel', '10', '--load', '300,2000,-100', '--at', 'cp',
                           '--moment', '20,-30,50')
    assert status == 0, err
    header, rows = table(out)
    row = dict(zip(header, rows[0]))
    res = solve_loaded(load_scene(name), 10.0, Load(tuple(force), 'cp', tuple(moment)))
    pickups = [n[:-len('_fx_N')] for n in header if n.endswith('_fx_N')]
    forces = {p: np.array([row[f'{p}_f{a}_N'] for a in 'xyz']) for p in pickups}
    couples = [np.array([row[n] for n in header if n.startswith(f'{b}_m') and n.endswith('_Nm')])
               for b in {n[:-len('_mx_Nm')] for n in header if n.endswith('_mx_Nm')}]
    up = np.array([0.0, 0.0, row['holding_force_N']])
    wheel = np.array([row[f'wheel_center_{a}_mm'] for a in 'xyz'])
    scale = max(np.abs(f).max() for f in forces.values())
    assert set(pickups) == set(res.body_points_mm) and couples
    assert np.abs(sum(forces.values()) - force - up).max() < 1e-9 * scale
    turning = sum(np.cross(res.body_points_mm[p], f) for p, f in forces.items()) \
        + 1000.0 * sum(couples) - np.cross(res.load_point_mm, force) - 1000.0 * moment \
        - np.cross(wheel, up)
    assert np.abs(turning).max() < 1e-9 * scale * 1000.0


def test_a_rigid_strut_scene_gives_its_strut_top_force_and_zero_pose_rates():
    status, out, err = run('macpherson', '--travel', '0', '--load', '0,1000,0', '--at', 'cp')
    header, rows = table(out)
    res = solve_loaded(load_scene('macpherson'), travel_mm=0.0,
                       load=Load(force_n=(0.0, 1000.0, 0.0), at='cp'))
    assert status == 0, err
    top = [header.index(f'strut_top_f{a}_N') for a in 'xyz']
    close(rows[0, top], res.body_forces_n['strut_top'])
    _, out, _ = run('macpherson', '--travel', '0')
    header, rows = table(out)
    pose = [k for k, name in enumerate(header) if name not in ('travel_mm', 'jacking_per_fy_cp')]
    # rigid: the held travel leaves nothing to move, and the table says so: 0, not 1e-13
    assert not rows[0, pose].any()
    assert out.splitlines()[1].split(',')[pose[0]] == '0'   # (a rate's column, as written)


def test_csv_is_the_issues_spelling_of_output(tmp_path):
    args = [SCENE, '--travel', '0', '--load', '0,1000,0', '--at', 'wc']
    status, out, _ = run(*args, '--csv', str(tmp_path / 'a.csv'))
    assert status == 0 and out == ''
    assert (tmp_path / 'a.csv').read_text() == run(*args)[1]


def test_the_matrix_file_is_6x6_labelled_with_its_vertical_row_and_column_zero(
        scene, tmp_path):
    path = tmp_path / 'matrix.csv'
    status, _, err = run(SCENE, '--travel', '0', '--matrix', str(path))
    assert status == 0, err
    lines = list(csv.reader(path.read_text().splitlines()))
    assert lines[0] == ['response_per_load', 'fx_kN', 'fy_kN', 'fz_kN', 'mx_kNm', 'my_kNm',
                        'mz_kNm']
    assert [line[0] for line in lines[1:]] == ['dx_mm', 'dy_mm', 'dz_mm', 'rx_deg', 'ry_deg',
                                               'rz_deg']
    matrix = np.array([line[1:] for line in lines[1:]], dtype=float)
    assert matrix.shape == (6, 6)
    close(matrix, compliance(scene, travel_mm=0.0).matrix)
    # the travel is held: a vertical force moves nothing, nothing moves the centre vertically:
    # the model knows these zeros, and the file says 0 (not round-off, 1e-13)
    assert not matrix[2].any() and not matrix[:, 2].any()
    assert lines[3][1:] == ['0'] * 6 and [line[3] for line in lines[1:]] == ['0'] * 6
    assert np.all(np.diag(matrix)[[0, 1, 3, 4, 5]] > 0)   # a compliance's diagonal


def test_a_load_the_linkage_cannot_carry_is_an_error_line_and_status_1(tmp_path):
    path = tmp_path / 'out.csv'
    status, out, err = run(SCENE, '--travel', '0:10:10', '--load', '0,1e6,0', '--at', 'cp',
                           '-o', str(path))
    lines = err.splitlines()
    assert status == 1 and out == ''
    assert lines[-1].startswith('linkage-kc: ERROR NOT_CARRIED: ') and 'Traceback' not in err
    assert '1000000' in lines[-1] and 'residual' in lines[-1], lines[-1]
    assert lines[-1].endswith('(0 positions written)')
    assert path.read_text() == 'travel_mm\n'   # written whole: the table, with no pose


def test_a_travel_out_of_reach_ends_the_table_there_with_status_1():
    status, out, err = run(SCENE, '--travel', '0:1000:200')
    _, rows = table(out)
    assert status == 1 and rows[:, 0].tolist() == [0.0, 200.0]
    assert err.splitlines()[-1].startswith('linkage-kc: ERROR OUT_OF_REACH: travel 400 mm')
    assert err.splitlines()[-1].endswith('(2 positions written)')


@pytest.mark.parametrize('argv, says', [
    (['SCENE', '--travel', '0'], 'bushing.axial: -1 N/mm is outside 0.001 to 1e+11 N/mm'),
    (['LINE', '--travel', '0'], 'a line takes no bushing'),
    (['NO_RADIUS', '--travel', '0', '--load', '0,1000,0', '--at', 'cp'],
     '--at cp: double_wishbone_bushings has no wheel_radius'),
    ([SCENE, '--travel', '0', '--no-such-option'], 'unrecognized arguments: --no-such-option'),
    ([SCENE, '--travel', '0', '--columns', 'toe_deg'], "--columns: unknown column 'toe_deg'"),
    ([SCENE, '--travel', '0', '--load', '0,1000,0'], '--load needs --at cp or --at wc'),
    ([SCENE, '--travel', '0', '--load', '0,nan,0', '--at', 'wc'], 'argument --load: expected'),
    ([SCENE, '--travel', '0:10:10', '--matrix', 'm.csv'], '--matrix: the matrix is of one'),
    ([SCENE, '--travel', '0', '--load', '1,1,1', '--at', 'wc', '--matrix', 'm.csv'],
     '--matrix is the compliance at zero load'),
    (['SCENE', '--travel', '0', '-o', 'SCENE'], 'is the input'),
])
def test_bad_input_is_one_line_with_status_2_and_no_file(argv, says, tmp_path):
    text = Path(load_scene(SCENE).source).read_text()
    (tmp_path / 'bad.yaml').write_text(text.replace('axial: 300.0', 'axial: -1', 1))
    line = Path(load_scene('macpherson').source).read_text().replace(
        'type: line,', 'type: line, bushing: {axial: 100, radial: 100},', 1)
    (tmp_path / 'line.yaml').write_text(line)
    (tmp_path / 'flat.yaml').write_text(text.replace('wheel_radius: 330', '', 1))
    given = {'SCENE': str(tmp_path / 'bad.yaml'), 'LINE': str(tmp_path / 'line.yaml'),
             'NO_RADIUS': str(tmp_path / 'flat.yaml')}
    if argv[-1] == 'SCENE':   # an output that is the input: a good scene, then itself
        (tmp_path / 'bad.yaml').write_text(text)
    before = sorted(p.read_bytes() for p in tmp_path.iterdir())
    status, out, err = run(*[given.get(a, a) for a in argv], cwd=tmp_path)
    assert (status, out) == (2, ''), err
    assert err.count('\n') == 1 and err.startswith('linkage-kc: ') and says in err, err
    assert sorted(p.read_bytes() for p in tmp_path.iterdir()) == before


@pytest.mark.parametrize('argv', [['--travel', '-40:40:20'],
                                  ['--travel', '0', '--load', '0,3000,0', '--at', 'cp']])
def test_plot_writes_a_picture(argv, tmp_path):
    path = tmp_path / 'kc.png'
    status, _, err = run(SCENE, *argv, '--plot', str(path))
    assert status == 0, err
    assert path.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n' and path.stat().st_size > 20000
    assert f'linkage-kc: wrote {path}' in err


def test_linkage_bench_kc_prints_1x_10x_and_100x_side_by_side():
    status, out, err = run('kc', SCENE, '--travel', '0', '--rounds', '1', program=BENCH)
    lines = out.splitlines()
    assert status == 0, err
    assert lines[0].startswith('double_wishbone_bushings: 1 positions (1x); loaded by '
                               'F (0, 1000, 0)')
    assert lines[1].split() == ['positions', 'kinematic_us', 'rates_us', 'loaded_us',
                                'rates/kinematic', 'loaded/kinematic']
    rows = np.array([line.split() for line in lines[2:]], dtype=float)
    assert rows[:, 0].tolist() == [1.0, 10.0, 100.0]
    # the ratios are of the times printed (to 0.1 us; the ratios to 0.01)
    np.testing.assert_allclose(rows[:, 4], rows[:, 2] / rows[:, 1], rtol=1e-2, atol=0.01)
    np.testing.assert_allclose(rows[:, 5], rows[:, 3] / rows[:, 1], rtol=1e-2, atol=0.01)
    assert np.all(rows[:, 1:] > 0)
