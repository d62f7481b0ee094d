# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node's axle roll centres (parameter vehicle, a vehicle file with axles) over DDS.

geometry_msgs/PointStamped on <axle>/roll_centre, m, in the vehicle frame. The expected
values are core.axle.axle's axle_quantities (the batch path of linkage-axle, Jacobians linearized
there) at the two poses the core's Continuations solve for the same commands, in order.
"""

import math
import subprocess
import sys

from geometry_msgs.msg import PointStamped
from linkage_ros.answer.cdr import point_stamped_cdr
from linkage_ros.core.axle import axle_of, axle_quantities, roll_centre_of_poses, solve_axle
from linkage_ros.core.model import load_vehicle
from linkage_ros.core.solve import Continuation, linearize
from linkage_ros.ros.node import QOS
from linkage_ros.ros.testing import spin_until
import numpy as np
import pytest
from rclpy.serialization import deserialize_message, serialize_message
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

CORNERS = ('front_left', 'front_right', 'rear_left', 'rear_right')
AXLES = {'front': ('front_left', 'front_right'), 'rear': ('rear_left', 'rear_right')}


class Core:
    """Each corner of demo_vehicle solved by the core, in the order of the node's commands."""

    def __init__(self):
        self.vehicle = load_vehicle('demo_vehicle')
        self.solvers = {c: Continuation(self.vehicle.corners[c]) for c in CORNERS}
        self.last = {}

    def solve(self, corner, travel_mm, rack_mm=None):
        self.last[corner] = self.solvers[corner].solve(travel_mm, rack_mm)
        return self.last[corner]

    def roll_centre_m(self, axle_name):
        """Return the roll centre (x, y, z) m of the axle's last two poses, by axle_quantities."""
        left, right = (self.last[c] for c in AXLES[axle_name])
        assert left.rack == right.rack     # axle_quantities takes one rack for both wheels
        found = axle_quantities(
            axle_of(self.vehicle, axle_name), np.zeros(1), np.zeros(1), np.array([left.rack]),
            np.array([[left.wheel_center, right.wheel_center]]),
            np.array([[left.rotation, right.rotation]]))
        x = found['contact_patch'][0, :, 0].mean()
        return np.array([x, *found['roll_centre'][0]]) / 1000.0


@pytest.fixture
def vehicle(suspension_node, probe, executor):
    """
    Give (publish(corner, m), step(joints), {axle: [PointStamped]}) of a demo_vehicle node.

    publish.travel: the corners' wheel_travel publishers.
    """
    suspension_node(vehicle='demo_vehicle', diagnostic_period=3600.0)
    received = {axle: [] for axle in AXLES}
    subscriptions = [probe.node.create_subscription(PointStamped, f'{axle}/roll_centre',
                                                    got.append, QOS)
                     for axle, got in received.items()]
    poses = {c: [] for c in CORNERS}     # each answer publishes the corner's elements
    subscriptions += [probe.node.create_subscription(JointState, f'{corner}/elements',
                                                     got.append, QOS)
                      for corner, got in poses.items()]
    travel = {c: probe.node.create_publisher(Float64, f'{c}/wheel_travel', QOS)
              for c in CORNERS}
    joints = probe.node.create_publisher(JointState, 'joint_states', QOS)
    assert spin_until(executor, lambda: all(p.get_subscription_count() for p in travel.values())
                      and joints.get_subscription_count()
                      and all(s.get_publisher_count() for s in subscriptions))

    def publish(corner, travel_m):
        """Send one corner's travel and wait for its answer (its elements message)."""
        count = len(poses[corner])
        travel[corner].publish(Float64(data=travel_m))
        assert spin_until(executor, lambda: len(poses[corner]) > count)

    def step(positions, sec=3, nanosec=500):
        """Send one JointState (joint: m) and wait until the corners it names have answered."""
        msg = JointState(name=list(positions), position=[float(v) for v in positions.values()])
        msg.header.stamp.sec, msg.header.stamp.nanosec = sec, nanosec
        named = [c for c in CORNERS if f'{c}_travel' in positions]
        counts = {c: len(poses[c]) for c in named}
        joints.publish(msg)
        spin_until(executor, lambda: all(len(poses[c]) > counts[c] for c in named), 5.0)

    publish.travel = travel
    return publish, step, received


