# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Recordings carry /tf, /tf_static and /robot_description: the node's and linkage-replay's.

Read back by two independent readers (rosbags, and mcap with mcap-ros2-support), each decoding
with the schemas the file embeds: tf2_msgs is not needed to read them.
"""

import math
from pathlib import Path
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import sweep
from linkage_ros.ros.testing import read_mcap_ros2, spin_until
import numpy as np
import pytest
from rosbags.highlevel import AnyReader

TF_TOPICS = ('/tf', '/tf_static', '/robot_description')


def read_rosbags(path):
    """Return {topic: [message]} and {topic: QoS profile} as rosbags reads them."""
    out, qos = {}, {}
    with AnyReader([Path(path)]) as reader:
        for connection, _, raw in reader.messages():
            out.setdefault(connection.topic, []).append(
                reader.deserialize(raw, connection.msgtype))
        qos = {c.topic: c.ext.offered_qos_profiles[0] for c in reader.connections}
    return out, qos


def check_recording(path, frame_id='base_link'):
    """
    Check the TF of a recording with both readers; return the number of answered commands.

    For each pose answered, a /tf message at its stamp whose transform from frame_id to the
    carrier is that pose to 1e-12 m; /robot_description a URDF holding every frame of /tf and
    /tf_static as a link.
    """
    for read in (lambda p: read_rosbags(p)[0], read_mcap_ros2):
        topics = read(path)
        poses, tfs = topics['/wheel_carrier_pose'], topics['/tf']
        assert len(tfs) == len(poses) > 0
        for pose, tf in zip(poses, tfs):
            (carrier,) = [t for t in tf.transforms if t.child_frame_id == 'wheel_carrier']
            assert carrier.header.frame_id == frame_id == pose.header.frame_id
            assert (carrier.header.stamp.sec, carrier.header.stamp.nanosec) == (
                pose.header.stamp.sec, pose.header.stamp.nanosec)
            p, t = pose.pose.position, carrier.transform.translation
            q, r = pose.pose.orientation, carrier.transform.rotation
            assert max(abs(p.x - t.x), abs(p.y - t.y), abs(p.z - t.z)) <= 1e-12
            assert max(abs(q.x - r.x), abs(q.y - r.y), abs(q.z - r.z), abs(q.w - r.w)) <= 1e-12
        (description,) = topics['/robot_description']
        robot = ElementTree.fromstring(description.data)
        links = {link.get('name') for link in robot.iter('link')}
        named = {t.child_frame_id for m in tfs + topics['/tf_static'] for t in m.transforms}
        named |= {t.header.frame_id for m in tfs + topics['/tf_static'] for t in m.transforms}
        assert named <= links
        assert robot.tag == 'robot' and frame_id in links
    return len(poses)


def test_a_replayed_sweep_carries_tf_per_answer_and_the_urdf(tmp_path):
    out = tmp_path / 'sweep.mcap'
    done = subprocess.run([str(Path(sys.executable).parent / 'linkage-replay'), 'sweep', '-o',
                           str(out), '--travel', '-40:40:10'],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert check_recording(out) == 9
    _, qos = read_rosbags(out)
    for topic in ('/tf_static', '/robot_description'):       # latched, as tf2 latches them
        assert qos[topic].durability.name.lower() == 'transient_local', topic
        assert qos[topic].depth == 1


def test_a_node_recording_carries_tf_per_answer_and_the_urdf(suspension_node, executor, probe,
                                                             tmp_path):
    path = tmp_path / 'run.mcap'
    node = suspension_node(scene='double_wishbone', record_mcap=str(path))
    travels = [0.02, -0.03, 0.05, 1.0]          # the last out of reach: no pose, no /tf
    probe.send(*travels)
    assert spin_until(executor, lambda: len(probe.poses) == 3 and probe.errors_about(1.0))
    node.destroy_node()
    assert check_recording(path) == 3
    # the frames are those of the scene at each answer: the core's sweep (independently of
    # TF), the carrier at the wheel centre of each answered travel
    expected = sweep(load_scene('double_wishbone'), np.array(travels[:3]) * 1000.0)
    tfs = read_mcap_ros2(path)['/tf']
    got = [[t.transform.translation.x, t.transform.translation.y, t.transform.translation.z]
           for m in tfs for t in m.transforms if t.child_frame_id == 'wheel_carrier']
    assert np.array(got) == pytest.approx(expected.wheel_center / 1000.0, abs=1e-12)
    assert [t.child_frame_id for t in tfs[0].transforms] == [
        'wheel_carrier', 'upper_arm', 'lower_arm', 'tie_rod']


def test_a_vehicle_recording_holds_every_corners_frames_under_its_name(ros_context, executor,
                                                                       tmp_path):
    from linkage_ros.ros.testing import start_suspension_node
    path = tmp_path / 'vehicle.mcap'
    node = start_suspension_node(ros_context, executor, vehicle='demo_vehicle',
                                 record_mcap=str(path))
    node.destroy_node()
    topics = read_mcap_ros2(path)
    (static,) = topics['/tf_static']
    assert [(t.header.frame_id, t.child_frame_id) for t in static.transforms] == [
        (f'{corner}/wheel_carrier', f'{corner}/wheel')
        for corner in ('front_left', 'front_right', 'rear_left', 'rear_right')]
    robot = ElementTree.fromstring(topics['/robot_description'][0].data)
    assert robot.get('name') == 'demo_vehicle'
    assert 'rear_right/tie_rod' in {link.get('name') for link in robot.iter('link')}


def test_with_tf_off_the_recording_holds_no_tf_and_the_node_imports_none_of_it(domain_id,
                                                                               tmp_path):
    path = tmp_path / 'off.mcap'
    code = f"""
