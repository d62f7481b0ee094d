# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node with parameter vehicle: one node, every corner of a vehicle file over DDS.

Each corner has its own topics under its name and its own Continuation; expected values come
from the core for the vehicle's corner scenes (right corners are the left scenes mirrored).
"""

from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import PoseStamped
from linkage_ros.core.model import load_vehicle
from linkage_ros.core.solve import Continuation
from linkage_ros.ros.messages import status_values
from linkage_ros.ros.node import QOS, SuspensionNode
from linkage_ros.ros.testing import spin_until
import pytest
from rclpy.parameter import Parameter
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64


CORNERS = ['front_left', 'front_right', 'rear_left', 'rear_right']


class CornerProbe:
    """Publishes a corner's wheel_travel and keeps its poses, cambers and toes."""

    def __init__(self, node, corner):
        self.travel = node.create_publisher(Float64, f'{corner}/wheel_travel', QOS)
        self.rack = node.create_publisher(Float64, f'{corner}/steering_rack', QOS)
        self.poses, self.cambers, self.toes = [], [], []
        node.create_subscription(PoseStamped, f'{corner}/wheel_carrier_pose', self.poses.append,
                                 QOS)
        node.create_subscription(Float64, f'{corner}/camber',
                                 lambda m: self.cambers.append(m.data), QOS)
        node.create_subscription(Float64, f'{corner}/toe', lambda m: self.toes.append(m.data),
                                 QOS)


@pytest.fixture
def vehicle_node(ros_context, executor, probe):
    """suspension_node serving demo_vehicle, and a CornerProbe per corner on the probe node."""
    node = SuspensionNode(context=ros_context, parameter_overrides=[
        Parameter('vehicle', value='demo_vehicle'), Parameter('diagnostic_period', value=0.05)])
    executor.add_node(node)
    corners = {c: CornerProbe(probe.node, c) for c in CORNERS}
    statuses = []       # one list per /diagnostics message
    probe.node.create_subscription(
        DiagnosticArray, '/diagnostics', lambda m: statuses.append(m.status), QOS)
    assert spin_until(executor, lambda: all(p.travel.get_subscription_count()
                                            for p in corners.values()))
    return node, corners, statuses


def core(corner, travel_mm):
    scene = load_vehicle('demo_vehicle').corners[corner]
    return Continuation(scene).solve(travel_mm)


def next_report(executor, statuses):
    """{corner name: status values} of the next /diagnostics message."""
    count = len(statuses)
    assert spin_until(executor, lambda: len(statuses) > count)
    return {s.name.split(': ')[1]: status_values(s) for s in statuses[-1]}


def test_a_command_to_one_corner_is_answered_by_that_corner_only(vehicle_node, executor):
    _, corners, statuses = vehicle_node
    corners['rear_left'].travel.publish(Float64(data=0.03))
    assert spin_until(executor, lambda: corners['rear_left'].poses)
    spin_until(executor, lambda: False, 0.2)     # anything else would have arrived by now
    assert [len(corners[c].poses) for c in CORNERS] == [0, 0, 1, 0]
    expected = core('rear_left', 30.0)
    p = corners['rear_left'].poses[0].pose.position
    assert [p.x, p.y, p.z] == pytest.approx(expected.wheel_center / 1000.0, abs=1e-9)
    assert corners['rear_left'].cambers == pytest.approx([expected.camber], abs=1e-9)
    report = next_report(executor, statuses)
    assert {c: v['commands_total'] for c, v in report.items()} == {
        'front_left': '0', 'front_right': '0', 'rear_left': '1', 'rear_right': '0'}


def test_every_corner_keeps_its_own_travel(vehicle_node, executor):
    _, corners, statuses = vehicle_node
    travels = {'front_left': 0.02, 'front_right': -0.03, 'rear_left': 0.04, 'rear_right': 0.0}
    for corner, travel in travels.items():
        corners[corner].travel.publish(Float64(data=travel))
    assert spin_until(executor, lambda: all(corners[c].toes for c in CORNERS))
    for corner, travel in travels.items():
        expected = core(corner, travel * 1000.0)
        p = corners[corner].poses[0].pose.position
        assert [p.x, p.y, p.z] == pytest.approx(expected.wheel_center / 1000.0, abs=1e-9)
        assert corners[corner].toes == pytest.approx([expected.toe], abs=1e-9)
    report = next_report(executor, statuses)     # one status per corner, named after it
    assert {c: float(v['travel_m']) for c, v in report.items()} == pytest.approx(travels)


