# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
An output onto a device or a FIFO is written in place and never replaced (outputs/whole.py).

The trial (as root): linkage-kc ... -o /dev/null made /dev/null a regular file, and
--matrix /dev/full and linkage-chrono export -o /dev/full said they were done: the whole-file
writer wrote a new file beside the device and renamed it over it. Where a program on old code
would replace the device, the test gives it a private one (os.mknod in its folder: the same
driver, major and minor, as /dev/null or /dev/full), so that no run risks the machine's; the
machine's own devices are given only where nothing is renamed over them.
"""

import os
from pathlib import Path
import stat
import threading

from hypothesis import given, HealthCheck, settings, strategies as st
from linkage_ros.outputs import output_problem, whole_file
from linkage_ros.record.errors import RecordingError
from linkage_ros.record.output_file import claim
from linkage_ros.study import cli as study_cli
from linkage_ros.tools import (axle, chrono, foxglove_layout, kc, plot, replay,
                               rerun_convert, sweep, urdf, vehicle)
import pytest

ROOT = Path(__file__).resolve().parents[2]
NULL, FULL = os.makedev(1, 3), os.makedev(1, 7)   # Linux's mem driver: null and full
FULL_LINE = 'cannot write (No space left on device)'


def device(folder, name, rdev):
    """Make a character device of rdev in folder (root only); return its path as text."""
    path = folder / name
    os.mknod(path, stat.S_IFCHR | 0o666, rdev)
    return str(path)


def is_device(path, rdev):
    """Tell whether path is (still) the character device rdev."""
    info = os.stat(path)
    return stat.S_ISCHR(info.st_mode) and info.st_rdev == rdev


def test_the_machine_has_its_null_and_full_devices():
    # every test below that gives the machine's devices first checks them here
    assert is_device('/dev/null', NULL) and is_device('/dev/full', FULL)


@settings(max_examples=20, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(size=st.integers(0, 200_000), links=st.integers(0, 3), binary=st.booleans())
def test_a_file_written_whole_onto_a_null_device_is_discarded_and_the_device_stays(
        size, links, binary, tmp_path_factory):
    folder = tmp_path_factory.mktemp('dev')
    path = Path(device(folder, 'null', NULL))
    for k in range(links):   # reached through symbolic links too
        (folder / f'link{k}').symlink_to(path)
        path = folder / f'link{k}'
    assert output_problem(path) == ''
    with whole_file(path, 'wb' if binary else 'w') as stream:
        stream.write(b'x' * size if binary else 'x' * size)
    assert is_device(folder / 'null', NULL)
    assert sorted(p.name for p in folder.iterdir()) == sorted(
        ['null'] + [f'link{k}' for k in range(links)])   # nothing new beside it


@pytest.mark.parametrize('path', ['/dev/full', 'private'])
def test_a_device_that_refuses_writes_is_refused_before_any_work(path, tmp_path):
    path = device(tmp_path, 'full', FULL) if path == 'private' else path
    assert output_problem(path) == f'{path}: {FULL_LINE}'
    assert is_device(path, FULL)


def test_a_full_device_met_while_writing_raises_naming_it_and_stays_a_device(tmp_path):
    path = device(tmp_path, 'full', FULL)
    with pytest.raises(OSError) as raised:
        with whole_file(path) as stream:
            stream.write('x' * 100_000)
    assert raised.value.filename == path and raised.value.strerror == 'No space left on device'
    assert is_device(path, FULL) and os.listdir(tmp_path) == ['full']


def within(seconds, function, *args):
    """Return [function(*args)] if it returns within seconds, [] if it is still waiting."""
    done = []
    worker = threading.Thread(target=lambda: done.append(function(*args)), daemon=True)
    worker.start()
    worker.join(timeout=seconds)
    return done


def test_a_fifo_is_written_in_place_and_its_reader_gets_every_byte(tmp_path):
    fifo = tmp_path / 'pipe'
    os.mkfifo(fifo)
    # not opened by the check: an open waits for a reader (once, forever), and its close
    # would end the reader's stream before the table came
    assert within(10, output_problem, fifo) == ['']
    got = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_bytes()), daemon=True)
    reader.start()
    text = 'travel_mm\n' + ''.join(f'{k}\n' for k in range(100_000))   # more than a pipe holds
    with whole_file(fifo) as stream:
        stream.write(text)
    reader.join(timeout=60)
    assert got == [text.encode()] and stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert os.listdir(tmp_path) == ['pipe']


def test_a_recorder_refuses_a_fifo_without_waiting_for_a_reader(tmp_path):
    fifo = tmp_path / 'run.mcap'
    os.mkfifo(fifo)

    def refusal():
        with pytest.raises(RecordingError) as raised:
            claim(str(fifo))   # once blocked in open() until a reader came
        return str(raised.value)

    assert within(10, refusal) == [f'{fifo}: is a FIFO; a recording is written to a file (or '
                                   'a device such as /dev/null)']


def test_a_symbolic_link_to_a_file_stays_a_link_and_the_file_is_replaced_whole(tmp_path):
    (tmp_path / 'real.csv').write_text('old\n')
    (tmp_path / 'link.csv').symlink_to('real.csv')
    with whole_file(tmp_path / 'link.csv') as stream:
        stream.write('new\n')
    assert (tmp_path / 'link.csv').is_symlink() and (tmp_path / 'real.csv').read_text() == 'new\n'
    assert sorted(os.listdir(tmp_path)) == ['link.csv', 'real.csv']


# (program, main, argv with DEV for the device, the option named when it is refused)
PROGRAMS = [
    ('linkage-sweep', sweep.main, ['five_link', '--travel', '0', '-o', 'DEV'], '-o'),
    ('linkage-axle', axle.main, ['demo_vehicle', '--axle', 'front', '--heave', '0', '-o',
                                 'DEV'], '-o'),
    ('linkage-kc', kc.main, ['double_wishbone_bushings', '--travel', '0', '-o', 'DEV'], '-o'),
    ('linkage-kc', kc.main, ['double_wishbone_bushings', '--travel', '0', '--matrix', 'DEV'],
     '--matrix'),
    ('linkage-vehicle', vehicle.main, ['demo_vehicle', '--csv', 'DEV'], '-o'),
    ('linkage-urdf', urdf.main, ['demo_vehicle', '-o', 'DEV'], '-o'),
    ('linkage-foxglove', foxglove_layout.main, ['demo_vehicle', '-o', 'DEV'], '-o'),
    ('linkage-chrono', chrono.main, [
        'import', str(ROOT / 'config/chrono/generic/suspension/DoubleWishbone.json'), '-o',
        'DEV'], '-o'),
    ('linkage-chrono', chrono.main, ['export', 'five_link', '-o', 'DEV'], '-o'),
    ('linkage-study', study_cli.main, ['sensitivity', 'five_link', '--travel', '0', '-o', 'DEV'],
     '-o'),
    ('linkage-study', study_cli.main, ['fit', str(ROOT / 'config/study/bump_steer_targets.yaml'),
                                       '-o', 'DEV'], '-o'),
    ('linkage-replay', replay.main, ['sweep', '--travel', '0:2:1', '-o', 'DEV'], '-o'),
    ('linkage-rerun', rerun_convert.main, [str(ROOT / 'bags' / 'five_link_sweep.mcap'), '-o',
                                           'DEV'], '-o'),
    ('linkage-plot', plot.main, ['camber-toe', '-o', 'DEV', 'five_link'], ''),
]
IDS = [f'{p[0]}{p[3]}-{p[2][0]}' for p in PROGRAMS]


def run(main, argv, capsys):
    """Run main(argv): (status, stderr)."""
    try:
        status = main(argv)
    except SystemExit as exited:
        status = exited.code
    return status, capsys.readouterr().err


@pytest.mark.parametrize('prog, main, argv, option', PROGRAMS, ids=IDS)
def test_every_program_writes_onto_a_null_device_in_place(prog, main, argv, option, tmp_path,
                                                          capsys):
    null = device(tmp_path, 'null', NULL)
    status, err = run(main, [null if a == 'DEV' else a for a in argv], capsys)
    assert status in (0, 1) and 'Traceback' not in err, err   # 1: a fit may leave a target
    assert is_device(null, NULL) and os.listdir(tmp_path) == ['null']


@pytest.mark.parametrize('prog, main, argv, option', PROGRAMS, ids=IDS)
def test_every_program_refuses_a_full_device_in_one_line_before_any_work(
        prog, main, argv, option, tmp_path, capsys):
    full = device(tmp_path, 'full', FULL)
    status, err = run(main, [full if a == 'DEV' else a for a in argv], capsys)
    assert (status, err) == (2, f'{prog}: {option + ": " if option else ""}{full}: {FULL_LINE}\n')
    assert is_device(full, FULL)


@pytest.mark.parametrize('prog, main, argv, option', [PROGRAMS[2], PROGRAMS[8]],
                         ids=['linkage-kc', 'linkage-chrono'])
def test_the_machines_null_and_full_devices_stay_devices(prog, main, argv, option, capsys):
    # the trial's commands, on the machine's devices (safe: nothing is renamed over a device)
    test_the_machine_has_its_null_and_full_devices()
    assert run(main, ['/dev/null' if a == 'DEV' else a for a in argv], capsys)[0] == 0
    status, err = run(main, ['/dev/full' if a == 'DEV' else a for a in argv], capsys)
    assert (status, err) == (2, f'{prog}: {option}: /dev/full: {FULL_LINE}\n')
    test_the_machine_has_its_null_and_full_devices()
    assert not [p for p in os.listdir('/dev') if '.partial' in p]
