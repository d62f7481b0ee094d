# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Recording failures in the field: loud, and nothing lost that was written.

The node runs in its own process under a real file-size limit (ulimit -f, RLIMIT_FSIZE): the
disk "fills" during the run. Expected: /diagnostics turns ERROR naming the recording, the
reason and the time, and stays ERROR in every report after; the node goes on answering; the
file holds what was written before, read back by the writing library's own reader.
"""

import signal
import subprocess
import sys

from linkage_ros.answer.cdr import float64_of
from linkage_ros.record.mcap_writer import McapRecorder, RecordingError
from linkage_ros.ros.testing import connect, Probe, spin_until
from mcap.stream_reader import StreamReader
import pytest
from rerun.chunk import RrdReader

LIMIT = 60_000     # bytes: a few chunks of the run's MCAP
RRD_LIMIT = 1_000_000   # bytes: beyond the .rrd's stopping distance (rerun_view.ROOM)


def errors(probe):
    return [s.message for s in probe.statuses if s.level == b'\x02']


def drive_until_it_fails(probe, executor, failure):
    """Send commands until an ERROR status saying failure comes; return their travels (m)."""
    sent = []
    for i in range(20000):
        travel = 0.05 * ((i % 200) / 100.0 - 1.0)
        probe.send(travel)
        sent.append(travel)
        if i % 50 == 49:
            spin_until(executor, lambda: False, 0.05)
            if any(failure in message for message in errors(probe)):
                return sent
    raise AssertionError(f'no ERROR saying {failure!r}: {errors(probe)[-3:]}')


def test_a_recording_that_hits_a_file_size_limit_is_reported_and_keeps_what_it_wrote(
        node_process, localhost_context, localhost_executor, tmp_path):
    path = tmp_path / 'run.mcap'
    # TF off: the limit is a few chunks of commands and answers; /tf per answer and the URDF
    # at start would take a third of it (66 commands were left in one run, against 100 asked)
    process = node_process('-p', f'record_mcap:={path}', '-p', 'diagnostic_period:=0.2',
                           '-p', 'tf:=false', file_size=LIMIT)
    probe = Probe(localhost_context, localhost_executor)
    connect(localhost_executor, probe)
    sent = drive_until_it_fails(probe, localhost_executor, 'McapRecorder')
    # Still ERROR in the periodic reports after, and still answering:
    count, poses = len(probe.statuses), len(probe.poses)
    probe.send(0.01, 0.02)
    assert spin_until(localhost_executor, lambda: len(probe.statuses) >= count + 2
                      and len(probe.poses) >= poses + 2)
    report = errors(probe)[-1]
    assert f'McapRecorder {path} stopped at t = ' in report
    assert 'File too large' in report and 'nothing is recorded since' in report
    assert process.stop(signal.SIGINT)[0] == 0
    # The file holds the commands in the order sent (after the connection's pings at 0),
    # up to the failure: read by mcap's own stream reader, which stops at the cut-off chunk.
    commands = read_commands(path)
    assert len(commands) > 100
    first = next(i for i, value in enumerate(commands) if value != 0.0)
    assert commands[first:] == sent[:len(commands) - first]
    assert path.stat().st_size <= LIMIT


def read_commands(path):
    """Return the /wheel_travel values (m) that mcap's StreamReader reads of path."""
    channels, values = {}, []
    with open(path, 'rb') as stream:
        try:
            for record in StreamReader(stream, validate_crcs=True).records:
                kind = type(record).__name__
                if kind == 'Channel':
                    channels[record.id] = record.topic
                elif kind == 'Message' and channels.get(record.channel_id) == '/wheel_travel':
                    values.append(float64_of(record.data))
        except Exception:   # noqa: B902 (the cut-off end of the file, of whatever kind)
            pass
    return values


def test_a_rerun_mirror_near_a_file_size_limit_stops_whole_and_is_reported(
        node_process, localhost_context, localhost_executor, tmp_path):
    # Rerun's own writer hangs on a failed write, so the mirror stops ROOM bytes before
    # the limit and ends its file with the footer: complete, not cut.
    path = tmp_path / 'run.rrd'
    process = node_process('-p', f'rerun_rrd:={path}', '-p', 'diagnostic_period:=0.2',
                           file_size=RRD_LIMIT)
    probe = Probe(localhost_context, localhost_executor)
    connect(localhost_executor, probe)
    drive_until_it_fails(probe, localhost_executor, 'RerunRecorder')
    count = len(probe.statuses)
    assert spin_until(localhost_executor, lambda: len(probe.statuses) >= count + 2)
    report = errors(probe)[-1]
    assert f'RerunRecorder {path} stopped at t = ' in report
    assert 'file size limit reached (' in report and f'of {RRD_LIMIT} bytes' in report
    assert process.stop(signal.SIGINT)[0] == 0
    assert path.read_bytes()[-12:-4] == b'RRF2FOOT'
    assert rerun_rows(path) > 1000


def rerun_rows(path):
    """Return the rows of data (not static) that Rerun's own reader reads of path."""
    reader = RrdReader(str(path))
    return sum(chunk.num_rows for chunk in reader.stream(store=reader.recordings()[0])
               if not chunk.is_static)


