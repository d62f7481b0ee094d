# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Republish recorded commands on ROS 2 at their recorded pace (linkage-replay publish).

    check_rate(commands, rate)                       ReplayError if the pace cannot be kept
    publish_commands(commands, topic, rate, wait)    std_msgs/Float64 on topic, the rack's on
                                                     steering_rack beside it (and /clock)
"""

import sys
import time

from .replay_commands import RACK, rack_topic, ReplayError, stamp_of

PROG = 'linkage-replay'
# The longest wait time.sleep() takes: int64 nanoseconds, about 292 years.
LONGEST_WAIT_S = (2**63 - 1) / 1e9


def check_rate(commands, rate):
    """Raise ReplayError naming --rate if publishing the commands at rate would take too long."""
    if not commands:
        return
    times = [c.log_time for c in commands]
    span = (max(times) - times[0]) / 1e9          # s of the recording
    if not span / rate <= LONGEST_WAIT_S:
        raise ReplayError('--rate', f'{rate:g}: the {span:.3g} s of recorded commands would '
                          f'take {span / rate:.3g} s to publish, longer than the '
                          f'{LONGEST_WAIT_S / 31_557_600:.0f} years a wait can last (choose '
                          'a larger --rate)')


def publish_commands(commands, topic, rate=1.0, wait=10.0, progress=None, clock=False):
    """
    Publish the commands as std_msgs/Float64 at the recorded pace / rate.

    Travel commands on topic, rack commands (if any) on steering_rack in its namespace.

    rate > 0 (2 = twice as fast). Waits up to wait s for a subscriber first (with clock, for
    one on /clock too). clock: before each command, publish rosgraph_msgs/Clock on /clock
    holding the command's recorded receive time, so that a node with use_sim_time stamps
    its answer with the recorded time. Returns the number of commands published.
    """
    import rclpy
    from rclpy.qos import QoSProfile
    from std_msgs.msg import Float64

    from ..record.interfaces import qualified
    check_rate(commands, rate)
    rclpy.init()
    node = rclpy.create_node('linkage_replay', start_parameter_services=False)
    published = 0
    try:
        # Reliable, keep last 1000: a burst is never overwritten before it is acknowledged.
        publisher = node.create_publisher(Float64, qualified(topic), QoSProfile(depth=1000))
        publishers = [publisher]
        by_kind = {}
        if any(c.kind == RACK for c in commands):
            by_kind[RACK] = node.create_publisher(Float64, rack_topic(qualified(topic)),
                                                  QoSProfile(depth=1000))
            publishers.append(by_kind[RACK])
        if clock:
            from rosgraph_msgs.msg import Clock
            clock_publisher = node.create_publisher(Clock, '/clock', QoSProfile(depth=1000))
            publishers.append(clock_publisher)
        deadline = time.monotonic() + wait
        while (not all(p.get_subscription_count() for p in publishers)
               and time.monotonic() < deadline):
            time.sleep(0.01)
        for p in publishers:
            if p.get_subscription_count() == 0:
                print(f'{PROG}: no subscriber on {p.topic_name} after {wait:g} s; publishing '
                      'anyway', file=sys.stderr)
        start, first = time.monotonic(), commands[0].log_time if commands else 0
        for command in commands:
            delay = start + (command.log_time - first) / 1e9 / rate - time.monotonic()
            if delay > 0:
                time.sleep(delay)
            if clock:   # the time first: the command's answer is stamped with it
                clock_publisher.publish(Clock(clock=stamp_of(command.log_time)))
            by_kind.get(command.kind, publisher).publish(Float64(data=command.travel))
            published += 1
            if progress:
                progress.update(published)
        # Reliable delivery of the last commands before the process goes away.
        from rclpy.duration import Duration
        for p in publishers:
            p.wait_for_all_acked(Duration(seconds=min(wait, 5.0)))
    except KeyboardInterrupt:
        print(f'{PROG}: interrupted after {published} commands', file=sys.stderr)
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
    return published
