# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-study at its limits: too large, a scheduler that does not answer, Ctrl-C, bad values.

Each is one line on stderr (status 2; 130 for Ctrl-C), never a traceback.
"""

import os
from pathlib import Path
import re
import signal
import socket
import subprocess
import sys
import threading
import time

import pytest

PROG = str(Path(sys.executable).parent / 'linkage-study')
TOLERANCE = ('tolerance', 'five_link', '--sigma', '0.05', '--travel', '-50', '0', '50')


def run(*args, cwd=None, timeout=300):
    """Run linkage-study; return (status, stdout, stderr)."""
    done = subprocess.run([PROG, *args], capture_output=True, text=True, timeout=timeout,
                          cwd=cwd)
    return done.returncode, done.stdout, done.stderr


@pytest.mark.parametrize('samples', ['1000000000000000', '1000000000'])
def test_a_monte_carlo_study_too_large_for_memory_is_refused_up_front(samples):
    # 1e15 built a list of 2.4e11 batches (MemoryError); 1e9 needs ~480 GB and was accepted.
    status, out, err = run(*TOLERANCE, '--samples', samples)
    assert status == 2 and out == '', err
    assert err.startswith(f'linkage-study: --samples: {int(samples):,} variants x 3 travels '
                          'need about ') and len(err.splitlines()) == 1


def test_the_memory_check_is_the_one_of_the_core_and_imports_no_program():
    # the study once imported linkage-map's module (tools/map_memory) for its memory check
    code = ('import sys; from linkage_ros.study.commands import _check_size; '
            '_check_size(1000, 3, 2); '
            'print(sorted(m for m in sys.modules if m.startswith("linkage_ros.tools")))')
    done = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                          check=True)
    assert done.stdout == '[]\n'


def test_a_long_study_says_how_long_it_will_take_before_it_starts():
    from linkage_ros.study.commands import _check_size
    said = _check_size(8_000_000, 3, 2)   # 2.4e7 solves at 15 us on 2 cores: 3 min
    assert said == ' (about 3 min on 2 local cores, by 1.5e-05 s a solve)'
    assert _check_size(1000, 3, 2) == ''


def test_the_batches_of_a_study_are_made_as_they_are_taken():
    from linkage_ros.study.executor import Items
    items = Items('problem', 10 ** 15)   # a list of these would not fit in any memory
    assert len(items) == 10 ** 15 and items[7] == ('problem', 7)
    assert list(Items('p', 3)) == [('p', 0), ('p', 1), ('p', 2)]


class Silent:
    """A TCP server that accepts and then writes nothing, or a byte every period s."""

    def __init__(self, drip=None, period=2.0):
        self.server = socket.create_server(('127.0.0.1', 0))
        self.port = self.server.getsockname()[1]
        self.drip, self.period, self.stop = drip, period, threading.Event()
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()

    def _serve(self):
        self.server.settimeout(0.2)
        held = []
        while not self.stop.is_set():
            try:
                held.append(self.server.accept()[0])
            except OSError:
                pass
            for conn in held if self.drip else []:
                try:
                    conn.send(self.drip[:1])
                except OSError:
                    pass
            if self.drip:
                self.stop.wait(self.period)
        for conn in held:
            conn.close()

    def close(self):
        self.stop.set()
        self.thread.join()
        self.server.close()


@pytest.mark.parametrize('drip', [None, b'\xff'])
@pytest.mark.parametrize('command', ['tolerance', 'fit'])
def test_a_scheduler_that_accepts_and_does_not_answer_is_one_line(tmp_path, command, drip):
    # Before: > 60 s hung (silent), or Dask allocated the 64 PiB that 0xff... bytes say.
    pytest.importorskip('distributed')
    server = Silent(drip)
    try:
        if command == 'fit':
            (tmp_path / 't.yaml').write_text(
                'scene: double_wishbone\nfree: {tie_rod.base: {x: [-1, 1]}}\n'
                'targets: [{quantity: toe_deg, travel: [-10, 10, 10], value: 0.0}]\n')
            args = ('fit', 't.yaml', '-o', 'out.yaml')
        else:
            args = TOLERANCE + ('--samples', '100')
        status, out, err = run(*args, '--scheduler', f'tcp://127.0.0.1:{server.port}',
                               cwd=tmp_path, timeout=120)
    finally:
        server.close()
    assert status == 2 and out == '', err
    assert err == (f'linkage-study: --scheduler: cannot reach the Dask scheduler '
                   f'tcp://127.0.0.1:{server.port} within 5 s (no answer)\n')


def test_a_scheduler_address_without_a_port_number_is_one_line_and_no_traceback():
    pytest.importorskip('distributed')
    status, out, err = run(*TOLERANCE, '--samples', '100', '--scheduler',
                           'tcp://127.0.0.1:notaport')
    assert status == 2 and 'Traceback' not in err and len(err.splitlines()) == 1
    assert err == ('linkage-study: --scheduler: expected tcp://HOST:PORT (PORT a number up to '
                   "65535), got 'tcp://127.0.0.1:notaport'\n")


def test_ctrl_c_during_a_study_ends_it_at_once_with_status_130_and_no_traceback(tmp_path):
    # Ctrl-C reaches the whole process group, the local workers too.
    # SIGINT as a terminal's program has it: a test run started in the background (`cmd &` in
    # a script) ignores SIGINT, and Python then installs no KeyboardInterrupt for its children
    study = subprocess.Popen([PROG, *TOLERANCE, '--samples', '4000000', '--workers', '2',
                              '-o', 'out.csv'], cwd=tmp_path, stderr=subprocess.PIPE,
                             text=True, start_new_session=True,
                             preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    lines = []
    for line in study.stderr:   # the first batches done: the workers are running
        lines.append(line)
        # a progress line '[#...] 12/977 batches (1%)' with a batch done; not the header line
        # '... in 977 batches (about 2 min ...)', which is said before any worker starts
        done = re.search(r'\] (\d+)/\d+ batches \(', line)
        if done and int(done.group(1)) >= 1:
            break
    os.killpg(study.pid, signal.SIGINT)
    rest = study.communicate(timeout=60)[1]
    assert study.returncode == 130, lines + [rest]
    assert rest.splitlines()[-1] == 'linkage-study: interrupted' and 'Traceback' not in rest
    assert not (tmp_path / 'out.csv').exists()
    # no worker left running: a terminated worker may stay a zombie until init reaps it (dead,
    # holding nothing), so only processes of the session in another state count
    deadline, running = time.monotonic() + 10.0, ['?']
    while running and time.monotonic() < deadline:
        time.sleep(0.1)
        states = subprocess.run(['ps', '-s', str(study.pid), '-o', 'stat='],
                                capture_output=True, text=True).stdout.split()
        running = [state for state in states if not state.startswith('Z')]
    assert running == []


@pytest.mark.parametrize('argv, said', [
    (('--sigma', '1e300'),
     '--sigma: must be at most 1e+12 mm (the length limit of a scene), got 1e+300'),
])
def test_a_sigma_beyond_any_scene_is_refused_without_numpy_warnings(argv, said):
    status, out, err = run('tolerance', 'five_link', '--samples', '100', '--travel', '0', *argv)
    assert status == 2 and err.startswith(f'linkage-study: {said}'), err
    assert len(err.splitlines()) == 1


def test_a_quantity_named_without_its_unit_is_suggested_with_it():
    status, out, err = run('sensitivity', 'five_link', '--travel', '0', '--quantity', 'camber')
    assert status == 2 and len(err.splitlines()) == 1
    assert err.startswith('linkage-study: camber: not a quantity of the scene five_link (did '
                          'you mean camber_deg?)')
