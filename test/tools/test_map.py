# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-map: every value of a map is the solve at its grid point; files read back the same.

The reference is a direct solve: a fresh Continuation walked straight from the design
position to (travel, rack), not the map's sweeps; its table row is made by linkage-sweep's
own table().
"""

import csv
from pathlib import Path
import subprocess
import sys

from linkage_ros.core.axle import axle_of, solve_axle
from linkage_ros.core.model import load_scene, load_vehicle
from linkage_ros.core.solve import Continuation, Sweep
from linkage_ros.core.solve.mechanism import carrier_points
from linkage_ros.tools.kinematic_map import main
from linkage_ros.tools.sweep import header, table
import numpy as np
import pyarrow.parquet as pq
import pytest

REPO = Path(__file__).resolve().parents[2]


def direct(scene, travel, rack):
    """Return {column: value} of one position solved directly, as linkage-sweep tables it."""
    cont = Continuation(scene)
    s = cont.solve(travel, rack)
    assert s.success
    one = Sweep(travel=np.array([travel]), wheel_center=s.wheel_center[None],
                rotation=s.rotation[None], camber=np.array([s.camber]), toe=np.array([s.toe]),
                iterations=np.array([s.iterations]), residual=np.array([s.residual]),
                joints=carrier_points(cont.mech, s.wheel_center[None], s.rotation[None]),
                rack=rack, quaternion=s.quaternion[None])
    elements = scene if scene.elements else None
    return dict(zip(header(scene, True, elements), table(one, scene, True, elements)[0]))


def run_map(tmp_path, capsys, *argv):
    code = main(list(argv) + ['-o', str(tmp_path)])
    return code, capsys.readouterr().err


@pytest.fixture(scope='module')
def steered_map(tmp_path_factory):
    folder = tmp_path_factory.mktemp('map')
    assert main(['double_wishbone', '--travel', '-60:60:30', '--rack', '-20:20:10', '-o',
                 str(folder), '--format', 'csv,npz,parquet']) == 0
    return folder


def test_every_stored_value_is_the_direct_solve_at_its_grid_point(steered_map):
    scene = load_scene('double_wishbone')
    stored = np.load(steered_map / 'double_wishbone.npz')
    assert stored['travel_mm'].tolist() == [-60.0, -30.0, 0.0, 30.0, 60.0]
    assert stored['rack_mm'].tolist() == [-20.0, -10.0, 0.0, 10.0, 20.0]
    names = [n for n in stored.files if n not in ('travel_mm', 'rack_mm')]
    assert names == [c for c in header(scene, True, scene)   # linkage-sweep's columns
                     if c not in ('travel_mm', 'rack_mm', 'iterations')]
    assert 'spring_wheel_rate_N_per_mm' in names
    for i, travel in enumerate(stored['travel_mm']):
        for j, rack in enumerate(stored['rack_mm']):
            solved = direct(scene, float(travel), float(rack))
            for name in names:
                assert stored[name][i, j] == pytest.approx(solved[name], rel=1e-9, abs=1e-9), (
                    name, travel, rack)


def test_long_csv_and_parquet_read_back_to_the_npz_arrays_exactly(steered_map):
    stored = np.load(steered_map / 'double_wishbone.npz')
    travel, rack = list(stored['travel_mm']), list(stored['rack_mm'])
    with open(steered_map / 'double_wishbone.csv', newline='') as stream:
        rows = list(csv.DictReader(stream))
    names = [n for n in stored.files if n not in ('travel_mm', 'rack_mm')]
    assert len(rows) == len(travel) * len(rack) * len(names)
    for row in rows:
        i, j = travel.index(float(row['travel_mm'])), rack.index(float(row['rack_mm']))
        assert row['corner'] == 'double_wishbone'
        assert float(row['value']) == stored[row['quantity']][i, j]   # exact floats
    table = pq.read_table(steered_map / 'double_wishbone.parquet').to_pydict()
    assert len(table['travel_mm']) == 25
    for name in names:
        assert np.array(table[name]).reshape(5, 5).tolist() == stored[name].tolist()


def test_points_beyond_a_travel_limit_are_nan_and_listed_with_status_1(tmp_path, capsys):
    # five_link's bump limit is a turning point at 387.469 mm (README).
    code, err = run_map(tmp_path, capsys, 'five_link', '--travel', '-100:450:50')
    stored = np.load(tmp_path / 'five_link.npz')
    assert code == 1
    assert f'2 solves are out of reach: NaN in the map, listed in {tmp_path}' in err
    beyond = stored['travel_mm'] > 387.469
    assert np.isnan(stored['camber_deg'][beyond]).all()
    assert np.isfinite(stored['camber_deg'][~beyond]).all()
    with open(tmp_path / 'out_of_reach.csv', newline='') as stream:
        listed = list(csv.DictReader(stream))
    assert [(row['travel_mm'], row['rack_mm']) for row in listed] == [('400', '0'),
                                                                      ('450', '0')]
    assert 'bump limit 387.469 mm' in listed[0]['reason']


def test_quantities_a_corner_has_not_are_left_out_and_said(tmp_path, capsys):
    code, err = run_map(tmp_path, capsys, 'five_link', '--travel', '-20:20:20')
    assert code == 0
    assert ('five_link: left out, not defined here: caster_deg, '
            'kingpin_inclination_deg, scrub_radius_mm, mechanical_trail_mm') in err
    assert 'caster_deg' not in np.load(tmp_path / 'five_link.npz').files


def test_a_right_corner_steered_left_mirrors_the_left_corner_steered_right(tmp_path, capsys):
    # Mirrored in y, a rack to the left (+) turns the right wheel as -rack turns the left.
    code, _ = run_map(tmp_path, capsys, 'demo_vehicle', '--travel', '-40:40:40', '--rack',
                      '-20:20:20')
    left, right = (np.load(tmp_path / f'front_{side}.npz') for side in ('left', 'right'))
    assert code == 0 and sorted(p.name for p in tmp_path.iterdir())[:2] == [
        'front_left.csv', 'front_left.npz']
    for name in ('camber_deg', 'toe_deg', 'spring_length_mm', 'spring_ratio'):
        assert right[name] == pytest.approx(left[name][:, ::-1], abs=1e-9)
    assert right['wheel_center_y_mm'] == pytest.approx(-left['wheel_center_y_mm'][:, ::-1])


def test_a_grid_too_large_for_memory_is_one_line_saying_what_it_needs(tmp_path, capsys):
    code, err = run_map(tmp_path, capsys, 'five_link', '--travel', '-1e6:1e6:0.001')
    assert code == 2 and len(err.splitlines()) == 1
    assert err.startswith('linkage-map: grid: 2,000,000,001 points need about 1,')
    assert 'GB of memory and' in err and list(tmp_path.iterdir()) == []


@pytest.mark.parametrize('argv, said', [
    (['--rack', '0:10:5'], 'linkage-map: --rack: no corner has a steer: rack link'),
    (['--travel', '10:0:0'], 'linkage-map: --travel: expected FROM[:TO:STEP], finite '
                             "numbers with STEP > 0, got '10:0:0'"),
    (['--format', 'csv,xlsx'], 'linkage-map: --format: unknown format xlsx'),
])
def test_a_mistake_is_one_line_and_status_2(tmp_path, capsys, argv, said):
    code, err = run_map(tmp_path, capsys, 'five_link', *argv)
    assert code == 2 and err.startswith(said) and len(err.splitlines()) == 1


def test_parquet_without_pyarrow_names_the_extra_to_install(tmp_path):
    # pyarrow made unimportable in a fresh interpreter (None in sys.modules fails the import).
    code = ('import sys; sys.modules["pyarrow"] = None; '
            'from linkage_ros.tools.kinematic_map import main; '
            f'sys.exit(main(["five_link", "-o", {str(tmp_path)!r}, '
            '"--format", "npz,parquet"]))')
    done = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True)
    assert done.returncode == 2
    assert done.stderr == ('linkage-map: --format parquet: needs the Python package pyarrow, '
                           "which is not installed: pip install -e '.[map]' (in a linkage_ros "
                           'checkout) or pip install pyarrow\n')


def test_an_axle_map_holds_what_the_axle_module_solves_at_each_pair_of_travels(tmp_path,
                                                                               capsys):
    # The reference: core.axle.axle.solve_axle, its own continuation, at the heave and roll that
    # give each (left, right) pair: heave (l + r) / 2, tan(roll) = (r - l) / design track.
    code, err = run_map(tmp_path, capsys, 'demo_vehicle', '--axle', 'front', '--travel',
                        '-60:60:30', '--format', 'csv,npz,parquet')
    assert code == 0 and 'front axle: 5 x 5 (left travel x right travel)' in err
    stored = np.load(tmp_path / 'front_axle.npz')
    axle = axle_of(load_vehicle('demo_vehicle'), 'front')
    left, right = np.meshgrid(stored['left_travel_mm'], stored['right_travel_mm'],
                              indexing='ij')
    solved = solve_axle(axle, (left + right).ravel() / 2,
                        np.arctan((right - left).ravel() / axle.design_track))
    assert solved.success
    expected = {'roll_centre_y_mm': solved.roll_centre[:, 0],
                'roll_centre_z_mm': solved.roll_centre[:, 1],
                'roll_centre_height_mm': solved.roll_centre_height, 'track_mm': solved.track,
                'left_camber_deg': np.degrees(solved.camber[:, 0]),
                'right_camber_deg': np.degrees(solved.camber[:, 1]),
                'left_toe_deg': np.degrees(solved.toe[:, 0]),
                'right_toe_deg': np.degrees(solved.toe[:, 1])}
    assert sorted(stored.files) == sorted(['left_travel_mm', 'right_travel_mm', *expected])
    for name, values in expected.items():
        assert stored[name].ravel() == pytest.approx(values, rel=1e-9, abs=1e-9), name
    # a mirrored pair at equal travels: the roll centre on the centreline
    assert np.diag(stored['roll_centre_y_mm']) == pytest.approx(0.0, abs=1e-6)
    with open(tmp_path / 'front_axle.csv') as stream:
        assert stream.readline() == 'axle,left_travel_mm,right_travel_mm,quantity,value\n'


def test_an_axle_map_of_a_scene_or_a_missing_axle_is_one_line(tmp_path, capsys):
    code, err = run_map(tmp_path, capsys, 'five_link', '--axle', 'front')
    assert code == 2 and err == ('linkage-map: --axle: five_link is a scene; an axle is in a '
                                 'vehicle file (e.g. demo_vehicle)\n')
    code, err = run_map(tmp_path, capsys, 'demo_vehicle', '--axle', 'middle')
    assert code == 2 and err.endswith("axles: no axle 'middle' (axles: front, rear)\n")


def test_a_scene_s_warnings_are_printed_once_before_the_map(tmp_path, capsys):
    singular = Path(__file__).resolve().parents[1] / 'data' / 'five_link_singular.yaml'
    status = main([str(singular), '--travel', '0:2:1', '-o', str(tmp_path)])
    err = capsys.readouterr().err
    warning = f'linkage-map: warning: {load_scene(singular).warnings[0]}\n'
    assert status == 1 and err.count(warning) == 1     # 1: travels 1 and 2 are out of reach
    assert err.startswith(warning)