def settle(executor, seconds=0.3):
    spin_until(executor, lambda: False, seconds)   # anything else would have arrived by now


def test_one_joint_state_step_publishes_each_axles_roll_centre_once(vehicle, executor):
    _, step, received = vehicle
    core = Core()
    travels = {'front_left': 0.03, 'front_right': -0.02, 'rear_left': 0.045, 'rear_right': 0.01}
    step({**{f'{c}_travel': t for c, t in travels.items()}, 'steering_rack': 0.008},
         sec=12, nanosec=250)
    for corner, travel in travels.items():
        core.solve(corner, travel * 1000.0, 8.0 if corner.startswith('front') else None)
    assert spin_until(executor, lambda: all(received.values()))
    settle(executor)
    for axle, got in received.items():
        assert len(got) == 1, axle
        point = got[0].point
        assert [point.x, point.y, point.z] == pytest.approx(core.roll_centre_m(axle), abs=1e-12)
        assert (got[0].header.stamp.sec, got[0].header.stamp.nanosec) == (12, 250)
        assert got[0].header.frame_id == 'base_link'
    # Real values: the wheels at different travels move the roll centre off the centreline.
    assert abs(received['front'][0].point.y) > 0.005
    assert 0.05 < received['front'][0].point.z < 0.2
    assert received['rear'][0].point.x == pytest.approx(-1.4, abs=0.01)


def test_per_corner_commands_publish_after_each_answer_once_both_corners_have_a_pose(
        vehicle, executor):
    publish, _, received = vehicle
    core = Core()
    publish('front_left', 0.02)        # front_right has no pose yet: nothing
    core.solve('front_left', 20.0)
    settle(executor)
    assert received == {'front': [], 'rear': []}
    expected = []
    for corner, travel in (('front_right', -0.01), ('front_left', 0.035), ('front_left', 0.0)):
        publish(corner, travel)
        core.solve(corner, travel * 1000.0)
        expected.append(core.roll_centre_m('front'))
        assert spin_until(executor, lambda: len(received['front']) == len(expected))
    settle(executor)
    assert len(received['front']) == 3 and received['rear'] == []
    got = np.array([[m.point.x, m.point.y, m.point.z] for m in received['front']])
    assert got == pytest.approx(np.array(expected), abs=1e-12)
    # Each command moved the roll centre (the wheels were never at equal travels).
    assert len({round(m.point.y, 9) for m in received['front']}) == 3


def test_a_failed_command_publishes_no_roll_centre(vehicle, executor, probe):
    publish, step, received = vehicle
    publish('rear_left', 0.01)
    publish('rear_right', 0.02)
    assert spin_until(executor, lambda: len(received['rear']) == 1)
    # Out of reach on one rear corner in a step that moves the other: the rear axle is left
    # out of that step (no roll centre from a mixed pair), the front one publishes.
    step({'rear_left_travel': 0.03, 'rear_right_travel': 5.0, 'front_left_travel': 0.01,
          'front_right_travel': 0.01})
    assert spin_until(executor, lambda: len(received['front']) == 1)
    settle(executor)
    assert len(received['rear']) == 1
    # A bad Float64 command (NaN) publishes none either: only its ERROR status.
    errors = len(probe.statuses)
    publish.travel['rear_left'].publish(Float64(data=math.nan))
    assert spin_until(executor, lambda: len(probe.statuses) > errors)
    assert 'not a finite number' in probe.statuses[-1].message
    settle(executor)
    assert len(received['rear']) == 1


