# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""so3.turn compiles into a kernel without reference counting (the statics' bare kernels)."""

from linkage_ros.core.base import so3
from numba import njit
import numpy as np
from scipy.spatial.transform import Rotation


def test_turn_compiles_cold_into_a_kernel_without_reference_counting():
    # compiled here, never from numba's cache: a warm cache hid that turn allocated, which a
    # kernel without reference counting refuses (TypingError on a fresh checkout)
    @njit(cache=False, _nrt=False)
    def bare_turn(x, y, z, rotation, out):
        so3.turn(x, y, z, rotation, out)

    start = Rotation.from_rotvec([0.3, -0.2, 0.5]).as_matrix()
    out = np.empty((3, 3))
    bare_turn(0.01, 0.02, -0.03, start, out)
    expected = Rotation.from_rotvec([0.01, 0.02, -0.03]).as_matrix() @ start
    # entries of products of rotations: a few eps each
    np.testing.assert_allclose(out, expected, rtol=0, atol=1e-15)
    bare_turn(0.01, 0.02, -0.03, start, start)   # in place: out is rotation itself
    np.testing.assert_allclose(start, expected, rtol=0, atol=1e-15)
