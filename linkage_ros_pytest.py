# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
pytest plugin for launch-free tests of suspension_node: real rclpy and DDS, no launch.

Registered as the pytest11 entry point `linkage_ros`, so an environment with linkage_ros
installed has these fixtures in every pytest run; they cost nothing unless a test asks for
one (no autouse fixtures, no hooks). A module of its own, outside the package: pytest
rewrites the assertions of the package that holds a plugin, and an editable install's whole
linkage_ros would be rewritten at every run's first import of it. The helpers the fixtures
wrap (Probe, spin_until, connect, NodeProcess, ...) are linkage_ros.ros.testing's, which
imports without pytest.

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
"""

import os

from linkage_ros.ros.isolation import environment_domain_id, init_context
from linkage_ros.ros.testing import executor_of, NodeProcess, Probe, rclpy_try_shutdown, \
    start_suspension_node
import pytest


@pytest.fixture(scope='session')
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


@pytest.fixture
def domain_id():
    """
    Give the ROS domain id of the run: the user's ROS_DOMAIN_ID, or 0 (ROS's default) if unset.

    Never one picked by pid or at random, which can be someone else's. In-process contexts
    (ros_context) use it with discovery OFF, so they stay private on any domain; the
    cross-process fixtures meet the machine's other ROS processes on it, unless the run is
    in a private network (linkage_ros.ros.isolation.enter_private_network).
    """
    return environment_domain_id()


@pytest.fixture
def ros_context(ros_environment, domain_id):
    """Give a private Context with discovery OFF: only nodes of this Context see each other."""
    context = init_context(domain_id, 'OFF')
    yield context
    rclpy_try_shutdown(context)


@pytest.fixture
def localhost_context(ros_environment, domain_id):
    """Give a private Context that discovers the other processes of this machine on domain_id."""
    context = init_context(domain_id, 'LOCALHOST')
    yield context
    rclpy_try_shutdown(context)


@pytest.fixture
def executor(ros_context):
    """Give the EventsExecutor of ros_context; nodes added to it are destroyed at teardown."""
    yield from executor_of(ros_context)


@pytest.fixture
def localhost_executor(localhost_context):
    """Give the EventsExecutor of localhost_context; its nodes are destroyed at teardown."""
    yield from executor_of(localhost_context)


@pytest.fixture
def probe(ros_context, executor):
    """Give a Probe node in ros_context: it publishes wheel_travel and keeps every output."""
    return Probe(ros_context, executor)


@pytest.fixture
def suspension_node(ros_context, executor):
    """
    Give a factory of SuspensionNodes running in the test's Context and executor.

    suspension_node(scene='five_link', sinks=(), **params) -> SuspensionNode; the nodes are
    destroyed at teardown.
    """
    def start(scene='five_link', sinks=(), **params):
        return start_suspension_node(ros_context, executor, scene, sinks, **params)
    return start


@pytest.fixture
def send_travel(probe):
    """
    Give a function that sends one travel to the suspension_node of this test.

    send_travel(travel_m, timeout=5.0) -> Answer(pose, camber, toe, diagnostics);
    TimeoutError if no answer comes within timeout s.
    """
    return probe.ask


@pytest.fixture
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
