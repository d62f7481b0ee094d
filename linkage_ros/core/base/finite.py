# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Finite numbers: the package's one test of a number it is given to compute with.

A command, a parameter, a scene coordinate or a command-line value is accepted only if it is
a real number (int, float or a numpy number; not a bool, not a string) and finite (not NaN,
not infinite, and an int within the float range, which float() can hold).
"""

from __future__ import annotations

import math
import numbers

import numpy as np


def is_finite_number(value: object) -> bool:
    """Tell whether value is a finite real number (see the module); never raises."""
    if isinstance(value, float):   # the usual case first (numpy's float64 is one too)
        return math.isfinite(value)
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        return False
    try:
        return math.isfinite(value)
    except OverflowError:      # an int beyond the float range
        return False


def all_finite(values: object) -> bool:
    """Tell whether values (a number or an array of any shape) are all finite real numbers."""
    try:
        array = np.asarray(values)
    except (TypeError, ValueError):   # ragged nesting
        return False
    if array.dtype.kind == 'O':       # Python ints beyond int64, mixed types
        return all(is_finite_number(v) for v in array.ravel())
    return array.dtype.kind in 'iuf' and bool(np.isfinite(array).all())
