# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Parameters angles, elements and roll_centres over real rclpy and DDS (issue 37).

A simulator that needs only the loaded pose leaves out what else each answer publishes:
camber and toe (angles:=false), the scene's elements (elements:=false) and each axle's roll
centre (roll_centres:=false), as it leaves out the pickup forces (pickups:=false,
test_node_pickups_switch.py) and TF (tf:=false). Each switched off: its topics are not
advertised (the ROS graph over DDS has none), nothing arrives on them, and nothing of them
is computed. wheel_carrier_pose is always published, and the poses are the same bit for bit
either way: the switches only leave out what is built after the solve, so the same commands
through the same compiled calls give the same floats (deterministic by construction). All
three are on by default and can be turned off and on again while the node runs
(doc/node.md, Parameters).
"""

from geometry_msgs.msg import PointStamped
from linkage_ros.ros.node import QOS
from linkage_ros.ros.testing import ParameterClient, spin_until
import pytest
from sensor_msgs.msg import JointState
from test_node_vehicle_bushings import CORNERS, Corners, FORCE, MOMENT

SETTLE = 0.5          # s spun after the answers, for a message on a topic left out to show up
LEAN = {'angles': False, 'elements': False, 'roll_centres': False}
STEPS_MM = ((10.0, 12.0, -5.0, 3.0), (20.0, 18.0, 0.0, -8.0), (-15.0, 5.0, 25.0, 1.0))


def advertised(probe, node):
    """Return the topics the node publishes, as the ROS graph over DDS has them."""
    return {name for name, _ in probe.node.get_publisher_names_and_types_by_node(
        node.get_name(), node.get_namespace())}


def pose_of(probe, travel_m):
    """Send one travel (m) to a single-scene node; return the PoseStamped it answers."""
    pose_sub = probe._subscriptions[0]     # wheel_carrier_pose, the probe's first
    assert spin_until(probe.executor, lambda: probe.travel.get_subscription_count() > 0
                      and pose_sub.get_publisher_count() > 0)
    before = len(probe.poses)
    probe.send(travel_m)
    assert spin_until(probe.executor, lambda: len(probe.poses) > before)
    return probe.poses[before]


class Heard:
    """Every message of the vehicle's left-out topics the probe takes, by topic."""

    def __init__(self, probe, node):
        from std_msgs.msg import Float64
        self.messages = {}
        kinds = {'camber': Float64, 'toe': Float64, 'elements': JointState}
        topics = [(f'/{c}/{name}', kind) for c in CORNERS for name, kind in kinds.items()]
        topics += [(f'/{axle}/roll_centre', PointStamped) for axle in ('front', 'rear')]
        for topic, kind in topics:
            self.messages[topic] = []
            probe.node.create_subscription(kind, topic, self.messages[topic].append, QOS)

    def topics(self):
        """Return the topics on which anything arrived."""
        return {topic for topic, got in self.messages.items() if got}


def vehicle_poses(probe, node, steps=STEPS_MM):
    """Send a wrench to front_left, then the steps; return the poses as tuples, per step."""
    corners = Corners(probe, node)
    corners.wrench('front_left', FORCE, MOMENT)
    out = []
    for travels in steps:
        poses = corners.step(travels)
        out.append([(p.pose.position.x, p.pose.position.y, p.pose.position.z,
                     p.pose.orientation.x, p.pose.orientation.y, p.pose.orientation.z,
                     p.pose.orientation.w) for p in (poses[c] for c in CORNERS)])
    return out


def test_angles_off_advertises_no_camber_or_toe_and_publishes_none(suspension_node, probe):
    node = suspension_node(angles=False, tf=False, diagnostic_period=3600.0)
    # the graph has the node's pose topic (so discovery has run) and neither angle
    assert spin_until(probe.executor, lambda: '/wheel_carrier_pose' in advertised(probe, node))
    assert not advertised(probe, node) & {'/camber', '/toe'}
    assert pose_of(probe, 0.02).pose.position.z != pose_of(probe, -0.01).pose.position.z
    spin_until(probe.executor, lambda: bool(probe.cambers or probe.toes), timeout=SETTLE)
    assert (probe.cambers, probe.toes) == ([], [])
    # five_link has elements: they still go out, the answer alone lost its angles
    assert node.corners[''].sends.keys() == {'wheel_carrier_pose', 'elements'}


def test_elements_off_advertises_no_elements_topic_and_builds_none(suspension_node, probe):
    node = suspension_node(elements=False, tf=False, diagnostic_period=3600.0)
    assert node.corners[''].scene.elements    # five_link declares elements to leave out
    received = []
    probe.node.create_subscription(JointState, 'elements', received.append, QOS)
    assert spin_until(probe.executor, lambda: '/wheel_carrier_pose' in advertised(probe, node))
    assert '/elements' not in advertised(probe, node)
    assert probe.ask(0.02).pose is not None
    spin_until(probe.executor, lambda: bool(received), timeout=SETTLE)
    assert received == []
    # not computed: no builder of the elements is made (answer/elements.py), none is called
    responder = node.corners[''].responder
    assert [name for name, _, _ in responder._extras] == []
    assert node.corners[''].sends.keys() == {'wheel_carrier_pose', 'camber', 'toe'}


