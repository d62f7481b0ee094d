# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
use_sim_time: with a /clock publisher every stamp suspension_node writes is simulated time.

In process over real DDS: a test node publishes rosgraph_msgs/Clock on /clock and jumps it
from 100 s to 5000 s; cross process: linkage-replay publish --clock drives the node's clock
from a bag's recorded times.
"""

import os
import subprocess
import sys

from builtin_interfaces.msg import Time
from linkage_ros.record.mcap_writer import McapRecorder
from linkage_ros.ros.messages import status_values
from linkage_ros.ros.node import SuspensionNode
from linkage_ros.ros.testing import Probe, spin_until, stamp_ns
import pytest
from rclpy.parameter import Parameter
from rclpy.qos import QoSProfile
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Float64

S = 1_000_000_000     # ns per s


class ListSink:
    """A sink that keeps receive_ns and publish_ns of everything it is given."""

    def __init__(self):
        self.times, self.started = [], []

    def record(self, topic, type_name, msg, receive_ns, publish_ns):
        # what the node sends once at start (TF on: the wheel frame, the URDF) apart
        started = topic in ('/tf_static', '/robot_description')
        (self.started if started else self.times).append((receive_ns, publish_ns))

    def close(self):
        pass


def set_clock(executor, clock_publisher, node, time_ns):
    """Publish time_ns on /clock and wait until node's clock reads it."""
    clock_publisher.publish(Clock(clock=stamp_msg(time_ns)))
    assert spin_until(executor, lambda: node.get_clock().now().nanoseconds == time_ns)


def stamp_msg(time_ns):
    return Time(sec=time_ns // S, nanosec=time_ns % S)


def test_with_use_sim_time_poses_are_stamped_with_the_simulated_clock(
        suspension_node, executor, probe, send_travel):
    node = suspension_node(use_sim_time=True)
    clock = probe.node.create_publisher(Clock, '/clock', QoSProfile(depth=10))
    stamps = []
    for time_ns in (100 * S, 5000 * S):           # a jump of the simulated clock
        set_clock(executor, clock, node, time_ns)
        answer = send_travel(0.01 * len(stamps))
        stamps.append(stamp_ns(answer.pose.header.stamp))
    assert stamps == [100 * S, 5000 * S]


def test_with_use_sim_time_diagnostics_come_every_period_of_simulated_time(
        suspension_node, executor, probe, send_travel):
    node = suspension_node(use_sim_time=True, diagnostic_period=0.5)
    clock = probe.node.create_publisher(Clock, '/clock', QoSProfile(depth=10))
    set_clock(executor, clock, node, 100 * S)       # from 0: a report may catch up at 100 s
    send_travel(0.01)
    spin_until(executor, lambda: False, 1.5)        # wall time passes, the simulation stands
    assert set(probe.status_stamps) <= {100 * S}
    for time_ns in (100 * S + S // 2, 101 * S):     # two periods of simulated time
        set_clock(executor, clock, node, time_ns)
        assert spin_until(executor, lambda: probe.status_stamps[-1:] == [time_ns])
    assert status_values(probe.statuses[-1])['commands_total'] == '1'


def test_with_use_sim_time_sinks_receive_simulated_times(suspension_node, executor, probe,
                                                         send_travel):
    sink = ListSink()
    # A period longer than the jump: no periodic report among the records.
    node = suspension_node(use_sim_time=True, sinks=[sink], diagnostic_period=86400.0)
    clock = probe.node.create_publisher(Clock, '/clock', QoSProfile(depth=10))
    set_clock(executor, clock, node, 100 * S)
    send_travel(0.01)
    set_clock(executor, clock, node, 5000 * S)
    send_travel(0.02)
    # Per command: the command, pose, camber, toe, elements (five_link has a spring and a
    # damper) and the bodies' frames (/tf), all at the clock's time.
    assert sink.times == [(100 * S, 100 * S)] * 6 + [(5000 * S, 5000 * S)] * 6
    # At start, before any /clock message: simulated time 0, as any sim-time node stamps then.
    assert sink.started == [(0, 0)] * 2


def test_each_command_is_stamped_with_the_clock_time_received_before_it(
        suspension_node, executor, probe):
    node = suspension_node(use_sim_time=True, diagnostic_period=86400.0)
    clock = probe.node.create_publisher(Clock, '/clock', QoSProfile(depth=10))
    set_clock(executor, clock, node, 100 * S)
    times = [200 * S, 300 * S, 400 * S, 500 * S]
    # All published before the node runs once, as when it is busy: in one process they are
    # taken in the order published, each command after its time.
    for i, time_ns in enumerate(times):
        clock.publish(Clock(clock=stamp_msg(time_ns)))
        probe.send(0.01 * i)
    assert spin_until(executor, lambda: len(probe.poses) == len(times))
    assert [stamp_ns(p.header.stamp) for p in probe.poses] == times


def test_without_use_sim_time_the_clock_topic_is_ignored(suspension_node, executor, probe,
                                                         send_travel):
    suspension_node()
    clock = probe.node.create_publisher(Clock, '/clock', QoSProfile(depth=10))
    clock.publish(Clock(clock=stamp_msg(100 * S)))
    answer = send_travel(0.01)
    assert stamp_ns(answer.pose.header.stamp) > 1_600_000_000 * S     # wall time (after 2020)


def test_replay_publish_clock_makes_a_sim_time_node_stamp_with_the_recorded_times(
        tmp_path, localhost_context, localhost_executor, domain_id):
    bag, t0 = tmp_path / 'run.mcap', 1000 * S
    travels = [i / 1000.0 for i in range(10)]
    recorded = [t0 + i * S // 50 for i in range(len(travels))]       # 50 Hz from 1000 s
    with McapRecorder(bag) as recorder:
        for travel, t in zip(travels, recorded):
            recorder.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=travel), t, t)
    node = SuspensionNode(context=localhost_context,
                          parameter_overrides=[Parameter('use_sim_time', value=True)])
    localhost_executor.add_node(node)
    probe = Probe(localhost_context, localhost_executor)
    env = dict(os.environ, ROS_DOMAIN_ID=str(domain_id),
               ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    replay = subprocess.Popen([sys.executable, '-m', 'linkage_ros.tools.replay', 'publish',
                               str(bag), '--clock', '--wait', '20'],
                              env=env, stderr=subprocess.PIPE, text=True)
    try:
        assert spin_until(localhost_executor, lambda: len(probe.poses) == len(travels), 30.0)
    finally:
        _, err = replay.communicate(timeout=30)
    assert replay.returncode == 0, err
    # Each answer carries the /clock time the node had received before its command: the
    # replay publishes each command's recorded time first, so that time, unless the command
    # overtook its clock message on the way (two topics have no order between them), when it
    # is an earlier one, or 0 (no /clock message yet: the node's /clock subscription, best
    # effort to match any publisher, may be matched a moment after the replay starts). Never a
    # later one: with rclpy's clock, which keeps only the newest /clock message, a node busy
    # for a moment stamped the first four with the fourth's.
    stamps = [stamp_ns(p.header.stamp) for p in probe.poses]
    assert len(stamps) == len(travels)
    assert all(s in [0, *recorded[:i + 1]] for i, s in enumerate(stamps)), (stamps, recorded)
    assert stamps == sorted(stamps)


def test_replay_clock_without_publish_is_refused(capsys):
    from linkage_ros.tools.replay import main
    with pytest.raises(SystemExit) as exited:
        main(['sweep', '--clock'])
    assert exited.value.code == 2
    assert '--clock is not an option of linkage-replay sweep (it is one of: publish)' in \
        capsys.readouterr().err
