# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
No exception of a solve leaves a callback of the node (issue 36, item 1).

The core's solve is made to raise, for one travel only (SENTINEL), as LinAlgError did for a
huge wrench: the kinematic Continuation.solve, or the corner's Statics.solve. The command is
answered with a status, not an exception: SOLVER_ERROR for the kinematics (the corner goes
back to its design position), NOT_CARRIED for the statics, an ERROR on /diagnostics naming
the exception, no pose; the node then answers the next good command with the pose the core
gives for it. Through every way in: the travel topic, the wrench path (loaded answers), the
solve service, a vehicle's joint_states and the managed (lifecycle) node. Real rclpy and DDS
in one process; the patch is of the core's function, not of ROS.
"""

import math

from diagnostic_msgs.msg import DiagnosticStatus
from linkage_ros.core import statics as core_statics
from linkage_ros.core.base import MM_PER_M, Status
from linkage_ros.core.model import load_scene, load_vehicle
from linkage_ros.core.solve import Continuation
from linkage_ros.ros import solve_service
from linkage_ros.ros.testing import Probe, spin_until
import numpy as np
import pytest
from test_node_statics import assert_pose_is, bushing_scene, Core

SENTINEL_M = 0.0137                  # the travel (m) whose solve raises
SENTINEL_MM = SENTINEL_M * MM_PER_M  # as the node reads it (messages.command_mm)
GOOD_M = 0.02
Solve = solve_service.solve_type()


class Injected(FloatingPointError):
    """The exception the patched solve raises."""


@pytest.fixture
def kinematics_raise(monkeypatch):
    """Make Continuation.solve raise Injected at SENTINEL_MM (any instance), else solve."""
    original = Continuation.solve

    def solve(self, travel, rack=None):
        if travel == SENTINEL_MM:
            raise Injected('injected into the kinematic solve')
        return original(self, travel, rack)

    monkeypatch.setattr(Continuation, 'solve', solve)


@pytest.fixture
def statics_raise(monkeypatch):
    """Make Statics.solve (any instance) raise LinAlgError at SENTINEL_MM, else solve."""
    original = core_statics.Statics.solve

    def solve(self, travel_mm, *args, **kwargs):
        if travel_mm == SENTINEL_MM:
            raise np.linalg.LinAlgError('Array must not contain infs or NaNs.')
        return original(self, travel_mm, *args, **kwargs)

    monkeypatch.setattr(core_statics.Statics, 'solve', solve)


def design_answer_z(scene, travel_m):
    """Return the wheel centre's z (m) the core gives for travel_m from design."""
    solution = Continuation(scene).solve(travel_m * MM_PER_M)
    assert solution.success
    return float(solution.wheel_center[2]) / MM_PER_M


def test_a_travel_whose_solve_raises_is_a_solver_error_and_the_next_is_answered(
        kinematics_raise, suspension_node, probe):
    node = suspension_node(diagnostic_period=3600.0)
    answer = probe.ask(SENTINEL_M)
    assert answer.pose is None and answer.diagnostics.level == DiagnosticStatus.ERROR
    said = answer.diagnostics.message
    assert said.startswith(f'/wheel_travel {SENTINEL_M!r} m: the solver failed (Injected: '
                           'injected into the kinematic solve): no pose'), said
    assert node.corners[''].health.last.status == Status.SOLVER_ERROR
    good = probe.ask(GOOD_M)
    # the corner went back to design: the answer is the core's from design (one branch)
    assert good.pose.pose.position.z == pytest.approx(
        design_answer_z(load_scene('five_link'), GOOD_M), abs=1e-12)