def test_a_step_that_names_no_corner_of_an_axle_publishes_none_for_it(vehicle, executor):
    _, step, received = vehicle
    step({'front_left_travel': 0.01, 'front_right_travel': 0.01})
    assert spin_until(executor, lambda: len(received['front']) == 1)
    settle(executor)
    assert received['rear'] == []
    assert received['front'][0].point.y == pytest.approx(0.0, abs=1e-12)   # symmetric heave


@pytest.mark.parametrize('axle_name', list(AXLES))
def test_the_nodes_roll_centre_of_two_poses_is_the_axles_over_heave_roll_and_rack(axle_name):
    axle = axle_of(load_vehicle('demo_vehicle'), axle_name)
    # heaves within the travel blocks (+-80 mm) once the 4 deg of roll add 53 mm to a wheel
    grid = np.meshgrid(np.linspace(-24, 24, 7), np.radians([-4.0, 0.0, 2.5]), indexing='ij')
    heave, roll = (a.ravel() for a in grid)
    rack = 10.0 if axle.steered else 0.0
    result = solve_axle(axle, heave, roll, rack)
    assert result.success
    mechs = axle.mechanisms
    for i in range(len(heave)):
        jac = np.array([linearize(m, result.wheel_center[i, k][None], result.rotation[i, k][None],
                                  np.array([rack]))[1][0] for k, m in enumerate(mechs)])
        point = roll_centre_of_poses([s.wheel_radius for s in axle.scenes],
                                     [m.spin_axis for m in mechs], result.wheel_center[i],
                                     result.rotation[i], jac)
        assert point[1:] == pytest.approx(result.roll_centre[i], abs=1e-9)     # mm
        assert point[0] == pytest.approx(result.contact_patch[i, :, 0].mean(), abs=1e-9)


def test_point_stamped_cdr_is_what_rclpy_reads_and_writes():
    msg = PointStamped()
    msg.header.stamp.sec, msg.header.stamp.nanosec = 17, 999
    msg.point.x, msg.point.y, msg.point.z = 1.4, -0.0123, 0.107
    for frame in ('', 'a', 'odom_1234', 'base_link'):   # every alignment of the point
        msg.header.frame_id = frame
        data = point_stamped_cdr((17, 999), frame, (1.4, -0.0123, 0.107))
        # rclpy's own bytes differ only in the padding, which it leaves unset
        assert len(data) == len(serialize_message(msg))
        assert deserialize_message(data, PointStamped) == msg


def test_a_vehicle_without_axles_imports_and_publishes_no_roll_centre(tmp_path, domain_id):
    path = tmp_path / 'car.yaml'
    path.write_text('name: car\ncorners:\n  fl: {scene: double_wishbone}\n'
                    '  fr: {scene: double_wishbone, mirror: true}\n')
    code = f"""
import sys
from linkage_ros.ros.node import SuspensionNode
from linkage_ros.ros.testing import init_context, rclpy_try_shutdown
from rclpy.parameter import Parameter
context = init_context({domain_id})
node = SuspensionNode(context=context, parameter_overrides=[
    Parameter('vehicle', value={str(path)!r})])
node.corners['fl'].answer(10.0, None, (0, 0), '')
topics = [name for name, _ in node.get_publisher_names_and_types_by_node(
    node.get_name(), node.get_namespace())]
print(node.roll_centres, [t for t in topics if 'roll_centre' in t],
      sorted(m for m in ('linkage_ros.ros.roll_centres', 'linkage_ros.core.axle.axle')
             if m in sys.modules))
node.destroy_node()
rclpy_try_shutdown(context)
"""
    done = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                          timeout=120)
    assert (done.returncode, done.stdout) == (0, 'None [] []\n'), done.stderr


def test_a_vehicle_with_axles_has_a_roll_centre_topic_per_axle(suspension_node):
    node = suspension_node(vehicle='demo_vehicle')
    names = [name for name, _ in node.get_publisher_names_and_types_by_node(
        node.get_name(), node.get_namespace())]
    assert '/front/roll_centre' in names and '/rear/roll_centre' in names
    assert math.isfinite(node.roll_centres.axles[0].point_mm()[2])   # design: finite