@pytest.fixture
def small_file_system(tmp_path):
    """Return a folder on a 4 MiB tmpfs mounted for the test (skip where mount is refused)."""
    folder = tmp_path / 'small'
    folder.mkdir()
    done = subprocess.run(['mount', '-t', 'tmpfs', '-o', 'size=4m', 'tmpfs', str(folder)],
                          capture_output=True, text=True)
    if done.returncode != 0:
        pytest.skip(f'cannot mount a tmpfs here: {done.stderr.strip()}')
    yield folder
    subprocess.run(['umount', '-l', str(folder)], check=True)


def fill(folder):
    """Write a file into folder until its file system is full."""
    with open(folder / 'filler', 'wb', buffering=0) as stream:
        try:
            while True:
                stream.write(b'\0' * 4096)
        except OSError:
            pass


def test_a_full_file_system_stops_both_recordings_loudly_and_keeps_what_they_wrote(
        node_process, localhost_context, localhost_executor, small_file_system):
    mcap, rrd = small_file_system / 'run.mcap', small_file_system / 'run.rrd'
    process = node_process('-p', f'record_mcap:={mcap}', '-p', f'rerun_rrd:={rrd}',
                           '-p', 'diagnostic_period:=0.2')
    probe = Probe(localhost_context, localhost_executor)
    connect(localhost_executor, probe)
    for i in range(40):
        probe.send(*[0.001 * k for k in range(50)])
        assert spin_until(localhost_executor, lambda: len(probe.poses) >= 50 * (i + 1))
    spin_until(localhost_executor, lambda: False, 1.5)   # the batches reach the files
    fill(small_file_system)
    drive_until_it_fails(probe, localhost_executor, 'McapRecorder')
    drive_until_it_fails(probe, localhost_executor, 'RerunRecorder')
    count, poses = len(probe.statuses), len(probe.poses)
    probe.send(0.01, 0.02)
    assert spin_until(localhost_executor, lambda: len(probe.statuses) >= count + 2
                      and len(probe.poses) >= poses + 2)
    report = errors(probe)[-1]
    assert 'No space left on device' in report and 'file system full' in report
    assert process.stop(signal.SIGINT)[0] == 0
    assert len(read_commands(mcap)) >= 2000
    assert rerun_rows(rrd) >= 2000


# The recorder alone, in a fresh interpreter under a real file-size limit: the flush thread
# meets the error in the background; record() then raises it, close() keeps the file.
RECORD_UNDER_A_LIMIT = """
import resource, signal, sys, time
from std_msgs.msg import Float64
from linkage_ros.record.mcap_writer import McapRecorder, RecordingError
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
resource.setrlimit(resource.RLIMIT_FSIZE, ({limit}, {limit}))
recorder = McapRecorder(sys.argv[1], chunk_size=10**9, flush_period=0.05)
raised = None
for i in range(20000):   # one chunk, never full: only the flush thread writes
    try:   # the thread may meet the error between two records: the next one raises it
        recorder.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=i * 1e-6), i, i)
    except RecordingError as exc:
        raised = exc
        break
    if i % 100 == 99:
        time.sleep(0.01)
    if recorder.error:
        break
print(i, recorder.error)
if raised is None:
    try:
        recorder.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=0.0), i, i)
    except RecordingError as exc:
        raised = exc
print(raised)
recorder.close()
recorder.close()
"""


def test_a_write_error_in_the_flush_thread_is_kept_raised_by_record_and_not_by_close(
        tmp_path):
    path = tmp_path / 'run.mcap'
    done = subprocess.run([sys.executable, '-c', RECORD_UNDER_A_LIMIT.format(limit=LIMIT),
                           str(path)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and done.stderr == '', done.stderr
    stopped, raised = done.stdout.splitlines()
    count, error = stopped.split(' ', 1)
    assert error == 'cannot write (File too large)'
    assert raised == f'{path}: cannot write (File too large)'
    # Every message up to the last whole chunk, in order: mcap's own reader.
    values = [round(v * 1e6) for v in read_commands(path)]
    assert 0 < len(values) <= int(count) + 1
    assert values == list(range(len(values)))
    assert path.stat().st_size <= LIMIT


def test_a_recording_that_cannot_start_writing_is_refused_at_once():
    with pytest.raises(RecordingError, match='/dev/full: cannot write \\(No space left'):
        McapRecorder('/dev/full')


# A Rerun writer broken in a way the room check does not foresee (the check is switched off
# here, so the size limit strikes mid-write): the error is reported, close() returns, the
# process exits (rerun-sdk would otherwise wait forever at exit), the file is cut to whole
# messages.
MIRROR_WITHOUT_ROOM_CHECK = """
import resource, signal, sys
from std_msgs.msg import Float64
from linkage_ros.core.model import load_scene
import linkage_ros.record.rerun_view as rerun_view
rerun_view.lack_of_room = lambda path, room=0: ''
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
resource.setrlimit(resource.RLIMIT_FSIZE, ({limit}, {limit}))
mirror = rerun_view.RerunRecorder(sys.argv[1], load_scene('five_link'))
for i in range(100000):
    mirror.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=i * 1e-6), i, i)
    if i % 500 == 499 and mirror.error:
        break
print(mirror.error)
mirror.close()
"""


def test_a_rerun_writer_broken_unforeseen_is_reported_and_lets_the_process_exit(tmp_path):
    path = tmp_path / 'run.rrd'
    done = subprocess.run([sys.executable, '-c',
                           MIRROR_WITHOUT_ROOM_CHECK.format(limit=RRD_LIMIT), str(path)],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout == 'the .rrd writer stopped: a write failed\n'
    assert rerun_rows(path) > 1000
