"""
Recording failures in the field: loud, and nothing lost that was written.

The node runs in its own process under a real file-size limit (ulimit -f, RLIMIT_FSIZE): the
disk "fills" during the run. Expected: /diagnostics turns ERROR naming the recording, the
reason and the time, and stays ERROR in every report after; the node goes on answering; the
file holds what was written before, read back by the writing library's own reader.
"""

import signal

from conftest import connect, Probe, spin_until
from linkage_ros.ros.messages import float64_of
from mcap.stream_reader import StreamReader
from rerun.chunk import RrdReader

LIMIT = 60_000     # bytes: a few chunks of the run's MCAP, a few batches of its .rrd


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
    process = node_process('-p', f'record_mcap:={path}', '-p', 'diagnostic_period:=0.2',
                           file_size=LIMIT)
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


def test_a_rerun_mirror_that_hits_a_file_size_limit_is_reported(
        node_process, localhost_context, localhost_executor, tmp_path):
    path = tmp_path / 'run.rrd'
    process = node_process('-p', f'rerun_rrd:={path}', '-p', 'diagnostic_period:=0.2',
                           file_size=LIMIT)
    probe = Probe(localhost_context, localhost_executor)
    connect(localhost_executor, probe)
    drive_until_it_fails(probe, localhost_executor, 'RerunRecorder')
    count = len(probe.statuses)
    assert spin_until(localhost_executor, lambda: len(probe.statuses) >= count + 2)
    report = errors(probe)[-1]
    assert f'RerunRecorder {path} stopped at t = ' in report
    assert 'file size limit reached' in report
    assert process.stop(signal.SIGINT)[0] == 0
    # What was written before reads back (Rerun's own reader), and some of it is data.
    reader = RrdReader(str(path))
    rows = sum(chunk.num_rows for chunk in reader.stream(store=reader.recordings()[0])
               if not chunk.is_static)
    assert rows > 0
