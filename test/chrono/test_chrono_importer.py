# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Chrono::Vehicle suspension files imported as scenes (linkage_ros.chrono).

The expected values are today's bundled chrono_* scenes, typed by hand from the same Chrono
files (config/chrono): the same points (1e-12 m: the file's decimals, read twice) and the
same sweep (1e-9 deg: the same scene solved by the same code).
"""

import math
from pathlib import Path

from linkage_ros.chrono.files import import_file
from linkage_ros.core import load_scene, sweep
from linkage_ros.core.model.bundled import config_dir
from linkage_ros.core.model.scene import parse_scene
import numpy as np
import pytest
import yaml

CHRONO = config_dir() / 'chrono'
BUNDLED = {
    'chrono_generic_doublewishbone': 'generic/suspension/DoubleWishbone.json',
    'chrono_generic_macpherson': 'generic/suspension/MacPhersonStrut.json',
    'chrono_generic_multilink': 'generic/suspension/MultiLink.json',
    'chrono_hmmwv_doublewishbone_front': 'hmmwv/suspension/HMMWV_DoubleWishboneFront.json',
    'chrono_hmmwv_doublewishbone_rear': 'hmmwv/suspension/HMMWV_DoubleWishboneRear.json',
    'chrono_sedan_doublewishbone': 'sedan/suspension/Sedan_DoubleWishbone.json',
    'chrono_sedan_multilink': 'sedan/suspension/Sedan_MultiLink.json',
}
TRAVELS = np.arange(-80.0, 80.5, 1.0)


def imported(source, tmp_path, name='imported'):
    """Return the scene imported from a Chrono file (through the text that would be written)."""
    out = tmp_path / f'{name}.yaml'
    texts, _ = import_file(str(source), str(out))
    return parse_scene(yaml.safe_load(texts[str(out)]), source=str(out))


@pytest.mark.parametrize('bundled', sorted(BUNDLED))
def test_imported_scene_has_the_bundled_scenes_points(bundled, tmp_path):
    scene, expected = imported(CHRONO / BUNDLED[bundled], tmp_path), load_scene(bundled)
    assert scene.point_names == expected.point_names
    np.testing.assert_allclose(scene.points, expected.points, rtol=0, atol=1e-9)   # mm


@pytest.mark.parametrize('bundled', sorted(BUNDLED))
def test_imported_scene_sweeps_as_the_bundled_scene(bundled, tmp_path):
    scene, expected = imported(CHRONO / BUNDLED[bundled], tmp_path), load_scene(bundled)
    ours, theirs = sweep(scene, TRAVELS), sweep(expected, TRAVELS)
    assert ours.success and theirs.success
    np.testing.assert_allclose(np.degrees(ours.camber), np.degrees(theirs.camber), atol=1e-9)
    np.testing.assert_allclose(np.degrees(ours.toe), np.degrees(theirs.toe), atol=1e-9)


def test_camber_and_toe_of_a_real_file_import_as_the_design_angles(tmp_path):
    data = json_of(CHRONO / 'generic/suspension/DoubleWishbone.json')
    data['Camber Angle (deg)'], data['Toe Angle (deg)'] = 1.5, -0.4
    source = tmp_path / 'angled.json'
    source.write_text(json_dump(data))
    result = sweep(imported(source, tmp_path), [0.0])
    assert math.degrees(result.camber[0]) == pytest.approx(1.5, abs=1e-9)
    assert math.degrees(result.toe[0]) == pytest.approx(-0.4, abs=1e-9)


def test_generic_replica_of_the_hmmwv_front_sweeps_as_the_double_wishbone(tmp_path):
    # The same suspension rebuilt as bodies and joints; its joint quaternions have six
    # decimals, so the arm axes agree to about 1e-6 rad and the angles to 1e-4 deg.
    scene = imported(CHRONO / 'hmmwv/suspension/HMMWV_DoubleWishboneFront_replica.json',
                     tmp_path)
    expected = load_scene('chrono_hmmwv_doublewishbone_front')
    assert [c.type for c in scene.constraints] == ['circle', 'circle', 'sphere']
    ours, theirs = sweep(scene, TRAVELS), sweep(expected, TRAVELS)
    np.testing.assert_allclose(np.degrees(ours.camber), np.degrees(theirs.camber), atol=1e-4)
    np.testing.assert_allclose(np.degrees(ours.toe), np.degrees(theirs.toe), atol=1e-4)


def test_reduced_double_wishbone_imports_its_shock_as_a_spring_and_a_damper(tmp_path):
    scene = imported(CHRONO / 'hmmwv/suspension/HMMWV_DoubleWishboneReducedFront.json',
                     tmp_path)
    spring, damper = scene.elements
    assert (spring.type, damper.type) == ('spring', 'damper')
    assert spring.rate == pytest.approx(167062.0 / 1000.0)   # N/m -> N/mm
    assert spring.free_length == pytest.approx(339.0)
    assert spring.mount.kind == 'carrier'


def test_macpherson_spring_runs_along_the_strut(tmp_path):
    scene = imported(CHRONO / 'generic/suspension/MacPhersonStrut.json', tmp_path)
    assert {e.name: e.mount.kind for e in scene.elements} == {'Spring': 'along',
                                                              'Shock': 'carrier'}


def test_spring_curve_turns_into_a_force_table_with_chronos_sign(tmp_path):
    # Chrono: force (compression +) = -f(L - L0); the table: deflection L0 - L, force +
    # compressed. The generic curve is linear, 369150 N/m: 369.15 N/mm either way.
    scene = imported(CHRONO / 'generic/suspension/DoubleWishboneCurve.json', tmp_path)
    spring = scene.elements[0]
    assert np.all(np.diff(spring.force_table[:, 0]) > 0)
    rows = spring.force_table[spring.force_table[:, 0] != 0]
    assert len(rows) == 10 and np.all(rows[:, 1] * rows[:, 0] > 0)   # compression: force +
    np.testing.assert_allclose(rows[:, 1] / rows[:, 0], 369.15)


def test_length_stops_become_bump_and_rebound_stops(tmp_path):
    scene = imported(CHRONO / 'hmmwv/suspension/HMMWV_DoubleWishboneFront.json', tmp_path)
    stops = {e.name: e for e in scene.elements if e.is_stop}
    assert sorted(stops) == ['SpringBump', 'SpringRebound']
    assert stops['SpringBump'].free_length == pytest.approx(150.0)      # "Minimum Length"
    assert stops['SpringRebound'].free_length == pytest.approx(300.0)   # "Maximum Length"


def test_multilink_spring_off_its_links_line_is_left_out_with_a_note(tmp_path):
    out = tmp_path / 'ml.yaml'
    texts, summary = import_file(str(CHRONO / 'generic/suspension/MultiLink.json'), str(out))
    assert 'Spring: not imported' in summary and 'off the line' in texts[str(out)]
    assert 'elements' not in yaml.safe_load(texts[str(out)])


def test_bushing_data_becomes_the_arms_bushing_at_its_centre(tmp_path):
    out = tmp_path / 'b.yaml'
    texts, summary = import_file(
        str(CHRONO / 'hmmwv/suspension/HMMWV_DoubleWishboneFront_bushings.json'), str(out))
    bushing = yaml.safe_load(texts[str(out)])['constraints'][0]['bushing']
    assert bushing['axial'] == bushing['radial'] == 7e7            # N/m, an m scene
    assert bushing['conical'] == pytest.approx(1e5 * math.pi / 180)   # N m/rad -> N m/deg
    assert bushing['torsion'] == 0.0 and bushing['at'] == 'centre'
    loaded = parse_scene(yaml.safe_load(texts[str(out)]), source=str(out))
    arm = loaded.constraints[0].bushing
    assert arm.axial == pytest.approx(7e4) and arm.radial == pytest.approx(7e4)   # N/mm
    assert 'not yet used' not in summary


def test_vehicle_file_gives_left_and_mirrored_right_corners(tmp_path):
    from linkage_ros.core.model import load_vehicle
    out = tmp_path / 'hmmwv.yaml'
    texts, _ = import_file(str(CHRONO / 'hmmwv/vehicle/HMMWV_Vehicle.json'), str(out))
    for path, text in texts.items():
        Path(path).write_text(text)
    vehicle = load_vehicle(str(out))
    assert sorted(vehicle.corners) == ['front_left', 'front_right', 'rear_left', 'rear_right']
    left, right = vehicle.corners['front_left'], vehicle.corners['front_right']
    np.testing.assert_allclose(right.wheel_center, left.wheel_center * [1, -1, 1], atol=1e-9)
    assert yaml.safe_load(texts[str(out)])['wheelbase'] == pytest.approx(2 * 1.688965)
    # the front axle has a "Steering Index", the rear none: its tie rod is on the chassis
    assert vehicle.corners['front_left'].steered and not vehicle.corners['rear_left'].steered


def json_of(path):
    from linkage_ros.chrono.reader import read_chrono
    return read_chrono(path)


def json_dump(data):
    import json
    return json.dumps(data)


def test_axle_says_where_each_corners_bump_stop_engages(tmp_path):
    import subprocess
    import sys
    out = tmp_path / 'hmmwv.yaml'
    texts, _ = import_file(str(CHRONO / 'hmmwv/vehicle/HMMWV_Vehicle.json'), str(out))
    for path, text in texts.items():
        # the bump stop 100 mm nearer: engaged in bump within the sweep
        Path(path).write_text(text.replace('free_length: 0.15,', 'free_length: 0.25,'))
    run = subprocess.run([str(Path(sys.executable).parent / 'linkage-axle'), str(out),
                          '--heave', '-80:80:10'], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    for corner in ('front_left', 'front_right'):
        assert f'{corner}: stop SpringBump engages: it carries a force from travel 0 to 80 mm' \
            in run.stderr
        assert f'{corner}: stop SpringRebound does not engage' in run.stderr


def test_scene_header_names_its_source_file_and_template(tmp_path):
    source = CHRONO / 'generic/suspension/MacPhersonStrut.json'
    out = tmp_path / 'mp.yaml'
    texts, _ = import_file(str(source), str(out))
    first = texts[str(out)].splitlines()[0]
    assert first == f'# Chrono::Vehicle MacPhersonStrut imported by linkage-chrono from {source}'
    assert 'BSD-3-Clause' in texts[str(out)].splitlines()[1]


def test_force_table_survives_export_and_import(tmp_path):
    # the export drops the template file's "Spring Coefficient": Chrono takes a curve first
    from linkage_ros.chrono.files import export_file
    source, out = CHRONO / 'generic/suspension/DoubleWishboneCurve.json', tmp_path / 'c.yaml'
    out.write_text(import_file(str(source), str(out))[0][str(out)])
    (tmp_path / 'c.json').write_text(export_file(str(out))[0])
    back = imported(tmp_path / 'c.json', tmp_path, 'back')
    np.testing.assert_allclose(back.elements[0].force_table,
                               imported(source, tmp_path).elements[0].force_table, rtol=1e-12)


def test_wheel_radius_must_be_positive(tmp_path):
    from linkage_ros.chrono.reader import ChronoError
    with pytest.raises(ChronoError, match='--wheel-radius'):
        import_file(str(CHRONO / 'generic/suspension/DoubleWishbone.json'),
                    str(tmp_path / 'x.yaml'), wheel_radius=-0.3)
