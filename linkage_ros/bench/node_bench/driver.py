# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""The driver of linkage-bench node: sends commands to a node process, times its answers."""

import time

from geometry_msgs.msg import PoseStamped, WrenchStamped
import numpy as np
import rclpy
from rclpy.experimental import EventsExecutor
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

from .tables import progress
from ...answer.cdr import float64_cdr, joint_state_cdr
from ...ros.node import QOS


class Driver:
    """
    Sends steps of commands to one node process and times the poses that answer them.

    prefixes: '' for one scene, '<corner>/' for each corner of a vehicle. A step is one
    Float64 per corner, or (joint_states=True) one JointState naming every corner's travel
    joint; with wrenches, each corner's contact_wrench first (as a simulator sends the tyre
    forces of a step, then the travels). Poses of a corner come in command order, so its i-th
    answers step i.
    """

    def __init__(self, context, prefixes=('',)):
        self.executor = EventsExecutor(context=context)
        self.node = rclpy.create_node('bench_driver', context=context, enable_rosout=False,
                                      start_parameter_services=False)
        self.prefixes = prefixes
        self.arrivals = {p: [] for p in prefixes}
        self.pubs = [self.node.create_publisher(Float64, p + 'wheel_travel', QOS)
                     for p in prefixes]
        self.joint_pub = self.node.create_publisher(JointState, 'joint_states', QOS)
        self.wrench_pubs = [self.node.create_publisher(WrenchStamped, p + 'contact_wrench', QOS)
                            for p in prefixes]
        # Raw (CDR) both ways: the driver must be much faster than what it measures, so it
        # neither builds nor decodes messages.
        self.subs = [self.node.create_subscription(
            PoseStamped, p + 'wheel_carrier_pose',
            lambda _, times=self.arrivals[p]: times.append(time.perf_counter()), QOS,
            raw=True) for p in prefixes]
        self.joint_layout = joint_state_layout([p.rstrip('/') + '_travel' for p in prefixes])
        self.executor.add_node(self.node)

    def answered(self):
        """Count the steps answered by every corner."""
        return min(len(times) for times in self.arrivals.values())

    def clear(self):
        for times in self.arrivals.values():
            times.clear()

    def step_arrivals(self):
        """Arrival (s) of the last answer of each step answered by every corner."""
        n = self.answered()
        return np.max([times[:n] for times in self.arrivals.values()], axis=0)

    def spin_until(self, predicate, timeout):
        deadline = time.perf_counter() + timeout
        while not predicate() and time.perf_counter() < deadline:
            self.executor.spin_once(timeout_sec=min(0.01, deadline - time.perf_counter()))
        return predicate()

    def send(self, travel_m, joint_states=False, wrenches=None):
        """Send one step: wrenches (CDR, one per corner) if given, then the travel (m)."""
        if wrenches is not None:
            for pub, wrench in zip(self.wrench_pubs, wrenches):
                pub.publish(wrench)
        if joint_states:
            self.joint_pub.publish(self.joint_layout(travel_m))
        else:
            data = float64_cdr(travel_m)
            for pub in self.pubs:
                pub.publish(data)

    def connect(self, joint_states=False, timeout=20.0, ping_period=0.5, wrenches=False):
        """
        Wait until the node answers every corner, then until no answer is in flight.

        A ping goes every ping_period s until then. wrenches: wait for the node's
        contact_wrench subscriptions too.
        """
        pubs = ([self.joint_pub] if joint_states else self.pubs) + (
            self.wrench_pubs if wrenches else [])
        if not self.spin_until(lambda: all(p.get_subscription_count() for p in pubs)
                               and all(s.get_publisher_count() for s in self.subs), timeout):
            raise RuntimeError('the node under test was not discovered')
        deadline = time.perf_counter() + timeout
        while not self.answered() and time.perf_counter() < deadline:
            self.send(0.0, joint_states)
            self.spin_until(self.answered, ping_period)
        if not self.answered():
            raise RuntimeError('the node under test never answered')
        self.first_answer = min(times[0] for times in self.arrivals.values())
        count = -1
        while count != sum(len(t) for t in self.arrivals.values()):   # answers to extra pings
            count = sum(len(t) for t in self.arrivals.values())
            self.spin_until(lambda: sum(len(t) for t in self.arrivals.values()) > count, 0.3)
        self.clear()

    def ping_pong(self, travels):
        """Latency (s) of each step sent when the previous one is answered."""
        self.clear()
        times = []
        for i, travel in enumerate(travels):
            start = time.perf_counter()
            self.send(travel)
            if not self.spin_until(lambda: self.answered() > i, 5.0):
                raise RuntimeError(f'no answer to command {i} within 5 s')
            times.append(self.step_arrivals()[i] - start)
        return np.array(times)

    def paced(self, travels, rate, joint_states=False, drain=3.0, label='', wrenches=None):
        """
        Send one step per travel at rate (Hz); with a label, a progress line every 30 s.

        wrenches: per step, the contact wrenches (CDR, one per corner) sent before its travel.

        Returns (steps sent, steps answered, lag of the last answer after the last step (s),
        step latencies (s)).
        """
        self.clear()
        sent, period = [], 1.0 / rate
        due = time.perf_counter()
        report = due + 30.0
        for i, travel in enumerate(travels):
            if label and due >= report:
                progress(f'{label}: {i}/{len(travels)} sent, {self.answered()} answered')
                report += 30.0
            now = time.perf_counter()
            while now < due:
                self.executor.spin_once(timeout_sec=due - now)
                now = time.perf_counter()
            sent.append(time.perf_counter())
            self.send(travel, joint_states, None if wrenches is None else wrenches[i])
            due += period
        self.spin_until(lambda: self.answered() >= len(travels), drain)
        arrivals = self.step_arrivals()
        lag = arrivals[-1] - sent[-1] if len(arrivals) else float('inf')
        return len(travels), len(arrivals), lag, arrivals - np.array(sent[:len(arrivals)])

    def destroy(self):
        self.executor.remove_node(self.node)
        self.node.destroy_node()
        self.executor.shutdown()


def joint_state_layout(names):
    """Return a function travel (m) -> CDR of a sensor_msgs/JointState (zero stamp)."""
    return lambda travel: joint_state_cdr((0, 0), '', names, [float(travel)] * len(names))


def sine(count, amplitude_m=0.02, step=0.01):
    """Travels (m) of a slow sine: small steps, one continuation substep each."""
    return amplitude_m * np.sin(np.arange(count) * step)
