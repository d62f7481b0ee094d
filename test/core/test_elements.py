# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Springs, dampers and lengths: their lengths, motion ratios, forces and wheel rates.

Every quantity is checked against a computation of this file's own, from the scene file as
YAML and the solved joints only: an arm's rotation angle recovered from its ball joint and the
point turned by it (scipy's Rotation), a link's point at its fraction of the link, a carrier
point placed by the pose's quaternion; the ratios by central differences of those lengths.
"""

import csv
import io
from pathlib import Path
import re

from linkage_ros.core.measure import element_values, ElementValues, prepare, values_at
from linkage_ros.core.model import (bundled_scenes, load_scene, load_vehicle, mirror, translate,
                                    UNITS_TO_MM)
from linkage_ros.core.solve import Continuation, sweep, travel_range
from linkage_ros.tools.sweep import main
import numpy as np
import pytest
from scipy.spatial.transform import Rotation
import yaml

WITH_ELEMENTS = [name for name in bundled_scenes() if load_scene(name).elements]
TRAVEL = travel_range(-60.0, 60.0, 20.0)
H_RATIO = 0.01    # mm: central difference of lengths held to ~1e-10 mm: error ~5e-9
H_RATE = 0.5      # mm: second difference: error ~2e-9 /mm from rounding, O(H^2) 1e-12


def scene_file(scene):
    data = yaml.safe_load(Path(scene.source).read_text())
    return data, UNITS_TO_MM[data['units']]


def unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def lengths_by_hand(scene, travels, rack=0.0):
    """Lengths (n, k) mm of the scene's elements, from its YAML and the solved joints."""
    data, scale = scene_file(scene)
    result = sweep(scene, travels, rack=rack)
    assert result.success
    names = [c['name'] for c in data['constraints']]
    joints = result.joints   # (n, m, 3) in constraint order
    columns = []
    for item in data['elements']:
        if 'along' in item:
            i = names.index(item['along'])
            body = np.array(data['constraints'][i]['base']) * scale
            point = joints[:, i]
        else:
            body = np.array(item['body']) * scale
            point = moving_point(item, data, scale, names, result, scene, rack)
        columns.append(np.linalg.norm(point - body, axis=1))
    return np.column_stack(columns)


def moving_point(item, data, scale, names, result, scene, rack):
    """Place the element's moving point at every row of the sweep result, mm."""
    if 'carrier' in item:
        turn = Rotation.from_quat(result.quaternion)
        return result.wheel_center + turn.apply(np.array(item['carrier']) * scale
                                                - scene.wheel_center)
    point = np.array(item['point']) * scale
    if 'arm' in item:
        i = names.index(item['arm'])
        a0, a1 = (np.array(p) * scale for p in data['constraints'][i]['axis'])
        joint0 = np.array(data['constraints'][i]['carrier']) * scale
        u = unit(a1 - a0)
        before = (joint0 - a0) - ((joint0 - a0) @ u) * u
        after = (result.joints[:, i] - a0) - ((result.joints[:, i] - a0) @ u)[:, None] * u
        angle = np.arctan2(np.cross(before, after) @ u, after @ before)
        return a0 + Rotation.from_rotvec(angle[:, None] * u).apply(point - a0)
    i = names.index(item['link'])
    link = data['constraints'][i]
    base, end = np.array(link['base']) * scale, np.array(link['carrier']) * scale
    fraction = np.linalg.norm(point - base) / np.linalg.norm(end - base)
    if link.get('steer') == 'rack':
        base = base + [0.0, rack, 0.0]
    return base + fraction * (result.joints[:, i] - base)


def exact(scene, travels, rack=0.0):
    result = sweep(scene, travels, rack=rack)
    return element_values(scene, result.wheel_center, result.rotation, rack)


@pytest.mark.parametrize('name', WITH_ELEMENTS)
def test_lengths_match_the_points_placed_by_hand(name):
    scene = load_scene(name)
    assert exact(scene, TRAVEL).length == pytest.approx(lengths_by_hand(scene, TRAVEL),
                                                        abs=1e-6)


@pytest.mark.parametrize('name', WITH_ELEMENTS)
def test_motion_ratios_match_central_differences_of_the_lengths(name):
    scene = load_scene(name)
    numeric = (lengths_by_hand(scene, TRAVEL + H_RATIO)
               - lengths_by_hand(scene, TRAVEL - H_RATIO)) / (2 * H_RATIO)
    assert exact(scene, TRAVEL).ratio == pytest.approx(numeric, abs=1e-7)


@pytest.mark.parametrize('name', WITH_ELEMENTS)
def test_ratio_rates_match_second_differences_of_the_lengths(name):
    scene = load_scene(name)
    numeric = (lengths_by_hand(scene, TRAVEL + H_RATE) - 2 * lengths_by_hand(scene, TRAVEL)
               + lengths_by_hand(scene, TRAVEL - H_RATE)) / H_RATE**2
    assert exact(scene, TRAVEL).ratio_rate == pytest.approx(numeric, abs=1e-8)


def test_double_wishbone_and_five_link_have_a_spring_and_a_damper_macpherson_its_strut():
    kinds = {name: {e.type: e.mount.kind for e in load_scene(name).elements}
             for name in ('double_wishbone', 'five_link', 'macpherson')}
    assert kinds == {'double_wishbone': {'damper': 'arm', 'spring': 'arm'},
                     'five_link': {'damper': 'link', 'spring': 'link'},
                     'macpherson': {'damper': 'along'}}


@pytest.fixture
def every_mount(tmp_path):
    """double_wishbone with an element on each kind of mount, the tie rod's steered."""
    data = yaml.safe_load((Path(load_scene('double_wishbone').source)).read_text())
    data['elements'] += [
        {'name': 'on_carrier', 'type': 'length', 'body': [100.0, 400.0, 600.0],
         'carrier': [-60.0, 650.0, 420.0]},
        {'name': 'on_upper_arm', 'type': 'length', 'body': [0.0, 300.0, 700.0],
         'arm': 'upper_arm', 'point': [-40.0, 500.0, 470.0]},
        {'name': 'on_tie_rod', 'type': 'spring', 'body': [-200.0, 450.0, 50.0],
         'link': 'tie_rod', 'point': [-145.0, 495.0, 255.0], 'rate': 20.0,
         'free_length': 300.0}]
    path = tmp_path / 'every_mount.yaml'
    path.write_text(yaml.safe_dump(data))
    return load_scene(path)


@pytest.mark.parametrize('rack', [0.0, 8.0])
def test_every_kind_of_mount_at_a_steering_rack_matches_by_hand(every_mount, rack):
    got = exact(every_mount, TRAVEL, rack)
    assert got.length == pytest.approx(lengths_by_hand(every_mount, TRAVEL, rack), abs=1e-6)
    numeric = (lengths_by_hand(every_mount, TRAVEL + H_RATIO, rack)
               - lengths_by_hand(every_mount, TRAVEL - H_RATIO, rack)) / (2 * H_RATIO)
    assert got.ratio == pytest.approx(numeric, abs=1e-7)
    second = (lengths_by_hand(every_mount, TRAVEL + H_RATE, rack)
              - 2 * lengths_by_hand(every_mount, TRAVEL, rack)
              + lengths_by_hand(every_mount, TRAVEL - H_RATE, rack)) / H_RATE**2
    assert got.ratio_rate == pytest.approx(second, abs=1e-8)


def spring_by_hand(scene, travels, column):
    """Spring force (N, + = compressed) and energy (N mm) from lengths by hand."""
    spring = scene.elements[column]
    stretch = lengths_by_hand(scene, travels)[:, column] - spring.free_length
    return -spring.rate * stretch, 0.5 * spring.rate * stretch**2


@pytest.mark.parametrize('name', ['double_wishbone', 'five_link'])
def test_wheel_rate_is_the_derivative_of_the_wheel_load_the_spring_carries(name):
    # The wheel load W = -F dL/dz (virtual work: F compresses the spring, dL/dz < 0 in bump);
    # the wheel rate is dW/dz, here by central differences of W from lengths by hand.
    scene = load_scene(name)
    column = [e.type for e in scene.elements].index('spring')

    def load(travels):
        ratio = (lengths_by_hand(scene, travels + H_RATIO)
                 - lengths_by_hand(scene, travels - H_RATIO))[:, column] / (2 * H_RATIO)
        return -spring_by_hand(scene, travels, column)[0] * ratio

    numeric = (load(TRAVEL + H_RATE) - load(TRAVEL - H_RATE)) / (2 * H_RATE)
    assert exact(scene, TRAVEL).wheel_rate[:, column] == pytest.approx(numeric, rel=1e-5)


@pytest.mark.parametrize('name', ['double_wishbone', 'five_link'])
def test_wheel_rate_is_the_second_derivative_of_the_spring_energy(name):
    scene = load_scene(name)
    column = [e.type for e in scene.elements].index('spring')
    energy = [spring_by_hand(scene, TRAVEL + h, column)[1] for h in (-H_RATE, 0.0, H_RATE)]
    numeric = (energy[0] - 2 * energy[1] + energy[2]) / H_RATE**2
    got = exact(scene, TRAVEL)
    assert got.wheel_rate[:, column] == pytest.approx(numeric, rel=1e-6)
    assert got.force[:, column] == pytest.approx(spring_by_hand(scene, TRAVEL, column)[0],
                                                 abs=1e-4)


def test_force_and_wheel_rate_are_nan_for_an_element_without_a_rate():
    got = exact(load_scene('double_wishbone'), TRAVEL)   # damper, spring
    assert np.isnan(got.force[:, 0]).all() and np.isnan(got.wheel_rate[:, 0]).all()
    assert np.isfinite(got.force[:, 1]).all()


def test_a_spring_on_the_lower_arm_is_compressed_in_bump_at_about_its_lever_ratio():
    # The double wishbone's spring seat is 270 mm out along a 450 mm lower arm, its axis
    # nearly vertical: dL/dz is close to -270/450 = -0.6 and the spring shortens in bump.
    got = exact(load_scene('double_wishbone'), TRAVEL)
    assert np.all(np.diff(got.length[:, 1]) < 0)
    assert got.ratio[:, 1] == pytest.approx(-0.6, abs=0.05)


def test_a_right_hand_corner_mirrors_its_elements_and_an_offset_moves_them():
    left = load_scene('double_wishbone')
    right = translate(mirror(left), [1400.0, 0.0, 50.0])
    assert right.elements[0].body == pytest.approx(left.elements[0].body * [1, -1, 1]
                                                   + [1400.0, 0.0, 50.0])
    for quantity in ('length', 'ratio', 'ratio_rate', 'wheel_rate'):
        assert getattr(exact(right, TRAVEL), quantity) == pytest.approx(
            getattr(exact(left, TRAVEL), quantity), abs=1e-9, nan_ok=True)


def test_vehicle_corners_carry_their_scenes_elements():
    vehicle = load_vehicle('demo_vehicle')
    assert [e.name for e in vehicle.corners['rear_right'].elements] == ['damper', 'spring']


def test_sweep_elements_columns_hold_the_element_values(capsys):
    assert main(['five_link', '--elements', '--travel', '-60:60:20']) == 0
    rows = list(csv.DictReader(io.StringIO(capsys.readouterr().out)))
    assert list(rows[0])[-6:] == ['damper_length_mm', 'damper_ratio', 'spring_length_mm',
                                  'spring_ratio', 'spring_force_N',
                                  'spring_wheel_rate_N_per_mm']
    got = exact(load_scene('five_link'), TRAVEL)
    table = np.array([[float(row[c]) for c in list(rows[0])[-6:]] for row in rows])
    expected = np.column_stack((got.length[:, 0], got.ratio[:, 0], got.length[:, 1],
                                got.ratio[:, 1], got.force[:, 1], got.wheel_rate[:, 1]))
    assert table == pytest.approx(expected, rel=1e-9)   # written to 10 significant digits


def test_one_command_at_a_time_with_the_solves_jacobian_gives_the_batch_values():
    # The node's path: each answer's pose and the Jacobian the solve already holds.
    scene = load_scene('double_wishbone')
    cont = Continuation(scene)
    model = prepare(scene, cont.mech)
    batch = exact(scene, TRAVEL, rack=6.0)
    for i, travel in enumerate(TRAVEL):
        answer = cont.solve(travel, 6.0)
        one = values_at(model, answer.wheel_center, answer.rotation, answer.rack,
                        cont.jacobian)
        for row, quantity in enumerate(ElementValues._fields):
            assert one[row] == pytest.approx(getattr(batch, quantity)[i], rel=1e-9,
                                             nan_ok=True)


def test_a_singular_jacobian_gives_nan_rates_and_the_length_not_an_exception():
    scene = load_scene('five_link')
    got = element_values(scene, scene.wheel_center, np.eye(3), jac=np.zeros((5, 6)))
    assert np.isfinite(got.length).all()
    assert np.isnan(got.ratio).all() and np.isnan(got.wheel_rate[:, 1]).all()


def test_the_python_of_doc_elements_runs_as_written(capsys):
    doc = (Path(__file__).resolve().parents[2] / 'doc' / 'elements.md').read_text()
    (code,) = re.findall(r'```python\n(.*?)```', doc, re.S)
    exec(compile(code, 'doc/elements.md', 'exec'), {'__name__': '__main__'})
    printed = capsys.readouterr().out.split('\n')
    assert printed[0].startswith('[') and len(printed) > 3


def spring_through_its_body_point(tmp_path, travel=40.0):
    """Return double_wishbone with its spring's body point where its seat is at travel (mm)."""
    from linkage_ros.core.measure import guidance_rows, mount_motion, mount_table, pose_batch
    from linkage_ros.core.solve import compile_scene
    scene = load_scene('double_wishbone')
    mech = compile_scene(scene)
    at = sweep(scene, [travel])
    seat = mount_motion(guidance_rows(scene, mech), mount_table(scene, [scene.elements[1].mount]),
                        pose_batch(mech, at.wheel_center, at.rotation, at.rack))[0][0, 0]
    data, _ = scene_file(scene)
    data['elements'][1]['body'] = seat.tolist()
    (tmp_path / 'through.yaml').write_text(yaml.safe_dump(data))
    return tmp_path / 'through.yaml'


def test_a_spring_whose_ends_pass_through_each_other_is_nan_from_there_not_a_huge_rate(
        tmp_path):
    # Before: -9.2e14 N/mm where the seat met the body point (1 / L of round-off), then a
    # force that fell again as the "spring" turned inside out.
    scene = load_scene(spring_through_its_body_point(tmp_path))
    travels = travel_range(30.0, 50.0, 2.0)
    result = sweep(scene, travels)
    got = element_values(scene, result.wheel_center, result.rotation)
    before, after = travels < 40.0, travels >= 40.0
    for quantity in ElementValues._fields:
        assert np.isnan(getattr(got, quantity)[after, 1]).all(), quantity
    assert np.isfinite(got.wheel_rate[before, 1]).all()
    assert np.abs(got.wheel_rate[before, 1]).max() < 100.0   # k ratio^2 ~ 60 x 0.34 N/mm
    assert got.length[before, 1] == pytest.approx(1.16 * (40.0 - travels[before]) / 2,
                                                  rel=0.01)   # 0.58 mm per mm of travel
    assert np.isfinite(got.length[:, 0]).all()   # the damper is not affected
    cont = Continuation(scene)                   # the node's path agrees
    model = prepare(scene, cont.mech)
    answer = cont.solve(44.0)
    assert np.isnan(values_at(model, answer.wheel_center, answer.rotation, answer.rack,
                              cont.jacobian)[:, 1]).all()


def test_sweep_warns_once_naming_the_element_and_the_travels_where_its_ends_cross(
        tmp_path, capsys):
    path = spring_through_its_body_point(tmp_path)
    code = main([str(path), '--elements', '--travel', '30:50:2'])
    out, err = capsys.readouterr()
    rows = list(csv.DictReader(io.StringIO(out)))
    assert code == 0 and len(rows) == 11
    assert [row['spring_wheel_rate_N_per_mm'] for row in rows[5:]] == ['nan'] * 6
    assert err.count('element spring') == 1
    assert ('linkage-sweep: warning: double_wishbone: element spring: its ends meet or pass '
            'through each other at 6 of 11 positions, travel 40 to 50 mm: its length, ratio, '
            'force and wheel rate are NaN there (doc/elements.md)\n') in err
