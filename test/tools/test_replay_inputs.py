# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-replay against hostile and extreme input: each case of issue 23 that concerns it.

Malformed messages in a valid MCAP (written by the mcap library's Writer directly, not
project code), damaged files that hold nothing, numbers that no run can carry out, outputs
that would overwrite an input or leave the current folder. Statuses: 1 done with something
lost (said on stderr); 2 a mistake, one line, nothing written. Bags are read back with mcap +
mcap_ros2 (not project code).
"""

from pathlib import Path
import shutil
import struct

from linkage_ros.bench.replay import main as bench
from linkage_ros.core.model import load_scene
from linkage_ros.tools.replay import main
from mcap.reader import make_reader
from mcap.writer import Writer
from mcap_ros2.decoder import DecoderFactory
import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / 'bags' / 'five_link_sweep.mcap'
T0 = 1_700_000_000_000_000_000
MS = 10**6
POSE_STAMPED = """std_msgs/Header header
geometry_msgs/Pose pose
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
================================================================================
MSG: geometry_msgs/Pose
Point position
Quaternion orientation
================================================================================
MSG: geometry_msgs/Point
float64 x
float64 y
float64 z
================================================================================
MSG: geometry_msgs/Quaternion
float64 x
float64 y
float64 z
float64 w
"""


def float64(value):
    """Return a std_msgs/Float64 in CDR (little-endian), by hand."""
    return b'\x00\x01\x00\x00' + struct.pack('<d', value)


def string(text):
    """Return a std_msgs/String in CDR: uint32 length with the NUL, the bytes, the NUL."""
    data = text.encode() + b'\0'
    return b'\x00\x01\x00\x00' + struct.pack('<I', len(data)) + data


def write_bag(path, channels):
    """
    Write an MCAP with mcap's Writer: channels is [(topic, type, schema text, [bytes])].

    Messages of each channel 10 ms apart from T0, channel after channel.
    """
    with open(path, 'wb') as stream:
        writer = Writer(stream)
        writer.start(profile='ros2', library='test')
        t = T0
        for topic, type_name, schema, datas in channels:
            schema_id = writer.register_schema(type_name, 'ros2msg', schema.encode())
            channel = writer.register_channel(topic, 'cdr', schema_id)
            for data in datas:
                writer.add_message(channel, log_time=t, data=data, publish_time=t)
                t += 10 * MS
        writer.finish()
    return path


def decoded(path):
    """Return [(topic, decoded message)] in file order, by mcap + mcap_ros2."""
    with open(path, 'rb') as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        return [(c.topic, d) for _, c, _, d in reader.iter_decoded_messages(
            log_time_order=False)]


@pytest.fixture
def malformed_bag(tmp_path):
    """Write a valid MCAP whose messages include each malformation of issue 23, item 8."""
    return write_bag(tmp_path / 'malformed.mcap', [
        ('/wheel_travel', 'std_msgs/msg/Float64', 'float64 data',
         [float64(0.01), float64(0.02)[:5], float64(0.02),          # a 5-byte Float64
          b'\x07\x07\x00\x00' + bytes(8), float64(0.03)]),          # not CDR
        ('/wheel_travel', 'std_msgs/msg/String', 'string data', [string('0.5')]),
        ('/wheel_carrier_pose', 'geometry_msgs/msg/PoseStamped', POSE_STAMPED,
         [b'\x00\x01\x00\x00' + bytes(16),                          # a short PoseStamped
          b'\x00\x01\x00\x00' + bytes(8) + b'\xff\xff\xff\xff' + bytes(64)]),  # frame 2^32-1
        ('/camber', 'std_msgs/msg/String', 'string data', [string('wide')]),
    ])


def test_commands_that_do_not_decode_are_lost_and_named_and_the_status_is_1(
        malformed_bag, tmp_path, capsys):
    out = tmp_path / 'out.mcap'
    assert main(['solve', str(malformed_bag), '-o', str(out)]) == 1
    err = capsys.readouterr().err
    assert (f'linkage-replay: warning: {malformed_bag}: 2 of the 5 commands on /wheel_travel '
            f'do not decode and are lost (the first at 1700000000.010000000 s: '
            'std_msgs/Float64 of 5 bytes: too short: it needs 12 bytes)\n') in err
    assert 'Traceback' not in err
    messages = decoded(out)
    assert [m.data for t, m in messages if t == '/wheel_travel'] == [0.01, 0.02, 0.03]
    assert len([m for t, m in messages if t == '/camber']) == 3


def test_a_channel_of_another_type_on_the_command_topic_is_skipped_with_a_line(
        malformed_bag, tmp_path, capsys):
    assert main(['solve', str(malformed_bag), '-o', str(tmp_path / 'out.mcap')]) == 1
    err = capsys.readouterr().err
    # The String '0.5' is not read as a Float64 (0.5 m would be out of reach: an ERROR).
    assert (f'linkage-replay: warning: {malformed_bag}: 1 message of std_msgs/msg/String on '
            '/wheel_travel skipped: commands are std_msgs/msg/Float64\n') in err
    reports = [m for t, m in decoded(tmp_path / 'out.mcap') if t == '/diagnostics']
    assert {r.status[0].level for r in reports} == {0}


def test_bench_counts_the_same_loss(malformed_bag, capsys):
    assert bench([str(malformed_bag)]) == 1
    captured = capsys.readouterr()
    assert '2 of the 5 commands on /wheel_travel do not decode' in captured.err
    assert captured.out.splitlines()[1].startswith('no recording,3,')


def test_a_topic_that_carries_no_commands_at_all_is_still_a_mistake(malformed_bag, capsys):
    assert main(['solve', str(malformed_bag), '--topic', '/camber']) == 2
    assert capsys.readouterr().err.count('\n') == 1


# --- damaged files from which nothing can be read ------------------------------------------

@pytest.mark.parametrize('size, damage', [
    (4, 'cut at byte 4 (the file ends inside the magic bytes)'),
    (8, 'cut at byte 8'),
    (20, 'cut at byte 20'),
])
def test_a_damaged_file_that_yields_nothing_is_status_1_naming_the_damage(
        tmp_path, capsys, size, damage):
    bag = tmp_path / 'stub.mcap'
    bag.write_bytes(EXAMPLE.read_bytes()[:size])
    out = tmp_path / 'out.mcap'
    assert main(['solve', str(bag), '-o', str(out)]) == 1
    err = capsys.readouterr().err
    assert f'linkage-replay: warning: {bag}: bag truncated after 0 messages' in err
    assert damage in err and 'no /wheel_travel among what could be read' in err
    assert decoded(out) == []                          # a complete file, with nothing in it
    assert main(['copy', str(bag), '-o', str(tmp_path / 'copy.mcap')]) == 1
    assert bench([str(bag)]) == 1
    assert 'nothing to time' in capsys.readouterr().err
    assert main(['publish', str(bag), '--wait', '60']) == 1      # at once: no ROS started
    assert 'nothing to publish' in capsys.readouterr().err


@pytest.mark.parametrize('content', [None, b'', b'PK\x03\x04 not a bag'])
def test_a_path_that_is_not_a_bag_is_a_mistake(tmp_path, capsys, content):
    bag = tmp_path / 'run.mcap'
    if content is not None:
        bag.write_bytes(content)
    for run in (lambda: main(['solve', str(bag)]), lambda: main(['copy', str(bag)]),
                lambda: bench([str(bag)])):
        assert run() == 2
        assert capsys.readouterr().err.count('\n') == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ([] if content is None
                                                          else ['run.mcap'])


# --- numbers no run can carry out ----------------------------------------------------------

@pytest.mark.parametrize('argv, line', [
    (['sweep', '--hz', '1e-300'], '--hz: 1e-300 Hz spreads the 161 commands over 1.6e+302 s, '
     'so their stamps would run past 2038-01-19 03:14:07 UTC, the last time a ROS 2 stamp '
     '(int32 seconds) can hold'),
    (['sweep', '--hz', '1e-7'], '--hz: 1e-07 Hz spreads the 161 commands over 1.6e+09 s'),
    (['sweep', '--hz', '1e300'], '--hz: 1e+300 Hz is a command every 1e-291 ns, faster than '
     'the 1 ns resolution of ROS 2 times (at most 1e+09 Hz)'),
    (['sweep', '--travel=-80:80:1e-300'], '--travel: 1e-300 mm from -80 to 80 mm makes '
     '1.6e+302 commands, more than the 1,000,000 a sweep may have (choose a larger STEP)'),
    (['sweep', '--travel=-80:20:1e-9'], 'makes 1e+11 commands'),
    (['sweep', '--travel=-1e300:1e300:1'], '--travel: 1 mm from -1e+300 to 1e+300 mm makes '
     '2e+300 commands'),
    (['sweep', '--travel=-1.7e308:1.7e308:1'], 'makes inf commands'),
    (['publish', '--travel=-80:80:1e-300'], 'makes 1.6e+302 commands'),
    (['publish', str(EXAMPLE), '--rate', '1e-300'], '--rate: 1e-300: the 3.2 s of recorded '
     'commands would take 3.2e+300 s to publish, longer than the 292 years a wait can last '
     '(choose a larger --rate)'),
])
def test_a_request_no_run_can_carry_out_is_one_line_saying_what_it_needs_and_status_2(
        tmp_path, monkeypatch, capsys, argv, line):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count('\n') == 1 and err.startswith('linkage-replay: ') and line in err, err
    assert list(tmp_path.iterdir()) == []


def test_linkage_bench_replay_refuses_a_sweep_no_run_can_carry_out_as_replay_does(
        tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert bench(['--hz', '1e-300']) == 2
    err = capsys.readouterr().err
    assert err.count('\n') == 1, err
    assert err.startswith('linkage-bench replay: --hz: 1e-300 Hz spreads the 161 commands'), err
    assert list(tmp_path.iterdir()) == []


def test_a_slow_but_possible_rate_is_accepted():
    from linkage_ros.tools.replay_commands import Command
    from linkage_ros.tools.replay_publish import check_rate
    commands = [Command(T0, T0, 0.0), Command(T0 + 10**9, T0 + 10**9, 0.0)]
    check_rate(commands, 1e-9)                  # 1 s over 31.7 years: slow, but it can run
    with pytest.raises(ValueError, match='--rate: 1e-10: the 1 s of recorded commands would '
                       r'take 1e\+10 s to publish'):
        check_rate(commands, 1e-10)


# --- outputs that would overwrite an input or leave the current folder ---------------------

def test_an_output_that_is_a_file_inside_the_input_bag_folder_is_refused(tmp_path, capsys):
    folder = tmp_path / 'bagdir'
    folder.mkdir()
    shutil.copy(EXAMPLE, folder / 'run.mcap')
    (folder / 'metadata.yaml').write_text('rosbag2_bagfile_information: {}\n')
    before = {p.name: p.read_bytes() for p in folder.iterdir()}
    for command in ('solve', 'copy'):
        for name in ('run.mcap', 'metadata.yaml'):
            target = folder / name
            assert main([command, str(folder), '-o', str(target)]) == 2
            err = capsys.readouterr().err
            assert err == (f'linkage-replay: -o: {target} is {target}, in the input {folder}; '
                           'give another file name\n')
    via_link = tmp_path / 'link.mcap'
    via_link.symlink_to(folder / 'run.mcap')
    assert main(['solve', str(folder), '-o', str(via_link)]) == 2
    assert {p.name: p.read_bytes() for p in folder.iterdir()} == before


def test_an_output_that_is_the_scene_file_is_refused(tmp_path, capsys):
    scene = tmp_path / 'my_scene.yaml'
    scene.write_text((ROOT / 'config' / 'scenes' / 'five_link.yaml').read_text())
    text = scene.read_text()
    assert main(['sweep', '--scene', str(scene), '-o', str(scene)]) == 2
    assert main(['solve', str(EXAMPLE), '--scene', str(scene), '-o', str(scene)]) == 2
    assert capsys.readouterr().err.count('is the input') == 2
    assert scene.read_text() == text


@pytest.mark.parametrize('name, expected', [
    ('../escaped', 'escaped_sweep.mcap'),
    ('a/../../tmp/absolute', 'a_.._.._tmp_absolute_sweep.mcap'),   # (a leading / is refused)
    ('..', 'scene_sweep.mcap'),
    ('front left (v2)', 'front_left_v2_sweep.mcap'),
])
def test_the_default_sweep_file_is_named_from_the_scene_name_made_safe(
        tmp_path, monkeypatch, name, expected):
    scene = tmp_path / 'scene.yaml'
    scene.write_text((ROOT / 'config' / 'scenes' / 'five_link.yaml').read_text().replace(
        'name: five_link', f'name: {name!r}'.replace("'", '"'), 1))
    work = tmp_path / 'a' / 'work'
    work.mkdir(parents=True)
    monkeypatch.chdir(work)
    before = sorted(p for p in tmp_path.rglob('*'))
    assert main(['sweep', '--scene', str(scene), '--travel', '0:2:1']) == 0
    assert sorted(p for p in tmp_path.rglob('*')) == sorted(before + [work / expected])
    assert not Path('/tmp/absolute_sweep.mcap').exists()


def test_a_scene_s_warnings_are_printed_once_before_its_commands_are_solved(tmp_path, capsys):
    # five_link_singular loads with a warning (a singular design position); every travel but
    # 0 is then out of reach, which the diagnostics of the new bag say.
    singular = ROOT / 'test' / 'data' / 'five_link_singular.yaml'
    status = main(['sweep', '--scene', str(singular), '--travel', '0:2:1',
                   '-o', str(tmp_path / 'singular.mcap')])
    err = capsys.readouterr().err
    warning = f'linkage-replay: warning: {load_scene(singular).warnings[0]}\n'
    assert status == 0 and err.count(warning) == 1
    assert err.index(warning) < err.index('solving 3 commands')
