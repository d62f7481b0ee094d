# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Helpers for launch-free tests of suspension_node: real rclpy and DDS, no launch, no pytest.

The fixtures of the pytest plugin (linkage_ros_pytest, the pytest11 entry point `linkage_ros`)
wrap these; a test without pytest uses them directly:

    Probe(context, executor)            a node that publishes wheel_travel, keeps every output
    spin_until(executor, predicate)     spin until predicate() or a deadline
    connect(executor, probe)            wait until the probe and the node see each other
    start_suspension_node(context, executor, scene, sinks, **params) -> SuspensionNode
    executor_of(context)                an EventsExecutor (a generator: its nodes destroyed
                                        and it shut down when closed)
    NodeProcess(ros_args, domain_id, script, file_size)
                                        suspension_node (or another console script) in a
                                        subprocess on domain_id
    ParameterClient, read_mcap_ros2, live_tf_topics, node_warnings, urdf_differences

Waits are deadline loops around executor.spin_once, never fixed sleeps. rclpy, the messages
and the node are imported when a helper first needs them, so that importing this module (as
the plugin does in every pytest run of an environment with linkage_ros) costs no import time.
"""

import math
import os
from pathlib import Path
import signal
import subprocess
import sys
import time
from typing import Any, NamedTuple

from .isolation import environment_domain_id, init_context  # noqa: F401 (the helpers' API)
from .testing_outputs import (live_tf_topics, node_warnings,  # noqa: F401 (the plugin's API)
                              read_mcap_ros2, urdf_differences)

WAIT = 10.0       # s: same-Context matching is immediate; cross-process discovery ~0.04 or ~3 s


def rclpy_try_shutdown(context):
    """Shut context down if it is still up (rclpy.try_shutdown)."""
    import rclpy
    rclpy.try_shutdown(context=context)


def spin_until(executor, predicate, timeout=WAIT):
    """Spin until predicate() is true or timeout (s) passes; returns predicate()."""
    deadline = time.monotonic() + timeout
    while not predicate() and time.monotonic() < deadline:
        executor.spin_once(timeout_sec=0.01)
    return predicate()


def node_script(name='suspension_node'):
    """Return the path of a console script of this environment (/tmp/venv/bin, .venv/bin in CI)."""
    return Path(sys.executable).parent / name


def stamp_ns(stamp):
    """Return a builtin_interfaces/Time as integer nanoseconds."""
    return stamp.sec * 1_000_000_000 + stamp.nanosec


class Answer(NamedTuple):
    """
    What suspension_node sent back for one command.

    pose: PoseStamped (wheel centre in m, carrier orientation relative to design), camber and
    toe: float rad; all None if the command could not be solved. diagnostics: for a command
    that could not be solved, the ERROR DiagnosticStatus the node published at once (message:
    why; values such as travel_m); None for a solved command, which the node's periodic
    report counts (Probe.statuses keeps every status).
    """

    pose: Any           # geometry_msgs/PoseStamped or None
    camber: Any         # float or None
    toe: Any            # float or None
    diagnostics: Any    # diagnostic_msgs/DiagnosticStatus


def _same_travel(text, travel_m):
    """Tell whether a diagnostics travel_m value (text) names the command travel_m (m)."""
    value = float(text)
    return value == travel_m or math.isnan(value) and math.isnan(travel_m) or math.isclose(
        value, travel_m, rel_tol=1e-8, abs_tol=1e-12)


class Probe:
    """
    A test node: publishes wheel_travel (m) and keeps every output of suspension_node.

    poses (PoseStamped), cambers and toes (float rad), statuses (DiagnosticStatus of the
    node, from /diagnostics) and status_stamps (their DiagnosticArray stamps, ns), in arrival
    order.
    """

    def __init__(self, context, executor, name='probe', node_name=None):
        """
        Make the probe's node, named name, in context; add it to executor.

        node_name: the name of the suspension_node whose statuses are kept (NODE_NAME).
        """
        import rclpy
        from diagnostic_msgs.msg import DiagnosticArray
        from geometry_msgs.msg import PoseStamped
        from std_msgs.msg import Float64

        from .node import NODE_NAME, QOS
        self._node_name = node_name or NODE_NAME
        self.node = rclpy.create_node(name, context=context, enable_rosout=False,
                                      start_parameter_services=False)
        self.executor = executor
        self.poses, self.cambers, self.toes, self.statuses = [], [], [], []
        self.status_stamps = []
        self.travel = self.node.create_publisher(Float64, 'wheel_travel', QOS)
        self._subscriptions = [
            self.node.create_subscription(PoseStamped, 'wheel_carrier_pose',
                                          self.poses.append, QOS),
            self.node.create_subscription(Float64, 'camber',
                                          lambda m: self.cambers.append(m.data), QOS),
            self.node.create_subscription(Float64, 'toe',
                                          lambda m: self.toes.append(m.data), QOS),
            self.node.create_subscription(DiagnosticArray, '/diagnostics', self._on_diagnostics,
                                          QOS),
        ]
        executor.add_node(self.node)

    def _on_diagnostics(self, msg):
        for status in msg.status:
            # '/namespace/suspension_kinematics: five_link': the node's full name first
            if status.name.split(': ')[0].rsplit('/', 1)[-1] == self._node_name:
                self.statuses.append(status)
                self.status_stamps.append(stamp_ns(msg.header.stamp))

    def send(self, *travels_m):
        for travel in travels_m:
            self.travel.publish(self.travel.msg_type(data=float(travel)))

    def matched(self):
        """Tell whether the node's subscription and its four publishers are matched here yet."""
        return (self.travel.get_subscription_count() > 0
                and all(s.get_publisher_count() > 0 for s in self._subscriptions))

    def answered_once(self):
        return bool(self.poses and self.cambers and self.toes)

    def answered(self, expected):
        """
        Tell whether the answers to the commands of expected (a core Sweep) have all arrived.

        That is at least that many of each output, the last ones those of the last command.
        """
        n = len(expected.travel)
        if min(len(self.poses), len(self.cambers), len(self.toes)) < n:
            return False
        return (math.isclose(self.poses[-1].pose.position.z * 1000.0,
                             expected.wheel_center[-1][2], abs_tol=1e-6)
                and math.isclose(self.cambers[-1], expected.camber[-1], abs_tol=1e-12)
                and math.isclose(self.toes[-1], expected.toe[-1], abs_tol=1e-12))

    def errors_about(self, travel_m, since=0):
        """
        Return the ERROR statuses (from index since) about a command of travel_m (m).

        They are what the node says at once about a command it cannot solve.
        """
        from diagnostic_msgs.msg import DiagnosticStatus

        from .messages import status_values
        return [s for s in self.statuses[since:] if s.level == DiagnosticStatus.ERROR
                and _same_travel(status_values(s)['travel_m'], travel_m)]

    def ask(self, travel_m, timeout=3 * WAIT):
        """
        Send one travel (m) and wait (at most timeout s) for its Answer.

        The bound is reached only by a failure: a first loaded answer on a busy 2-core machine
        (its statics built, the other core taken) took over 5 s once, so it is generous.

        The Answer holds pose, camber and toe for a solved command, the ERROR status for one
        that cannot be solved. Raises TimeoutError if neither arrives in time.
        """
        before = [len(self.poses), len(self.cambers), len(self.toes), len(self.statuses)]
        deadline = time.monotonic() + timeout
        if not spin_until(self.executor, self.matched, timeout):
            raise TimeoutError(f'no suspension_node matched wheel_travel within {timeout:g} s')

        def solved():
            return min(len(self.poses) - before[0], len(self.cambers) - before[1],
                       len(self.toes) - before[2]) > 0

        self.send(travel_m)
        if not spin_until(self.executor, lambda: solved() or self.errors_about(
                travel_m, before[3]), max(0.0, deadline - time.monotonic())):
            raise TimeoutError(f'suspension_node did not answer travel {travel_m!r} m within '
                               f'{timeout:g} s')
        if not solved():
            return Answer(None, None, None, self.errors_about(travel_m, before[3])[0])
        return Answer(self.poses[before[0]], self.cambers[before[1]], self.toes[before[2]],
                      None)


