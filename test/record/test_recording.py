# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
McapRecorder writes the layout rosbag2's MCAP storage writes; read back by independent readers.

Readers: mcap's make_reader with mcap_ros2's DecoderFactory, rosbags' AnyReader, and mcap's
StreamReader for cut files. Expected layout from ros2/rosbag2 rosbag2_storage_mcap (Jazzy):
mcap_storage.cpp (channels, 'rosbag2' metadata record) and message_definition_cache.cpp
(schema text). No DDS is needed: messages are real rclpy messages serialized with rclpy.
"""

import collections
import json
import os
from pathlib import Path
import re
import signal
import subprocess
import sys
import textwrap

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from geometry_msgs.msg import PoseStamped
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import sweep
from linkage_ros.record.interfaces import message_definition, SEPARATOR, share_dirs
from linkage_ros.record.mcap_reader import read_bag, RecordingError
from linkage_ros.record.mcap_writer import McapRecorder
from linkage_ros.ros.testing import connect, Probe, spin_until
from mcap.reader import make_reader
from mcap.stream_reader import breakup_chunk, StreamReader
from mcap_ros2.decoder import DecoderFactory
import numpy as np
import pytest
from rerun.chunk import RrdReader
from rosbags.highlevel import AnyReader
from std_msgs.msg import Float64
import yaml

T0 = 1_700_000_000_000_000_000   # ns since the epoch
PERIOD = 10_000_000              # 100 Hz
TYPES = {'/wheel_travel': 'std_msgs/msg/Float64',
         '/wheel_carrier_pose': 'geometry_msgs/msg/PoseStamped',
         '/camber': 'std_msgs/msg/Float64', '/toe': 'std_msgs/msg/Float64',
         '/diagnostics': 'diagnostic_msgs/msg/DiagnosticArray'}
# suspension_node's on five_link, whose spring and damper it publishes with every answer,
# with TF on (the default): the bodies' frames per answer, the wheel's and the URDF at start
NODE_TYPES = {**TYPES, '/elements': 'sensor_msgs/msg/JointState',
              '/tf': 'tf2_msgs/msg/TFMessage', '/tf_static': 'tf2_msgs/msg/TFMessage',
              '/robot_description': 'std_msgs/msg/String'}


def pose(i):
    msg = PoseStamped()
    msg.header.frame_id = 'base_link'
    msg.header.stamp.sec, msg.header.stamp.nanosec = divmod(T0 + i * PERIOD, 10**9)
    msg.pose.position.x, msg.pose.position.y, msg.pose.position.z = 0.001 * i, 0.76, 0.3
    msg.pose.orientation.z, msg.pose.orientation.w = 0.6, 0.8
    return msg


def diagnostics(i):
    status = DiagnosticStatus(level=DiagnosticStatus.ERROR, name='suspension_node',
                              message=f'travel {i} mm is out of reach',
                              values=[KeyValue(key='travel_mm', value=str(i))])
    return DiagnosticArray(status=[status])


def write_run(path, n=50, **options):
    """
    Write n commands, each followed by the node's four outputs; every 10th a diagnostic too.

    Topic names given without the leading '/' for the commands: recorded fully qualified.
    Returns the expected [(topic, log time, value)] in write order.
    """
    expected = []
    with McapRecorder(path, custom_data={'scene': 'five_link'}, **options) as rec:
        for i in range(n):
            t = T0 + i * PERIOD
            rec.record('wheel_travel', TYPES['/wheel_travel'], Float64(data=i / 1000.0), t,
                       t - 1000)
            expected.append(('/wheel_travel', t, i / 1000.0))
            rec.record('/wheel_carrier_pose', TYPES['/wheel_carrier_pose'], pose(i), t + 1, t + 1)
            expected.append(('/wheel_carrier_pose', t + 1, 0.001 * i))
            for topic, value in (('/camber', -0.01 * i), ('/toe', 0.002 * i)):
                rec.record(topic, TYPES[topic], Float64(data=value), t + 2, t + 2)
                expected.append((topic, t + 2, value))
            if i % 10 == 0:
                rec.record('/diagnostics', TYPES['/diagnostics'], diagnostics(i), t + 3, t + 3)
                expected.append(('/diagnostics', t + 3, f'travel {i} mm is out of reach'))
    return expected


def value_of(topic, msg):
    if topic == '/wheel_carrier_pose':
        return msg.pose.position.x
    if topic == '/diagnostics':
        return msg.status[0].message
    return msg.data


@pytest.fixture
def run(tmp_path):
    path = tmp_path / 'run.mcap'
    return path, write_run(path)


def test_mcap_reader_decodes_every_message_in_order_with_its_type(run):
    path, expected = run
    with open(path, 'rb') as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        got = [(channel.topic, schema.name, message.log_time, value_of(channel.topic, decoded))
               for schema, channel, message, decoded in reader.iter_decoded_messages(
                   log_time_order=False)]
    assert [(t, TYPES[t], time, v) for t, time, v in expected] == got


def test_header_schemas_and_channels_follow_the_rosbag2_layout(run):
    path, expected = run
    with open(path, 'rb') as stream:
        reader = make_reader(stream)
        header, summary = reader.get_header(), reader.get_summary()
    assert header.profile == 'ros2'
    assert header.library.startswith('linkage_ros')
    assert sorted(s.name for s in summary.schemas.values()) == sorted(set(TYPES.values()))
    assert {s.encoding for s in summary.schemas.values()} == {'ros2msg'}
    channels = {c.topic: c for c in summary.channels.values()}
    assert set(channels) == set(TYPES)
    for topic, channel in channels.items():
        assert channel.message_encoding == 'cdr'
        assert summary.schemas[channel.schema_id].name == TYPES[topic]
        package, _, name = TYPES[topic].split('/')
        installed = json.loads((Path(sys.prefix) / 'share' / package / 'msg' / f'{name}.json')
                               .read_text())['type_hashes'][0]
        assert installed['type_name'] == TYPES[topic]
        assert channel.metadata['topic_type_hash'] == installed['hash_string']
        qos = yaml.safe_load(channel.metadata['offered_qos_profiles'])
        assert qos[0]['reliability'] == 'reliable' and qos[0]['history'] == 'keep_last'


def test_summary_statistics_count_messages_per_channel_and_chunks_are_zstd(run):
    path, expected = run
    with open(path, 'rb') as stream:
        summary = make_reader(stream).get_summary()
    stats = summary.statistics
    assert stats.message_count == len(expected)
    by_topic = {c.topic: stats.channel_message_counts[i] for i, c in summary.channels.items()}
    assert by_topic == {t: sum(1 for e in expected if e[0] == t) for t in TYPES}
    assert stats.message_start_time == expected[0][1]
    assert stats.message_end_time == max(e[1] for e in expected)
    assert {c.compression for c in summary.chunk_indexes} == {'zstd'}


def test_rosbag2_metadata_record_is_version_9_with_counts_and_qos(run):
    path, expected = run
    with open(path, 'rb') as stream:
        records = list(make_reader(stream).iter_metadata())
    assert [m.name for m in records] == ['rosbag2']
    meta = yaml.safe_load(records[0].metadata['serialized_metadata'])
    assert meta['version'] == 9 and meta['storage_identifier'] == 'mcap'
    assert meta['message_count'] == len(expected)
    assert meta['starting_time']['nanoseconds_since_epoch'] == expected[0][1]
    assert meta['duration']['nanoseconds'] == max(e[1] for e in expected) - expected[0][1]
    topics = {t['topic_metadata']['name']: t for t in meta['topics_with_message_count']}
    assert set(topics) == set(TYPES)
    for name, entry in topics.items():
        assert entry['topic_metadata']['type'] == TYPES[name]
        assert entry['topic_metadata']['serialization_format'] == 'cdr'
        assert entry['topic_metadata']['offered_qos_profiles'][0]['durability'] == 'volatile'
        assert entry['topic_metadata']['type_description_hash'].startswith('RIHS01_')
        assert entry['message_count'] == sum(1 for e in expected if e[0] == name)
    assert meta['relative_file_paths'] == ['run.mcap']
    assert meta['custom_data'] == {'scene': 'five_link'}


def test_rosbags_reads_types_counts_order_and_values(run):
    path, expected = run
    with AnyReader([path]) as reader:
        assert {c.topic: (c.msgtype, c.msgcount) for c in reader.connections} == {
            t: (TYPES[t], sum(1 for e in expected if e[0] == t)) for t in TYPES}
        got = [(c.topic, time, value_of(c.topic, reader.deserialize(raw, c.msgtype)))
               for c, time, raw in reader.messages()]
        qos = {c.topic: c.ext.offered_qos_profiles[0] for c in reader.connections}
    assert got == sorted(expected, key=lambda e: e[1])
    assert qos['/wheel_travel'].depth == 10
    assert qos['/wheel_travel'].reliability.name.lower() == 'reliable'


def test_the_rerun_binary_checks_the_recording_and_decodes_its_ros2_stamps(run):
    path, expected = run
    rerun = Path(sys.executable).parent / 'rerun'
    result = subprocess.run([str(rerun), 'mcap', 'check', '--full', str(path)],
                            capture_output=True, text=True, timeout=60,
                            env=dict(os.environ, RERUN_ANALYTICS='0'))
    assert result.returncode == 0, result.stderr
    report = result.stdout + result.stderr
    assert 'ros2_timestamp' in report            # it decoded the ROS 2 message headers
    for topic in TYPES:
        assert re.search(rf'^ok\s+\d+\s+\d+\s+{topic}\s', report, re.MULTILINE), report


def test_schema_is_msg_text_then_each_dependency_once_depth_first_in_sorted_order():
    text = message_definition('geometry_msgs/msg/PoseStamped')
    share = Path(sys.prefix) / 'share'
    parts = text.split(f'\n{SEPARATOR}\n')
    assert parts[0] == (share / 'geometry_msgs' / 'msg' / 'PoseStamped.msg').read_text()
    names = [p.split('\n', 1)[0] for p in parts[1:]]
    # rosbag2: dependencies of each type sorted, each appended once, recursively.
    assert names == ['MSG: geometry_msgs/Pose', 'MSG: geometry_msgs/Point',
                     'MSG: geometry_msgs/Quaternion', 'MSG: std_msgs/Header',
                     'MSG: builtin_interfaces/Time']
    time_msg = share / 'builtin_interfaces' / 'msg' / 'Time.msg'
    assert parts[-1].split('\n', 1)[1] == time_msg.read_text()


def test_message_definitions_are_found_through_ament_prefix_path(monkeypatch):
    monkeypatch.setenv('AMENT_PREFIX_PATH', '/nonexistent' + os.pathsep + sys.prefix)
    assert share_dirs()[:2] == [Path('/nonexistent/share'), Path(sys.prefix) / 'share']
    assert 'MSG: diagnostic_msgs/KeyValue' in message_definition(
        'diagnostic_msgs/msg/DiagnosticArray')


@pytest.mark.parametrize('type_name, problem', [
    ('std_msgs/msg/NoSuchType', 'no NoSuchType.msg found'),
    ('Float64', "expected a ROS 2 message type like 'std_msgs/msg/Float64'"),
])
def test_unknown_type_raises_an_error_naming_it(tmp_path, type_name, problem):
    with McapRecorder(tmp_path / 'x.mcap') as rec:
        with pytest.raises(RecordingError, match=problem):
            rec.record('/x', type_name, b'\0\1\0\0', 1, 1)


def test_unwritable_path_raises_an_error_naming_it(tmp_path):
    blocker = tmp_path / 'file'
    blocker.write_text('')
    with pytest.raises(RecordingError, match='file/run.mcap: cannot write'):
        McapRecorder(blocker / 'run.mcap')


def test_close_is_idempotent_and_later_records_are_refused(tmp_path):
    rec = McapRecorder(tmp_path / 'x.mcap')
    rec.record('/camber', 'std_msgs/msg/Float64', Float64(data=1.0), 5, 5)
    rec.close()
    size = os.path.getsize(tmp_path / 'x.mcap')
    rec.close()
    assert os.path.getsize(tmp_path / 'x.mcap') == size
    with pytest.raises(RecordingError, match='closed'):
        rec.record('/camber', 'std_msgs/msg/Float64', Float64(data=2.0), 6, 6)


def test_a_topic_keeps_its_first_type(tmp_path):
    with McapRecorder(tmp_path / 'x.mcap') as rec:
        rec.record('/camber', 'std_msgs/msg/Float64', Float64(data=1.0), 5, 5)
        with pytest.raises(RecordingError, match='recorded as std_msgs/msg/Float64'):
            rec.record('/camber', 'geometry_msgs/msg/PoseStamped', PoseStamped(), 6, 6)


def chunk_ends(path):
    """
    Return (start offset, end offset, messages up to and including it) of each chunk.

    Offsets from the summary's chunk indexes, counts from the chunks themselves (mcap's
    stream reader).
    """
    with open(path, 'rb') as stream:
        chunks = sorted(make_reader(stream).get_summary().chunk_indexes,
                        key=lambda c: c.chunk_start_offset)
    with open(path, 'rb') as stream:
        counts = [sum(1 for r in breakup_chunk(record) if type(r).__name__ == 'Message')
                  for record in StreamReader(stream, emit_chunks=True).records
                  if type(record).__name__ == 'Chunk']
    totals = [sum(counts[:i + 1]) for i in range(len(counts))]
    return [(c.chunk_start_offset, c.chunk_start_offset + c.chunk_length, n)
            for c, n in zip(chunks, totals)]


def test_cut_file_yields_every_message_of_the_chunks_before_the_cut(tmp_path):
    path = tmp_path / 'run.mcap'
    expected = write_run(path, n=200, chunk_size=2048)
    ends = chunk_ends(path)
    assert len(ends) > 5
    data = path.read_bytes()
    cut = tmp_path / 'cut.mcap'
    for start, end, count in ends[1:4]:
        # Cut after a chunk, in the header of its first message index, inside the next chunk.
        for offset, problem in (
                (end, f'cut at byte {end} (the file ends after the chunk record at byte '
                 f'{start}, before the footer)'),
                (end + 5, f'cut at byte {end + 5} (the file ends inside the message index '
                 f'record at byte {end})')):
            cut.write_bytes(data[:offset])
            bag = read_bag(cut)
            assert bag.truncated and bag.cut and bag.problem == problem
            assert [(m.topic, m.log_time) for m in bag.messages] == [
                (t, time) for t, time, _ in expected[:count]]


def test_hard_kill_loses_only_the_chunk_being_built(tmp_path):
    """
    Keep the chunks written before a SIGKILL readable.

    By mcap's own stream reader, and by read_bag (linkage-replay's reader).
    """
    path = tmp_path / 'killed.mcap'
    script = textwrap.dedent(f"""
        import os, signal, time
        from std_msgs.msg import Float64
        from linkage_ros.record.mcap_writer import McapRecorder
        rec = McapRecorder({str(path)!r}, flush_period=0.1)
        for i in range(100):
            rec.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=i), i + 1, i + 1)
        time.sleep(1.0)       # the flush thread writes the chunk of those 100
        for i in range(100, 110):
            rec.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=i), i + 1, i + 1)
        os.kill(os.getpid(), signal.SIGKILL)
    """)
    proc = subprocess.run([sys.executable, '-c', script], timeout=60)
    assert proc.returncode == -signal.SIGKILL
    independent = []
    with open(path, 'rb') as stream:
        with pytest.raises(Exception):   # no summary, no footer: the reader hits the end
            for record in StreamReader(stream).records:
                if type(record).__name__ == 'Message':
                    independent.append(record.log_time)
    bag = read_bag(path)
    assert bag.truncated
    assert len(independent) >= 100 and len(bag.messages) == len(independent)
    assert [m.log_time for m in bag.messages] == list(range(1, len(independent) + 1))


def test_a_rosbag2_bag_folder_is_read_through_its_mcap_file(tmp_path):
    folder = tmp_path / 'run'
    expected = write_run(folder / 'run_0.mcap', n=3)
    (folder / 'metadata.yaml').write_text('rosbag2_bagfile_information: {}\n')
    assert len(read_bag(folder).messages) == len(expected)
    (folder / 'run_1.mcap').write_bytes(b'')
    with pytest.raises(RecordingError, match='exactly one .mcap file'):
        read_bag(folder)


def test_reading_a_foreign_file_says_it_is_not_mcap(tmp_path):
    path = tmp_path / 'notes.mcap'
    path.write_text('travel,camber\n0,0\n')
    with pytest.raises(RecordingError, match='not an MCAP file'):
        read_bag(path)


def test_reading_a_complete_file_gives_all_messages_and_no_truncation(run):
    path, expected = run
    bag = read_bag(path)
    assert not bag.truncated and bag.profile == 'ros2'
    assert bag.topics == TYPES
    assert [(m.topic, m.log_time) for m in bag.messages] == [(t, time) for t, time, _ in expected]
    assert bag.custom_data == {'scene': 'five_link'}
    assert bag.qos['/camber']['reliability'] == 'reliable'


# --- end to end: suspension_node with record_mcap and rerun_rrd, stopped by a signal --------

@pytest.mark.parametrize('sig', [signal.SIGINT, signal.SIGTERM], ids=['SIGINT', 'SIGTERM'])
def test_node_run_stopped_by_a_signal_leaves_complete_files_with_every_message(
        node_process, localhost_context, localhost_executor, tmp_path, sig):
    """
    Record and mirror a run of suspension_node stopped by SIGINT or SIGTERM.

    The MCAP is complete (summary, rosbag2 metadata) and holds each command and each answer
    in order, with the core's values; the .rrd holds one sample per command and per pose.
    """
    mcap_path, rrd_path = tmp_path / 'run.mcap', tmp_path / 'run.rrd'
    process = node_process('-p', f'record_mcap:={mcap_path}', '-p', f'rerun_rrd:={rrd_path}')
    probe = Probe(localhost_context, localhost_executor)
    connect(localhost_executor, probe)                  # travel 0 pings until answered
    travels = [0.01 * i for i in range(-5, 6)]
    expected = sweep(load_scene('five_link'), np.array(travels) * 1000.0)
    probe.send(*travels)
    assert spin_until(localhost_executor, lambda: probe.answered(expected))
    # The node records each output before publishing it, so an answer the probe has is in
    # the file even when the signal comes right after it.
    code, _, err = process.stop(sig)
    assert code == 0, err

    with open(mcap_path, 'rb') as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        summary = reader.get_summary()
        rows = [(c.topic, s.name, m.log_time, d) for s, c, m, d in
                reader.iter_decoded_messages(log_time_order=False)]
    assert summary is not None and summary.statistics.message_count == len(rows)
    commands = [r for r in rows if r[0] == '/wheel_travel']
    n = len(commands)                                     # pings + the 11 travels
    assert n >= len(travels) + 1
    # /diagnostics: once a second; the wheel frame and the URDF: once, at start
    answers = {t: 1 if t in ('/tf_static', '/robot_description') else n
               for t in NODE_TYPES if t != '/diagnostics'}
    assert {t: sum(1 for r in rows if r[0] == t) for t in answers} == answers, err
    assert {(r[0], r[1]) for r in rows} <= set(NODE_TYPES.items())
    assert [r[3].data for r in commands[-len(travels):]] == travels
    for topic, values in (('/camber', expected.camber), ('/toe', expected.toe)):
        got = [r[3].data for r in rows if r[0] == topic][-len(travels):]
        assert got == pytest.approx(list(values), abs=1e-12)
    # Order: at start the wheel frame and the URDF, then every command followed by its pose,
    # camber, toe, elements and the bodies' frames.
    assert [r[0] for r in rows if r[0] != '/diagnostics'] == [
        '/tf_static', '/robot_description'] + [
        '/wheel_travel', '/wheel_carrier_pose', '/camber', '/toe', '/elements', '/tf'] * n
    assert all(a[2] <= b[2] for a, b in zip(rows, rows[1:]))
    with AnyReader([mcap_path]) as bag:
        assert {c.topic: c.msgcount for c in bag.connections
                if c.topic != '/diagnostics'} == answers
        depths = {c.topic: c.ext.offered_qos_profiles[0].depth for c in bag.connections}
        # latched (transient local, the last one) as tf2 and robot_state_publisher latch them
        assert {t: d for t, d in depths.items() if d != 1000} == {
            '/tf_static': 1, '/robot_description': 1}

    reader = RrdReader(str(rrd_path))
    samples = collections.Counter()
    for chunk in reader.stream(store=reader.recordings()[0]):
        if not chunk.is_static:
            samples[chunk.entity_path] += chunk.num_rows
    assert samples == {'/plots/travel_mm': n, '/plots/camber_deg': n, '/plots/toe_deg': n,
                       '/suspension/carrier': n, '/suspension/links': n}
