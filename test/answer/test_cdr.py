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
import struct

from geometry_msgs.msg import PoseStamped
from hypothesis import given, HealthCheck, settings, strategies as st
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


# --- sensor_msgs/JointState read in place (cdr.joint_state_of) -----------------------------
# rosbags writes the bytes (either byte order: rclpy only writes little-endian) and rclpy's
# deserializer reads them too: joint_state_of must read what rclpy reads, field for field,
# and refuse what rclpy refuses. Names: any text but NUL (a ROS string ends at its first
# NUL, so no writer can send one; nor a lone surrogate, which is not UTF-8), empty, long,
# non-ASCII; values: any float64.
TEXT = st.characters(blacklist_categories=('Cs',), blacklist_characters='\x00')
NAMES = st.lists(st.one_of(st.text(TEXT, max_size=40),
                           st.text(alphabet='abc_-0123456789', min_size=60, max_size=300),
                           st.just('')), max_size=12)
FLOATS = st.floats(allow_nan=True, allow_infinity=True, width=64)


@st.composite
def joint_states(draw):
    names = draw(NAMES)
    n = len(names)
    msg = JointState(name=names,
                     position=draw(st.lists(FLOATS, min_size=0, max_size=n + 1)),
                     velocity=draw(st.lists(FLOATS, max_size=3)),
                     effort=draw(st.lists(FLOATS, max_size=3)))
    msg.header.stamp.sec = draw(st.integers(-2**31, 2**31 - 1))
    msg.header.stamp.nanosec = draw(st.integers(0, 2**32 - 1))
    msg.header.frame_id = draw(st.text(TEXT, max_size=20))
    return msg


def same_floats(a, b):
    """Equal as float64 bit patterns (NaN payloads and the sign of zero included)."""
    return np.array(a, dtype=float).tobytes() == np.array(b, dtype=float).tobytes()


@settings(deadline=None, max_examples=150, suppress_health_check=[HealthCheck.too_slow])
@given(msg=joint_states(), little=st.booleans())
def test_a_joint_state_is_read_in_place_as_rclpy_reads_it(msg, little):
    data = joint_state_bytes(msg, little)
    theirs = deserialize_message(data, JointState)
    read = cdr.joint_state_of(data)
    assert read.stamp == (theirs.header.stamp.sec, theirs.header.stamp.nanosec)
    assert read.name == tuple(theirs.name)
    assert same_floats(read.position, theirs.position)


@settings(deadline=None, max_examples=60, suppress_health_check=[HealthCheck.too_slow])
@given(msg=joint_states(), little=st.booleans(), cut=st.floats(0.0, 1.0, exclude_max=True))
def test_a_joint_state_cut_short_is_a_cdr_error_as_rclpy_refuses_it(msg, little, cut):
    data = joint_state_bytes(msg, little)
    short = data[:int(cut * len(data))]
    with pytest.raises(cdr.CdrError):
        cdr.from_cdr(cdr.JOINT_STATE, short)        # rclpy refuses it: the reference
    with pytest.raises(cdr.CdrError, match=f'^sensor_msgs/msg/JointState of {len(short)} '):
        cdr.joint_state_of(short)


def test_a_joint_state_with_a_sequence_longer_than_its_bytes_is_a_cdr_error():
    data = bytearray(cdr.joint_state_cdr((1, 2), 'base', ['a'], [0.5]))
    value = data.rindex(struct.pack('<d', 0.5))
    # position's count (1): just before its value, or before the padding that aligns it to 8
    at = next(at for at in (value - 4, value - 8)
              if int.from_bytes(data[at:at + 4], 'little') == 1)
    data[at:at + 4] = (2**32 - 1).to_bytes(4, 'little')
    with pytest.raises(cdr.CdrError, match='too short: 4294967295 doubles'):
        cdr.joint_state_of(bytes(data))
    with pytest.raises(cdr.CdrError, match='not CDR'):
        cdr.joint_state_of(b'\x07\x07\x00\x00' + bytes(data[4:]))


def joint_state_bytes(msg, little):
    """Return the CDR bytes of msg in the byte order asked, written by rosbags."""
    store = get_typestore(Stores.ROS2_JAZZY)
    kind = 'sensor_msgs/msg/JointState'
    fields = store.types[kind]
    header = store.types['std_msgs/msg/Header'](
        stamp=store.types['builtin_interfaces/msg/Time'](sec=msg.header.stamp.sec,
                                                         nanosec=msg.header.stamp.nanosec),
        frame_id=msg.header.frame_id)
    return bytes(store.serialize_cdr(fields(
        header=header, name=list(msg.name), position=np.array(msg.position, dtype=float),
        velocity=np.array(msg.velocity, dtype=float),
        effort=np.array(msg.effort, dtype=float)), kind, little_endian=little))