class ParameterClient:
    """SetParameters of suspension_node (NODE_NAME), called from a Probe's node."""

    def __init__(self, probe):
        from rcl_interfaces.srv import SetParameters

        from .node import NODE_NAME
        self.probe = probe
        self.client = probe.node.create_client(SetParameters, f'/{NODE_NAME}/set_parameters')

    def set(self, **values):  # noqa: A003 (SetParameters' verb)
        """Set each parameter (one request); return [(successful, reason)] per parameter."""
        from rcl_interfaces.srv import SetParameters
        from rclpy.parameter import Parameter
        assert spin_until(self.probe.executor, self.client.service_is_ready, 20.0)
        request = SetParameters.Request(parameters=[
            Parameter(name, value=value).to_parameter_msg() for name, value in values.items()])
        future = self.client.call_async(request)
        assert spin_until(self.probe.executor, future.done, 20.0)
        return [(r.successful, r.reason) for r in future.result().results]


def connect(executor, probe, timeout=20.0):
    """
    Wait until a node in another process answers on every topic.

    Matching seen from the probe's side does not prove the node's writers have matched the
    probe's readers yet, so travel 0 is sent every 0.5 s until each output has arrived once.
    After this every reply reaches the probe. Replies to the pings come before later ones
    on each topic, and a few may still be on their way: compare the last answers (tails).
    """
    deadline = time.monotonic() + timeout
    assert spin_until(executor, probe.matched, timeout), 'suspension_node was not discovered'
    while not probe.answered_once() and time.monotonic() < deadline:
        probe.send(0.0)
        spin_until(executor, probe.answered_once, min(0.5, deadline - time.monotonic()))
    assert probe.answered_once(), 'suspension_node matched but never answered'


