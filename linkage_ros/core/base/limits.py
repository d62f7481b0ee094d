# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Bounds on what an input may ask for: a length, the number of sweep positions, a wheel's wrench.

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


# A wrench on a wheel (the tyre's force and moment at the contact patch, or a load of linkage-kc)
# beyond these is no load a road vehicle's tyre carries: a unit slip (N for kN, N mm for N m) or
# a hostile input, refused in one line wherever a wrench comes in (the node's contact_wrench,
# its solve service, linkage-kc --load and --moment, linkage-replay solve). Each force component
# at most 1e7 N: 100 times the largest static wheel load of a road vehicle (a 40 t truck's most
# loaded wheel carries about 5e4 N) and 20 times a 10 g impact on it; each moment component at
# most 1e6 N m: that force at a lever of 0.1 m, 100 times a truck tyre's aligning or overturning
# moment (about 1e4 N m). Within them the statics' arithmetic (forces times levers of 1e3 mm,
# squared in its residual norm: below 1e27) stays far from overflow; beyond about 1e150 N it
# does not (NaN and infinities in the Newton system, issue 36).
FORCE_LIMIT_N = 1e7
MOMENT_LIMIT_NM = 1e6


def wrench_problem(force_n, moment_nm) -> str:
    """
    Say why a wrench (force N, moment N m: 3 numbers each) cannot be taken; '' if it can.

    Not finite, or a component beyond FORCE_LIMIT_N or MOMENT_LIMIT_NM: the message names
    the first such component and the bound, on one line.
    """
    for what, values, limit, unit in (('force', force_n, FORCE_LIMIT_N, 'N'),
                                      ('moment', moment_nm, MOMENT_LIMIT_NM, 'N m')):
        for axis, value in zip('xyz', values):
            if not is_finite_number(value):
                return f'{what}.{axis} {value!r} {unit} is not finite'
            if abs(value) > limit:
                return (f'{what}.{axis} {float(value):g} {unit} is beyond the bound of '
                        f'{limit:g} {unit} on each component (no tyre carries that: a unit '
                        'slip, or not a load)')
    return ''


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
