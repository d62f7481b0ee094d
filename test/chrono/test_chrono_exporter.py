# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Scenes exported to Chrono::Vehicle JSON (linkage-chrono export) and read back.

Round trip: import(export(scene)) has the scene's hardpoints (1e-9 mm: a division by 1000
and a multiplication back, each correctly rounded). The GenericWheeledSuspension keys are
those Chrono's reader asks for (GenericWheeledSuspension::Create, the manual's template).
"""

import json
from pathlib import Path
import subprocess
import sys

from linkage_ros.chrono.exporter import export_scene
from linkage_ros.chrono.files import export_file, import_file
from linkage_ros.chrono.reader import read_chrono
from linkage_ros.core import load_scene
from linkage_ros.core.model.bundled import bundled_scenes, config_dir
from linkage_ros.core.model.scene import parse_scene
import numpy as np
import pytest
import yaml

CHRONO = config_dir() / 'chrono'
PROGRAM = Path(sys.executable).parent / 'linkage-chrono'
SCENES = sorted(s for s in bundled_scenes())


def round_trip(name, tmp_path):
    text, _ = export_file(name)
    source = tmp_path / f'{name}.json'
    source.write_text(text)
    out = tmp_path / f'{name}.yaml'
    texts, _ = import_file(str(source), str(out))
    return parse_scene(yaml.safe_load(texts[str(out)]), source=str(out))


@pytest.mark.parametrize('name', SCENES)
def test_export_then_import_gives_every_bundled_scenes_hardpoints(name, tmp_path):
    scene, back = load_scene(name), round_trip(name, tmp_path)
    if scene.side == 'right':
        from linkage_ros.core.model import mirror
        scene = mirror(scene)
    assert sorted(c.type for c in back.constraints) == sorted(c.type for c in scene.constraints)
    np.testing.assert_allclose(back.wheel_center, scene.wheel_center, atol=1e-9)
    # every carrier point and body point comes back (arms: the same axis line)
    for c in scene.constraints:
        match = [b for b in back.constraints if np.allclose(b.carrier, c.carrier, atol=1e-9)]
        assert len(match) == 1, c.name
        np.testing.assert_allclose(match[0].base[0], c.base[0], atol=1e-9)
        if c.type == 'circle':
            np.testing.assert_allclose(match[0].base[1], c.base[1], atol=1e-9)


def test_five_link_goes_out_as_a_generic_suspension_with_all_chrono_needs(tmp_path):
    data, template, _ = export_scene(load_scene('five_link'))
    assert template == 'GenericWheeledSuspension'
    for key in ('Steerable', 'Independent', 'Spindle', 'Antiroll Body', 'Axle'):
        assert key in data, key
    for key in ('Mass', 'COM', 'Inertia', 'Radius', 'Width', 'Attachment Body'):
        assert key in data['Spindle'], key
    bodies = {b['Name'] for b in data['Bodies']}
    for body in data['Bodies']:
        assert set(body) >= {'Name', 'Mirrored', 'Position', 'Rotation', 'Mass',
                             'Moments of Inertia', 'Products of Inertia'}
    for joint in data['Joints']:
        assert set(joint) >= {'Name', 'Mirrored', 'Type', 'Body1', 'Body2', 'Position',
                              'Rotation'}
        assert {joint['Body1'], joint['Body2']} <= bodies | {'Chassis', 'Steering'}
    for dist in data['Distance Constraints']:
        assert set(dist) >= {'Name', 'Mirrored', 'Body1', 'Body2', 'Point1', 'Point2'}
    for tsda in data['TSDAs']:
        assert set(tsda) >= {'Name', 'Mirrored', 'Body1', 'Body2', 'Point1', 'Point2'}
        assert 'Spring Coefficient' in tsda or 'Damping Coefficient' in tsda
    assert data['Spindle']['Attachment Body'] in bodies
    # five links: the spring's and damper's links as bodies, the other three as distances
    assert len(data['Distance Constraints']) + len(bodies) - 1 == 5


def test_like_keeps_every_other_field_of_the_original(tmp_path):
    original = CHRONO / 'generic/suspension/DoubleWishbone.json'
    out = tmp_path / 'dw.yaml'
    texts, _ = import_file(str(original), str(out))
    out.write_text(texts[str(out)])
    text, _ = export_file(str(out), str(original))
    before, after = read_chrono(original), json.loads(text)
    assert after == before   # the same points came back: the file is json-equal


def test_like_replaces_the_points_of_a_moved_design(tmp_path):
    original = CHRONO / 'generic/suspension/DoubleWishbone.json'
    scene = load_scene('chrono_generic_doublewishbone')
    from linkage_ros.core.model import with_points
    moved = with_points(scene, scene.points + [0.0, 0.0, 5.0])
    data, _, _ = export_scene(moved, read_chrono(original), str(original))
    before = read_chrono(original)
    assert data['Upper Control Arm']['Location Upright'][2] == pytest.approx(
        before['Upper Control Arm']['Location Upright'][2] + 0.005)
    for key in ('Mass', 'COM', 'Moments of Inertia', 'Radius'):
        assert data['Upper Control Arm'][key] == before['Upper Control Arm'][key]
    assert data['Axle'] == before['Axle'] and data['Spring'] == before['Spring']


def test_like_of_another_template_is_refused_in_one_line(tmp_path):
    out = tmp_path / 'x.json'
    run = subprocess.run([str(PROGRAM), 'export', 'five_link', '-o', str(out), '--like',
                          str(CHRONO / 'generic/suspension/DoubleWishbone.json')],
                         capture_output=True, text=True)
    assert run.returncode == 2 and len(run.stderr.splitlines()) == 1
    assert 'DoubleWishbone' in run.stderr and not out.exists()


def test_arm_bushings_go_out_as_chronos_bushing_data_and_come_back(tmp_path):
    source = CHRONO / 'hmmwv/suspension/HMMWV_DoubleWishboneFront_bushings.json'
    out = tmp_path / 'b.yaml'
    out.write_text(import_file(str(source), str(out))[0][str(out)])
    text, _ = export_file(str(out))   # without --like: the bushings from the scene
    data = json.loads(text)
    original = read_chrono(source)['Upper Control Arm']['Bushing Data']
    ours = data['Upper Control Arm']['Bushing Data']
    assert ours['Stiffness Linear'] == pytest.approx(original['Stiffness Linear'])
    assert ours['Stiffness Rotational'] == pytest.approx(original['Stiffness Rotational'])
    assert ours['DOF']['Stiffness Rotational'] == 0.0
    (tmp_path / 'b.json').write_text(text)
    texts, _ = import_file(str(tmp_path / 'b.json'), str(tmp_path / 'back.yaml'))
    back = parse_scene(yaml.safe_load(texts[str(tmp_path / 'back.yaml')]), source='back')
    ours, theirs = back.constraints[0].bushing, load_scene(str(out)).constraints[0].bushing
    for key in ('axial', 'radial', 'torsion', 'conical'):   # N/mm, N m/deg: two conversions
        assert getattr(ours, key) == pytest.approx(getattr(theirs, key), rel=1e-12)
    assert ours.at == theirs.at == 'centre'


def test_like_of_a_generic_original_keeps_its_bodies_joints_and_springs(tmp_path):
    original = CHRONO / 'hmmwv/suspension/HMMWV_DoubleWishboneFront_replica.json'
    out = tmp_path / 'replica.yaml'
    out.write_text(import_file(str(original), str(out))[0][str(out)])
    text, _ = export_file(str(out), str(original))
    assert json.loads(text) == read_chrono(original)


def test_length_stops_fold_back_into_the_springs_minimum_and_maximum_length(tmp_path):
    original = CHRONO / 'hmmwv/suspension/HMMWV_DoubleWishboneFront.json'
    out = tmp_path / 'front.yaml'
    out.write_text(import_file(str(original), str(out))[0][str(out)])
    spring = json.loads(export_file(str(out))[0])['Spring']   # without --like
    before = read_chrono(original)['Spring']
    assert spring['Minimum Length'] == pytest.approx(before['Minimum Length'])
    assert spring['Maximum Length'] == pytest.approx(before['Maximum Length'])
    np.testing.assert_allclose(spring['Spring Curve Data'], before['Spring Curve Data'],
                               rtol=1e-12, atol=1e-12)
    assert 'Spring Coefficient' not in spring


def test_a_spring_or_shock_the_scene_lacks_goes_out_holding_nothing_and_stays_so(tmp_path):
    # The template's own file has a spring of 369149 N/m on another car's points: written
    # into a scene without springs it added a preloaded spring (and changed the compliance).
    first = json.loads(export_file('chrono_sedan_doublewishbone_bushings')[0])
    assert first['Spring']['Spring Coefficient'] == 0.0
    assert first['Shock']['Damping Coefficient'] == 0.0
    length = np.linalg.norm(np.subtract(first['Spring']['Location Chassis'],
                                        first['Spring']['Location Arm']))
    assert first['Spring']['Free Length'] == pytest.approx(length, rel=1e-15)
    source, out = tmp_path / 'one.json', tmp_path / 'one.yaml'
    source.write_text(json.dumps(first))
    texts, summary = import_file(str(source), str(out))
    out.write_text(texts[str(out)])
    spring = next(e for e in yaml.safe_load(texts[str(out)])['elements'] if e['name'] == 'Spring')
    assert 'rate' not in spring and 'force_table' not in spring   # a length only
    again = json.loads(export_file(str(out))[0])
    assert again['Spring']['Spring Coefficient'] == 0.0   # not the template file's rate
