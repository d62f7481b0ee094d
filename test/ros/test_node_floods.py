# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Floods are counted, and every solve request is answered (issue 36, item 5), over real DDS.

Before: a wrench flood reached the node as 11716 of 44142 messages and nothing said so; of
2000 solve requests sent at once at the default depth about 750 were never answered. Now:
    - a travel flood that overflows the node's queue (qos_depth 10, across processes): every
      message sent is either answered (commands_total) or counted lost (lost_total), exactly,
      and each answer's pose is in the node's recording;
    - a contact_wrench flood: every message is either recorded by the node as received (its
      MCAP, read by mcap's own reader) or counted lost, exactly;
    - 2000 solve requests at once, the node at its default depth (1000): every one answered,
      OK with the core's pose or REFUSED 'overloaded', and the REFUSED ones counted
      (refused_total).
Losses are counted from a publisher's first message the node takes on (ros/inbox.py): each
flood follows one message taken. The client of the service keeps its own requests and
answers (KEEP_ALL): what it loses is its own.
"""

import math

from diagnostic_msgs.msg import DiagnosticArray
from linkage_ros.core.base import Status
from linkage_ros.core.model import load_scene
from linkage_ros.ros import solve_service
from linkage_ros.ros.messages import status_values
from linkage_ros.ros.testing import read_mcap_ros2, spin_until
import pytest
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import Float64

WAIT = 30.0
FLOOD = 10_000        # messages sent as fast as one Python publisher sends them
LAST_M = 0.0271       # the last command of a flood: its answer says the flood is through
Solve = solve_service.solve_type()
KEEP_ALL = QoSProfile(history=HistoryPolicy.KEEP_ALL, reliability=ReliabilityPolicy.RELIABLE)


class Reports:
    """The node's DiagnosticStatus values, as they come on /diagnostics, by corner."""

    def __init__(self, node):
        self.values = []
        node.create_subscription(DiagnosticArray, '/diagnostics', lambda m: self.values.extend(
            status_values(s) for s in m.status), 100)

    def total(self, key):
        return int(self.values[-1][key]) if self.values else -1


def flood_client(context, executor, topic, kind=Float64):
    import rclpy
    node = rclpy.create_node('flood', context=context, enable_rosout=False,
                             start_parameter_services=False)
    executor.add_node(node)
    return node, node.create_publisher(kind, topic, 1000)


def test_a_travel_flood_is_answered_or_counted_lost_message_for_message(
        node_process, localhost_context, localhost_executor, tmp_path):
    from geometry_msgs.msg import PoseStamped
    path = tmp_path / 'run.mcap'
    node = node_process('-p', 'qos_depth:=10', '-p', 'tf:=false', '-p',
                        'diagnostic_period:=0.2', '-p', f'record_mcap:={path}')
    client, travel = flood_client(localhost_context, localhost_executor, '/wheel_travel')
    reports, poses = Reports(client), []
    client.create_subscription(PoseStamped, '/wheel_carrier_pose', poses.append, 1000)
    executor = localhost_executor
    assert spin_until(executor, lambda: travel.get_subscription_count() > 0 and reports.values,
                      WAIT)
    design_z = load_scene('five_link').wheel_center[2] / 1000.0
    # the node knows this publisher before the flood: losses are counted from its first
    # message taken on (ros/inbox.py); a flood from the first message on is another test
    travel.publish(Float64(data=0.0))
    assert spin_until(executor, lambda: poses, WAIT)
    for i in range(FLOOD):
        travel.publish(Float64(data=0.02 * math.sin(i / 50.0)))
    travel.publish(Float64(data=LAST_M))
    assert spin_until(executor, lambda: poses and abs(
        poses[-1].pose.position.z - design_z - LAST_M) < 1e-9, WAIT), 'the flood never ended'
    # a report after the last answer holds the final counts
    count = len(reports.values)
    assert spin_until(executor, lambda: len(reports.values) > count + 1, WAIT)
    answered, lost = reports.total('commands_total'), reports.total('lost_total')
    assert lost > 0                       # a queue of 10 overflowed
    assert answered + lost == FLOOD + 2   # every message sent: answered, or counted lost
    # and each answered one has its pose: counted in the node's recording, since the pose
    # publisher's own keep-last queue (depth 10) may drop poses this busy client has not taken
    status, _, err = node.stop()
    assert status == 0, err
    assert len(read_mcap_ros2(path).get('/wheel_carrier_pose', [])) == answered


def test_a_wrench_flood_is_received_or_counted_lost_message_for_message(
        node_process, localhost_context, localhost_executor, tmp_path):
    from geometry_msgs.msg import WrenchStamped
    path = tmp_path / 'run.mcap'
    node = node_process('-p', 'scene:=five_link_bushings', '-p', 'qos_depth:=10', '-p',
                        'tf:=false', '-p', 'diagnostic_period:=0.2', '-p',
                        f'record_mcap:={path}')
    client, wrench = flood_client(localhost_context, localhost_executor, '/contact_wrench',
                                  WrenchStamped)
    reports, executor = Reports(client), localhost_executor
    assert spin_until(executor, lambda: wrench.get_subscription_count() > 0 and reports.values,
                      WAIT)
    msg = WrenchStamped()
    msg.header.frame_id = 'base_link'
    msg.wrench.force.x = math.nan      # refused at once: the node has taken this publisher's
    wrench.publish(msg)                # first message (losses are counted from it on)
    assert spin_until(executor, lambda: reports.values[-1]['failures_total'] == '1', WAIT)
    msg.wrench.force.x = 0.0
    for i in range(FLOOD):
        msg.wrench.force.y = float(i)            # N: within the bound, each one different
        wrench.publish(msg)
    # the last: refused at once, so its report says the flood is through (a keep-last queue
    # drops the oldest, never the newest) with the final count
    msg.wrench.force.x = math.nan
    wrench.publish(msg)
    assert spin_until(executor, lambda: reports.values[-1]['failures_total'] == '2', WAIT)
    lost = reports.total('lost_total')
    status, _, err = node.stop()
    assert status == 0, err
    received = read_mcap_ros2(path).get('/contact_wrench', [])
    assert len(received) + lost == FLOOD + 2   # every one sent: received, or counted lost
    assert lost > 0


@pytest.mark.skipif(Solve is None, reason='linkage_ros_interfaces is not built here')
def test_2000_requests_at_once_are_all_answered_ok_or_refused_and_counted(
        node_process, localhost_context, localhost_executor):
    import rclpy
    node_process('-p', 'tf:=false', '-p', 'diagnostic_period:=0.2')   # qos_depth: 1000
    client_node = rclpy.create_node('lockstep', context=localhost_context)
    localhost_executor.add_node(client_node)
    reports = Reports(client_node)
    client = client_node.create_client(Solve, '/solve', qos_profile=KEEP_ALL)
    executor = localhost_executor
    assert spin_until(executor, lambda: client.service_is_ready() and reports.values, WAIT)
    travels = [0.0001 * (i % 300) for i in range(2000)]
    futures = [client.call_async(Solve.Request(travel=t)) for t in travels]
    assert spin_until(executor, lambda: all(f.done() for f in futures), 60.0), (
        f'{sum(not f.done() for f in futures)} of 2000 requests never answered')
    answers = [f.result() for f in futures]
    ok = [(a, t) for a, t in zip(answers, travels) if a.status == Status.OK]
    refused = [a for a in answers if a.status == Solve.Response.REFUSED]
    assert len(ok) + len(refused) == 2000 and ok
    assert all(a.status_text.startswith('REFUSED: overloaded: ') for a in refused)
    design_z = load_scene('five_link').wheel_center[2] / 1000.0
    assert max(abs(a.pose.position.z - design_z - t) for a, t in ok) < 1e-9
    count = len(reports.values)
    assert spin_until(executor, lambda: len(reports.values) > count + 1, WAIT)
    assert (reports.total('commands_total'), reports.total('refused_total')) == (
        len(ok), len(refused))
