# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The stated range of every number a scene or vehicle file gives the statics and the setup sheet.

RANGES is the one table: the loader checks each field against its row (core/model), the
manual prints it (doc/scenes.md#ranges is markdown_table(); a test checks), and the programs'
--help say the rows they read (say_ranges()). A value outside is refused in one line that names the
file, the field, the value as given with its unit, and the range in the file's units.

The ranges cover every real vehicle, from a model car or a bicycle to a mining truck (810 t,
tyres and struts of 1e4 N/mm), with room on both sides, and the stiff limit the statics tests
take (bushing rates x1e7: 5e10 N/mm); beyond them a number is a typo, a unit slip or a hostile
file. They keep the arithmetic finite: the largest products the statics and the sheet form
(a rate times a squared lever of 1e12 mm, a mass times g times a height over a track) stay
below 1e60, and a solve whose rates span the whole range still gives finite rates or a status
(test/core/test_ranges_arithmetic.py). Units are the core's (mm, N, kg, deg); a file in m
gives a rate per m and a length in m, converted on load.
"""

from __future__ import annotations

import math
import numbers
import textwrap
from typing import NamedTuple

from .limits import LENGTH_LIMIT_MM

DOC = 'doc/scenes.md#ranges'


class Range(NamedTuple):
    """
    A stated range: low <= |value| <= high in unit, or 0 where zero, or negative where signed.

    length_power: how the value scales with the file's unit of length (1 a length, -1 a rate
    per length, 0 none): a value v in a file of scale mm per unit is v * scale ** power in
    the core's unit.
    """

    key: str
    fields: str          # the fields of the files it bounds, as the manual names them
    low: float           # > 0: the least magnitude accepted (besides 0 where zero)
    high: float
    unit: str            # the core's unit; {length} where the file's length unit enters
    length_power: int = 0
    zero: bool = False   # 0 accepted (none, or a flat segment)
    signed: bool = False  # -high to -low accepted too
    why: str = ''

    def problem(self, value: float, scale: float = 1.0) -> str:
        """Say why value (in the file's units, scale mm per unit) is out of range; '' if not."""
        core = _times(value, scale ** self.length_power)
        if core == 0.0 and value == 0:          # not a tiny value that underflowed
            within = self.zero
        else:
            within = (self.signed or core > 0) and self.low <= abs(core) <= self.high
        return '' if within else f'{self.given(value, scale)} is outside {self.said(scale)}'

    def given(self, value: float, scale: float = 1.0) -> str:
        """Return value as the file gives it, with the file's unit: '1e+308 N/m'."""
        return f'{shown(value)} {self.unit_of(scale)}'.rstrip()

    def unit_of(self, scale: float = 1.0) -> str:
        """Return the unit in a file of scale mm per unit ('N/mm', 'N/m', 'kg')."""
        return self.unit.format(length='mm' if scale == 1.0 else 'm')

    def said(self, scale: float = 1.0) -> str:
        """Say the range in a file's units: '0.001 to 1e+11 N/mm', '0, or ...', '-1e+09 to...'."""
        factor = scale ** -self.length_power
        low, high, unit = self.low * factor, self.high * factor, self.unit_of(scale)
        span = f'-{high:g} to {high:g}' if self.signed else f'{low:g} to {high:g}'
        text = f'{span} {unit}'.rstrip()
        if self.zero and not self.signed:
            text = f'0, or {text}'
        if scale != 1.0 and self.length_power:
            text += f' ({self.said(1.0)})'
        return text


def _times(value: float, factor: float) -> float:
    """Return value * factor as a float, inf past the float range (a huge int included)."""
    try:
        return float(value) * factor
    except OverflowError:
        return math.inf if value > 0 else -math.inf


def shown(value: object) -> str:
    """Say a number as it was given, in at most a few dozen characters (a huge int too)."""
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        if abs(value) < 10 ** 16:
            return str(value)
        digits = int(value.bit_length() * math.log10(2)) + 1
        try:
            return f'{float(value):.6g}'
        except OverflowError:
            return f'{"-" if value < 0 else ""}an integer of about {digits} digits'
    if isinstance(value, float):
        return repr(value)
    text = repr(value)
    return text if len(text) <= 60 else f'{text[:40]}... ({len(text)} characters)'


# The masses, rates and forces (the lengths: coordinates, heights and the like below).
RATE_HIGH = 1e11     # N/mm: x1e7 the stiffest bush of the bundled scenes (5000 N/mm)
ANGULAR_HIGH = 1e10  # N m/deg: x1e6 the stiffest conical rate bundled (1745 N m/deg)
LENGTH_LOW = 1e-6    # mm: a nanometre, the least height, track or free length

RANGES = (
    Range('bushing_rate', 'bushing `axial`, `radial`', 1e-3, RATE_HIGH, 'N/{length}', -1,
          why='a cab mount is 10 N/mm, a steel joint 1e6; up to the stiff limit of the '
          'statics tests (x1e7: 5e10)'),
    Range('bushing_angular_rate', 'bushing `torsion`, `conical`', 1e-3, ANGULAR_HIGH,
          'N m/deg', zero=True,
          why='0 is none; rubber bushes 0.1-2000 N m/deg; up to the stiff limit (x1e6)'),
    Range('spring_rate', 'element `rate`', 1e-3, RATE_HIGH, 'N/{length}', -1,
          why='a model car 0.1 N/mm, a mining truck 1e4'),
    Range('force_table_force', 'element `force_table` forces', 0.0, 1e9, 'N', zero=True,
          signed=True, why='100 times the weight of the largest mining truck (8e6 N)'),
    Range('force_table_slope', 'element `force_table`: the slope of each segment', 0.0,
          RATE_HIGH, 'N/{length}', -1, zero=True, signed=True,
          why='as a spring rate; 0 where the force is flat, negative where it falls'),
    Range('tyre_rate', 'vehicle `tyre_rate`', 1e-3, RATE_HIGH, 'N/{length}', -1,
          why='a model car 1 N/mm, a bicycle 50, a mining truck 5000'),
    Range('bar_rate', 'vehicle `anti_roll_bar.rate`', 1e-3, ANGULAR_HIGH, 'N m/deg',
          why='cars 10-2000 N m/deg'),
    Range('sprung_mass', 'vehicle `mass.sprung`', 1e-3, 1e7, 'kg',
          why='a model car 1 kg, a mining truck 8.1e5 kg'),
    Range('unsprung_mass', 'vehicle `mass.unsprung`', 1e-3, 1e7, 'kg', zero=True,
          why='0 is none'),
    Range('front_share', 'vehicle `mass.front_share` (or the share `mass.cg_x` gives)', 1e-3,
          1.0 - 1e-3, '', why='the sprung mass on the front axle: a centre of gravity off '
          'both axles'),
    Range('height', 'vehicle `cg_height`, `mass.cg_height`, `mass.unsprung_cg_height`, '
          "`wheelbase`, an axle's track; element `free_length`", LENGTH_LOW, LENGTH_LIMIT_MM,
          '{length}', 1, why='lengths the sheet divides by, or whose difference is a '
          'deflection'),
    Range('wheel_radius', 'scene `wheel_radius`', LENGTH_LOW, LENGTH_LIMIT_MM, '{length}', 1,
          zero=True, why='0 is not given'),
    Range('coordinate', 'every point and offset, `travel`, `force_table` deflections; the '
          "node's travel and rack commands", 0.0,
          LENGTH_LIMIT_MM, '{length}', 1, zero=True, signed=True,
          why='beyond it a length squared loses every digit of a millimetre'),
)
RANGE = {r.key: r for r in RANGES}


def markdown_table() -> str:
    """Return RANGES as the table of doc/scenes.md#ranges (in mm; a file in m converts)."""
    lines = ['| numbers | range (a file in m: rates per m, lengths in m) | why these bounds |',
             '|---|---|---|']
    lines += [f'| {r.fields} | {r.said()} | {r.why} |' for r in RANGES]
    return '\n'.join(lines) + '\n'


def say_ranges(*keys: str) -> str:
    """Say the ranges of keys for a --help: a line each, '  bushing axial, radial: 0.001 ...'."""
    lines = [f'{RANGE[k].fields.replace("`", "")}: {RANGE[k].said()}' for k in keys]
    return '\n'.join(textwrap.fill(line, 92, initial_indent='  ', subsequent_indent='    ')
                     for line in lines)


if __name__ == '__main__':   # the table of doc/scenes.md#ranges
    print(markdown_table(), end='')
