# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Fuzzed commands to an in-process suspension_node: arbitrary JointState and Float64 messages.

The node (travel_joint set, the plugin's fixtures) must never crash, never publish a pose,
camber or toe that is not finite, and answer every command with a pose or an ERROR status:
a Float64 is always a command; a JointState is one when it names the travel joint and has a
position for it (the first entry of that name), else it is not answered. Travel within the
scene's range (|travel| <= 50 mm) must be solved; non-finite or beyond 1 m must be refused.
"""

import math

from hypothesis import given, HealthCheck, settings, strategies as st
from linkage_ros.core.model import load_scene
import pytest

JOINT = 'wheel'
DESIGN_Z_M = 0.001 * float(load_scene('five_link').wheel_center[2])
FUZZ = settings(deadline=None, database=None, max_examples=60,
                suppress_health_check=[HealthCheck.function_scoped_fixture,
                                       HealthCheck.too_slow])
# Any float64, and values near the scene's travel range (m).
travels = st.floats() | st.floats(-0.2, 0.2) | st.sampled_from(
    [0.0, -0.0, 0.05, -0.05, 1e308, -1e308, 5e-324, math.inf, -math.inf, math.nan, 1.0])
names = st.sampled_from([JOINT, 'other', '', 'wheel ', 'WHEEL', 'steering_rack']) | st.text(
    st.characters(blacklist_categories=('Cs',), blacklist_characters='\x00'), max_size=6)
joint_states = st.builds(
    lambda n, p, v, e: (n, p, v, e), st.lists(names, max_size=4), st.lists(travels, max_size=4),
    st.lists(travels, max_size=4), st.lists(travels, max_size=4))
commands = st.lists(st.tuples(st.just('float64'), travels) | st.tuples(
    st.just('joint_states'), joint_states), min_size=1, max_size=6)


def command_travel(kind, value):
    """Return the travel (m) a message commands, or None if it is not a command."""
    if kind == 'float64':
        return value
    name, position, _, _ = value
    if JOINT not in name or name.index(JOINT) >= len(position):
        return None
    return position[name.index(JOINT)]


def finite_pose(pose):
    p, q = pose.pose.position, pose.pose.orientation
    return all(math.isfinite(v) for v in (p.x, p.y, p.z, q.x, q.y, q.z, q.w))


@pytest.fixture
def fuzz_node(suspension_node, probe, executor):
    """Return (probe, JointState publisher) for a node with travel_joint and no periodic report."""
    from sensor_msgs.msg import JointState

    from linkage_ros.ros.node import QOS
    from linkage_ros.ros.testing import spin_until
    suspension_node(travel_joint=JOINT, diagnostic_period=3600.0)
    joints = probe.node.create_publisher(JointState, 'joint_states', QOS)
    assert spin_until(executor, lambda: probe.matched() and joints.get_subscription_count())
    return probe, joints


@FUZZ
@given(messages=commands)
def test_any_command_is_answered_by_a_finite_pose_or_an_error_status(fuzz_node, executor,
                                                                     messages):
    from diagnostic_msgs.msg import DiagnosticStatus
    from sensor_msgs.msg import JointState

    from linkage_ros.ros.testing import spin_until
    probe, joints = fuzz_node
    for kind, value in messages:
        travel = command_travel(kind, value)
        before = (len(probe.poses), len(probe.cambers), len(probe.toes), len(probe.statuses))
        if kind == 'float64':
            probe.send(value)
        else:
            name, position, velocity, effort = value
            joints.publish(JointState(name=name, position=position, velocity=velocity,
                                      effort=effort))
        if travel is None:
            continue

        def errors():
            return [s for s in probe.statuses[before[3]:]
                    if s.level == DiagnosticStatus.ERROR]

        def answered():
            return min(len(probe.poses) - before[0], len(probe.cambers) - before[1],
                       len(probe.toes) - before[2]) > 0 or errors()

        assert spin_until(executor, answered, 10.0), (kind, value)
        solved = len(probe.poses) > before[0]
        assert solved != bool(errors()), (kind, value)
        if solved:
            assert finite_pose(probe.poses[-1]), probe.poses[-1]
            assert math.isfinite(probe.cambers[-1]) and math.isfinite(probe.toes[-1])
        if math.isfinite(travel) and abs(travel) <= 0.05:
            assert solved, (kind, value, errors()[0].message)
        if not math.isfinite(travel) or abs(travel) > 1.0:
            assert not solved, (kind, value)
    # Travel 0 last, answered by the design pose: nothing of this example is still on its
    # way, and every pose, camber and toe that came was finite.
    count = len(probe.poses)
    probe.send(0.0)
    assert spin_until(executor, lambda: len(probe.poses) > count)
    assert len(probe.poses) == count + 1
    assert probe.poses[-1].pose.position.z == pytest.approx(DESIGN_Z_M, abs=1e-9)
    assert all(finite_pose(p) for p in probe.poses)
    assert all(math.isfinite(v) for v in probe.cambers + probe.toes)


def test_random_bytes_on_every_input_of_a_vehicle_node_for_10_s_leave_it_answering(
        suspension_node, probe, executor):
    # Issue 23's fuzz: random byte strings of 0 to 64 bytes, raw, on every topic the node
    # subscribes to, for 10 s. The node must stay up (an exception in a callback would come
    # out of spin_once here), publish nothing that is not finite, and answer a good command
    # afterwards.
    import random
    import time

    from geometry_msgs.msg import PoseStamped
    from rclpy.serialization import deserialize_message
    from std_msgs.msg import Float64

    from linkage_ros.ros.qos import QOS
    from linkage_ros.ros.testing import spin_until
    node = suspension_node(vehicle='demo_vehicle', diagnostic_period=3600.0)
    own = [s for s in node.subscriptions if s.topic_name != '/parameter_events']
    assert len(own) == 7     # four wheel_travel, two steering_rack, one joint_states
    publishers = [probe.node.create_publisher(s.msg_type, s.topic_name, QOS) for s in own]
    poses = []
    probe.node.create_subscription(PoseStamped, '/rear_left/wheel_carrier_pose', poses.append,
                                   QOS, raw=True)
    others = []
    for topic in ('/front_left/wheel_carrier_pose', '/front_right/wheel_carrier_pose',
                  '/rear_right/wheel_carrier_pose', '/front_left/camber', '/rear_left/toe'):
        probe.node.create_subscription(PoseStamped if topic.endswith('pose') else Float64,
                                       topic, others.append, QOS, raw=True)
    assert spin_until(executor, lambda: all(p.get_subscription_count() for p in publishers))
    rng = random.Random(23)
    sent = refused_by_the_publisher = 0
    deadline = time.monotonic() + 10.0
    while time.monotonic() < deadline:
        data = bytes(rng.getrandbits(8) for _ in range(rng.randrange(65)))
        if rng.random() < 0.5 and len(data) >= 4:   # half of them with a CDR header
            data = b'\x00\x01\x00\x00' + data[4:]
        try:
            rng.choice(publishers).publish(data)
            sent += 1
        except Exception:  # longer than the type's largest sample: DDS refuses it at the source
            refused_by_the_publisher += 1
        executor.spin_once(timeout_sec=0.0)
    assert sent > 1000, (sent, refused_by_the_publisher)
    spin_until(executor, lambda: False, 1.0)     # what is still queued
    decoded = [deserialize_message(d, PoseStamped) for d in poses] + [
        deserialize_message(d, PoseStamped if len(d) > 12 else Float64) for d in others]
    for msg in decoded:
        values = ([msg.pose.position.x, msg.pose.position.y, msg.pose.position.z,
                   msg.pose.orientation.w] if isinstance(msg, PoseStamped) else [msg.data])
        assert all(math.isfinite(v) for v in values), msg
    count = len(poses)
    publishers[[s.topic_name for s in own].index('/rear_left/wheel_travel')].publish(
        Float64(data=0.0))
    assert spin_until(executor, lambda: len(poses) > count)
    assert deserialize_message(poses[-1], PoseStamped).pose.position.z == pytest.approx(
        DESIGN_Z_M, abs=1e-9)     # rear_left is five_link, the vehicle's offset is in x only
