# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node's steering input and its optional outputs over real rclpy and DDS.

steering_rack (scenes with a steer: rack link), alignment (Float64MultiArray) and markers
(MarkerArray). Expected values come from the core (Continuation, alignment) for the same
commands, solved in the same order.
"""

import math

from diagnostic_msgs.msg import DiagnosticStatus
from linkage_ros.core.measure import alignment
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import Continuation
from linkage_ros.ros import messages
from linkage_ros.ros.markers import marker_points
from linkage_ros.ros.node import QOS, SuspensionNode
from linkage_ros.ros.testing import spin_until
import numpy as np
import pytest
from rclpy.parameter import Parameter
from std_msgs.msg import Float64, Float64MultiArray
from visualization_msgs.msg import MarkerArray


STEERED = 'double_wishbone'     # tie_rod has steer: rack
# (kind, value m): a travel, then rack commands at that travel, then a travel at the last rack
COMMANDS = [('travel', 0.02), ('rack', 0.01), ('rack', -0.015), ('travel', -0.03)]
BAD_RACKS_M = {'nan': math.nan, 'inf': math.inf, 'beyond reach': 1.0}
BAD_WHY = {'nan': 'not a finite number', 'inf': 'not a finite number',
           'beyond reach': 'out of reach'}


def core_solutions(scene_name, commands):
    """
    Return the core's Solutions for commands (kind, m), each from the last.

    A rack command solves at the last travel with the new rack, a travel command at the last
    rack.
    """
    cont = Continuation(load_scene(scene_name))
    solutions = []
    for kind, value in commands:
        if kind == 'travel':
            solutions.append(cont.solve(value * 1000.0))
        else:
            solutions.append(cont.solve(cont.travel, value * 1000.0))
    return cont, solutions


@pytest.fixture
def make_node(ros_context, executor):
    def make(**params):
        # An hour between periodic reports: every status a test sees came at once.
        params = {'diagnostic_period': 3600.0, **params}
        overrides = [Parameter(name, value=value) for name, value in params.items()]
        node = SuspensionNode(context=ros_context, parameter_overrides=overrides)
        executor.add_node(node)
        return node
    return make


@pytest.fixture
def commander(probe, executor):
    """
    Give send(*(kind, value m)): commands on wheel_travel or steering_rack, one at a time.

    They go from the probe node, each once the previous one is answered (its pose, or its
    ERROR status arrived), because two topics have no order between them (a burst on both
    could be taken in any order).
    """
    rack = probe.node.create_publisher(Float64, 'steering_rack', QOS)

    def answers():
        return len(probe.poses) + sum(s.level == DiagnosticStatus.ERROR for s in probe.statuses)

    def send(*commands):
        for kind, value in commands:
            answered = answers() + 1
            (probe.travel if kind == 'travel' else rack).publish(Float64(data=float(value)))
            assert spin_until(executor, lambda: answers() >= answered)
    send.rack = rack
    return send


def collect(probe, msg_type, topic):
    """Return a list that receives every message of topic on the probe node."""
    received = []
    probe.node.create_subscription(msg_type, topic, received.append, QOS)
    return received


def position_m(pose):
    p = pose.pose.position
    return [p.x, p.y, p.z]


# --- steering_rack ---------------------------------------------------------------------------

@pytest.mark.parametrize('scene, subscribed', [(STEERED, True), ('five_link', False)])
def test_steering_rack_is_subscribed_only_when_the_scene_has_a_rack_link(
        make_node, commander, executor, scene, subscribed):
    make_node(scene=scene)
    spin_until(executor, lambda: commander.rack.get_subscription_count() > 0, 0.5)
    assert (commander.rack.get_subscription_count() > 0) == subscribed


def test_rack_commands_solve_at_the_last_travel_and_equal_the_core(make_node, commander,
                                                                   executor, probe):
    make_node(scene=STEERED, diagnostic_period=0.05)
    spin_until(executor, lambda: commander.rack.get_subscription_count() > 0)
    _, expected = core_solutions(STEERED, COMMANDS)
    commander(*COMMANDS)
    assert spin_until(executor, lambda: len(probe.toes) == len(COMMANDS))
    assert np.array([position_m(p) for p in probe.poses]) == pytest.approx(
        np.array([s.wheel_center for s in expected]) / 1000.0, abs=1e-9)
    assert probe.toes == pytest.approx([s.toe for s in expected], abs=1e-9)
    assert probe.cambers == pytest.approx([s.camber for s in expected], abs=1e-9)
    # The next report names the last command: travel -30 mm at the rack of -15 mm before it.
    count = len(probe.statuses)
    assert spin_until(executor, lambda: len(probe.statuses) > count)
    values = messages.status_values(probe.statuses[-1])
    assert (float(values['travel_m']), float(values['rack_m'])) == pytest.approx((-0.03, -0.015))
    # Steering moves the wheel: the rack commands changed the toe at the same travel.
    assert abs(probe.toes[1] - probe.toes[0]) > 0.01


@pytest.mark.parametrize('bad', list(BAD_RACKS_M))
def test_bad_rack_publishes_no_pose_an_error_saying_why_and_keeps_the_state(
        make_node, commander, executor, probe, bad):
    make_node(scene=STEERED)
    spin_until(executor, lambda: commander.rack.get_subscription_count() > 0)
    commander(('travel', 0.02), ('rack', 0.01), ('rack', BAD_RACKS_M[bad]), ('rack', 0.01))
    # At once: the ERROR of the bad rack, then OK again (a change of level) with the next.
    assert spin_until(executor, lambda: len(probe.statuses) == 2 and len(probe.poses) == 3)
    assert [s.level for s in probe.statuses] == [DiagnosticStatus.ERROR, DiagnosticStatus.OK]
    assert BAD_WHY[bad] in probe.statuses[0].message
    # Back at the last good rack: the very same pose, the state stayed there.
    assert probe.poses[2].pose == probe.poses[1].pose


# --- alignment -------------------------------------------------------------------------------

def test_alignment_is_not_published_by_default(make_node, probe):
    node = make_node(scene=STEERED)
    assert node.count_publishers(node.resolve_topic_name('alignment')) == 0
    assert node.count_publishers(node.resolve_topic_name('markers')) == 0


def test_alignment_over_dds_equals_the_core_alignment_in_si(make_node, commander, executor,
                                                            probe):
    make_node(scene=STEERED, alignment=True)
    received = collect(probe, Float64MultiArray, 'alignment')
    spin_until(executor, lambda: commander.rack.get_subscription_count() > 0)
    cont, solutions = core_solutions(STEERED, COMMANDS)
    commander(*COMMANDS)
    assert spin_until(executor, lambda: len(received) == len(COMMANDS))
    for msg, solution in zip(received, solutions):
        core = alignment(cont.scene, cont.mech, solution.wheel_center, solution.rotation,
                         solution.rack)
        values = messages.alignment_values(msg)
        assert values['camber_gain_rad_per_m'] == pytest.approx(core.camber_gain[0] * 1e3,
                                                                rel=1e-9)
        assert values['bump_steer_rad_per_m'] == pytest.approx(core.bump_steer[0] * 1e3,
                                                               rel=1e-9)
        assert values['caster_rad'] == pytest.approx(core.caster[0], rel=1e-9)
        assert values['kingpin_inclination_rad'] == pytest.approx(
            core.kingpin_inclination[0], rel=1e-9)
        assert values['scrub_radius_m'] == pytest.approx(core.scrub_radius[0] / 1e3, rel=1e-9)
        assert values['svic_z_m'] == pytest.approx(core.side_view_ic[0, 1] / 1e3, rel=1e-9)
        assert values['fvic_y_m'] == pytest.approx(core.front_view_ic[0, 0] / 1e3, rel=1e-9)


# --- markers ---------------------------------------------------------------------------------

def test_marker_joints_over_dds_equal_the_core_joints_in_metres(make_node, commander,
                                                                executor, probe):
    make_node(scene=STEERED, markers=True, frame_id='chassis')
    received = collect(probe, MarkerArray, 'markers')
    spin_until(executor, lambda: commander.rack.get_subscription_count() > 0)
    cont, solutions = core_solutions(STEERED, COMMANDS)
    commander(*COMMANDS)
    assert spin_until(executor, lambda: len(received) == len(COMMANDS))
    for msg, solution in zip(received, solutions):
        links, joints = msg.markers
        core_joints = np.array(list(cont.joints(solution).values()))
        assert marker_points(joints) == pytest.approx(core_joints / 1000.0, abs=1e-12)
        # Every link ends at its joint: the second point of each pair is a carrier joint.
        ends = marker_points(links)[1::2]
        assert all(np.min(np.linalg.norm(core_joints / 1000.0 - end, axis=1)) < 1e-12
                   for end in ends)
        assert {links.header.frame_id, joints.header.frame_id} == {'chassis'}
