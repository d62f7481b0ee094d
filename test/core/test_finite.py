# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Finiteness and quaternions, each written once in the core.

The one test of finiteness (linkage_ros.core.base.finite) and the one quaternion conversion of each
direction (linkage_ros.core.base.geometry), against Python's and an independent construction.
"""

import math

from linkage_ros.core.base import (all_finite, exp_so3, is_finite_number, matrix_from_quaternion,
                                   quaternion_from_matrix)
import numpy as np
import pytest


@pytest.mark.parametrize('value', [0, -3, 2.5, np.float64(1e300), np.float32(-2.0),
                                   np.int64(7), np.uint8(3), 10**300])
def test_a_finite_real_number_is_finite(value):
    assert is_finite_number(value) and all_finite(value)


@pytest.mark.parametrize('value', [math.nan, math.inf, -math.inf, np.float32('nan'),
                                   10**400, True, np.bool_(False), '1.0', None, 1j, [1.0]])
def test_anything_else_is_not(value):
    assert not is_finite_number(value)


@pytest.mark.parametrize('values, expected', [
    ([1.0, 2, np.float32(3)], True), (np.zeros((2, 3)), True), ([], True),
    ([1.0, math.nan], False), (np.array([[1.0], [math.inf]]), False), (['1.0'], False),
    ([1, 10**400], False), ([True, False], False), ([[1.0, 2.0], [3.0]], False)])
def test_all_finite_looks_at_every_value(values, expected):
    assert all_finite(values) is expected


def test_quaternion_of_a_rotation_about_an_axis_is_the_half_angle_formula():
    # independent: q = (sin(t/2) u, cos(t/2)) for a rotation by t about the unit axis u
    u, t = np.array([1.0, -2.0, 2.0]) / 3.0, 2.5
    expected = np.append(math.sin(t / 2) * u, math.cos(t / 2))
    assert quaternion_from_matrix(exp_so3(t * u)) == pytest.approx(expected, abs=1e-15)
    assert np.allclose(matrix_from_quaternion(expected), exp_so3(t * u), atol=1e-15)


def test_matrix_and_quaternion_conversions_invert_each_other_in_batches():
    rng = np.random.default_rng(5)
    rotations = exp_so3(rng.normal(scale=1.5, size=(4, 50, 3)))
    quaternions = quaternion_from_matrix(rotations)
    assert quaternions.shape == (4, 50, 4) and (quaternions[..., 3] >= 0).all()
    assert np.abs(matrix_from_quaternion(quaternions) - rotations).max() <= 1e-14
    # q and -q are one rotation; a quaternion off unit length is normalised first
    assert np.allclose(matrix_from_quaternion(-3.0 * quaternions), rotations, atol=1e-14)
