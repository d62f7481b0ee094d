# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-replay solve of a statics run: the recorded contact wrenches are applied again.

The recording is made in process by suspension_node on the bundled five_link_bushings, with
travel commands and contact wrenches (one refused, as the node refuses it); the replay must
give the node's answers bit for bit: the same code (protocol.Responder) on the same inputs.
"""

import math

from geometry_msgs.msg import WrenchStamped
from linkage_ros.ros.node import QOS
from linkage_ros.ros.testing import spin_until
from linkage_ros.tools.replay import main
from test_replay import decoded

SCENE = 'five_link_bushings'
# N, N m at the contact patch, vehicle frame: cornering, then braking; one not finite
WRENCHES = [((300.0, -2500.0, 4000.0), (0.0, 0.0, 60.0)),
            ((-1800.0, 400.0, 3500.0), (0.0, 20.0, -30.0))]
BAD = ((math.nan, 0.0, 0.0), (0.0, 0.0, 0.0))
ERROR = 2      # diagnostic_msgs/DiagnosticStatus ERROR, as mcap_ros2 decodes a byte


def send_wrench(probe, corner, pub, force, moment):
    """Publish one wrench; wait until the corner holds it or has refused it."""
    refused = corner.health.failures_total
    msg = WrenchStamped()
    msg.header.frame_id = 'base_link'
    (msg.wrench.force.x, msg.wrench.force.y, msg.wrench.force.z) = force
    (msg.wrench.torque.x, msg.wrench.torque.y, msg.wrench.torque.z) = moment
    pub.publish(msg)
    assert spin_until(probe.executor, lambda: (
        corner.statics.force, corner.statics.moment) == (force, moment)
        or corner.health.failures_total > refused)


def record_statics_run(suspension_node, probe, path):
    """Record travels at zero wrench, then under each wrench (a bad one refused between)."""
    node = suspension_node(scene=SCENE, record_mcap=str(path), diagnostic_period=3600.0)
    corner = node.corners['']
    pub = probe.node.create_publisher(WrenchStamped, 'contact_wrench', QOS)
    assert spin_until(probe.executor, lambda: pub.get_subscription_count() > 0, 20.0)
    assert probe.ask(0.01).pose is not None
    for force, moment in WRENCHES:
        send_wrench(probe, corner, pub, force, moment)
        assert probe.ask(0.02).pose is not None
        assert probe.ask(-0.015).pose is not None
        send_wrench(probe, corner, pub, *BAD)    # refused: the last good one holds
        assert probe.ask(0.005).pose is not None
    assert corner.health.failures_total == 2
    node.destroy_node()


def answers(path):
    """Return {topic: [message fields]} of every answer in a bag: pose, camber, toe, pickups."""
    got = {}
    for topic, _, msg in decoded(path):
        if topic == '/wheel_carrier_pose':
            p = msg.pose
            value = (msg.header.frame_id, p.position.x, p.position.y, p.position.z,
                     p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w)
        elif topic in ('/camber', '/toe'):
            value = msg.data
        elif topic.startswith('/pickup/'):
            f, t = msg.wrench.force, msg.wrench.torque
            value = (msg.header.frame_id, f.x, f.y, f.z, t.x, t.y, t.z)
        else:
            continue
        got.setdefault(topic, []).append(value)
    return got


def test_solve_applies_the_recorded_wrenches_and_gives_the_node_s_answers_bit_for_bit(
        suspension_node, probe, tmp_path):
    recorded = tmp_path / 'run.mcap'
    record_statics_run(suspension_node, probe, recorded)
    out = tmp_path / 'replayed.mcap'
    assert main(['solve', str(recorded), '-o', str(out), '--scene', SCENE]) == 0
    expected, got = answers(recorded), answers(out)
    assert len(expected['/wheel_carrier_pose']) == 7
    assert any(t.startswith('/pickup/') for t in expected)
    # exact: the same code on the same recorded floats
    assert got == expected


def test_a_refused_wrench_is_an_error_in_the_replay_s_diagnostics_as_on_the_node(
        suspension_node, probe, tmp_path):
    recorded = tmp_path / 'run.mcap'
    record_statics_run(suspension_node, probe, recorded)
    out = tmp_path / 'replayed.mcap'
    assert main(['solve', str(recorded), '-o', str(out), '--scene', SCENE]) == 0
    errors = [s.message for t, _, m in decoded(out) if t == '/diagnostics'
              for s in m.status if s.level == ERROR]
    assert len(errors) == 2
    assert all('/contact_wrench' in e and 'finite' in e for e in errors)


def test_a_message_of_another_type_on_contact_wrench_is_skipped_naming_the_type_it_needs(
        tmp_path, capsys):
    from std_msgs.msg import Float64
    from test_replay import write_commands
    bag = tmp_path / 'run.mcap'
    write_commands(bag, [0.01, 0.02], extra=[('/contact_wrench', 'std_msgs/msg/Float64',
                                              Float64(data=1.0))])
    assert main(['solve', str(bag), '-o', str(tmp_path / 'out.mcap'), '--scene', SCENE]) == 0
    assert ('1 message of std_msgs/msg/Float64 on /contact_wrench skipped: contact wrenches '
            'are geometry_msgs/msg/WrenchStamped') in capsys.readouterr().err
