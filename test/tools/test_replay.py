# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-replay: solves the commands of a bag into a new bag, republishes them, recovers cuts.

Bags are read back with mcap's make_reader + mcap_ros2's decoder or rosbags (not project code).
Expected values: the scene file's reference rows (refdata) and the recorded outputs.
"""

import math
import os
from pathlib import Path
import subprocess
import sys
import time

from linkage_ros.record.mcap_writer import McapRecorder
from linkage_ros.ros.messages import status_values
from linkage_ros.ros.testing import urdf_differences
from linkage_ros.tools.replay import main
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
import numpy as np
import pytest
from rosbags.highlevel import AnyReader
import yaml

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / 'bags' / 'five_link_sweep.mcap'
T0 = 1_700_000_000_000_000_000
OUTPUTS = ('/wheel_carrier_pose', '/camber', '/toe', '/diagnostics')


def decoded(path):
    """[(topic, log time, decoded message)] in file order, by mcap + mcap_ros2."""
    with open(path, 'rb') as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        return [(c.topic, m.log_time, d) for _, c, m, d in reader.iter_decoded_messages(
            log_time_order=False)]


# What a replay also writes, as the node does with TF on: tested in test_tf_recording.py.
# What the node sends beside pose, camber and toe: TF, and five_link's elements per answer
TF_TOPICS = ('/tf', '/tf_static', '/robot_description', '/elements')


def by_topic(messages, topic):
    return [msg for t, _, msg in messages if t == topic]


def write_commands(path, travels_m, topic='/wheel_travel', chunk_size=64 * 1024, extra=()):
    """Write a bag of Float64 commands at 100 Hz (extra (topic, type, msg) at the start)."""
    from std_msgs.msg import Float64
    with McapRecorder(path, chunk_size=chunk_size) as rec:
        for topic_name, type_name, msg in extra:
            rec.record(topic_name, type_name, msg, T0 - 1, T0 - 1)
        for i, value in enumerate(travels_m):
            rec.record(topic, 'std_msgs/msg/Float64', Float64(data=value), T0 + i * 10**7,
                       T0 + i * 10**7)


def test_example_bag_is_small_complete_and_a_sweep_of_the_default_scene():
    assert EXAMPLE.stat().st_size < 1_000_000
    messages = decoded(EXAMPLE)
    travels = [round(m.data * 1000.0, 9) for m in by_topic(messages, '/wheel_travel')]
    assert travels == list(range(-80, 81))
    # 161 commands at 50 Hz: a diagnostics report each second of it, and one at the end.
    assert [len(by_topic(messages, t)) for t in OUTPUTS] == [161, 161, 161, 4]
    reports = by_topic(messages, '/diagnostics')
    assert {m.status[0].level for m in reports} == {0}   # all OK
    assert [status_values(m.status[0])['commands'] for m in reports] == ['50', '50', '50', '11']


def test_example_bag_outputs_match_the_reference_data_of_the_scene():
    scene_file = yaml.safe_load((ROOT / 'config' / 'scenes' / 'five_link.yaml').read_text())
    messages = decoded(EXAMPLE)
    travels = [round(m.data * 1000.0, 6) for m in by_topic(messages, '/wheel_travel')]
    camber = dict(zip(travels, (math.degrees(m.data) for m in by_topic(messages, '/camber'))))
    toe = dict(zip(travels, (math.degrees(m.data) for m in by_topic(messages, '/toe'))))
    rows = scene_file['reference']['rows']       # travel_mm, camber_deg, toe_deg (4 decimals)
    assert len(rows) == 3
    for travel, camber_deg, toe_deg in rows:
        assert camber[travel] == pytest.approx(camber_deg, abs=1e-4)
        assert toe[travel] == pytest.approx(toe_deg, abs=1e-4)


def test_replaying_the_example_bag_reproduces_its_outputs(tmp_path):
    out = tmp_path / 'again.mcap'
    assert main(['solve', str(EXAMPLE), '-o', str(out)]) == 0
    recorded, replayed = decoded(EXAMPLE), decoded(out)
    assert [(t, time) for t, time, _ in replayed] == [(t, time) for t, time, _ in recorded]
    for (_, _, a), (topic, _, b) in zip(recorded, replayed):
        if topic == '/wheel_carrier_pose':
            assert b.header.frame_id == a.header.frame_id
            for field in ('x', 'y', 'z'):
                assert getattr(b.pose.position, field) == pytest.approx(
                    getattr(a.pose.position, field), abs=1e-12)
            for field in ('x', 'y', 'z', 'w'):
                assert getattr(b.pose.orientation, field) == pytest.approx(
                    getattr(a.pose.orientation, field), abs=1e-12)
        elif topic == '/diagnostics':
            assert [(s.level, s.name, s.message) for s in b.status] == [
                (s.level, s.name, s.message) for s in a.status]
        elif topic in ('/tf', '/tf_static'):       # the frames of the bodies
            def frames(message):
                return [(t.header.frame_id, t.child_frame_id) for t in message.transforms]

            def values(message):
                return [[v.x, v.y, v.z] + [w.x, w.y, w.z, w.w] for v, w in (
                    (t.transform.translation, t.transform.rotation) for t in message.transforms)]

            assert frames(b) == frames(a)
            assert np.array(values(b)) == pytest.approx(np.array(values(a)), abs=1e-12)
        elif topic == '/robot_description':    # recorded on another processor: 1e-12 m
            assert urdf_differences(b.data, a.data, abs_tol=1e-12) == []
        elif topic == '/elements':                 # five_link's damper and spring
            assert (b.name, b.header.frame_id) == (a.name, a.header.frame_id)
            assert list(b.position) == pytest.approx(list(a.position), abs=1e-12)
            assert list(b.velocity) == pytest.approx(list(a.velocity), abs=1e-12)
        else:
            assert b.data == pytest.approx(a.data, abs=1e-12)


def test_each_command_is_followed_by_pose_camber_toe_at_its_receive_time(tmp_path):
    out = tmp_path / 'sweep.mcap'
    assert main(['sweep', '--travel', '-2:2:1', '--hz', '10', '-o',
                 str(out)]) == 0
    with AnyReader([out]) as reader:
        rows = [(c.topic, t, reader.deserialize(raw, c.msgtype))
                for c, t, raw in reader.messages() if c.topic not in TF_TOPICS]
    # 0.4 s of good commands: no change of level, no full period; one report at the end.
    assert [r[0] for r in rows] == ['/wheel_travel', *OUTPUTS[:3]] * 5 + ['/diagnostics']
    for i in range(5):
        command = rows[4 * i]
        assert command[2].data == pytest.approx((i - 2) / 1000.0)
        assert {t for _, t, _ in rows[4 * i:4 * i + 4]} == {command[1]}
        stamp = rows[4 * i + 1][2].header.stamp
        assert stamp.sec * 10**9 + stamp.nanosec == command[1]
    assert rows[4][1] - rows[0][1] == 100_000_000        # 10 Hz
    assert status_values(rows[-1][2].status[0])['commands'] == '5'


def test_diagnostics_are_reported_every_second_of_the_recorded_time(tmp_path):
    bag, out = tmp_path / 'in.mcap', tmp_path / 'out.mcap'
    write_commands(bag, [0.001 * (i % 20) for i in range(250)])    # 2.5 s at 100 Hz
    assert main(['solve', str(bag), '-o', str(out)]) == 0
    reports = [(t, msg) for topic, t, msg in decoded(out) if topic == '/diagnostics']
    assert [t - T0 for t, _ in reports] == [10**9, 2 * 10**9, 249 * 10**7]
    assert [status_values(m.status[0])['commands'] for _, m in reports] == ['100', '100', '50']


def test_a_command_out_of_reach_gives_an_error_diagnostic_and_no_pose(tmp_path):
    bag, out = tmp_path / 'in.mcap', tmp_path / 'out.mcap'
    write_commands(bag, [0.01, 0.5, 0.02])                 # 500 mm: beyond the bump stop
    assert main(['solve', str(bag), '-o', str(out)]) == 0
    messages = [m for m in decoded(out) if m[0] not in TF_TOPICS]
    # At once: the ERROR of the failed command, the OK of the next (a change of level); then
    # the report after the last command.
    assert [t for t, _, _ in messages] == ['/wheel_travel', *OUTPUTS[:3], '/wheel_travel',
                                           '/diagnostics', '/wheel_travel', *OUTPUTS,
                                           '/diagnostics']
    levels = [m.status[0].level for m in by_topic(messages, '/diagnostics')]
    assert levels == [2, 0, 0]                              # ERROR, OK, OK
    assert 'out of reach' in by_topic(messages, '/diagnostics')[0].status[0].message
    assert by_topic(messages, '/wheel_carrier_pose')[1].pose.position.z == pytest.approx(
        0.32, abs=0.01)                                     # 300 mm + 20 mm, after the failure


def test_a_topic_of_another_type_is_refused_naming_its_type_and_the_topics(tmp_path, capsys):
    assert main(['solve', str(EXAMPLE), '--topic', '/wheel_carrier_pose']) == 2
    err = capsys.readouterr().err
    assert 'topic /wheel_carrier_pose carries geometry_msgs/msg/PoseStamped' in err
    assert '/wheel_travel (std_msgs/msg/Float64)' in err


def test_a_missing_topic_is_refused_listing_the_topics_present(capsys):
    assert main(['solve', str(EXAMPLE), '--topic', 'travel']) == 2
    err = capsys.readouterr().err
    assert 'no topic /travel' in err and '/camber (std_msgs/msg/Float64)' in err


def test_another_topic_name_is_solved_and_answered_in_its_namespace(tmp_path):
    bag, out = tmp_path / 'in.mcap', tmp_path / 'out.mcap'
    write_commands(bag, [0.0, 0.01], topic='/car/front_left/bump')
    assert main(['solve', str(bag), '--topic', '/car/front_left/bump', '-o', str(out)]) == 0
    topics = [t for t, _, _ in decoded(out) if t not in TF_TOPICS]
    assert topics == ['/car/front_left/bump', '/car/front_left/wheel_carrier_pose',
                      '/car/front_left/camber', '/car/front_left/toe',
                      '/car/front_left/elements'] * 2 + ['/diagnostics']


def test_a_foreign_file_is_refused_clearly(tmp_path, capsys):
    path = tmp_path / 'run.mcap'
    path.write_bytes(b'PK\x03\x04 a zip file, not a recording')
    assert main(['solve', str(path)]) == 2
    assert 'not an MCAP file' in capsys.readouterr().err


def cut_bag(tmp_path, n=300):
    """Write n commands in small chunks, cut in the middle; return (path, commands kept)."""
    bag = tmp_path / 'full.mcap'
    write_commands(bag, [i / 10000.0 for i in range(n)], chunk_size=1024)
    data = bag.read_bytes()
    cut = tmp_path / 'cut.mcap'
    cut.write_bytes(data[:len(data) // 2])
    with open(cut, 'rb') as stream:   # mcap's stream reader: what it yields before the cut
        kept = 0
        try:
            from mcap.stream_reader import StreamReader
            for record in StreamReader(stream).records:
                kept += type(record).__name__ == 'Message'
        except Exception:
            pass
    return cut, kept


def test_a_truncated_bag_is_solved_up_to_the_cut_with_a_warning(tmp_path, capsys):
    cut, kept = cut_bag(tmp_path)
    assert 0 < kept < 300
    out = tmp_path / 'out.mcap'
    assert main(['solve', str(cut), '-o', str(out)]) == 1
    assert f'bag truncated after {kept} messages' in capsys.readouterr().err
    messages = decoded(out)
    assert len(by_topic(messages, '/wheel_travel')) == kept
    assert len(by_topic(messages, '/camber')) == kept


def test_copy_turns_a_truncated_recording_into_a_complete_one(tmp_path, capsys):
    cut, kept = cut_bag(tmp_path)
    out = tmp_path / 'recovered.mcap'
    assert main(['copy', str(cut), '-o', str(out)]) == 1
    assert 'copied the' in capsys.readouterr().err
    with AnyReader([out]) as reader:       # needs the summary: the file is complete again
        values = [reader.deserialize(raw, c.msgtype).data for c, _, raw in reader.messages()]
    assert values == pytest.approx([i / 10000.0 for i in range(kept)])


def test_publish_republishes_the_commands_in_order_at_the_recorded_pace(tmp_path, domain_id):
    import rclpy
    from rclpy.context import Context
    from rclpy.executors import SingleThreadedExecutor
    from std_msgs.msg import Float64
    bag = tmp_path / 'in.mcap'
    travels = [i / 1000.0 for i in range(20)]          # 20 commands, 0.19 s apart end to end
    write_commands(bag, travels)
    domain = domain_id      # the user's (a private network in the project's runs)
    env = dict(os.environ, ROS_DOMAIN_ID=str(domain), ROS_LOG_DIR=str(tmp_path),
               ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST')
    ctx = Context()
    rclpy.init(context=ctx, domain_id=domain)
    received = []
    try:
        node = rclpy.create_node('probe', context=ctx)
        node.create_subscription(Float64, '/wheel_travel',
                                 lambda msg: received.append((time.monotonic(), msg.data)), 100)
        executor = SingleThreadedExecutor(context=ctx)
        executor.add_node(node)
        proc = subprocess.Popen([sys.executable, '-m', 'linkage_ros.tools.replay', 'publish',
                                 str(bag), '--rate', '0.5', '--wait', '20'], env=env,
                                stderr=subprocess.PIPE, text=True)
        deadline = time.monotonic() + 40
        while len(received) < len(travels) and time.monotonic() < deadline:
            executor.spin_once(timeout_sec=0.01)
        _, err = proc.communicate(timeout=30)
        assert proc.returncode == 0, err
    finally:
        rclpy.try_shutdown(context=ctx)
    assert [v for _, v in received] == travels
    # rate 0.5: the 0.19 s of the recording take 0.38 s (a lower bound: never faster)
    assert received[-1][0] - received[0][0] >= 0.9 * 0.38
    assert '20/20 commands published' in err


# --- the scene a recording stores ----------------------------------------------------------

def write_stored(path, metadata, travels_m, topic='/wheel_travel'):
    """Write Float64 commands at 100 Hz with metadata records, as a node's recording."""
    from std_msgs.msg import Float64
    with McapRecorder(path, metadata=metadata) as rec:
        for i, value in enumerate(travels_m):
            rec.record(topic, 'std_msgs/msg/Float64', Float64(data=value), T0 + i * 10**7,
                       T0 + i * 10**7)


