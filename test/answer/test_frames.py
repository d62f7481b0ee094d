# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The TF frames of a solved corner (linkage_ros.core.measure.bodies, linkage_ros.answer.frames).

Each frame is checked against what it must carry, computed independently of the frame code:
the solved carrier joints (Continuation.joints), the scene's hardpoints and the rack.
"""

import math
from pathlib import Path

from linkage_ros.answer.cdr import pose_of, tf_message_cdr, transforms_of
from linkage_ros.answer.frames import CornerFrames, static_cdr, tf2_msgs_missing
from linkage_ros.answer.protocol import answer_outputs
from linkage_ros.core.measure import body_poses, corner_bodies
from linkage_ros.core.model import load_scene, parse_scene
from linkage_ros.core.solve import Continuation
import numpy as np
import pytest
import yaml

TRAVELS_MM = [-60.0, -25.0, 0.0, 35.0, 70.0]


def rotation(q):
    """Return the rotation matrix of a unit quaternion (x, y, z, w), written out (no library)."""
    x, y, z, w = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def frames_at(scene, travel, rack=None):
    """Return ({name: (origin mm, rotation)}, {constraint name: solved carrier joint mm})."""
    cont = Continuation(scene)
    solution = cont.solve(travel, rack)
    assert solution.success
    bodies = corner_bodies(scene)
    rows = body_poses(bodies, solution)
    frames = {name: (row[:3], rotation(row[3:])) for name, row in zip(bodies.names, rows)}
    joints = dict(zip([c.name for c in scene.constraints],
                      cont.joints(solution).values()))
    return frames, joints, solution


@pytest.mark.parametrize('scene_name', ['five_link', 'double_wishbone', 'macpherson'])
def test_the_carrier_frame_is_the_answered_pose_bit_for_bit(scene_name):
    scene = load_scene(scene_name)
    cont, frames = Continuation(scene), CornerFrames(scene, 'base_link')
    for travel in TRAVELS_MM:
        solution = cont.solve(travel)
        pose = {name: data for name, _, data in answer_outputs(solution, (7, 9), 'base_link')}
        (stamp, parent, child, translation, quaternion) = transforms_of(
            frames.tf_cdr(solution, (7, 9)))[0]
        assert (stamp, parent, child) == ((7, 9), 'base_link', 'wheel_carrier')
        assert (translation, quaternion) == pose_of(pose['wheel_carrier_pose'])


@pytest.mark.parametrize('scene_name', ['five_link', 'double_wishbone'])
def test_a_link_frame_sits_at_its_body_end_with_z_through_its_carrier_joint(scene_name):
    scene = load_scene(scene_name)
    for travel in TRAVELS_MM:
        frames, joints, _ = frames_at(scene, travel)
        for c in scene.constraints:
            if c.type != 'sphere':
                continue
            origin, rot = frames[c.name]
            length = np.linalg.norm(c.carrier - c.base[0])      # the link's, from the scene
            assert origin == pytest.approx(c.base[0], abs=1e-12)
            assert origin + length * rot[:, 2] == pytest.approx(joints[c.name], abs=1e-9)
            assert rot.T @ rot == pytest.approx(np.eye(3), abs=1e-14)


def test_a_link_frame_turns_by_the_smallest_rotation_from_design():
    # A ball-jointed link's spin about its own line is free: the frame takes none, so the
    # rotation from design is about an axis square to both directions of the link.
    scene = load_scene('five_link')
    design, _, _ = frames_at(scene, 0.0)
    moved, _, _ = frames_at(scene, 70.0)
    for c in scene.constraints:
        turn = moved[c.name][1] @ design[c.name][1].T
        angle = math.acos(min(1.0, (np.trace(turn) - 1) / 2))
        axis = np.array([turn[2, 1] - turn[1, 2], turn[0, 2] - turn[2, 0],
                         turn[1, 0] - turn[0, 1]]) / (2 * math.sin(angle))
        assert axis @ design[c.name][1][:, 2] == pytest.approx(0.0, abs=1e-12)
        assert axis @ moved[c.name][1][:, 2] == pytest.approx(0.0, abs=1e-12)


def test_an_arm_frame_turns_about_its_fixed_axis_carrying_its_ball_joint_rigidly():
    scene = load_scene('double_wishbone')
    arms = [c for c in scene.constraints if c.type == 'circle']
    assert len(arms) == 2
    for c in arms:
        axis = (c.base[1] - c.base[0]) / np.linalg.norm(c.base[1] - c.base[0])
        local = []
        for travel in TRAVELS_MM:
            frames, joints, _ = frames_at(scene, travel)
            origin, rot = frames[c.name]
            assert origin == pytest.approx(c.base[0], abs=1e-12)
            assert rot[:, 2] == pytest.approx(axis, abs=1e-14)
            local.append(rot.T @ (joints[c.name] - origin))
        # the ball joint keeps its place in the arm's frame: design (x, 0, z), x > 0
        arm = c.carrier - c.base[0]
        expected = [np.linalg.norm(np.cross(arm, axis)), 0.0, arm @ axis]
        assert np.array(local) == pytest.approx(np.tile(expected, (len(TRAVELS_MM), 1)),
                                                abs=1e-9)


def test_a_strut_frame_turns_with_the_carrier_about_its_fixed_top_mount():
    scene = load_scene('macpherson')
    (strut,) = [c for c in scene.constraints if c.type == 'line']
    for travel in TRAVELS_MM:
        frames, joints, solution = frames_at(scene, travel)
        origin, rot = frames[strut.name]
        assert origin == pytest.approx(strut.base[0], abs=1e-12)
        # its rotation from design is the carrier's; its z axis is the strut line through
        # the carrier joint
        design = (strut.carrier - strut.base[0]) / np.linalg.norm(strut.carrier - strut.base[0])
        assert rot[:, 2] == pytest.approx(solution.rotation @ design, abs=1e-14)
        along = joints[strut.name] - origin
        assert np.linalg.norm(np.cross(along, rot[:, 2])) == pytest.approx(0.0, abs=1e-9)


def test_a_steered_tie_rod_frame_moves_with_the_rack_along_y():
    scene = load_scene('double_wishbone')
    (rod,) = [c for c in scene.constraints if c.steer == 'rack']
    frames, joints, _ = frames_at(scene, 10.0, rack=12.5)
    origin, rot = frames[rod.name]
    assert origin == pytest.approx(rod.base[0] + [0.0, 12.5, 0.0], abs=1e-12)
    length = np.linalg.norm(rod.carrier - rod.base[0])
    assert origin + length * rot[:, 2] == pytest.approx(joints[rod.name], abs=1e-9)


def test_frame_names_come_from_the_corner_and_constraint_names():
    scene = load_scene('double_wishbone')
    assert CornerFrames(scene).names == ('wheel_carrier', 'upper_arm', 'lower_arm', 'tie_rod')
    vehicle = CornerFrames(scene, prefix='front_left/')
    assert vehicle.names == ('front_left/wheel_carrier', 'front_left/upper_arm',
                             'front_left/lower_arm', 'front_left/tie_rod')
    assert vehicle.static_transforms()[0][:2] == ('front_left/wheel_carrier',
                                                  'front_left/wheel')


def test_a_constraint_named_like_a_taken_frame_gets_its_index():
    data = yaml.safe_load(Path(load_scene('five_link').source).read_text())
    data['constraints'][0]['name'] = 'wheel_carrier'
    data['constraints'][1]['name'] = 'base_link'
    del data['kingpin'], data['elements']                # they name the links renamed here
    # (two constraints of one name are refused at load: test_names_as_tokens.py)
    frames = CornerFrames(parse_scene(data), 'base_link')
    assert frames.names == ('wheel_carrier', 'wheel_carrier_0', 'base_link_1', 'lower_front',
                            'lower_rear', 'tie_rod')


def test_the_wheel_frame_is_fixed_to_the_carrier_with_z_along_the_spin_axis():
    scene = load_scene('five_link')
    static = transforms_of(static_cdr([CornerFrames(scene)], (3, 4)))
    ((stamp, parent, child, translation, quaternion),) = static
    assert (stamp, parent, child, translation) == ((3, 4), 'wheel_carrier', 'wheel',
                                                   (0.0, 0.0, 0.0))
    spin = scene.wheel_center - scene.spin_axis_point
    assert rotation(quaternion)[:, 2] == pytest.approx(spin / np.linalg.norm(spin), abs=1e-15)


def test_tf_message_bytes_decode_with_rosbags_from_the_bundled_definition():
    # An independent CDR reader (rosbags), given the message definition the package ships.
    from linkage_ros.record.interfaces import message_definition
    from rosbags.typesys import get_types_from_msg, get_typestore, Stores
    store = get_typestore(Stores.ROS2_JAZZY)
    store.register(get_types_from_msg(message_definition('tf2_msgs/msg/TFMessage').split(
        '\n' + '=' * 80)[0], 'tf2_msgs/msg/TFMessage'))
    data = tf_message_cdr((5, 6), ['base_link', 'base_link'], ['a', 'front_left/bc'],
                          [(1.0, 2.0, 3.0), (-1.5, 0.25, 1e-9)],
                          [(0.0, 0.0, 0.0, 1.0), (0.5, -0.5, 0.5, 0.5)])
    msg = store.deserialize_cdr(data, 'tf2_msgs/msg/TFMessage')
    second = msg.transforms[1]
    assert (second.header.stamp.sec, second.header.stamp.nanosec) == (5, 6)
    assert (second.header.frame_id, second.child_frame_id) == ('base_link', 'front_left/bc')
    assert (second.transform.translation.x, second.transform.translation.z) == (-1.5, 1e-9)
    assert second.transform.rotation.w == 0.5
    assert store.serialize_cdr(msg, 'tf2_msgs/msg/TFMessage') == data


@pytest.mark.skipif(bool(tf2_msgs_missing()), reason='tf2_msgs is not installed here')
def test_tf_message_bytes_are_what_rclpy_serializes_where_tf2_msgs_is_installed():
    from rclpy.serialization import deserialize_message, serialize_message
    from tf2_msgs.msg import TFMessage
    scene = load_scene('double_wishbone')
    data = CornerFrames(scene).tf_cdr(Continuation(scene).solve(20.0, 5.0), (11, 12))
    msg = deserialize_message(data, TFMessage)
    assert [t.child_frame_id for t in msg.transforms] == list(CornerFrames(scene).names)
    assert transforms_of(serialize_message(msg)) == transforms_of(data)


def test_without_tf2_msgs_the_reason_names_it_and_the_way_to_build_it(monkeypatch):
    import sys
    monkeypatch.setitem(sys.modules, 'tf2_msgs', None)      # import tf2_msgs then fails
    monkeypatch.delitem(sys.modules, 'tf2_msgs.msg', raising=False)
    why = tf2_msgs_missing()
    assert why.startswith('tf2_msgs cannot be imported')
    assert 'linkage-tf2-msgs' in why and 'recorded but not published' in why
