# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node's joint_states input (sensor_msgs/JointState), over real DDS in process.

The parameter travel_joint names the joint whose position is the wheel travel (m, + = bump);
answers carry the JointState's header stamp, not the time of receipt.
"""

from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import sweep
from linkage_ros.ros.messages import status_values
from linkage_ros.ros.node import QOS
from linkage_ros.ros.testing import spin_until, stamp_ns
import numpy as np
import pytest
from sensor_msgs.msg import JointState

JOINT = 'wheel_travel_fl'


def joint_state(names, positions, sec=0, nanosec=0):
    msg = JointState(name=list(names), position=[float(p) for p in positions])
    msg.header.stamp.sec, msg.header.stamp.nanosec = sec, nanosec
    return msg


@pytest.fixture
def joint_states(probe):
    """Give a publisher of sensor_msgs/JointState on joint_states, in the probe's node."""
    return probe.node.create_publisher(JointState, 'joint_states', QOS)


def test_travel_joint_position_is_answered_like_the_core(suspension_node, executor, probe,
                                                         joint_states):
    suspension_node(travel_joint=JOINT)
    assert spin_until(executor, lambda: joint_states.get_subscription_count() > 0)
    joint_states.publish(joint_state(['steer_fl', JOINT, 'wheel_travel_fr'],
                                     [0.3, 0.035, -0.05]))
    assert spin_until(executor, lambda: probe.poses and probe.cambers)
    expected = sweep(load_scene('five_link'), np.array([35.0]))
    position = probe.poses[0].pose.position
    assert [position.x, position.y, position.z] == pytest.approx(
        expected.wheel_center[0] / 1000.0, abs=1e-9)
    assert probe.cambers[0] == pytest.approx(expected.camber[0], abs=1e-9)


def test_answers_to_a_joint_state_carry_its_header_stamp(suspension_node, executor, probe,
                                                         joint_states):
    suspension_node(travel_joint=JOINT)
    assert spin_until(executor, lambda: joint_states.get_subscription_count() > 0)
    joint_states.publish(joint_state([JOINT], [0.01], sec=42, nanosec=5))
    assert spin_until(executor, lambda: probe.poses)
    assert stamp_ns(probe.poses[0].header.stamp) == 42_000_000_005


def test_a_joint_state_without_the_travel_joint_changes_nothing(suspension_node, executor,
                                                                probe, joint_states):
    suspension_node(travel_joint=JOINT, diagnostic_period=0.05)
    assert spin_until(executor, lambda: joint_states.get_subscription_count() > 0)
    joint_states.publish(joint_state(['steer_fl', 'wheel_travel_fr'], [0.3, 0.02]))
    joint_states.publish(joint_state([JOINT], [], sec=1))      # named, but no position
    joint_states.publish(joint_state([JOINT], [0.01], sec=2))
    # One topic delivers in order: an answer to either of the first two would come first.
    assert spin_until(executor, lambda: probe.poses)
    assert [stamp_ns(p.header.stamp) for p in probe.poses] == [2_000_000_000]
    # The next report has counted one command, and the node has not failed any.
    count = len(probe.statuses)
    assert spin_until(executor, lambda: len(probe.statuses) > count)
    values = status_values(probe.statuses[-1])
    assert (values['commands_total'], values['failures_total']) == ('1', '0')


def test_without_travel_joint_joint_states_is_not_subscribed(suspension_node):
    node = suspension_node()
    assert node.get_parameter('travel_joint').value == ''
    assert '/joint_states' not in [s.topic_name for s in node.subscriptions]


def test_a_joint_state_input_is_recorded_with_its_type(suspension_node, executor, probe,
                                                       joint_states):
    records = []

    class Sink:
        """A sink that keeps the topic and type name of everything it is given."""

        def record(self, topic, type_name, msg, receive_ns, publish_ns):
            records.append((topic, type_name))

        def close(self):
            pass

    suspension_node(travel_joint=JOINT, sinks=[Sink()])
    assert spin_until(executor, lambda: joint_states.get_subscription_count() > 0)
    joint_states.publish(joint_state([JOINT], [0.01]))
    assert spin_until(executor, lambda: probe.poses)
    # after what the node sends at start (TF on: /tf_static and robot_description)
    started = [r for r in records if r[0] not in ('/tf_static', '/robot_description')]
    assert started[0] == ('/joint_states', 'sensor_msgs/msg/JointState')