def stored_metadata(path):
    """{record name: {key: value}} of an MCAP's metadata records, by mcap's reader."""
    with open(path, 'rb') as stream:
        return {m.name: m.metadata for m in make_reader(stream).iter_metadata()}


def test_solve_uses_the_scene_a_recording_stores_when_its_file_is_gone(
        tmp_path, monkeypatch, capsys):
    from linkage_ros import Continuation, load_scene
    text = (ROOT / 'config' / 'scenes' / 'macpherson.yaml').read_text().replace(
        'name: macpherson', 'name: my_corner', 1)
    scene_file = tmp_path / 'a' / 'my_corner.yaml'
    scene_file.parent.mkdir()
    scene_file.write_text(text)
    travels = [-0.02, 0.0, 0.03]
    expected = [Continuation(load_scene(scene_file)).solve(t * 1000.0) for t in travels]
    bag = tmp_path / 'a' / 'run.mcap'
    write_stored(bag, {'linkage_ros': {'scene_yaml': text}}, travels)
    scene_file.unlink()                                   # the path as typed is gone
    other = tmp_path / 'b'
    other.mkdir()
    monkeypatch.chdir(other)
    assert main(['solve', str(bag), '-o', 'solved.mcap']) == 0
    assert f'the scene stored in {bag}: my_corner' in capsys.readouterr().err
    poses = by_topic(decoded(other / 'solved.mcap'), '/wheel_carrier_pose')
    assert [p.pose.position.z for p in poses] == pytest.approx(
        [s.wheel_center[2] / 1000.0 for s in expected], abs=1e-12)
    # replay's recording stores it in turn, so it can be solved again anywhere
    assert stored_metadata(other / 'solved.mcap')['linkage_ros'] == {'scene_yaml': text}
    assert main(['solve', 'solved.mcap', '-o', 'again.mcap']) == 0
    assert 'the scene stored in solved.mcap: my_corner' in capsys.readouterr().err