import sys
import rclpy
from linkage_ros.ros.node import SuspensionNode
from linkage_ros.ros.testing import init_context
from rclpy.parameter import Parameter
context = init_context({domain_id})
node = SuspensionNode(context=context, parameter_overrides=[
    Parameter('tf', value=False), Parameter('record_mcap', value={str(path)!r})])
corner = node.corners['']
corner.answer(20.0, None, (1, 0), lambda: 'x')
node.destroy_node()
loaded = [m for m in sys.modules if m.startswith(
    ('linkage_ros.answer.frames', 'linkage_ros.core.bod', 'linkage_ros.answer.robot_description',
     'tf2_msgs'))]
print(loaded)
"""
    done = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == '[]'
    topics = read_mcap_ros2(path)
    assert '/wheel_carrier_pose' in topics
    assert not set(TF_TOPICS) & set(topics)
    assert math.isfinite(topics['/wheel_carrier_pose'][0].pose.position.z)


def test_the_bundled_bag_carries_tf_and_linkage_rerun_draws_it_from_urdf_and_tf(tmp_path):
    # bags/five_link_sweep.mcap is made by `linkage-replay sweep -o bags/five_link_sweep.mcap`
    bag = Path(__file__).resolve().parents[2] / 'bags' / 'five_link_sweep.mcap'
    assert check_recording(bag) == 161
    out = tmp_path / 'five_link_tf.rrd'
    bindir = Path(sys.executable).parent
    done = subprocess.run([str(bindir / 'linkage-rerun'), str(bag), '--tf', '-o', str(out)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    # 6 moving frames (carrier, 5 links) per answer, and the wheel's on /tf_static
    assert done.stderr == (f'linkage-rerun: wrote {out} (URDF and TF): 7 frames, '
                           '966 transforms, 483 plotted values\n')
    import rerun as rr
    columns = set()
    for chunk in rr.chunk.RrdReader(out).stream():
        batch = chunk.to_record_batch()
        if batch.num_rows:
            columns |= {(str(chunk.entity_path), name) for name in batch.schema.names}
    assert ('/tf/wheel_carrier', 'Transform3D:translation') in columns
    # the URDF's geometry, by Rerun's URDF loader, in the frame of its link
    assert ('/robot/five_link/visual_geometries/tie_rod/visual_0',
            'Cylinders3D:lengths') in columns


def test_the_foxglove_layout_draws_the_urdf_by_tf_and_plots_what_the_bag_holds():
    import json
    root = Path(__file__).resolve().parents[2]
    layout = json.loads((root / 'config' / 'foxglove_layout.json').read_text())
    panels = layout['configById']
    (three_d,) = [v for k, v in panels.items() if k.startswith('3D!')]
    (urdf,) = [v for v in three_d['layers'].values() if v['layerId'] == 'foxglove.Urdf']
    assert (urdf['sourceType'], urdf['topic']) == ('topic', '/robot_description')
    assert three_d['followTf'] == 'base_link'
    plotted = [p['value'] for k, v in panels.items() if k.startswith('Plot!')
               for p in v['paths']]
    assert plotted == ['/wheel_carrier_pose.pose.position.z', '/camber.data.@degrees',
                       '/toe.data.@degrees']
    # every panel is placed, and every topic it reads is in the bundled bag
    placed, stack = [], [layout['layout']]
    while stack:
        node = stack.pop()
        if isinstance(node, str):
            placed.append(node)
        else:
            stack += [node['first'], node['second']]
    assert sorted(placed) == sorted(panels)
    topics = set(read_mcap_ros2(root / 'bags' / 'five_link_sweep.mcap'))
    assert {urdf['topic']} | {p.split('.')[0] for p in plotted} <= topics
