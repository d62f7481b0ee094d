# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node's elements topic over real rclpy and DDS: lengths and motion ratios per answer.

sensor_msgs/JointState on elements (under each corner's namespace): name = the scene's element
names, position = length (m), velocity = motion ratio (m/m). The expected values are the
core's element_values (elements.py, its own batch path, the Jacobian linearized there) at the
poses the core's Continuation solves for the same commands, in the same order.
"""

import math

from diagnostic_msgs.msg import DiagnosticStatus
from linkage_ros.core.measure import element_values
from linkage_ros.core.model import load_scene, load_vehicle
from linkage_ros.core.solve import Continuation
from linkage_ros.ros.node import QOS
from linkage_ros.ros.testing import spin_until
import numpy as np
import pytest
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64


def collect(probe, topic):
    """Return a list that receives every JointState of topic on the probe node."""
    received = []
    probe.node.create_subscription(JointState, topic, received.append, QOS)
    return received


def expected(scene, commands):
    """Return the core's (names, lengths m, ratios) after each (travel mm, rack mm or None)."""
    cont = Continuation(scene)
    out = []
    for travel, rack in commands:
        solution = cont.solve(travel, rack)
        values = element_values(scene, solution.wheel_center[None], solution.rotation[None],
                                solution.rack)
        out.append((values.length[0] / 1000.0, values.ratio[0]))
    return [e.name for e in scene.elements], out


def test_each_answer_publishes_the_lengths_and_ratios_of_the_core(suspension_node, probe,
                                                                  executor):
    node = suspension_node(scene='five_link', diagnostic_period=3600.0)
    received = collect(probe, 'elements')
    travels = [0.02, -0.035, 0.05, 0.0]
    for travel in travels:
        probe.ask(travel)
    assert spin_until(executor, lambda: len(received) == len(travels))
    names, values = expected(node.corners[''].scene, [(t * 1000.0, None) for t in travels])
    assert names == ['damper', 'spring']
    for msg, pose, (length, ratio) in zip(received, probe.poses, values):
        assert list(msg.name) == names and list(msg.effort) == []
        assert np.array(msg.position) == pytest.approx(length, abs=1e-12)      # m
        assert np.array(msg.velocity) == pytest.approx(ratio, abs=1e-12)       # m/m
        assert (msg.header.stamp, msg.header.frame_id) == (pose.header.stamp, 'base_link')
    # The values are real: at 20 mm of bump the damper is 0.4416 m long and shortens with a
    # ratio near -0.77.
    assert received[0].position[0] == pytest.approx(0.44163, abs=1e-5)
    assert -0.8 < received[0].velocity[0] < -0.7


def test_a_rack_command_publishes_the_elements_at_the_steered_pose(suspension_node, probe,
                                                                   executor):
    node = suspension_node(scene='double_wishbone', diagnostic_period=3600.0)
    received = collect(probe, 'elements')
    rack = probe.node.create_publisher(Float64, 'steering_rack', QOS)
    probe.ask(0.03)
    assert spin_until(executor, lambda: rack.get_subscription_count() > 0)
    rack.publish(Float64(data=0.012))
    assert spin_until(executor, lambda: len(received) == 2)
    _, values = expected(node.corners[''].scene, [(30.0, None), (30.0, 12.0)])
    for msg, (length, ratio) in zip(received, values):
        assert np.array(msg.position) == pytest.approx(length, abs=1e-12)
        assert np.array(msg.velocity) == pytest.approx(ratio, abs=1e-12)


def test_a_command_without_a_pose_publishes_no_elements(suspension_node, probe, executor):
    suspension_node(scene='five_link', diagnostic_period=3600.0)
    received = collect(probe, 'elements')
    probe.ask(0.01)
    assert spin_until(executor, lambda: len(received) == 1)
    answer = probe.ask(math.nan)
    assert answer.diagnostics.level == DiagnosticStatus.ERROR
    probe.ask(0.02)
    assert spin_until(executor, lambda: len(received) == 2)
    spin_until(executor, lambda: False, 0.2)     # anything else would have arrived by now
    assert len(received) == 2 and all(np.isfinite(m.position).all() for m in received)


def test_a_scene_without_elements_has_no_elements_topic(suspension_node, probe, executor):
    scene = load_scene('chrono_generic_doublewishbone')
    assert scene.elements == ()
    node = suspension_node(scene='chrono_generic_doublewishbone')
    probe.ask(0.01)
    topics = [name for name, _ in node.get_publisher_names_and_types_by_node(
        node.get_name(), node.get_namespace())]
    assert '/wheel_carrier_pose' in topics and '/elements' not in topics


def test_every_corner_of_a_vehicle_publishes_its_own_elements(suspension_node, probe,
                                                              executor):
    suspension_node(vehicle='demo_vehicle', diagnostic_period=3600.0)
    vehicle = load_vehicle('demo_vehicle')
    travels = {'front_left': 0.025, 'front_right': 0.025, 'rear_left': -0.04,
               'rear_right': 0.01}
    received = {corner: collect(probe, f'{corner}/elements') for corner in travels}
    publishers = {corner: probe.node.create_publisher(Float64, f'{corner}/wheel_travel', QOS)
                  for corner in travels}
    assert spin_until(executor, lambda: all(p.get_subscription_count()
                                            for p in publishers.values()))
    for corner, travel in travels.items():
        publishers[corner].publish(Float64(data=travel))
    assert spin_until(executor, lambda: all(received.values()))
    for corner, travel in travels.items():
        _, [(length, ratio)] = expected(vehicle.corners[corner], [(travel * 1000.0, None)])
        assert np.array(received[corner][0].position) == pytest.approx(length, abs=1e-12)
        assert np.array(received[corner][0].velocity) == pytest.approx(ratio, abs=1e-12)
    # A right corner is its left mirrored: at the same travel the same lengths and ratios.
    assert received['front_right'][0].position == pytest.approx(
        received['front_left'][0].position, abs=1e-12)