def test_a_sweep_stores_the_text_of_its_scene_file(tmp_path):
    out = tmp_path / 'sweep.mcap'
    assert main(['sweep', '--scene', 'macpherson', '--travel', '0:1:1', '-o',
                 str(out)]) == 0
    assert stored_metadata(out)['linkage_ros'] == {
        'scene_yaml': (ROOT / 'config' / 'scenes' / 'macpherson.yaml').read_text()}


def test_a_vehicle_recording_is_solved_with_the_corner_its_topic_names(tmp_path, capsys):
    from linkage_ros import Continuation
    from linkage_ros.core.model import load_vehicle
    text = (ROOT / 'config' / 'vehicles' / 'demo_vehicle.yaml').read_text()
    bag, out = tmp_path / 'car.mcap', tmp_path / 'out.mcap'
    write_stored(bag, {'linkage_ros': {'vehicle_yaml': text}}, [0.01, 0.02],
                 topic='/front_right/wheel_travel')
    assert main(['solve', str(bag), '--topic', '/front_right/wheel_travel', '-o',
                 str(out)]) == 0
    assert f'the scene stored in {bag}: front_right' in capsys.readouterr().err
    corner = Continuation(load_vehicle('demo_vehicle').corners['front_right'])
    poses = by_topic(decoded(out), '/front_right/wheel_carrier_pose')
    for travel, pose in zip([0.01, 0.02], poses):
        centre = corner.solve(travel * 1000.0).wheel_center / 1000.0    # m; y < 0: right
        assert [pose.pose.position.x, pose.pose.position.y, pose.pose.position.z] == \
            pytest.approx(centre.tolist(), abs=1e-12)


def test_a_stored_scene_with_an_alias_chain_is_refused_in_one_line(tmp_path, capsys):
    # A "billion laughs" chain: 10 levels of 10 aliases stand for 1e10 values, refused by the
    # loader's bound on values (core.model.yaml_file.VALUES_LIMIT) before anything is expanded.
    levels = ['l0: &l0 [x, x, x, x, x, x, x, x, x, x]'] + [
        f'l{i}: &l{i} [' + ', '.join([f'*l{i - 1}'] * 10) + ']' for i in range(1, 10)]
    bag = tmp_path / 'run.mcap'
    write_stored(bag, {'linkage_ros': {'scene_yaml': '\n'.join(levels) + '\nname: *l9\n'}},
                 [0.0])
    assert main(['solve', str(bag), '-o', str(tmp_path / 'out.mcap')]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f'linkage-replay: {bag} (its scene_yaml): line ') and 'values' in err
    assert err.count('\n') == 1
    assert main(['solve', str(bag), '--scene', 'five_link', '-o',
                 str(tmp_path / 'out.mcap')]) == 0              # --scene takes precedence