def test_roll_centres_off_advertises_no_roll_centre_and_publishes_none(suspension_node,
                                                                       probe):
    node = suspension_node(vehicle='demo_vehicle_bushings', roll_centres=False, tf=False,
                           pickups=False, diagnostic_period=3600.0)
    assert node.roll_centres is None       # nothing of the roll centres is built
    heard = Heard(probe, node)
    assert spin_until(probe.executor,
                      lambda: '/front_left/wheel_carrier_pose' in advertised(probe, node))
    assert not [t for t in advertised(probe, node) if t.endswith('/roll_centre')]
    vehicle_poses(probe, node, STEPS_MM[:2])
    # the outputs still on have arrived; a roll centre would have come with them
    assert spin_until(probe.executor, lambda: heard.topics() == {
        t for t in heard.messages if not t.endswith('/roll_centre')})
    spin_until(probe.executor, lambda: any(t.endswith('/roll_centre') for t in heard.topics()),
               timeout=SETTLE)
    assert not [t for t in heard.topics() if t.endswith('/roll_centre')]
    assert all(node.corners[c].listeners == [] for c in CORNERS)   # no corner listened to


def test_a_vehicle_with_every_switch_off_publishes_only_its_poses(suspension_node, probe):
    # the simulator's configuration (the bench's node_lean): the same traffic as an echo node
    node = suspension_node(vehicle='demo_vehicle_bushings', tf=False, pickups=False,
                           diagnostic_period=3600.0, **LEAN)
    heard = Heard(probe, node)
    assert spin_until(probe.executor,
                      lambda: '/front_left/wheel_carrier_pose' in advertised(probe, node))
    assert {t for t in advertised(probe, node) if t.startswith(tuple(
        f'/{c}/' for c in CORNERS)) or t.endswith('/roll_centre')} == {
        f'/{c}/wheel_carrier_pose' for c in CORNERS}
    vehicle_poses(probe, node, STEPS_MM[:2])
    spin_until(probe.executor, lambda: bool(heard.topics()), timeout=SETTLE)
    assert heard.topics() == set()
    assert all(node.corners[c].sends.keys() == {'wheel_carrier_pose'} for c in CORNERS)


def test_loaded_poses_are_bit_for_bit_the_same_with_the_switches_off(
        suspension_node, probe, executor):
    answers = {}
    for name, switches in (('on', {}), ('off', LEAN)):
        node = suspension_node(vehicle='demo_vehicle_bushings', tf=False, pickups=False,
                               diagnostic_period=3600.0, **switches)
        answers[name] = vehicle_poses(probe, node)
        executor.remove_node(node)
        node.destroy_node()
    assert answers['off'] == answers['on']     # bit for bit (module docstring)
    assert answers['on'][0] != answers['on'][1]   # the commands moved the wheels


def test_switched_off_while_running_their_topics_go_and_on_again_they_come_back(
        suspension_node, probe):
    node = suspension_node(vehicle='demo_vehicle_bushings', tf=False, pickups=False,
                           diagnostic_period=3600.0)
    switched = {f'/{c}/{name}' for c in CORNERS for name in ('camber', 'toe', 'elements')}
    switched |= {'/front/roll_centre', '/rear/roll_centre'}
    assert spin_until(probe.executor, lambda: switched <= advertised(probe, node))
    client = ParameterClient(probe)
    assert client.set(**LEAN) == [(True, '')] * 3
    assert spin_until(probe.executor, lambda: not switched & advertised(probe, node))
    heard = Heard(probe, node)
    vehicle_poses(probe, node, STEPS_MM[:1])
    spin_until(probe.executor, lambda: bool(heard.topics()), timeout=SETTLE)
    assert heard.topics() == set()
    # on again: the topics come back, and the next steps are answered on every one of them
    assert client.set(angles=True, elements=True, roll_centres=True) == [(True, '')] * 3
    assert spin_until(probe.executor, lambda: switched <= advertised(probe, node))
    vehicle_poses(probe, node, STEPS_MM[1:])
    assert spin_until(probe.executor, lambda: heard.topics() == switched)


@pytest.mark.parametrize('name', ['angles', 'elements', 'roll_centres'])
@pytest.mark.parametrize('value', ['no', 1, 0.0])
def test_a_switch_value_that_is_not_a_bool_is_refused_in_one_line(
        suspension_node, name, value):
    from linkage_ros.core.base import LinkageError
    with pytest.raises(LinkageError, match=f'{name}: expected true or false'):
        suspension_node(**{name: value})
