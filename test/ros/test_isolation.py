# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Where the tests' ROS traffic goes: nothing crosses between them and other ROS work.

An "outsider" is another ROS process on the same machine and the same domain (the user's
ROS_DOMAIN_ID), as someone else's node would be: it publishes and listens on /wheel_travel
and /clock, the topics a test once published into another user's domain. Two outsiders run
side by side (one with discovery LOCALHOST, one with ROS's default range) and must hear each
other: that shows they are alive on the domain, so that a test would see anything crossing.
The user's own suspension_node runs beside them: the test's nodes have names of their own,
and only those are looked for.
"""

import json
import os
from pathlib import Path
import select
import signal
import subprocess
import sys
import time
import uuid

from linkage_ros.ros.isolation import environment_domain_id, init_context, start_outside
from linkage_ros.ros.node import NODE_NAME
from linkage_ros.ros.testing import connect, node_script, Probe, rclpy_try_shutdown, spin_until
import pytest

BAG = Path(__file__).resolve().parents[2] / 'bags' / 'five_link_sweep.mcap'  # 161 commands
# What each outsider publishes: travel (m) on /wheel_travel, time (s) on /clock.
OUTSIDERS = {'outsider_a': (0.0123, 4242), 'outsider_b': (0.0321, 2424)}
QUIET_S = 3.5    # s: longer than Fast DDS's 3 s announcement period, to let discovery happen

OUTSIDER = """
import json, select, sys, time
import rclpy
from builtin_interfaces.msg import Time
from rclpy.qos import QoSProfile
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Float64

name, travel, seconds, other = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
rclpy.init()
node = rclpy.create_node(name)
qos = QoSProfile(depth=1000)                    # reliable, as the node's topics
heard = {'travels': set(), 'clocks': set(), 'nodes': set()}
node.create_subscription(Float64, '/wheel_travel', lambda m: heard['travels'].add(m.data), qos)
node.create_subscription(Clock, '/clock', lambda m: heard['clocks'].add(m.clock.sec), qos)
travels = node.create_publisher(Float64, '/wheel_travel', qos)
clocks = node.create_publisher(Clock, '/clock', qos)
met = False
while not select.select([sys.stdin], [], [], 0)[0]:      # until the test closes stdin
    travels.publish(Float64(data=travel))
    clocks.publish(Clock(clock=Time(sec=seconds)))
    rclpy.spin_once(node, timeout_sec=0.02)
    heard['nodes'].update(node.get_node_names())
    if not met and other in heard['nodes'] and len(heard['travels']) > 1:
        met = True
        print('met', flush=True)
print(json.dumps({k: sorted(v) for k, v in heard.items()}), flush=True)
node.destroy_node()
rclpy.try_shutdown()
"""


class Outsiders:
    """The two outsiders, started by start (Popen's signature) on the user's domain."""

    def __init__(self, start):
        names = list(OUTSIDERS)
        self.processes = {}
        for name, other, discovery in zip(names, names[::-1], ('LOCALHOST', None)):
            env = {k: v for k, v in os.environ.items() if k != 'ROS_AUTOMATIC_DISCOVERY_RANGE'}
            if discovery:
                env['ROS_AUTOMATIC_DISCOVERY_RANGE'] = discovery
            travel, seconds = OUTSIDERS[name]
            self.processes[name] = start(
                [sys.executable, '-c', OUTSIDER, name, str(travel), str(seconds), other],
                env=env, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)

    def wait_until_they_meet(self, timeout=30.0):
        """Wait until each outsider has heard the other; False if not within timeout s."""
        deadline = time.monotonic() + timeout
        for process in self.processes.values():
            ready = select.select([process.stdout], [], [], max(0.0, deadline - time.monotonic()))
            if not ready[0] or process.stdout.readline() != 'met\n':
                return False
        return True

    def stop(self):
        """Close their stdin; return {name: {'travels', 'clocks', 'nodes'}} each one heard."""
        heard = {}
        for name, process in self.processes.items():
            out, _ = process.communicate(timeout=30)        # closes stdin first
            heard[name] = json.loads(out.splitlines()[-1]) if out.strip() else None
        return heard

    def kill(self):
        for process in self.processes.values():
            if process.poll() is None:
                process.kill()
                process.communicate()


def skip_without_a_private_network(network):
    """Skip (saying where the tests run) if the run is not in a private network."""
    if not network.entered:
        pytest.skip(f'no private network ({network.text}): the cross-process tests run on ROS '
                    f'domain {environment_domain_id()} beside the other ROS processes of this '
                    'machine, and outsiders would publish there')


@pytest.fixture
def outsiders_outside(private_network):
    """Give the two outsiders, started outside the run's private network (skip if none)."""
    skip_without_a_private_network(private_network)
    outsiders = Outsiders(start_outside)
    yield outsiders
    outsiders.kill()


@pytest.fixture
def outsiders_beside(private_network):
    """Give the two outsiders in the tests' own (private) network: beside the tests."""
    skip_without_a_private_network(private_network)
    outsiders = Outsiders(subprocess.Popen)
    yield outsiders
    outsiders.kill()


class Listener:
    """A node of context that keeps what arrives on /wheel_travel (m) and /clock (s)."""

    def __init__(self, context, executor, name='listener'):
        import rclpy
        from rclpy.qos import QoSProfile
        from rosgraph_msgs.msg import Clock
        from std_msgs.msg import Float64
        self.node = rclpy.create_node(name, context=context)
        self.travels, self.clocks = [], []
        qos = QoSProfile(depth=1000)
        self.node.create_subscription(Float64, '/wheel_travel',
                                      lambda m: self.travels.append(m.data), qos)
        self.node.create_subscription(Clock, '/clock',
                                      lambda m: self.clocks.append(m.clock.sec), qos)
        self.clock = self.node.create_publisher(Clock, '/clock', qos)
        executor.add_node(self.node)


def assert_nothing_crossed(heard, listener, our_node_names):
    """Assert that the outsiders heard each other, and nothing of ours; ours none of theirs."""
    theirs_travels = {travel for travel, _ in OUTSIDERS.values()}
    theirs_clocks = {seconds for _, seconds in OUTSIDERS.values()}
    for name, other in zip(OUTSIDERS, list(OUTSIDERS)[::-1]):
        assert heard[name] is not None, f'{name} gave no report'
        # alive on the domain: each heard the other (a third party's traffic may add more)
        assert OUTSIDERS[other][0] in heard[name]['travels'] and other in heard[name]['nodes']
        assert OUTSIDERS[other][1] in heard[name]['clocks']
        # nothing of ours: no travel or time we sent or heard, none of our nodes
        assert not set(heard[name]['travels']) & set(listener.travels), heard[name]
        assert not set(heard[name]['clocks']) & set(listener.clocks), heard[name]
        assert not set(heard[name]['nodes']) & set(our_node_names), heard[name]
    assert listener.travels and not set(listener.travels) & theirs_travels
    assert listener.clocks and not set(listener.clocks) & theirs_clocks


@pytest.fixture
def users_node_outside(private_network):
    """Give the user's own suspension_node, outside the private network, on the domain."""
    skip_without_a_private_network(private_network)
    node = start_outside([str(node_script())], env=dict(
        os.environ, ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST'), stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE, text=True)
    yield node
    if node.poll() is None:
        node.send_signal(signal.SIGINT)
    node.communicate(timeout=30)


def test_nothing_crosses_between_cross_process_tests_and_another_ros_process_on_the_domain(
        outsiders_outside, users_node_outside, node_process, localhost_context,
        localhost_executor):
    # The outsiders run outside the private network, on the same domain (the user's), beside
    # the user's own suspension_node; inside run what the cross-process tests run:
    # suspension_node in its own process answering a probe, and linkage-replay publish
    # --clock, which publishes /wheel_travel and /clock.
    assert outsiders_outside.wait_until_they_meet(), 'the outsiders did not hear each other'
    # Each node of the test has a name of its own, so that another's of the same program
    # (the user's suspension_node) is not taken for a leak.
    ours = {role: f'{role}_{uuid.uuid4().hex}' for role in
            ('suspension_kinematics', 'probe', 'listener', 'linkage_replay')}
    process = node_process('-r', f'__node:={ours["suspension_kinematics"]}')
    probe = Probe(localhost_context, localhost_executor, ours['probe'])
    listener = Listener(localhost_context, localhost_executor, ours['listener'])
    connect(localhost_executor, probe)
    travels = [0.011, 0.012, 0.013]
    probe.send(*travels)
    assert spin_until(localhost_executor, lambda: len(probe.poses) >= len(travels) + 1, 20.0)
    # linkage-replay's main, its node renamed by the ROS arguments rclpy.init reads (sys.argv)
    replay = subprocess.Popen(
        [sys.executable, '-c', 'import sys; from linkage_ros.tools.replay import main; '
         f'sys.exit(main(["publish", {str(BAG)!r}, "--clock", "--rate", "4", "--wait", "20"]))',
         '--ros-args', '-r', f'__node:={ours["linkage_replay"]}'],
        env=dict(os.environ, ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST'),
        stderr=subprocess.PIPE, text=True)
    seen = set()      # the node names of the graph inside, while the replay runs

    def replayed():
        seen.update(listener.node.get_node_names())
        return replay.poll() is not None
    spin_until(localhost_executor, replayed, 60.0)  # all acknowledged
    _, err = replay.communicate(timeout=30)
    assert replay.returncode == 0, err
    assert set(ours.values()) <= seen, seen      # the names looked for are those of our nodes
    spin_until(localhost_executor, lambda: False, QUIET_S)      # time to discover, if it could
    assert process.stop()[0] == 0
    heard = outsiders_outside.stop()
    assert_nothing_crossed(heard, listener, list(ours.values()))
    # the user's node was there to be heard
    assert all(NODE_NAME in heard[name]['nodes'] for name in OUTSIDERS), heard
    assert set(travels) <= set(listener.travels)
    assert len(listener.clocks) == 161          # the replay's, every one, and nothing else


def test_an_in_process_context_is_private_even_beside_another_ros_process_on_its_domain(
        outsiders_beside, suspension_node, send_travel, probe, ros_context, executor):
    # The outsiders share the tests' network and domain; the test's Context has discovery
    # OFF, so they cannot discover it, whether or not the run is in a private network.
    assert outsiders_beside.wait_until_they_meet(), 'the outsiders did not hear each other'
    from builtin_interfaces.msg import Time
    from rosgraph_msgs.msg import Clock
    suspension_node()
    listener = Listener(ros_context, executor)
    assert send_travel(0.021).pose is not None
    assert spin_until(executor, lambda: 0.021 in listener.travels)
    deadline = time.monotonic() + QUIET_S
    while time.monotonic() < deadline:              # time to discover, if it could
        listener.clock.publish(Clock(clock=Time(sec=1111)))
        probe.send(0.022)
        spin_until(executor, lambda: False, 0.05)
    heard = outsiders_beside.stop()
    assert 1111 in listener.clocks and 0.022 in listener.travels
    assert_nothing_crossed(heard, listener, ['suspension_kinematics', 'probe', 'listener'])


def test_the_fixtures_run_on_the_users_ros_domain_id(tmp_path):
    # Once they took 1..101 from the pid: someone else's domain, on a shared machine.
    (tmp_path / 'test_domain.py').write_text(
        'def test_domain(domain_id, ros_context, localhost_context):\n'
        '    assert domain_id == 7\n'
        '    assert ros_context.get_domain_id() == localhost_context.get_domain_id() == 7\n')
    result = subprocess.run(
        [sys.executable, '-m', 'pytest', '-q', '-p', 'no:cacheprovider', 'test_domain.py'],
        cwd=tmp_path, capture_output=True, text=True, timeout=120,
        env=dict(os.environ, ROS_DOMAIN_ID='7'))
    assert result.returncode == 0, result.stdout + result.stderr
    assert '1 passed' in result.stdout


def test_without_ros_domain_id_the_fixtures_run_on_ros_default_domain_0(tmp_path):
    (tmp_path / 'test_domain.py').write_text(
        'def test_domain(domain_id, ros_context):\n'
        '    assert domain_id == ros_context.get_domain_id() == 0\n')
    env = {k: v for k, v in os.environ.items() if k != 'ROS_DOMAIN_ID'}
    result = subprocess.run(
        [sys.executable, '-m', 'pytest', '-q', '-p', 'no:cacheprovider', 'test_domain.py'],
        cwd=tmp_path, capture_output=True, text=True, timeout=120, env=env)
    assert result.returncode == 0, result.stdout + result.stderr


def test_init_context_leaves_the_environments_discovery_range_as_it_was(monkeypatch):
    monkeypatch.setenv('ROS_AUTOMATIC_DISCOVERY_RANGE', 'SUBNET')
    context = init_context(None, 'OFF')
    try:
        assert context.get_domain_id() == environment_domain_id()
    finally:
        rclpy_try_shutdown(context)
    assert os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] == 'SUBNET'
