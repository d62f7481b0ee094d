# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage_ros.core.warmup: telling that the kernels must be compiled, and compiling them aside.

Each check runs in a fresh Python process on its own numba cache folder (NUMBA_CACHE_DIR,
which numba reads when it is imported): an empty one is cold, and a program's first run
(compile_if_cold: compile_in_child) fills it with every kernel, so that the next process is
warm (no message, no compile).
"""

import os
import subprocess
import sys

from linkage_ros.core import warmup
import pytest


def python(code, cache, timeout=600):
    """Run code in a fresh Python with numba's cache in folder cache; (status, out, err)."""
    done = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                          timeout=timeout, env=dict(os.environ, NUMBA_CACHE_DIR=str(cache)))
    return done.returncode, done.stdout, done.stderr


def test_an_empty_cache_is_cold_and_said_once(tmp_path):
    status, out, err = python(
        'from linkage_ros.core import warmup\n'
        'print(warmup.cold(), len(warmup.uncached_kernels()) > 10)\n'
        "warmup.say_if_cold('prog'); warmup.say_if_cold('prog')\n", tmp_path)
    assert status == 0, err
    assert out == 'True True\n'
    assert err == f'prog: {warmup.MESSAGE}\n'      # once, however often asked


def sweep_program(cache, out):
    """Run linkage-sweep (five_link, 3 positions) on numba's cache folder; (status, err)."""
    done = subprocess.run(
        [sys.executable, '-m', 'linkage_ros.tools.sweep', 'five_link', '--travel', '0:10:5',
         '-o', str(out)], capture_output=True, text=True, timeout=900,
        env=dict(os.environ, NUMBA_CACHE_DIR=str(cache)))
    return done.returncode, done.stderr


def test_a_program_s_first_run_says_it_compiles_once_and_leaves_every_kernel_cached(tmp_path):
    # The one test that compiles (a minute or two on a busy machine): a program on a cold
    # cache says so once, before it solves, and compiles every kernel in a child process
    # (compile_in_child), not only those it needs: so the next run of any program is warm,
    # and silent. A kernel the child's solves missed would make every later run say (and
    # do) the compile again.
    status, err = sweep_program(tmp_path, tmp_path / 'first.csv')
    assert status == 0, err
    lines = err.splitlines()
    assert lines.count(f'linkage-sweep: {warmup.MESSAGE}') == 1
    assert lines[0] == f'linkage-sweep: {warmup.MESSAGE}'
    assert lines[1].startswith('linkage-sweep: five_link: 3 positions')
    status, out, err = python(
        'from linkage_ros.core import warmup\n'
        "print(warmup.uncached_kernels(), warmup.say_if_cold('prog'))\n", tmp_path)
    assert (status, out, err) == (0, '[] False\n', '')
    status, err = sweep_program(tmp_path, tmp_path / 'again.csv')
    assert status == 0 and warmup.MESSAGE not in err
    assert (tmp_path / 'again.csv').read_text() == (tmp_path / 'first.csv').read_text()


def test_the_statics_kernels_are_checked_and_compiled_only_when_asked_for(tmp_path):
    # A program without statics neither waits for nor compiles the statics kernels; one with
    # (statics=True: a scene with bushings) finds them cold, and warm after its compile.
    status, out, err = python(
        'from linkage_ros.core import warmup\n'
        'warmup.compile_in_child()\n'
        'print(warmup.cold(), warmup.cold(statics=True))\n'
        'warmup.compile_in_child(statics=True)\n'
        'print(warmup.uncached_kernels(statics=True))\n', tmp_path)
    assert (status, out, err) == (0, 'False True\n[]\n', '')


@pytest.mark.parametrize('cold, statics, said', [
    ((), False, ''), ((), True, ''),
    (('kinematic',), False, warmup.MESSAGE), (('kinematic',), True, warmup.MESSAGE),
    (('statics',), False, ''), (('statics',), True, warmup.STATICS_MESSAGE),
    (('kinematic', 'statics'), False, warmup.MESSAGE),
    (('kinematic', 'statics'), True, warmup.BOTH_MESSAGE)])
def test_the_compile_said_names_the_kernels_due_and_their_time(monkeypatch, cold, statics,
                                                               said):
    # linkage-kc said 'about 20 s' of nothing and compiled the statics kernels for a minute
    def cached(kernel):
        module = kernel.py_func.__module__
        return ('statics' if module in warmup.STATICS_MODULES else 'kinematic') not in cold
    monkeypatch.setattr(warmup, '_in_cache', cached)
    assert warmup.message(statics) == said
