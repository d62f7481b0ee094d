# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Vehicle files: four corners, right-hand side by mirroring, placed by offsets."""

from pathlib import Path

from linkage_ros.core.model import load_vehicle, SceneError, vehicle_dir
from linkage_ros.core.solve import sweep
import numpy as np
import pytest


def test_demo_vehicle_has_four_corners_with_mirrored_right_side():
    vehicle = load_vehicle('demo_vehicle')
    assert list(vehicle.corners) == ['front_left', 'front_right', 'rear_left', 'rear_right']
    left, right = vehicle.corners['front_left'], vehicle.corners['front_right']
    assert left.side == 'left' and right.side == 'right'
    assert right.wheel_center == pytest.approx(left.wheel_center * [1, -1, 1])
    assert left.wheel_center == pytest.approx([1400.0, 760.0, 300.0])   # offset applied


def test_mirrored_corners_solve_to_the_same_camber_and_toe():
    vehicle = load_vehicle('demo_vehicle')
    travels = [-40.0, 0.0, 40.0]
    left = sweep(vehicle.corners['rear_left'], travels)
    right = sweep(vehicle.corners['rear_right'], travels)
    assert right.camber == pytest.approx(left.camber, abs=1e-12)
    assert right.toe == pytest.approx(left.toe, abs=1e-12)
    assert np.max(right.residual) <= 1e-9


def test_vehicle_corner_with_bad_offset_names_the_field(tmp_path):
    path = tmp_path / 'car.yaml'
    path.write_text('corners:\n  front_left: {scene: five_link, offset: [1, 2]}\n')
    with pytest.raises(SceneError, match=r'corners\.front_left\.offset'):
        load_vehicle(path)


def test_vehicle_corner_name_must_be_a_ros_name(tmp_path):
    path = tmp_path / 'car.yaml'
    path.write_text('corners:\n  Front-Left: {scene: five_link}\n')
    with pytest.raises(SceneError, match="corners.Front-Left: corner name 'Front-Left' is not a "
                       'ROS name token'):
        load_vehicle(path)


def test_demo_vehicle_names_the_joint_states_joints_of_each_corner():
    assert load_vehicle('demo_vehicle').joints == {
        'front_left': ('front_left_travel', 'steering_rack'),
        'front_right': ('front_right_travel', 'steering_rack'),
        'rear_left': ('rear_left_travel', ''), 'rear_right': ('rear_right_travel', '')}


def test_a_joint_name_that_is_not_text_names_the_field(tmp_path):
    path = tmp_path / 'car.yaml'
    path.write_text('corners:\n  rear_left: {scene: five_link, travel_joint: [1]}\n')
    with pytest.raises(SceneError, match=r'corners\.rear_left\.travel_joint: expected a joint'):
        load_vehicle(path)


def test_a_rack_joint_on_a_corner_that_does_not_steer_is_refused(tmp_path):
    path = tmp_path / 'car.yaml'
    path.write_text('corners:\n  rear_left: {scene: five_link, rack_joint: steering_rack}\n')
    with pytest.raises(SceneError, match=r'rear_left\.rack_joint: .* no steer: rack link'):
        load_vehicle(path)


@pytest.mark.parametrize('scene', ["''", 'no_such_scene', 'missing.yaml', '.'])
def test_a_corner_scene_that_names_no_scene_file_names_the_vehicle_field(tmp_path, scene):
    # '' once read as the folder '.', and the error named '.' instead of the vehicle file
    path = tmp_path / 'car.yaml'
    path.write_text(f'corners:\n  rear_left: {{scene: {scene}}}\n')
    with pytest.raises(SceneError) as raised:
        load_vehicle(path)
    assert raised.value.source == str(path)
    assert raised.value.field == 'corners.rear_left.scene'
    assert raised.value.problem.startswith(repr(scene.strip("'")))


@pytest.mark.parametrize('name', ['', 'demo_vehicl', 'config'])
def test_a_vehicle_that_is_no_file_and_not_bundled_lists_the_bundled_ones(name):
    # '' is said to be empty, as an empty scene name is
    bundled = ', '.join(sorted(p.stem for p in vehicle_dir().glob('*.yaml')))
    with pytest.raises(SceneError, match=r"^'.*': vehicle: (.* not a bundled vehicle|empty: .*) "
                       rf'\(bundled: {bundled}\)$'):
        load_vehicle(name)


def test_a_corner_scene_path_is_read_from_the_vehicle_folder(tmp_path):
    (tmp_path / 'mine.yaml').write_text(
        (Path(__file__).parents[2] / 'config' / 'scenes' / 'five_link.yaml').read_text())
    path = tmp_path / 'car.yaml'
    path.write_text('corners:\n  rear_left: {scene: mine.yaml}\n')
    assert load_vehicle(path).corners['rear_left'].source == str(tmp_path / 'mine.yaml')


