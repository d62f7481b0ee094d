# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
pytest plugin for launch-free tests of suspension_node: real rclpy and DDS, no launch.

Registered as the pytest11 entry point `linkage_ros`, so an environment with linkage_ros
installed has these fixtures in every pytest run; they cost nothing unless a test asks for
one (no autouse fixtures, no hooks). Without pytest the module still imports: the helpers
(Probe, spin_until, connect, NodeProcess, ...) are plain functions and classes, the fixtures
only wrap them.

Fixtures:
    ros_context          private rclpy Context on domain_id, automatic discovery OFF (nodes
                         of this Context talk; nothing outside the process sees or reaches
                         them, whatever else runs on that domain)
    executor             EventsExecutor of ros_context; its nodes are destroyed at teardown
    suspension_node      factory: suspension_node(scene='five_link', sinks=(), **params)
                         starts a SuspensionNode in ros_context and executor
    probe                Probe node in ros_context: publishes wheel_travel, keeps every output
    send_travel          send_travel(travel_m, timeout=5.0) -> Answer(pose, camber, toe,
                         diagnostics): one command and what came back (pose, camber and toe,
                         or the ERROR status of a bad command), waited with a deadline
    localhost_context, localhost_executor, node_process
                         the same across processes: a Context that discovers this machine
                         (ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST) and the console script
                         started on domain_id: they share it with the machine's other ROS
                         processes unless the run is in a private network
                         (isolation.enter_private_network, as the project's conftest does)
    domain_id            the user's ROS domain id: ROS_DOMAIN_ID, or 0 (ROS's default)
    ros_environment      session: rcl log files in a temporary folder, discovery range
                         LOCALHOST unless set; every fixture above that starts ROS uses it

Waits are deadline loops around executor.spin_once, never fixed sleeps. rclpy, the messages
and the node are imported when a fixture or helper first needs them, so that the plugin costs
a pytest run that does not use it no import time.
"""

import math
import os
from pathlib import Path
import signal
import subprocess
import sys
import time
from typing import Any, NamedTuple

from .isolation import environment_domain_id, init_context  # noqa: F401 (init_context: API)
from .testing_outputs import (live_tf_topics, node_warnings,  # noqa: F401 (the plugin's API)
                              read_mcap_ros2, urdf_differences)

try:
    import pytest
except ImportError:   # the helpers work without pytest; only the fixtures need it
    pytest = None

WAIT = 10.0       # s: same-Context matching is immediate; cross-process discovery ~0.04 or ~3 s


def _fixture(*args, **kwargs):
    """Return pytest.fixture, or without pytest a decorator that leaves the function alone."""
    if pytest is not None:
        return pytest.fixture(*args, **kwargs)
    return args[0] if args and callable(args[0]) else (lambda function: function)


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

    def __init__(self, context, executor):
        import rclpy
        from diagnostic_msgs.msg import DiagnosticArray
        from geometry_msgs.msg import PoseStamped
        from std_msgs.msg import Float64

        from .node import NODE_NAME, QOS
        self._node_name = NODE_NAME
        self.node = rclpy.create_node('probe', context=context, enable_rosout=False,
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

    def ask(self, travel_m, timeout=5.0):
        """
        Send one travel (m) and wait (at most timeout s) for its Answer.

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


def _executor(context):
    from rclpy.experimental import EventsExecutor
    executor = EventsExecutor(context=context)
    yield executor
    for node in executor.get_nodes():
        executor.remove_node(node)
        node.destroy_node()
    executor.shutdown()


# --- fixtures ------------------------------------------------------------------------------

@_fixture(scope='session')
def ros_environment(tmp_path_factory):
    """Send rcl log files into a temporary folder and keep discovery to this machine."""
    saved = {k: os.environ.get(k) for k in ('ROS_LOG_DIR', 'ROS_AUTOMATIC_DISCOVERY_RANGE')}
    os.environ['ROS_LOG_DIR'] = str(tmp_path_factory.mktemp('ros_log'))
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    yield
    for key, value in saved.items():
        if value is None:
            os.environ.pop(key, None)
        else:
            os.environ[key] = value


@_fixture
def domain_id():
    """
    Give the ROS domain id of the run: the user's ROS_DOMAIN_ID, or 0 (ROS's default) if unset.

    Never one picked by pid or at random, which can be someone else's. In-process contexts
    (ros_context) use it with discovery OFF, so they stay private on any domain; the
    cross-process fixtures meet the machine's other ROS processes on it, unless the run is
    in a private network (linkage_ros.ros.isolation.enter_private_network).
    """
    return environment_domain_id()


@_fixture
def ros_context(ros_environment, domain_id):
    """Give a private Context with discovery OFF: only nodes of this Context see each other."""
    context = init_context(domain_id, 'OFF')
    yield context
    rclpy_try_shutdown(context)


@_fixture
def localhost_context(ros_environment, domain_id):
    """Give a private Context that discovers the other processes of this machine on domain_id."""
    context = init_context(domain_id, 'LOCALHOST')
    yield context
    rclpy_try_shutdown(context)


@_fixture
def executor(ros_context):
    """Give the EventsExecutor of ros_context; nodes added to it are destroyed at teardown."""
    yield from _executor(ros_context)


@_fixture
def localhost_executor(localhost_context):
    """Give the EventsExecutor of localhost_context; its nodes are destroyed at teardown."""
    yield from _executor(localhost_context)


@_fixture
def probe(ros_context, executor):
    """Give a Probe node in ros_context: it publishes wheel_travel and keeps every output."""
    return Probe(ros_context, executor)


@_fixture
def suspension_node(ros_context, executor):
    """
    Give a factory of SuspensionNodes running in the test's Context and executor.

    suspension_node(scene='five_link', sinks=(), **params) -> SuspensionNode; the nodes are
    destroyed at teardown.
    """
    def start(scene='five_link', sinks=(), **params):
        return start_suspension_node(ros_context, executor, scene, sinks, **params)
    return start


@_fixture
def send_travel(probe):
    """
    Give a function that sends one travel to the suspension_node of this test.

    send_travel(travel_m, timeout=5.0) -> Answer(pose, camber, toe, diagnostics);
    TimeoutError if no answer comes within timeout s.
    """
    return probe.ask


@_fixture
def node_process(ros_environment, domain_id):
    """
    Give a factory that starts suspension_node in a subprocess on the test's domain id.

    Call it with the node's ROS arguments (*ros_args) and optionally script= and file_size=
    (a limit in bytes on the files it writes, as ulimit -f sets); processes still running at
    teardown are ended.
    """
    started = []

    def start(*ros_args, script='suspension_node', file_size=None):
        started.append(NodeProcess(ros_args, domain_id, script, file_size))
        return started[-1]

    yield start
    for process in started:
        process.close()
