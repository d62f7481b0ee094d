# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node against samples that do not decode, over real DDS (raw bytes published).

Any participant on the domain can publish any bytes on a topic: a Float64 of 6 bytes (the CDR
header and 2 bytes), an empty sample, a JointState cut short. The node answers each with an
ERROR status that names the topic and the byte count (linkage_ros.answer.cdr.CdrError),
publishes no pose, and goes on answering (issue 23, item 1: struct.error ended the process,
and a vehicle node lost all four corners with it).
"""

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from geometry_msgs.msg import PoseStamped
from linkage_ros.core.model import load_scene, load_vehicle
from linkage_ros.ros.messages import status_values
from linkage_ros.ros.qos import QOS
from linkage_ros.ros.testing import spin_until
import pytest
from rclpy.serialization import serialize_message
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

SHORT = b'\x00\x01\x00\x00\x01\x02'       # CDR little-endian header + 2 bytes: 6 of 12
NOT_CDR = b'\x07\x07\x00\x00' + bytes(8)   # 12 bytes, an encapsulation that is not CDR
EMPTY = b''
BAD = {'6 bytes': (SHORT, 'too short: it needs 12 bytes'),
       'not CDR': (NOT_CDR, 'not CDR'),
       'empty': (EMPTY, 'not CDR')}
CORNERS = ['front_left', 'front_right', 'rear_left', 'rear_right']


def errors(statuses, since=0):
    return [s for s in statuses[since:] if s.level == DiagnosticStatus.ERROR]


@pytest.mark.parametrize('bad', list(BAD))
@pytest.mark.parametrize('topic, scene', [('wheel_travel', 'five_link'),
                                          ('steering_rack', 'double_wishbone')])
def test_a_float64_that_does_not_decode_is_an_error_naming_topic_and_size_and_no_pose(
        suspension_node, executor, probe, topic, scene, bad):
    suspension_node(scene=scene, diagnostic_period=3600.0)
    publisher = probe.node.create_publisher(Float64, topic, QOS)
    assert spin_until(executor, lambda: publisher.get_subscription_count() and probe.matched())
    data, why = BAD[bad]
    publisher.publish(data)
    assert spin_until(executor, lambda: probe.statuses)
    (error,) = errors(probe.statuses)
    assert error.message.startswith(f'/{topic}: std_msgs/Float64 of {len(data)} bytes: ')
    assert why in error.message
    assert (status_values(error)['failures'], status_values(error)['commands']) == ('1', '1')
    # No pose for it, and the node answers on: the next good command is solved.
    probe.send(0.02)
    assert spin_until(executor, lambda: probe.poses and len(probe.statuses) == 2)
    assert len(probe.poses) == 1 and probe.statuses[1].level == DiagnosticStatus.OK
    design_z = float(load_scene(scene).wheel_center[2]) / 1000.0
    assert probe.poses[0].pose.position.z == pytest.approx(design_z + 0.02, abs=1e-9)


def test_a_joint_state_that_does_not_decode_is_an_error_naming_topic_and_size(
        suspension_node, executor, probe):
    suspension_node(travel_joint='wheel', diagnostic_period=3600.0)
    joints = probe.node.create_publisher(JointState, 'joint_states', QOS)
    assert spin_until(executor, lambda: joints.get_subscription_count() and probe.matched())
    whole = serialize_message(JointState(name=['wheel'], position=[0.01]))
    cut = whole[:len(whole) - 9]      # rclpy writes 8 bytes past the end: effort's count cut
    joints.publish(cut)
    assert spin_until(executor, lambda: probe.statuses)
    (error,) = errors(probe.statuses)
    # read in place (answer/cdr.joint_state_of), which says how many bytes it needed
    assert error.message.startswith(
        f'/joint_states: sensor_msgs/msg/JointState of {len(cut)} bytes: too short: it needs '
        f'at least {len(cut) + 1} bytes')
    joints.publish(whole)
    assert spin_until(executor, lambda: probe.poses)
    assert len(probe.poses) == 1


class Vehicle:
    """Publishers of every input of demo_vehicle's corners, and their poses, on one node."""

    def __init__(self, node):
        self.travel = {c: node.create_publisher(Float64, f'{c}/wheel_travel', QOS)
                       for c in CORNERS}
        self.rack = {c: node.create_publisher(Float64, f'{c}/steering_rack', QOS)
                     for c in CORNERS[:2]}
        self.joints = node.create_publisher(JointState, 'joint_states', QOS)
        self.poses = {c: [] for c in CORNERS}
        for corner in CORNERS:
            node.create_subscription(PoseStamped, f'{corner}/wheel_carrier_pose',
                                     self.poses[corner].append, QOS)
        self.statuses = []
        node.create_subscription(DiagnosticArray, '/diagnostics',
                                 lambda m: self.statuses.extend(m.status), QOS)

    def publishers(self):
        return [*self.travel.values(), *self.rack.values(), self.joints]


def test_a_vehicle_node_answers_every_corner_after_bad_bytes_on_each_of_its_inputs(
        suspension_node, executor, probe):
    suspension_node(vehicle='demo_vehicle', diagnostic_period=3600.0)
    vehicle = Vehicle(probe.node)
    assert spin_until(executor, lambda: all(p.get_subscription_count()
                                            for p in vehicle.publishers()))
    for publisher in vehicle.publishers():
        publisher.publish(SHORT)
    # Per corner: its wheel_travel, its steering_rack if it steers, and the vehicle's
    # joint_states, which names every corner's travel joint.
    expected = {'front_left': 3, 'front_right': 3, 'rear_left': 2, 'rear_right': 2}
    assert spin_until(executor, lambda: len(errors(vehicle.statuses)) == sum(
        expected.values()))
    by_corner = {c: [s.message for s in errors(vehicle.statuses) if s.name.endswith(f': {c}')]
                 for c in CORNERS}
    assert {c: len(m) for c, m in by_corner.items()} == expected
    assert all('6 bytes' in m for messages in by_corner.values() for m in messages)
    assert any(m.startswith('/front_right/steering_rack: ') for m in by_corner['front_right'])
    assert any(m.startswith('/joint_states: sensor_msgs/msg/JointState of 6 bytes')
               for m in by_corner['rear_left'])
    # Every corner still answers, by its own topic and by the vehicle's joint_states.
    for corner in CORNERS:
        vehicle.travel[corner].publish(Float64(data=0.01))
    vehicle.joints.publish(JointState(name=[f'{c}_travel' for c in CORNERS],
                                      position=[0.02] * 4))
    assert spin_until(executor, lambda: all(len(vehicle.poses[c]) == 2 for c in CORNERS))
    demo = load_vehicle('demo_vehicle')
    for corner in CORNERS:
        design_z = float(demo.corners[corner].wheel_center[2]) / 1000.0
        assert [p.pose.position.z for p in vehicle.poses[corner]] == pytest.approx(
            [design_z + 0.01, design_z + 0.02], abs=1e-9)
