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
from linkage_ros.core.scene import load_scene
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