def test_a_loaded_answer_whose_statics_raises_is_not_carried_and_the_next_is_answered(
        statics_raise, suspension_node, probe, tmp_path):
    node = suspension_node(scene=str(bushing_scene(tmp_path)), diagnostic_period=3600.0)
    answer = probe.ask(SENTINEL_M)
    assert answer.pose is None and answer.diagnostics.level == DiagnosticStatus.ERROR
    assert 'the statics solve failed (LinAlgError: Array must not contain infs or NaNs.)' \
        in answer.diagnostics.message
    assert node.corners[''].health.last.status == Status.NOT_CARRIED
    scene = node.corners[''].scene
    assert_pose_is(probe.ask(GOOD_M), Core(scene).answer(GOOD_M * MM_PER_M))


@pytest.mark.skipif(Solve is None, reason='linkage_ros_interfaces is not built here')
def test_a_solve_request_whose_solve_raises_gets_its_status_and_the_next_is_answered(
        kinematics_raise, ros_context, executor, suspension_node):
    import rclpy
    suspension_node(diagnostic_period=3600.0)
    client_node = rclpy.create_node('client', context=ros_context)
    client = client_node.create_client(Solve, 'solve')
    executor.add_node(client_node)
    assert spin_until(executor, client.service_is_ready, 20.0)
    answers = []
    for travel in (SENTINEL_M, GOOD_M):
        future = client.call_async(Solve.Request(travel=travel))
        assert spin_until(executor, future.done, 20.0)
        answers.append(future.result())
    bad, good = answers
    assert bad.status == Status.SOLVER_ERROR
    assert bad.status_text.startswith('SOLVER_ERROR: the solver failed (Injected: ')
    assert math.isnan(bad.pose.position.z)
    assert good.status == Status.OK
    assert good.pose.position.z == pytest.approx(
        design_answer_z(load_scene('five_link'), GOOD_M), abs=1e-12)


def test_a_vehicle_corner_whose_solve_raises_fails_alone_and_all_answer_next(
        kinematics_raise, suspension_node, probe):
    from test_node_hostile import CORNERS, errors, Vehicle
    from sensor_msgs.msg import JointState
    node = suspension_node(vehicle='demo_vehicle', diagnostic_period=3600.0)
    vehicle = Vehicle(probe.node)
    assert spin_until(probe.executor, lambda: vehicle.joints.get_subscription_count() > 0)
    names = [f'{c}_travel' for c in CORNERS]
    vehicle.joints.publish(JointState(name=names, position=[SENTINEL_M] + [0.01] * 3))
    assert spin_until(probe.executor, lambda: all(len(vehicle.poses[c]) == 1
                                                  for c in CORNERS[1:]) and errors(
        vehicle.statuses))
    (error,) = errors(vehicle.statuses)
    assert error.name.endswith(': front_left') and 'the solver failed (Injected' in \
        error.message
    assert vehicle.poses['front_left'] == []
    vehicle.joints.publish(JointState(name=names, position=[GOOD_M] * 4))
    assert spin_until(probe.executor, lambda: all(len(vehicle.poses[c]) == 1 + (c != CORNERS[0])
                                                  for c in CORNERS))
    demo = load_vehicle('demo_vehicle')
    for corner in CORNERS:
        assert vehicle.poses[corner][-1].pose.position.z == pytest.approx(
            design_answer_z(demo.corners[corner], GOOD_M), abs=1e-12)
    assert node.corners['front_left'].health.failures_total == 1


def test_the_managed_node_answers_on_after_a_solve_that_raises(
        kinematics_raise, ros_context, executor):
    from linkage_ros.ros.lifecycle import ManagedSuspensionNode
    from rclpy.lifecycle import TransitionCallbackReturn
    node = ManagedSuspensionNode(context=ros_context)
    executor.add_node(node)
    assert node.trigger_configure() == TransitionCallbackReturn.SUCCESS
    assert node.trigger_activate() == TransitionCallbackReturn.SUCCESS
    probe = Probe(ros_context, executor)
    bad = probe.ask(SENTINEL_M)
    assert bad.pose is None and 'the solver failed (Injected' in bad.diagnostics.message
    good = probe.ask(GOOD_M)
    assert good.pose.pose.position.z == pytest.approx(
        design_answer_z(load_scene('five_link'), GOOD_M), abs=1e-12)
