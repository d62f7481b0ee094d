"""
linkage_ros.core.warmup: telling that the kernels must be compiled, and compiling them aside.

Each check runs in a fresh Python process on its own numba cache folder (NUMBA_CACHE_DIR,
which numba reads when it is imported): an empty one is cold, and compile_in_child fills it
with every kernel, so that the next process is warm (no message, no compile).
"""

import os
import subprocess
import sys

from linkage_ros.core import warmup


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


def test_compile_in_child_leaves_every_kernel_in_the_cache(tmp_path):
    # The child's solves must reach every kernel: one it missed would make every later start
    # say (and do) the compile again.
    status, out, err = python(
        'from linkage_ros.core import warmup\n'
        'print(warmup.cold())\n'
        'print(warmup.compile_in_child(), warmup.uncached_kernels())\n', tmp_path)
    assert status == 0, err
    assert out == 'True\nTrue []\n'
    status, out, err = python(
        'from linkage_ros.core import warmup\n'
        "print(warmup.say_if_cold('prog'))\n", tmp_path)
    assert (status, out, err) == (0, 'False\n', '')
