# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Bounds on what an input may ask for: the size of a length, the number of sweep positions.

Past a bound the input is a mistake (a typo, a unit slip, a hostile file), refused with a
LinkageError that says what the request would need, before anything is allocated for it.
"""

from __future__ import annotations

import math

from .errors import LinkageError
from .finite import is_finite_number

# Lengths beyond this (1e6 km) are typos: their squares, which the solver forms, lose every
# digit of a suspension's millimetres, and near 1e154 mm they overflow.
LENGTH_LIMIT_MM = 1e12

# Positions one sweep (or a travel x rack grid) may solve: about 10 s and 1 GB.
MAX_POSITIONS = 1_000_000
# Memory one solved position takes on the way to a table: the kernel's state (52 floats),
# the Sweep's arrays and the table's row (measured: about 700 B in sweep, 300 B in the table).
BYTES_PER_POSITION = 1000


def within_length_limit(value: float, scale: float) -> bool:
    """Tell whether value (scene units, scale mm each) is a length within LENGTH_LIMIT_MM."""
    try:
        return abs(value) * scale <= LENGTH_LIMIT_MM   # False for NaN
    except OverflowError:                              # an integer beyond the float range
        return False


def positions_needed(start: float, stop: float, step: float, where: str = 'travel') -> int:
    """
    Return how many positions kinematics.travel_range(start, stop, step) gives (mm).

    Raises LinkageError naming where (an option or a field) when start, stop or step is not
    finite, step is not above 0, or the count is beyond MAX_POSITIONS; the message says the
    positions and the memory the request would need.
    """
    if not all(is_finite_number(v) for v in (start, stop, step)) or not step > 0:
        raise LinkageError(where, f'from, to and step must be finite and step > 0 (got '
                           f'{start!r}, {stop!r}, {step!r})')
    steps = abs(stop - start) / step   # inf for a step near the smallest float
    if steps + 1 > MAX_POSITIONS:
        check_position_count(steps + 1, where,
                             f'from {start:g} to {stop:g} mm at steps of {step:g} mm')
    count = int(math.floor(steps + 1e-9))   # as travel_range counts them
    last = start + math.copysign(step, stop - start) * count
    return count + 1 + (last != stop)


def check_position_count(count: float, where: str, what: str) -> None:
    """Raise LinkageError naming where if count positions (what: how made) are too many."""
    if count > MAX_POSITIONS:
        size = count * BYTES_PER_POSITION
        many = f'{count:.3g}' if math.isfinite(count) else 'more than 1e308'
        need = f'about {_bytes(size)}' if math.isfinite(size) else 'more memory than there is'
        raise LinkageError(where, f'{many} positions ({what}) would need {need}; the limit '
                           f'is {MAX_POSITIONS:,} positions (a larger step, or a shorter '
                           'range)')


def _bytes(size: float) -> str:
    """Say a size in bytes as people read it: '745 GiB', '1.6e+293 GiB'."""
    for unit, scale in (('GiB', 2**30), ('MiB', 2**20), ('KiB', 2**10)):
        if size >= scale:
            return f'{size / scale:.3g} {unit}'
    return f'{size:.0f} B'
