# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node -p vehicle:=demo_vehicle_bushings over real rclpy and DDS (issue 37 item 4).

Four bushed corners (front double_wishbone_bushings, rear five_link_bushings, the right ones
mirrored), each taking its own <corner>/contact_wrench, driven as a simulator drives them:
one joint_states message per step with every corner's travel joint. A wrench sent to one
corner moves that corner's loaded pose, and only that corner's: each corner answers exactly
what a core.statics.Statics of its own scene gives for the same commands (the node's corner
is a Continuation and a Statics fed the commands in the same order: the same compiled calls,
the same bits), and to the statics' round-off what a fresh solve_loaded gives.
"""

from geometry_msgs.msg import PoseStamped, WrenchStamped
from linkage_ros.core.statics import Load, solve_loaded
from linkage_ros.ros.node import QOS
from linkage_ros.ros.testing import spin_until
import numpy as np
import pytest
from sensor_msgs.msg import JointState
from test_node_statics import Core, POSITION_MM

CORNERS = ('front_left', 'front_right', 'rear_left', 'rear_right')
FORCE, MOMENT = (300.0, -2500.0, 4000.0), (0.0, 0.0, 60.0)   # N, N m: a left corner's
STEPS_MM = ((10.0, 12.0, -5.0, 3.0), (20.0, 18.0, 0.0, -8.0), (-15.0, 5.0, 25.0, 1.0))


class Corners:
    """The probe's joint_states and contact_wrench publishers, and each corner's poses."""

    def __init__(self, probe, node):
        self.probe, self.node = probe, node
        self.joints = probe.node.create_publisher(JointState, '/joint_states', QOS)
        self.wrenches = {c: probe.node.create_publisher(WrenchStamped, f'/{c}/contact_wrench',
                                                        QOS) for c in CORNERS}
        self.poses = {c: [] for c in CORNERS}
        for c in CORNERS:
            probe.node.create_subscription(PoseStamped, f'/{c}/wheel_carrier_pose',
                                           self.poses[c].append, QOS)

    def wrench(self, corner, force, moment):
        """Publish one wrench to corner; wait until the corner holds it."""
        pub = self.wrenches[corner]
        assert spin_until(self.probe.executor, lambda: pub.get_subscription_count() > 0)
        msg = WrenchStamped()
        msg.header.frame_id = 'base_link'
        (msg.wrench.force.x, msg.wrench.force.y, msg.wrench.force.z) = force
        (msg.wrench.torque.x, msg.wrench.torque.y, msg.wrench.torque.z) = moment
        pub.publish(msg)
        statics = self.node.corners[corner].statics
        assert spin_until(self.probe.executor,
                          lambda: (statics.force, statics.moment) == (force, moment))

    def step(self, travels_mm):
        """Send one joint_states with every corner's travel; return {corner: its pose}."""
        assert spin_until(self.probe.executor,
                          lambda: self.joints.get_subscription_count() > 0)
        before = {c: len(p) for c, p in self.poses.items()}
        self.joints.publish(JointState(name=[f'{c}_travel' for c in CORNERS],
                                       position=[t / 1000.0 for t in travels_mm]))
        assert spin_until(self.probe.executor, lambda: all(
            len(self.poses[c]) > before[c] for c in CORNERS))
        return {c: self.poses[c][before[c]] for c in CORNERS}


def position_mm(pose):
    p = pose.pose.position
    return np.array([p.x, p.y, p.z]) * 1000.0


def test_a_wrench_to_one_corner_moves_that_corner_as_the_core_s_statics_says(
        suspension_node, probe):
    node = suspension_node(vehicle='demo_vehicle_bushings', diagnostic_period=3600.0,
                           tf=False)
    assert all(node.corners[c].statics is not None for c in CORNERS)
    corners = Corners(probe, node)
    cores = {c: Core(node.corners[c].scene) for c in CORNERS}
    # the right rear corner mirrored: its wrench is the left one's mirrored in y
    mirrored = ((FORCE[0], -FORCE[1], FORCE[2]), (-MOMENT[0], MOMENT[1], -MOMENT[2]))
    loads = {c: ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0)) for c in CORNERS}
    for k, travels in enumerate(STEPS_MM):
        if k == 1:   # a wrench to front_left, then to rear_right: the others keep none
            corners.wrench('front_left', FORCE, MOMENT)
            loads['front_left'] = (FORCE, MOMENT)
        if k == 2:
            corners.wrench('rear_right', *mirrored)
            loads['rear_right'] = mirrored
        poses = corners.step(travels)
        for corner, sent in zip(CORNERS, travels):
            travel = sent / 1000.0 * 1000.0   # as the node reads it: m, then mm
            want = cores[corner].answer(travel, *loads[corner])
            # the same commands through the same compiled calls: the same numbers, but that
            # the message holds metres: mm * 1e-3 and back * 1e3, three roundings of eps / 2
            got = position_mm(poses[corner])
            assert got == pytest.approx(np.asarray(want.wheel_center_mm), rel=4e-16, abs=0), \
                (k, corner)
            fresh = solve_loaded(node.corners[corner].scene, travel,
                                 Load(loads[corner][0], 'cp', loads[corner][1]))
            assert np.abs(got - fresh.wheel_center_mm).max() < POSITION_MM
    # the load moved the loaded corners away from their unloaded pose at the same travel
    for corner in ('front_left', 'rear_right'):
        unloaded = solve_loaded(node.corners[corner].scene, STEPS_MM[2][CORNERS.index(corner)])
        assert np.abs(position_mm(corners.poses[corner][-1])
                      - unloaded.wheel_center_mm).max() > 1e-2
