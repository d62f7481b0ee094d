# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Parameter pickups over real rclpy and DDS: a simulator leaves the pickup forces out.

With statics on, each answer also goes out as one WrenchStamped per body pickup
(pickup/<name>). A simulator that needs only the loaded pose sets pickups:=false: then no
pickup topic is advertised, none is published, and the forces are neither read nor built
(issue 37; doc/node.md, parameter pickups). The loaded poses are the same either way, bit for
bit: the switch only leaves out what is built after the solve, so the same commands through
the same compiled calls give the same floats (deterministic by construction).
"""

from geometry_msgs.msg import WrenchStamped
from linkage_ros.answer.pickups import pickup_points
from linkage_ros.ros.node import QOS
from linkage_ros.ros.testing import spin_until
import pytest
from test_node_statics import bushing_scene, FORCE, MOMENT, Wrenches

TRAVELS_M = (0.02, -0.01, 0.035, 0.0)


def loaded_answers(probe, node):
    """Send a wrench, then the travels; return [(x, y, z, qx, qy, qz, qw, camber, toe)]."""
    WrenchesOnly(probe, node).send(FORCE, MOMENT)
    out = []
    for travel in TRAVELS_M:
        answer = probe.ask(travel)
        p, q = answer.pose.pose.position, answer.pose.pose.orientation
        out.append((p.x, p.y, p.z, q.x, q.y, q.z, q.w, answer.camber, answer.toe))
    return out


class WrenchesOnly(Wrenches):
    """Wrenches without the pickup subscriptions: their names come from the core."""

    def __init__(self, probe, node, prefix=''):
        self.probe, self.node, self.prefix = probe, node, prefix
        self.corner = node.corners[prefix.rstrip('/')]
        self.pub = probe.node.create_publisher(WrenchStamped, prefix + 'contact_wrench', QOS)
        self.pickups = {}


def advertised(probe, node):
    """Return the topics the node publishes, as the ROS graph over DDS has them."""
    return {name for name, _ in probe.node.get_publisher_names_and_types_by_node(
        node.get_name(), node.get_namespace())}


def test_pickups_off_advertises_no_pickup_topic_and_publishes_none(suspension_node, probe,
                                                                   tmp_path):
    node = suspension_node(scene=str(bushing_scene(tmp_path)), pickups=False,
                           diagnostic_period=3600.0)
    names = list(pickup_points(node.corners[''].scene))
    assert names     # double_wishbone with bushings has body pickups to leave out
    received = []
    for name in names:
        probe.node.create_subscription(WrenchStamped, f'pickup/{name}', received.append, QOS)
    # the graph has the node's answer topics (so discovery has run) and no pickup topic
    assert spin_until(probe.executor, lambda: '/wheel_carrier_pose' in advertised(probe, node))
    assert not [t for t in advertised(probe, node) if '/pickup/' in t]
    WrenchesOnly(probe, node).send(FORCE, MOMENT)
    assert probe.ask(0.02).pose is not None
    spin_until(probe.executor, lambda: bool(received), timeout=0.5)
    assert received == []
    assert node.corners[''].sends.keys() == {'wheel_carrier_pose', 'camber', 'toe', '/tf'}


def test_pickups_on_by_default_advertises_every_pickup_topic(suspension_node, probe,
                                                             tmp_path):
    node = suspension_node(scene=str(bushing_scene(tmp_path)), diagnostic_period=3600.0)
    want = {f'/pickup/{name}' for name in pickup_points(node.corners[''].scene)}
    assert spin_until(probe.executor, lambda: want <= advertised(probe, node))


def test_loaded_poses_are_bit_for_bit_the_same_with_pickups_off(suspension_node, probe,
                                                                executor, tmp_path):
    scene = str(bushing_scene(tmp_path))
    answers = {}
    for pickups in (True, False):
        node = suspension_node(scene=scene, pickups=pickups, diagnostic_period=3600.0)
        answers[pickups] = loaded_answers(probe, node)
        executor.remove_node(node)
        node.destroy_node()
        probe.poses.clear(), probe.cambers.clear(), probe.toes.clear()
    assert answers[False] == answers[True]     # bit for bit (module docstring)
    assert answers[True][0] != answers[True][1]   # the commands moved the wheel


def test_pickups_turned_off_while_running_removes_their_topics(suspension_node, probe,
                                                               tmp_path):
    from linkage_ros.ros.testing import ParameterClient
    node = suspension_node(scene=str(bushing_scene(tmp_path)), diagnostic_period=3600.0)
    names = set(pickup_points(node.corners[''].scene))
    assert {n.split('/', 1)[1] for n in node.corners[''].publishers if
            n.startswith('pickup/')} == names
    assert ParameterClient(probe).set(pickups=False) == [(True, '')]
    assert not [n for n in node.corners[''].publishers if n.startswith('pickup/')]
    assert probe.ask(0.02).pose is not None


@pytest.mark.parametrize('value', ['no', 1, 0.0])
def test_a_pickups_value_that_is_not_a_bool_is_refused_in_one_line(suspension_node, value):
    from linkage_ros.core.base import LinkageError
    with pytest.raises(LinkageError, match='pickups: expected true or false'):
        suspension_node(pickups=value)


@pytest.mark.parametrize('pickups', [True, False])
def test_the_pickup_frames_warning_is_said_only_where_pickup_forces_go_out(
        suspension_node, capfd, tmp_path, pickups):
    # tf off: the pickup wrenches name the vehicle frame, which the node says once; with no
    # pickup wrenches published there is nothing to say (rcutils logs to stderr: fd 2)
    suspension_node(scene=str(bushing_scene(tmp_path)), tf=False, pickups=pickups)
    said = [line for line in capfd.readouterr().err.splitlines()
            if 'the pickup frames are unavailable' in line]
    assert len(said) == (1 if pickups else 0)
