# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
so3.turn compiles into a kernel without numba's reference counting (compiled.bare).

The statics' kernels are bare (they allocate nothing) and call turn; turn allocated a (3, 3)
scratch, which numba refuses to compile without reference counting. With a warm cache turn
came compiled already and nothing showed; with a cold one (a new worktree, an edit of any
kernel source) the first loaded solve raised TypingError. So the kernel here is compiled in
a process of its own, with a cache of its own that is empty.
"""

import math
import os
from pathlib import Path
import subprocess
import sys

import numpy as np
import pytest

SCRIPT = """
from linkage_ros.core.base import so3
from numba import njit
import numpy as np

@njit(error_model='numpy', _nrt=False)
def bare_turn(x, y, z, rotation, out):
    so3.turn(x, y, z, rotation, out)

out = np.empty((3, 3))
bare_turn(0.3, -0.2, 0.5, np.eye(3)[[1, 2, 0]], out)
print(repr(out.tolist()))
"""


def test_turn_compiles_cold_into_a_bare_kernel_and_turns_by_rodrigues(tmp_path):
    env = {**os.environ, 'NUMBA_CACHE_DIR': str(tmp_path / 'cache')}
    done = subprocess.run([sys.executable, '-c', SCRIPT], env=env, capture_output=True,
                          text=True, timeout=600, cwd=Path(__file__).resolve().parents[2])
    assert done.returncode == 0, done.stderr[-2000:]
    out = np.array(eval(done.stdout))   # noqa: S307 (our own script's repr of a list)
    # expected: Rodrigues' formula in numpy (an independent evaluation)
    w = np.array([0.3, -0.2, 0.5])
    t = np.linalg.norm(w)
    k = np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]]) / t
    step = np.eye(3) + math.sin(t) * k + (1.0 - math.cos(t)) * k @ k
    # a dozen operations on numbers of order 1: a few eps
    assert out == pytest.approx(step @ np.eye(3)[[1, 2, 0]], rel=0, abs=1e-15)
