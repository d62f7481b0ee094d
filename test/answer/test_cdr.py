# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
CDR layouts built in place (linkage_ros.answer.cdr): byte for byte what rclpy serializes.

Two independent codecs are the reference: rosbags' serialize_cdr (pure Python) gives the
bytes, for any frame_id or joint-name lengths (alignment padding changes with each), and
rclpy (rmw_fastrtps' XCDR1 codec) must read them back as the message it was given. (rclpy's
own bytes cannot be compared: it leaves padding bytes, and 8 bytes after a JointState,
uninitialised.)
"""

import array

from geometry_msgs.msg import PoseStamped
from linkage_ros.answer import cdr
import numpy as np
import pytest
from rclpy.serialization import deserialize_message
from rosbags.typesys import get_typestore, Stores
from sensor_msgs.msg import JointState

FRAMES = ['', 'a', 'ab', 'abc', 'base_link', 'odom_1234567', 'x' * 63]


@pytest.mark.parametrize('frame_id', FRAMES)
def test_a_pose_stamped_is_the_bytes_rosbags_serializes_and_rclpy_reads(frame_id):
    pose = PoseStamped()
    pose.header.stamp.sec, pose.header.stamp.nanosec = -3, 999_999_999
    pose.header.frame_id = frame_id
    position = (0.125, -0.76, 0.3)
    quaternion = (0.01, -0.02, 0.03, 0.99935)
    p, q = pose.pose.position, pose.pose.orientation
    p.x, p.y, p.z = position
    q.x, q.y, q.z, q.w = quaternion
    built = cdr.pose_stamped_cdr((-3, 999_999_999), frame_id, position, quaternion)
    assert built == reference(pose, 'geometry_msgs/msg/PoseStamped')
    assert deserialize_message(built, PoseStamped) == pose
    assert cdr.pose_of(built) == (position, quaternion)


@pytest.mark.parametrize('names, velocity, effort', [
    ([], (), ()),
    (['travel'], (), ()),
    (['front_left_travel', 'front_right_travel', 'rear_left_travel', 'rear_right_travel',
      'steering_rack'], (), ()),
    (['a', 'bc', 'def'], (0.5, -0.5, 0.0), ()),
    (['a', 'bc'], (), (1.0, 2.0)),
    (['abcdefg'], (3.0,), (4.0,)),
])
@pytest.mark.parametrize('frame_id', ['', 'base', 'base_link'])
def test_a_joint_state_is_the_bytes_rosbags_serializes_and_rclpy_reads(
        names, velocity, effort, frame_id):
    position = [0.001 * (i + 1) for i in range(len(names))]
    msg = JointState(name=names, position=position, velocity=list(velocity),
                     effort=list(effort))
    msg.header.stamp.sec, msg.header.stamp.nanosec = 12, 34
    msg.header.frame_id = frame_id
    built = cdr.joint_state_cdr((12, 34), frame_id, names, position, velocity, effort)
    assert built == reference(msg, 'sensor_msgs/msg/JointState')
    assert deserialize_message(built, JointState) == msg


def reference(msg, kind):
    """Return the CDR bytes rosbags serializes for the fields of an rclpy message."""
    store = get_typestore(Stores.ROS2_JAZZY)

    def convert(value, kind):
        if not hasattr(value, 'get_fields_and_field_types'):
            return np.array(value, dtype=float) if isinstance(value, array.array) else value
        fields = {name: convert(getattr(value, name), kind) for name, kind in
                  value.get_fields_and_field_types().items()}
        return store.types[kind.replace('/', '/msg/', 1)](**fields)

    return store.serialize_cdr(convert(msg, kind.replace('/msg/', '/')), kind)