@pytest.mark.parametrize('axle', ['front', 'rear'])
def test_right_corner_has_the_camber_and_toe_of_the_left_at_the_same_travel(
        vehicle_node, executor, axle):
    _, corners, _ = vehicle_node
    left, right = corners[f'{axle}_left'], corners[f'{axle}_right']
    for travel in (0.035, -0.045):
        left.travel.publish(Float64(data=travel))
        right.travel.publish(Float64(data=travel))
    assert spin_until(executor, lambda: len(left.toes) == 2 and len(right.toes) == 2)
    assert right.cambers == pytest.approx(left.cambers, abs=1e-9)
    assert right.toes == pytest.approx(left.toes, abs=1e-9)
    for lp, rp in zip(left.poses, right.poses):     # mirrored in y
        lpos, rpos = lp.pose.position, rp.pose.position
        assert [rpos.x, rpos.y, rpos.z] == pytest.approx([lpos.x, -lpos.y, lpos.z], abs=1e-9)
    assert abs(left.cambers[0] - left.cambers[1]) > 1e-3    # the travels did move the wheel


def test_only_steered_corners_take_steering_rack(vehicle_node, executor):
    _, corners, _ = vehicle_node
    assert spin_until(executor, lambda: corners['front_right'].rack.get_subscription_count())
    spin_until(executor, lambda: False, 0.2)
    assert [corners[c].rack.get_subscription_count() > 0 for c in CORNERS] == [
        True, True, False, False]
    corners['front_right'].rack.publish(Float64(data=0.01))
    assert spin_until(executor, lambda: corners['front_right'].toes)
    scene = load_vehicle('demo_vehicle').corners['front_right']
    expected = Continuation(scene).solve(0.0, 10.0)
    assert corners['front_right'].toes == pytest.approx([expected.toe], abs=1e-9)
    assert corners['front_left'].toes == []


# --- one JointState per simulation step ----------------------------------------------------

def vehicle_step(positions, sec=7, nanosec=250_000_000):
    """Return a sensor_msgs/JointState of demo_vehicle's joints ({joint: m}), stamped."""
    msg = JointState(name=list(positions), position=[float(v) for v in positions.values()])
    msg.header.stamp.sec, msg.header.stamp.nanosec = sec, nanosec
    return msg


def test_one_joint_state_answers_every_corner_it_names_at_its_stamp(vehicle_node, executor,
                                                                    probe):
    _, corners, _ = vehicle_node
    step = probe.node.create_publisher(JointState, 'joint_states', QOS)
    assert spin_until(executor, lambda: step.get_subscription_count() > 0)
    travels = {'front_left': 0.02, 'front_right': -0.01, 'rear_left': 0.035, 'rear_right': 0.0}
    joints = {f'{corner}_travel': travel for corner, travel in travels.items()}
    step.publish(vehicle_step({**joints, 'steering_rack': 0.012, 'unrelated_joint': 1.0}))
    assert spin_until(executor, lambda: all(corners[c].toes for c in CORNERS))
    vehicle = load_vehicle('demo_vehicle')
    for corner, travel in travels.items():
        rack = 12.0 if corner.startswith('front') else None     # only front corners steer
        expected = Continuation(vehicle.corners[corner]).solve(travel * 1000.0, rack)
        pose = corners[corner].poses[0]
        p = pose.pose.position
        assert [p.x, p.y, p.z] == pytest.approx(expected.wheel_center / 1000.0, abs=1e-9)
        assert corners[corner].toes == pytest.approx([expected.toe], abs=1e-9)
        assert (pose.header.stamp.sec, pose.header.stamp.nanosec) == (7, 250_000_000)


def test_a_joint_state_naming_one_corner_answers_that_corner_only(vehicle_node, executor,
                                                                  probe):
    _, corners, _ = vehicle_node
    step = probe.node.create_publisher(JointState, 'joint_states', QOS)
    assert spin_until(executor, lambda: step.get_subscription_count() > 0)
    step.publish(vehicle_step({'rear_right_travel': -0.025}))
    assert spin_until(executor, lambda: corners['rear_right'].poses)
    spin_until(executor, lambda: False, 0.2)     # anything else would have arrived by now
    assert [len(corners[c].poses) for c in CORNERS] == [0, 0, 0, 1]


