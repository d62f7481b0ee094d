# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A number outside its stated range is one line and status 2 in every program (issue 36, item 2).

`axial: 1e308`, `torsion: 1e305`, `conical: 1e304` passed the loader and gave linkage-kc a
traceback (numpy's LinAlgError out of the statics); `sprung: 1e308` gave a sheet of infinities
with status 0. Each program that reads a scene or a vehicle now refuses them before any
work: one line on stderr naming the file, the field and the range, nothing on stdout.
"""

import copy
from pathlib import Path
import subprocess
import sys

from linkage_ros.core.model import load_scene
import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def bad_files(tmp_path):
    """Return (scene path, vehicle path, {field: said}) of a bushed scene and a vehicle."""
    data = yaml.safe_load(Path(load_scene('double_wishbone_bushings').source).read_text())
    arm = next(c for c in data['constraints'] if c['type'] == 'circle')
    arm['bushing'].update(axial=1e308, torsion=1e305, conical=1e304)
    scene = tmp_path / 'bad_scene.yaml'
    scene.write_text(yaml.safe_dump(data))
    car = yaml.safe_load((ROOT / 'config' / 'vehicles' / 'demo_vehicle.yaml').read_text())
    car['mass']['sprung'] = 1e308
    vehicle = tmp_path / 'bad_vehicle.yaml'
    vehicle.write_text(yaml.safe_dump(car))
    return str(scene), str(vehicle), arm['name']


def program(name):
    """Return the main(argv) of a program by its command name."""
    from linkage_ros.study import cli as study
    from linkage_ros.tools import (axle, chrono, foxglove_layout, kc, kinematic_map, sweep,
                                   urdf, vehicle)
    return {'linkage-kc': kc.main, 'linkage-sweep': sweep.main, 'linkage-map': kinematic_map.main,
            'linkage-study': study.main, 'linkage-chrono': chrono.main,
            'linkage-urdf': urdf.main, 'linkage-foxglove': foxglove_layout.main,
            'linkage-vehicle': vehicle.main, 'linkage-axle': axle.main}[name]


SCENE_RUNS = [('linkage-kc', ['{scene}', '--travel', '0']),
              ('linkage-sweep', ['{scene}', '--travel', '0']),
              ('linkage-map', ['{scene}', '-o', '{out}']),
              ('linkage-study', ['sensitivity', '{scene}', '--travel', '0', '-o', '{out}.csv']),
              ('linkage-chrono', ['export', '{scene}', '-o', '{out}.json']),
              ('linkage-urdf', ['{scene}', '-o', '{out}.urdf']),
              ('linkage-foxglove', ['{scene}', '-o', '{out}.json'])]
VEHICLE_RUNS = [('linkage-vehicle', ['{vehicle}']), ('linkage-axle', ['{vehicle}']),
                ('linkage-map', ['{vehicle}', '-o', '{out}'])]


def run(name, argv, files, tmp_path, capsys):
    scene, vehicle, _ = files
    args = [a.format(scene=scene, vehicle=vehicle, out=tmp_path / 'out') for a in argv]
    status = program(name)(args)
    out, err = capsys.readouterr()
    return status, out, err


@pytest.mark.parametrize('name, argv', SCENE_RUNS, ids=[r[0] for r in SCENE_RUNS])
def test_a_bushing_rate_out_of_range_is_one_line_and_status_2(name, argv, bad_files, tmp_path,
                                                              capsys):
    status, out, err = run(name, argv, bad_files, tmp_path, capsys)
    scene, _, arm = bad_files
    assert (status, out) == (2, '')
    assert err == (f'{name}: {scene}: constraints[0] ({arm}).bushing.axial: 1e+308 N/mm is '
                   'outside 0.001 to 1e+11 N/mm (doc/scenes.md#ranges)\n')
    assert not list(tmp_path.glob('out*'))                   # nothing written


@pytest.mark.parametrize('name, argv', VEHICLE_RUNS, ids=[r[0] for r in VEHICLE_RUNS])
def test_a_mass_out_of_range_is_one_line_and_status_2(name, argv, bad_files, tmp_path, capsys):
    status, out, err = run(name, argv, bad_files, tmp_path, capsys)
    assert (status, out) == (2, '')
    assert err == (f'{name}: {bad_files[1]}: mass.sprung: 1e+308 kg is outside 0.001 to 1e+07 '
                   'kg (doc/scenes.md#ranges)\n')


def test_linkage_kc_as_a_process_says_it_in_one_line_without_a_traceback(bad_files):
    # the issue's report: a traceback (LinAlgError) and status 1
    result = subprocess.run([sys.executable, '-m', 'linkage_ros.tools.kc', bad_files[0],
                             '--travel', '0'], capture_output=True, text=True, timeout=300)
    assert (result.returncode, result.stdout) == (2, '')
    assert len(result.stderr.splitlines()) == 1 and 'Traceback' not in result.stderr
    assert 'bushing.axial: 1e+308 N/mm is outside' in result.stderr


@pytest.mark.parametrize('key, value, said', [
    ('torsion', 1e305, '1e+305 N m/deg is outside 0, or 0.001 to 1e+10 N m/deg'),
    ('conical', 1e304, '1e+304 N m/deg is outside 0, or 0.001 to 1e+10 N m/deg')])
def test_each_of_the_issues_rates_is_refused_on_its_own(tmp_path, capsys, key, value, said):
    data = yaml.safe_load(Path(load_scene('double_wishbone_bushings').source).read_text())
    arm = next(c for c in data['constraints'] if c['type'] == 'circle')
    arm['bushing'][key] = value
    path = tmp_path / 'one.yaml'
    path.write_text(yaml.safe_dump(copy.deepcopy(data)))
    assert program('linkage-kc')([str(path), '--travel', '0']) == 2
    assert f'bushing.{key}: {said}' in capsys.readouterr().err
