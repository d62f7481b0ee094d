# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Finite numbers: the package's one test of a number it is given, and of a number it writes.

A command, a parameter, a scene coordinate or a command-line value is accepted only if it is
a real number (int, float or a numpy number; not a bool, not a string) and finite (not NaN,
not infinite, and an int within the float range, which float() can hold).

A number it writes into a table follows the writers' rule (lost_cells, say_lost): a result
that is not finite is never written as a number; the program that writes it ends 1 and
says what was lost.
"""

from __future__ import annotations

import math
import numbers
from typing import TYPE_CHECKING

import numpy as np

from .errors import listed

if TYPE_CHECKING:
    from collections.abc import Mapping

    from numpy.typing import ArrayLike


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


def lost_cells(columns: Mapping[str, ArrayLike],
               undefined: Mapping[str, ArrayLike | bool] | None = None) -> dict[str, np.ndarray]:
    """
    Return the cells of a table that may not be written as numbers: {column: mask (n,)}.

    The writers' rule: a result that is not finite is never written as a number. An infinity
    is always lost (an overflow); a NaN is lost unless undefined[column] allows it there (a
    mask (n,), or True for the whole column): a quantity its documentation leaves undefined
    (a steer axis a scene has not, an element whose ends crossed). Only columns with a lost
    cell are returned; the writer writes them as its empty value and ends 1 (say_lost).
    """
    undefined = undefined or {}
    lost = {}
    for name, values in columns.items():
        values = np.asarray(values, dtype=float)
        allowed = np.asarray(undefined.get(name, False), dtype=bool)   # () or (n,)
        bad = ~np.isfinite(values) & ~(np.isnan(values) & allowed)
        if bad.any():
            lost[name] = bad
    return lost


def say_lost(lost: Mapping[str, np.ndarray], rows: str = 'row') -> str:
    """
    Say in one line which cells lost_cells found: 'spring_force_N at 3 of 11 positions, ...'.

    rows: what a row is ('position', 'axle'). Names the first few columns and the count of
    the others (errors.listed); '' if nothing is lost.
    """
    said = [f'{name} at {int(mask.sum())} of {mask.size} {rows}{"s" if mask.size != 1 else ""}'
            for name, mask in lost.items()]
    if not said:
        return ''
    return (f'not finite, so not written as numbers: {listed(said)} (an overflow, or a '
            'quantity that does not exist there); the rest of the table is whole')