def test_an_unknown_vehicle_is_refused_naming_the_file(ros_context):
    with pytest.raises(ValueError, match='no_such_vehicle'):
        SuspensionNode(context=ros_context,
                       parameter_overrides=[Parameter('vehicle', value='no_such_vehicle')])


def test_record_mcap_records_every_corner_under_its_name(ros_context, executor, probe,
                                                         tmp_path):
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory
    path = tmp_path / 'vehicle.mcap'
    node = SuspensionNode(context=ros_context, parameter_overrides=[
        Parameter('vehicle', value='demo_vehicle'), Parameter('record_mcap', value=str(path)),
        Parameter('alignment', value=True)])
    executor.add_node(node)
    corners = {c: CornerProbe(probe.node, c) for c in CORNERS}
    assert spin_until(executor, lambda: all(p.travel.get_subscription_count()
                                            for p in corners.values()))
    corners['front_right'].travel.publish(Float64(data=0.01))
    corners['rear_left'].travel.publish(Float64(data=-0.02))
    assert spin_until(executor, lambda: corners['front_right'].toes and corners['rear_left'].toes)
    executor.remove_node(node)
    node.destroy_node()
    with open(path, 'rb') as stream:
        decoded = [(channel.topic, msg) for _, channel, _, msg in make_reader(
            stream, decoder_factories=[DecoderFactory()]).iter_decoded_messages()]
    topics = [topic for topic, _ in decoded]
    for corner in ('front_right', 'rear_left'):
        for name in ('wheel_travel', 'wheel_carrier_pose', 'camber', 'toe', 'alignment'):
            assert topics.count(f'/{corner}/{name}') == 1, (corner, name)
    assert not any(t.startswith(('/front_left/', '/rear_right/')) for t in topics)
    assert [m.data for t, m in decoded if t == '/rear_left/wheel_travel'] == [-0.02]


def test_rerun_rrd_writes_one_file_with_every_corner_under_its_name(ros_context, executor,
                                                                    probe, tmp_path):
    import collections
    from rerun.chunk import RrdReader
    node = SuspensionNode(context=ros_context, parameter_overrides=[
        Parameter('vehicle', value='demo_vehicle'),
        Parameter('rerun_rrd', value=str(tmp_path / 'run.rrd'))])
    executor.add_node(node)
    corners = {c: CornerProbe(probe.node, c) for c in CORNERS}
    assert spin_until(executor, lambda: all(p.travel.get_subscription_count()
                                            for p in corners.values()))
    sent = {'front_left': [0.01, 0.02, 0.03], 'rear_right': [-0.02]}
    for corner, travels in sent.items():
        for travel in travels:
            corners[corner].travel.publish(Float64(data=travel))
    assert spin_until(executor, lambda: len(corners['front_left'].toes) == 3
                      and len(corners['rear_right'].toes) == 1)
    executor.remove_node(node)
    node.destroy_node()
    assert [p.name for p in tmp_path.iterdir()] == ['run.rrd']
    reader = RrdReader(str(tmp_path / 'run.rrd'))
    static, rows, travels = set(), collections.Counter(), collections.defaultdict(list)
    for chunk in reader.stream(store=reader.recordings()[0]):
        if chunk.is_static:
            static.add(chunk.entity_path)
            continue
        rows[chunk.entity_path] += chunk.num_rows
        if chunk.entity_path.endswith('/travel_mm'):
            travels[chunk.entity_path] += [float(v[0]) for v in chunk.to_record_batch().column(
                'Scalars:scalars').to_pylist()]
    for corner in CORNERS:     # every corner drawn, each under its own name
        assert {f'/{corner}/suspension/links', f'/{corner}/suspension/carrier/wheel',
                f'/plots/{corner}/camber_deg'} <= static, corner
        n = len(sent.get(corner, []))
        assert rows[f'/{corner}/suspension/carrier'] == n, corner
        assert rows[f'/plots/{corner}/toe_deg'] == n, corner
        assert sorted(travels[f'/plots/{corner}/travel_mm']) == pytest.approx(
            sorted(1000.0 * t for t in sent.get(corner, [])))
    assert not any(e.startswith(('/suspension', '/plots/travel')) for e in static | set(rows))