class NodeProcess:
    """suspension_node (or another console script) in a subprocess on a given domain."""

    def __init__(self, ros_args, domain_id, script='suspension_node', file_size=None):
        """file_size: a limit (bytes) on the files the process writes (ulimit -f), or None."""
        env = dict(os.environ, ROS_DOMAIN_ID=str(domain_id),
                   ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')

        def limit():
            import resource
            resource.setrlimit(resource.RLIMIT_FSIZE, (file_size, file_size))

        self.popen = subprocess.Popen([str(node_script(script)), '--ros-args', *ros_args],
                                      env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                      text=True, preexec_fn=limit if file_size else None)

    def stop(self, sig=signal.SIGINT, timeout=WAIT):
        """Send sig and wait for the exit; return (exit code, stdout, stderr)."""
        if self.popen.poll() is None:
            self.popen.send_signal(sig)
        return self.finish(timeout)

    def finish(self, timeout=WAIT):
        """Wait for the process to end by itself; return (exit code, stdout, stderr)."""
        out, err = self.popen.communicate(timeout=timeout)
        return self.popen.returncode, out, err

    def close(self):
        """
        End the process if a test left it running.

        SIGINT first, so that Fast DDS removes its shared-memory segments (a SIGKILL leaves
        them in /dev/shm), SIGKILL if stuck.
        """
        if self.popen.poll() is None:
            try:
                self.stop(signal.SIGINT)
            except subprocess.TimeoutExpired:
                self.popen.kill()
                self.popen.communicate()


def start_suspension_node(context, executor, scene='five_link', sinks=(), **params):
    """
    Start a SuspensionNode in context and add it to executor.

    params are its ROS parameters by name (e.g. method='paper', use_sim_time=True).
    """
    from rclpy.parameter import Parameter

    from .node import SuspensionNode
    overrides = [Parameter(name, value=value) for name, value in dict(scene=scene,
                                                                      **params).items()]
    node = SuspensionNode(sinks=sinks, context=context, parameter_overrides=overrides)
    executor.add_node(node)
    return node


def executor_of(context):
    """Yield an EventsExecutor of context; at the end destroy its nodes and shut it down."""
    from rclpy.experimental import EventsExecutor
    executor = EventsExecutor(context=context)
    yield executor
    for node in executor.get_nodes():
        executor.remove_node(node)
        node.destroy_node()
    executor.shutdown()
