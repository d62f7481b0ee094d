# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A recording's file is its recorder's alone, and one removed or replaced is said at once.

Both recorders (McapRecorder, RerunRecorder) hold an exclusive lock (flock) on their file:
a second recorder of it, in the same process or another, is refused and the first one's file
is left whole (read back by mcap's own reader). A file removed or replaced while recorded
stops the recording with a reason naming it; in the node, every status turns ERROR naming
the file, and the node answers on.
"""

import os
import subprocess
import sys

from linkage_ros.core.model import load_scene
from linkage_ros.record.errors import RecordingError
from linkage_ros.record.mcap_writer import McapRecorder
from linkage_ros.record.rerun_view import RerunRecorder
from linkage_ros.ros.testing import spin_until
from mcap.reader import make_reader
import pytest
from std_msgs.msg import Float64

TRAVEL = '/wheel_travel'
FLOAT64 = 'std_msgs/msg/Float64'
REFUSED = 'another recorder is writing this file (it holds its lock); give another file name'


def travels(path):
    """Return the /wheel_travel values (m) of a complete MCAP, by mcap's own reader."""
    from mcap_ros2.decoder import DecoderFactory
    with open(path, 'rb') as stream:
        return [msg.data for _, channel, _, msg in make_reader(
            stream, decoder_factories=[DecoderFactory()]).iter_decoded_messages()
            if channel.topic == TRAVEL]


def record(recorder, *values):
    for i, value in enumerate(values):
        recorder.record(TRAVEL, FLOAT64, Float64(data=value), i, i)


def wait_for(predicate, timeout=10.0):
    """Return predicate() once true, or its last value after timeout s (a deadline loop)."""
    import time
    deadline = time.monotonic() + timeout
    while not predicate() and time.monotonic() < deadline:
        time.sleep(0.02)
    return predicate()


# --- removed or replaced -------------------------------------------------------------------

def test_an_mcap_removed_while_recorded_stops_the_recording_naming_the_file(tmp_path):
    path = tmp_path / 'run.mcap'
    recorder = McapRecorder(path, flush_period=0.05)
    record(recorder, 0.01, 0.02)
    assert recorder.error == ''
    path.unlink()
    assert wait_for(lambda: recorder.error)   # the flush thread sees it, or reading error
    assert recorder.error == f'{path} was removed while recording'
    with pytest.raises(RecordingError, match='was removed while recording'):
        record(recorder, 0.03)
    recorder.close()
    assert not path.exists()     # nothing was written anew in its place


def test_an_mcap_replaced_while_recorded_stops_and_leaves_the_new_file_alone(tmp_path):
    path = tmp_path / 'run.mcap'
    recorder = McapRecorder(path, flush_period=0)    # no thread: seen when error is read
    record(recorder, 0.01)
    other = tmp_path / 'other'
    other.write_bytes(b'somebody else')
    os.replace(other, path)
    assert recorder.error == f'{path} was replaced by another file while recording'
    recorder.close()
    assert path.read_bytes() == b'somebody else'


def test_a_rerun_mirror_removed_while_recorded_stops_naming_the_file(tmp_path):
    path = tmp_path / 'run.rrd'
    mirror = RerunRecorder(path, load_scene('five_link'), batch_rows=1)
    record(mirror, 0.01)
    assert mirror.error is None
    path.unlink()
    assert mirror.error == f'{path} was removed while recording; the .rrd ends there'
    record(mirror, 0.02)          # ignored: the mirror stopped
    mirror.close()
    assert not path.exists()


def test_a_node_whose_mcap_is_removed_reports_error_naming_it_and_answers_on(
        suspension_node, probe, executor, tmp_path):
    path = tmp_path / 'run.mcap'
    suspension_node(record_mcap=str(path), diagnostic_period=0.2)
    assert probe.ask(0.01).pose is not None
    path.unlink()

    def error_about_the_file():
        return [s.message for s in probe.statuses if s.level == b'\x02'
                and f'{path} was removed while recording' in s.message]

    assert spin_until(executor, error_about_the_file, 10.0), probe.statuses[-1:]
    assert f'McapRecorder {path} stopped at t = ' in error_about_the_file()[0]
    count = len(probe.statuses)
    assert probe.ask(0.02).pose is not None                  # it answers on
    assert spin_until(executor, lambda: len(probe.statuses) >= count + 2, 10.0)
    assert all(s.level == b'\x02' and str(path) in s.message for s in probe.statuses[count:])


# --- one recorder per file -----------------------------------------------------------------

def test_a_second_mcap_recorder_of_a_file_is_refused_and_the_first_file_stays_whole(tmp_path):
    path = tmp_path / 'run.mcap'
    with McapRecorder(path, flush_period=0) as first:
        record(first, 0.01)
        first.flush()
        with pytest.raises(RecordingError) as refused:
            McapRecorder(path)
        assert str(refused.value) == f'{path}: {REFUSED}'
        with pytest.raises(RecordingError, match='holds its lock'):
            RerunRecorder(path, load_scene('five_link'))
        record(first, 0.01, 0.02)
    assert travels(path) == [0.01, 0.01, 0.02]


def test_a_recorder_in_another_process_is_refused(tmp_path):
    path = tmp_path / 'run.mcap'
    code = ('import sys\n'
            'from linkage_ros.record.mcap_writer import McapRecorder, RecordingError\n'
            'try:\n'
            '    McapRecorder(sys.argv[1])\n'
            'except RecordingError as exc:\n'
            '    print(exc)\n')
    with McapRecorder(path, flush_period=0) as first:
        record(first, 0.03)
        done = subprocess.run([sys.executable, '-c', code, str(path)], capture_output=True,
                              text=True, timeout=60)
        assert done.stdout == f'{path}: {REFUSED}\n', done.stderr
    assert travels(path) == [0.03]


def test_a_rerun_mirror_holds_its_file_too(tmp_path):
    path = tmp_path / 'run.rrd'
    with RerunRecorder(path, load_scene('five_link')):
        with pytest.raises(RecordingError, match='holds its lock'):
            McapRecorder(path)
    with McapRecorder(path, flush_period=0):    # released at close
        pass


def test_a_node_recording_mcap_and_rerun_to_one_file_is_refused_in_one_line(
        node_process, tmp_path):
    path = tmp_path / 'run.out'
    process = node_process('-p', f'record_mcap:={path}', '-p', f'rerun_rrd:={path}')
    status, _, err = process.finish()
    assert status == 2
    assert err.count('\n') == 1 and str(path) in err and 'rerun_rrd' in err, err
