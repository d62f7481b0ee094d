# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node's /tf, /tf_static and robot_description, live over DDS.

Live /tf needs tf2_msgs (built by linkage-tf2-msgs, which README command 1 and .ci/run run).
Where it is missing these tests are skipped, except on CI (CI=true) when this machine can
build it (a compiler and the Python headers): there the install route must have built it. A
node without tf2_msgs is tested in a process that cannot import it.
"""

import os
from pathlib import Path
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

from linkage_ros.answer.frames import tf2_msgs_missing
from linkage_ros.answer.robot_description import robot_description
from linkage_ros.core.model import load_scene
from linkage_ros.ros.testing import connect, Probe, spin_until
from linkage_ros.tools.tf2_msgs_build import missing_tools
import pytest
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

MISSING = tf2_msgs_missing()
if MISSING and os.environ.get('CI') == 'true' and not missing_tools():
    raise AssertionError(f'CI on a machine that can build tf2_msgs, but {MISSING}')
live = pytest.mark.skipif(bool(MISSING), reason=MISSING)
LATCHED = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL)
RELIABLE = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE)


class TfProbe(Probe):
    """A Probe that also keeps /tf, the last /tf_static and robot_description."""

    def __init__(self, context, executor):
        super().__init__(context, executor)
        from std_msgs.msg import String
        from tf2_msgs.msg import TFMessage
        self.tf, self.static, self.descriptions = [], [], []
        self._subscriptions += [
            self.node.create_subscription(TFMessage, '/tf', self.tf.append, RELIABLE),
            self.node.create_subscription(TFMessage, '/tf_static', self.static.append, LATCHED),
            self.node.create_subscription(String, 'robot_description',
                                          lambda m: self.descriptions.append(m.data), LATCHED)]


def carrier_of(message):
    (carrier,) = [t for t in message.transforms if t.child_frame_id.endswith('wheel_carrier')]
    return carrier


def assert_tf_is_the_pose(pose, message):
    carrier = carrier_of(message)
    assert carrier.header.stamp == pose.header.stamp
    assert carrier.header.frame_id == pose.header.frame_id
    t, p = carrier.transform.translation, pose.pose.position
    assert (t.x, t.y, t.z) == (p.x, p.y, p.z)
    r, q = carrier.transform.rotation, pose.pose.orientation
    assert (r.x, r.y, r.z, r.w) == (q.x, q.y, q.z, q.w)


@live
def test_a_late_subscriber_gets_tf_static_and_the_urdf_and_tf_per_answer(suspension_node,
                                                                         ros_context,
                                                                         executor):
    suspension_node(scene='macpherson')
    probe = TfProbe(ros_context, executor)      # made after the node sent them: latched
    assert spin_until(executor, lambda: probe.static and probe.descriptions)
    assert probe.descriptions == [robot_description({'': load_scene('macpherson')},
                                                    'base_link', 'macpherson')]
    (wheel,) = probe.static[0].transforms
    assert (wheel.header.frame_id, wheel.child_frame_id) == ('wheel_carrier', 'wheel')
    for travel in (0.03, -0.02):
        probe.ask(travel)
    assert spin_until(executor, lambda: len(probe.tf) == 2)
    for pose, message in zip(probe.poses, probe.tf):
        assert_tf_is_the_pose(pose, message)
    links = {link.get('name') for link in ElementTree.fromstring(
        probe.descriptions[0]).iter('link')}
    assert {t.child_frame_id for t in probe.tf[0].transforms} <= links


@live
def test_live_tf_across_processes_for_a_vehicle(node_process, localhost_context,
                                                localhost_executor):
    import rclpy
    from geometry_msgs.msg import PoseStamped
    from std_msgs.msg import Float64
    from tf2_msgs.msg import TFMessage
    process = node_process('-p', 'vehicle:=demo_vehicle')
    client = rclpy.create_node('tf_client', context=localhost_context)
    localhost_executor.add_node(client)
    poses, tf, static = [], [], []
    travel = client.create_publisher(Float64, 'rear_left/wheel_travel', RELIABLE)
    client.create_subscription(PoseStamped, 'rear_left/wheel_carrier_pose', poses.append,
                               RELIABLE)
    client.create_subscription(TFMessage, '/tf', tf.append, RELIABLE)
    client.create_subscription(TFMessage, '/tf_static', static.append, LATCHED)
    assert spin_until(localhost_executor, lambda: static, 20.0)
    assert len(static[0].transforms) == 4        # every corner's wheel, in one message
    for _ in range(40):        # until the node's writers have matched the client's readers
        travel.publish(Float64(data=0.025))
        if spin_until(localhost_executor, lambda: poses and tf, 0.5):
            break
    assert spin_until(localhost_executor, lambda: poses and any(
        carrier_of(m).header.stamp == poses[-1].header.stamp for m in tf))
    (message,) = [m for m in tf if carrier_of(m).header.stamp == poses[-1].header.stamp]
    assert_tf_is_the_pose(poses[-1], message)
    assert carrier_of(message).child_frame_id == 'rear_left/wheel_carrier'
    code, _, err = process.stop()
    assert code == 0, err


def test_without_tf2_msgs_the_node_says_why_once_answers_and_records_tf(
        domain_id, localhost_context, localhost_executor, tmp_path):
    from test_tf_recording import check_recording
    path = tmp_path / 'run.mcap'
    code = ('import sys; sys.modules["tf2_msgs"] = None\n'     # import tf2_msgs fails
            'from linkage_ros.ros.entry import main\n'
            f'sys.exit(main(["--ros-args", "-p", "record_mcap:={path}"]))')
    env = dict(os.environ, ROS_DOMAIN_ID=str(domain_id),
               ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    node = subprocess.Popen([sys.executable, '-c', code], env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        probe = Probe(localhost_context, localhost_executor)
        connect(localhost_executor, probe)
        probe.ask(0.04)
    finally:
        node.send_signal(2)
        _, err = node.communicate(timeout=30)
    assert node.returncode == 0, err
    warnings = [line for line in err.splitlines() if 'tf2_msgs' in line]
    assert len(warnings) == 1 and warnings[0].startswith('[WARN]')
    assert warnings[0].endswith(
        ': tf2_msgs cannot be imported (it has no wheel on the package index): /tf and '
        '/tf_static are recorded but not published; `linkage-tf2-msgs` builds it into this '
        'environment (needs a C/C++ compiler and the Python headers)')
    assert 'Traceback' not in err
    assert check_recording(path) >= 2         # the pings of connect and the command


@pytest.mark.parametrize('optional,status', [(False, 1), (True, 0)])
def test_linkage_tf2_msgs_without_a_compiler_says_so_and_builds_nothing(tmp_path, optional,
                                                                        status):
    tool = Path(sys.executable).parent / 'linkage-tf2-msgs'
    env = dict(os.environ, CC=str(tmp_path / 'no-cc'), CXX=str(tmp_path / 'no-c++'))
    done = subprocess.run([str(tool), '--force', *(['--optional'] * optional)], env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == status
    assert done.stderr == ('linkage-tf2-msgs: cannot build tf2_msgs and linkage_ros_interfaces '
                           'here: it needs a C compiler (Debian: build-essential) and a C++ '
                           'compiler (Debian: build-essential); suspension_node records /tf '
                           'but publishes it only where tf2_msgs is installed, and '
                           'suspension_node serves no <corner>/solve service\n')
