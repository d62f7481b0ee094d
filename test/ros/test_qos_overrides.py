# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
QoS by parameter, the rclpy way: qos_overrides.<topic>.<publisher|subscription>.<policy>.

The default stays reliable, keep-last qos_depth (1000); an override wins for its topic alone.
Over DDS, the sensor-pipeline preset (best effort) is checked by a best-effort client, which a
reliable-only node could not serve... and the other way round.
"""

import subprocess
import sys

from geometry_msgs.msg import PoseStamped
from linkage_ros.record.mcap_reader import read_bag
from linkage_ros.ros.testing import live_tf_topics, spin_until
import pytest
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import Float64

BEST_EFFORT = QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT)
SENSOR_PRESET = [
    '-p', 'qos_overrides./wheel_travel.subscription.reliability:=best_effort',
    '-p', 'qos_overrides./wheel_carrier_pose.publisher.reliability:=best_effort',
    '-p', 'qos_overrides./wheel_carrier_pose.publisher.depth:=10',
]


def qos_of(node):
    """Return {topic: QoSProfile} of the node's own publishers and subscriptions."""
    return {e.topic_name: e.qos_profile for e in [*node.publishers, *node.subscriptions]
            if e.topic_name not in ('/parameter_events', '/rosout')}


def test_an_override_wins_for_its_topic_and_qos_depth_for_the_others(suspension_node,
                                                                     tmp_path):
    node = suspension_node(qos_depth=50, **{
        'qos_overrides./wheel_carrier_pose.publisher.depth': 1,
        'qos_overrides./camber.publisher.reliability': 'best_effort',
        'qos_overrides./wheel_travel.subscription.history': 'keep_all',
        'record_mcap': str(tmp_path / 'run.mcap')})
    qos = qos_of(node)
    assert qos['/wheel_carrier_pose'].depth == 1
    assert qos['/camber'].reliability == ReliabilityPolicy.BEST_EFFORT
    assert qos['/camber'].depth == 50
    assert qos['/wheel_travel'].history == HistoryPolicy.KEEP_ALL
    assert qos['/toe'].depth == 50 and qos['/toe'].reliability == ReliabilityPolicy.RELIABLE
    assert {qos[t].depth for t in live_tf_topics() - {'/tf_static'}} <= {50}   # none: no tf2
    node.corners[''].answer(20.0, None, (1, 0), lambda: 'travel 20 mm')   # one of each
    node.destroy_node()
    # the recording says what each topic offered, the override included
    bag = read_bag(tmp_path / 'run.mcap')
    assert bag.qos['/wheel_carrier_pose']['depth'] == 1
    assert bag.qos['/camber']['reliability'] == 'best_effort'
    assert bag.qos['/toe']['depth'] == 50


def test_the_default_stays_reliable_keep_last_1000(suspension_node):
    qos = qos_of(suspension_node())
    latched = {'/tf_static', '/robot_description'}
    assert {(p.reliability, p.history, p.depth) for t, p in qos.items() if t not in latched} \
        == {(ReliabilityPolicy.RELIABLE, HistoryPolicy.KEEP_LAST, 1000)}


def run_node(*args, timeout=120):
    code = ('import sys; from linkage_ros.ros.entry import main; '
            f'sys.exit(main({list(args)!r}))')
    return subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                          timeout=timeout)


def test_a_bad_override_is_one_line_and_status_2():
    done = run_node('--ros-args', '-p',
                    'qos_overrides./wheel_travel.subscription.reliability:=sometimes')
    assert done.returncode == 2
    assert done.stderr.splitlines()[-1] + '\n' == (
        'suspension_node: qos_overrides./wheel_travel.subscription.reliability: expected one '
        "of reliable, best_effort, system_default, got 'sometimes'\n")


def test_an_override_of_a_topic_the_node_lacks_is_refused_with_the_closest_name():
    done = run_node('--ros-args', '-p', 'qos_overrides./wheel_carier_pose.publisher.depth:=1')
    assert done.returncode == 2      # (a first start may say it compiles the kernels first)
    assert done.stderr.splitlines()[-1] + '\n' == (
        'suspension_node: parameter qos_overrides./wheel_carier_pose.publisher.depth: '
        'the node does not publish /wheel_carier_pose (did you mean '
        'qos_overrides./wheel_carrier_pose.publisher.depth?)\n')


class ParameterNames:
    """The one method of a Node that unknown_overrides asks: its parameters' names."""

    def __init__(self, *names):
        self.names = list(names)

    def list_parameters(self, prefixes, depth):
        return self


KNOWN = {('/wheel_travel', 'subscription'), ('/wheel_carrier_pose', 'publisher'),
         ('/camber', 'publisher')}


@pytest.mark.parametrize('name, problem', [
    ('qos_overrides./wheel_carier_pose.publisher.depth', 'the node does not publish '
     '/wheel_carier_pose (did you mean qos_overrides./wheel_carrier_pose.publisher.depth?)'),
    # issue 27 item 25: the topic is the node's, the wrong end of it was named
    ('qos_overrides./wheel_travel.publisher.depth', 'the node does not publish /wheel_travel '
     '(it subscribes to it) (did you mean qos_overrides./wheel_travel.subscription.depth?)'),
    ('qos_overrides./camber.subscription.reliability', 'the node does not subscribe to '
     '/camber (it publishes it) (did you mean qos_overrides./camber.publisher.reliability?)'),
    ('qos_overrides./speed.subscription.depth', 'the node does not subscribe to /speed'),
])
def test_an_override_of_an_end_the_node_lacks_says_what_the_node_does_with_the_topic(
        name, problem):
    from linkage_ros.ros.qos import unknown_overrides
    assert unknown_overrides(ParameterNames(name, 'qos_depth'), KNOWN) == {name: problem}


def test_the_sensor_pipeline_preset_serves_a_best_effort_client_over_dds(
        node_process, localhost_context, localhost_executor):
    import rclpy
    process = node_process(*SENSOR_PRESET)
    client = rclpy.create_node('sensor_client', context=localhost_context)
    localhost_executor.add_node(client)
    poses = []
    travel = client.create_publisher(Float64, 'wheel_travel', BEST_EFFORT)
    sub = client.create_subscription(PoseStamped, 'wheel_carrier_pose', poses.append,
                                     BEST_EFFORT)
    assert spin_until(localhost_executor, lambda: travel.get_subscription_count() > 0
                      and sub.get_publisher_count() > 0, 20.0)
    # best effort both ways: a sample may be lost, so send until answers come
    for value in [0.01 * (i % 5) for i in range(200)]:
        travel.publish(Float64(data=value))
        if spin_until(localhost_executor, lambda: len(poses) >= 3, 0.05):
            break
    assert len(poses) >= 3
    publishers = client.get_publishers_info_by_topic('/wheel_carrier_pose')
    assert [p.qos_profile.reliability for p in publishers] == [ReliabilityPolicy.BEST_EFFORT]
    assert [p.qos_profile.depth for p in publishers] in ([10], [0])   # depth as DDS says it
    code, _, err = process.stop()
    assert code == 0, err