def test_a_misspelt_corner_key_is_named_with_the_key_it_resembles(tmp_path):
    # mirorr: true was ignored, and the right-hand corner silently was a left one
    path = tmp_path / 'car.yaml'
    path.write_text('corners:\n  rear_right: {scene: five_link, mirorr: true}\n')
    with pytest.raises(SceneError) as raised:
        load_vehicle(path)
    assert (raised.value.field, raised.value.problem) == (
        'corners.rear_right.mirorr', 'unknown key (did you mean mirror?)')


def test_a_misspelt_top_level_key_is_named_before_corners_is_said_missing(tmp_path):
    path = tmp_path / 'car.yaml'
    path.write_text('corner:\n  rear_left: {scene: five_link}\n')
    with pytest.raises(SceneError) as raised:
        load_vehicle(path)
    assert (raised.value.field, raised.value.problem) == (
        'corner', 'unknown key (did you mean corners?)')


def test_axle_keys_are_read_into_axles_and_free_keys_kept_in_extras(tmp_path):
    # wheelbase, cg_height and axles are core.model.vehicle_axles'; description, x_... the user's
    path = tmp_path / 'car.yaml'
    path.write_text('wheelbase: 2800\ncg_height: 550\n'
                    'axles: {front: {left: front_left, right: front_right}}\n'
                    'description: test car\nx_owner: me\n'
                    'corners:\n  front_left: {scene: double_wishbone}\n'
                    '  front_right: {scene: double_wishbone, mirror: true}\n')
    vehicle = load_vehicle(path)
    assert vehicle.extras == {'description': 'test car', 'x_owner': 'me'}
    assert (vehicle.axles.wheelbase, vehicle.axles.cg_height) == (2800.0, 550.0)
    assert list(vehicle.axles.axles) == ['front']


def test_a_vehicle_carries_its_corners_scene_warnings_once(tmp_path):
    stress = Path(__file__).parents[2] / 'config' / 'stress' / 'five_link_kilometres.yaml'
    path = tmp_path / 'car.yaml'
    path.write_text(f'corners:\n  rear_left: {{scene: {stress}}}\n'
                    f'  rear_right: {{scene: {stress}, mirror: true}}\n'
                    '  front_left: {scene: five_link}\n')
    vehicle = load_vehicle(path)
    assert vehicle.warnings == vehicle.corners['rear_left'].warnings
    assert len(vehicle.warnings) == 1 and 'implausible for a road vehicle' in vehicle.warnings[0]


def test_a_bare_name_is_the_bundled_vehicle_whatever_the_current_folder_holds(
        tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / 'demo_vehicle').write_text('corners:\n  rear_left: {scene: five_link}\n')
    assert list(load_vehicle('demo_vehicle').corners) == [
        'front_left', 'front_right', 'rear_left', 'rear_right']
    assert list(load_vehicle('./demo_vehicle').corners) == ['rear_left']


AXLE = 'axles: {front: {left: front_left, right: front_right}}\n'


@pytest.mark.parametrize('left_offset, right_offset, said', [
    # a right corner at +y: the mirrored scene moved 1520 mm left (coincident wheels)
    ([0, 0, 0], [0, 1520, 0], r'axles\.front\.right: corner front_right is a right wheel '
                              r'with its centre at y = 760 mm: a right wheel is at -y'),
    # a negative track: the left corner moved across
    ([0, -1520, 0], [0, 0, 0], r'axles\.front\.left: corner front_left is a left wheel with '
                               r'its centre at y = -760 mm'),
    # front and rear of one side taken for an axle: 2800 mm apart in x
    ([1400, 0, 0], [-1400, 0, 0], r'axles\.front: the wheel centres of front_left and '
                                  r'front_right are 2800 mm apart in x, more than 0\.1 x '
                                  r'their track of 1520 mm'),
    ([0, 0, 0], [0, -400, 0], r'apart in y \(middle off the centre plane\)'),
])
def test_an_axle_that_is_no_mirrored_pair_is_refused_at_load(tmp_path, left_offset,
                                                             right_offset, said):
    # Before, such an axle loaded: coincident wheels gave a NaN roll centre at a solved point.
    path = tmp_path / 'car.yaml'
    path.write_text(AXLE + 'corners:\n'
                    f'  front_left: {{scene: double_wishbone, offset: {left_offset}}}\n'
                    f'  front_right: {{scene: double_wishbone, mirror: true, '
                    f'offset: {right_offset}}}\n')
    with pytest.raises(SceneError, match=said):
        load_vehicle(path)


def test_an_axle_of_a_corner_and_its_mirror_image_loads_with_its_track(tmp_path):
    path = tmp_path / 'car.yaml'
    path.write_text(AXLE + 'corners:\n  front_left: {scene: double_wishbone}\n'
                    '  front_right: {scene: double_wishbone, mirror: true}\n')
    corners = load_vehicle(path).corners
    assert corners['front_left'].wheel_center[1] - corners['front_right'].wheel_center[1] \
        == pytest.approx(1520.0, abs=1e-9)
