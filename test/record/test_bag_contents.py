# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
What a bag holds beyond our own recordings: schemas of any encoding, malformed messages.

The bags are written with the mcap library's own Writer (as rosbag2, Foxglove or an attacker
would write them), never with McapRecorder; what linkage-replay copy writes is read back by
mcap's reader and by rosbags' AnyReader.
"""

import struct

from linkage_ros.answer import cdr
from linkage_ros.record.mcap_reader import read_bag
from linkage_ros.record.mcap_writer import McapRecorder
from linkage_ros.tools import replay
from mcap.reader import make_reader
from mcap.writer import CompressionType, Writer
from rosbags.highlevel import AnyReader

FLOAT64 = 'std_msgs/msg/Float64'
SEPARATOR = '=' * 80
# An IDL type as rosbag2 stores it (schema encoding 'ros2idl'): each type after a line of '='
# and 'IDL: <type>'. No package of this name is installed, so there is no .msg to look up.
READING = 'idl_demo_msgs/msg/Reading'
READING_IDL = (f'{SEPARATOR}\nIDL: {READING}\n'
               'module idl_demo_msgs {\n  module msg {\n    struct Reading {\n'
               '      double value;\n      string label;\n    };\n  };\n};\n')


def reading_cdr(value, label):
    """Return an idl_demo_msgs/msg/Reading in CDR: a double, then a string (length, NUL)."""
    text = label.encode() + b'\0'
    return cdr.CDR_LE + struct.pack(f'<dI{len(text)}s', value, len(text), text)


def write(path, channels, messages):
    """
    Write an MCAP (profile ros2) with the mcap library's Writer.

    channels: {topic: (schema name, schema encoding, schema text)}; messages: [(topic,
    bytes)], logged 1 ms apart in this order.
    """
    with open(path, 'wb') as stream:
        writer = Writer(stream, compression=CompressionType.ZSTD)
        writer.start(profile='ros2', library='test')
        ids = {}
        for topic, (name, encoding, text) in channels.items():
            schema = writer.register_schema(name=name, encoding=encoding, data=text.encode())
            ids[topic] = writer.register_channel(topic=topic, message_encoding='cdr',
                                                 schema_id=schema)
        for i, (topic, data) in enumerate(messages):
            writer.add_message(ids[topic], log_time=10**6 * i, data=data,
                               publish_time=10**6 * i)
        writer.finish()


def test_copy_keeps_a_ros2idl_topic_and_everything_after_it_as_stored(tmp_path, capsys):
    source, out = tmp_path / 'idl.mcap', tmp_path / 'copy.mcap'
    stored = [('/wheel_travel', cdr.float64_cdr(0.01)), ('/reading', reading_cdr(1.5, 'hello')),
              ('/wheel_travel', cdr.float64_cdr(0.02)), ('/reading', reading_cdr(-2.0, 'x'))]
    write(source, {'/wheel_travel': (FLOAT64, 'ros2msg', 'float64 data\n'),
                   '/reading': (READING, 'ros2idl', READING_IDL)}, stored)
    assert replay.main(['copy', str(source), '-o', str(out)]) == 0
    assert 'wrote 4 messages' in capsys.readouterr().err
    with open(out, 'rb') as stream:        # mcap's reader: schema and bytes as they were
        reader = make_reader(stream)
        copied = [(channel.topic, schema.name, schema.encoding, schema.data, message.data)
                  for schema, channel, message in reader.iter_messages(log_time_order=False)]
    assert [(topic, data) for topic, *_, data in copied] == stored
    assert {(topic, name, encoding, text.decode()) for topic, name, encoding, text, _ in copied} \
        == {('/wheel_travel', FLOAT64, 'ros2msg', 'float64 data\n'),
            ('/reading', READING, 'ros2idl', READING_IDL)}
    with AnyReader([out]) as reader:       # rosbags decodes the IDL type from the copy
        decoded = [(c.topic, reader.deserialize(data, c.msgtype))
                   for c, _, data in reader.messages()]
    assert [(m.value, m.label) for topic, m in decoded if topic == '/reading'] == [
        (1.5, 'hello'), (-2.0, 'x')]
    assert [m.data for topic, m in decoded if topic == '/wheel_travel'] == [0.01, 0.02]


def test_copy_keeps_a_topic_that_a_bag_holds_in_two_types(tmp_path):
    source, out = tmp_path / 'two.mcap', tmp_path / 'copy.mcap'
    stored = [(FLOAT64, cdr.float64_cdr(0.5)), (READING, reading_cdr(0.0, 'text')),
              (FLOAT64, cdr.float64_cdr(0.25))]
    with open(source, 'wb') as stream:     # two channels named /camber, of two types
        writer = Writer(stream)
        writer.start(profile='ros2', library='test')
        ids = {}
        for name, encoding, text in ((FLOAT64, 'ros2msg', 'float64 data\n'),
                                     (READING, 'ros2idl', READING_IDL)):
            schema = writer.register_schema(name=name, encoding=encoding, data=text.encode())
            ids[name] = writer.register_channel(topic='/camber', message_encoding='cdr',
                                                schema_id=schema)
        for i, (name, data) in enumerate(stored):
            writer.add_message(ids[name], log_time=i, data=data, publish_time=i)
        writer.finish()
    assert replay.main(['copy', str(source), '-o', str(out)]) == 0
    with open(out, 'rb') as stream:
        copied = [(channel.topic, schema.name, message.data) for schema, channel, message in
                  make_reader(stream).iter_messages(log_time_order=False)]
    assert copied == [('/camber', name, data) for name, data in stored]


# --- messages that do not decode -----------------------------------------------------------

def test_bag_messages_keep_their_schema_and_encoding(tmp_path):
    source = tmp_path / 'idl.mcap'
    write(source, {'/reading': (READING, 'ros2idl', READING_IDL)},
          [('/reading', reading_cdr(1.0, 'a'))])
    message, = read_bag(source).messages
    assert message.type_name == READING and message.encoding == 'cdr'
    assert message.schema == (READING, 'ros2idl', READING_IDL.encode())
    assert message.carries(READING) and not message.carries(FLOAT64)


def test_decode_counts_and_names_what_does_not_decode_and_reads_the_rest(tmp_path):
    source = tmp_path / 'bad.mcap'
    write(source, {'/camber': (FLOAT64, 'ros2msg', 'float64 data\n')},
          [('/camber', cdr.float64_cdr(0.25)), ('/camber', cdr.CDR_LE + b'\x01'),
           ('/camber', cdr.float64_cdr(-0.5)), ('/camber', b'\x00\x01\x00')])
    bag = read_bag(source)
    assert bag.complete
    assert [bag.decode(m, cdr.float64_of) for m in bag.messages] == [0.25, None, -0.5, None]
    assert not bag.complete and not bag.truncated
    assert bag.undecoded == {'/camber': (2, 'std_msgs/Float64 of 5 bytes: too short: it '
                                         'needs 12 bytes')}
    assert bag.losses() == ['2 messages on /camber do not decode, left out (the first: '
                            'std_msgs/Float64 of 5 bytes: too short: it needs 12 bytes)']
    # The default reader is rclpy's message of the stored type:
    assert bag.decode(bag.messages[0]).data == 0.25


def test_metadata_given_to_the_recorder_is_in_the_file_even_after_a_hard_kill(tmp_path):
    path = tmp_path / 'run.mcap'
    stored = {'linkage_ros': {'scene_yaml': 'name: x\nunits: mm\n', 'vehicle_yaml': ''}}
    recorder = McapRecorder(path, flush_period=0, metadata=stored)
    recorder.record('/camber', FLOAT64, cdr.float64_cdr(0.1), 1, 1)
    recorder.flush()
    cut = tmp_path / 'cut.mcap'      # as a hard kill leaves it: no summary, no close
    cut.write_bytes(path.read_bytes())
    recorder.close()
    with open(path, 'rb') as stream:      # mcap's reader: ours, and rosbag2's at close
        records = {m.name: m.metadata for m in make_reader(stream).iter_metadata()}
    assert sorted(records) == ['linkage_ros', 'rosbag2']
    assert records['linkage_ros'] == stored['linkage_ros']
    bag = read_bag(cut)
    assert bag.truncated and bag.metadata == stored
