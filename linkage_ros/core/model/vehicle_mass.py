# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The masses of a vehicle file and its tyres' vertical rates: what a setup sheet needs.

    mass:
      sprung: 1280                  # kg
      cg_x: -1150                   # x of the sprung mass's centre, vehicle frame (file units)
                                    #   (or front_share: 0.54, the sprung mass's front share)
      cg_height: 550                # above the ground (file units); else the file's cg_height
      unsprung: {front: 70, rear: 90}           # kg per corner
      unsprung_cg_height: {front: 300, rear: 300}   # above the ground; default: wheel radius
    tyre_rate: {front: 250, rear: 260}          # N per file unit of length, per tyre, vertical

A vehicle without `mass` has no setup sheet (core/vehicle). With it, every key a quantity of the
sheet needs is required, and refused if bad: a number outside its stated range (base/ranges.py:
sprung_mass, unsprung_mass, tyre_rate, height; front_share, also the share cg_x gives, for a
centre of gravity inside the wheelbase and off both axles), a front and a rear axle missing.
Errors raise SceneError naming the file and the key, the value as given and the range.
vehicle.py imports this module only for a file that has a mass or tyre_rate key.
Units once loaded: kg, mm, N/mm.
"""

from __future__ import annotations

from dataclasses import dataclass
import math
from typing import TYPE_CHECKING

from .fields import Fields
from ..base.ranges import DOC as RANGES_DOC, RANGE, shown

if TYPE_CHECKING:
    from .vehicle_axles import VehicleAxles

MASS_KEYS = ('sprung', 'cg_x', 'front_share', 'cg_height', 'unsprung', 'unsprung_cg_height')
AXLES = ('front', 'rear')


@dataclass(frozen=True)
class MassData:
    """A vehicle's masses (kg), centres of gravity (mm, vehicle frame) and tyre rates (N/mm)."""

    sprung: float               # kg
    cg_x: float                 # mm, the sprung mass's centre, vehicle frame (x forward)
    cg_height: float            # mm above the ground
    unsprung: dict              # axle -> kg per corner
    unsprung_cg_height: dict    # axle -> mm above the ground; NaN: the wheel radius
    tyre_rate: dict             # axle -> N/mm per tyre, vertical

    @property
    def total(self) -> float:
        """Return the vehicle's mass (kg): sprung plus four unsprung corners."""
        return self.sprung + 2.0 * sum(self.unsprung.values())


def parse_mass(path: object, data: dict, axles: VehicleAxles | None, axle_x: dict,
               scale: float) -> MassData:
    """
    Read mass and tyre_rate of a vehicle file's mapping; raise SceneError if bad or missing.

    axles: the file's axles (parse_axles), needed for a front and a rear axle; axle_x: the x
    (mm) of each axle (the mean of its wheel centres); scale: mm per unit of the file.
    """
    check = Fields(str(path))
    check.scale = scale
    block = data.get('mass')
    if not isinstance(block, dict):
        check.fail('mass', 'missing: tyre_rate is given without the masses it needs; expected '
                   '{sprung, cg_x or front_share, cg_height, unsprung}'
                   if block is None else f'expected a mapping {{sprung, cg_x, cg_height, '
                   f'unsprung}}, got {shown(block)}')
    check.keys(block, MASS_KEYS, 'mass')
    if axles is None or set(AXLES) - set(axles.axles):
        check.fail('axles', 'missing: the setup sheet (mass:) needs a front and a rear axle')
    if block.get('sprung') is None:
        check.fail('mass.sprung', 'missing (required, kg)')
    sprung = check.ranged(block, 'sprung', 'mass.sprung', 'sprung_mass')
    front, rear = axle_x['front'], axle_x['rear']
    problem = RANGE['height'].problem(front - rear)   # mm, from the corners' wheel centres
    if front > rear and problem:
        check.fail('axles', f'the wheelbase (front axle x - rear axle x) of {problem}')
    if 'cg_x' in block and 'front_share' in block:
        check.fail('mass.front_share', 'give cg_x or front_share, not both')
    if 'front_share' in block:
        share = check.ranged(block, 'front_share', 'mass.front_share', 'front_share')
        cg_x = rear + share * (front - rear)
    else:
        cg_x = check.number(block, 'cg_x', 'mass.cg_x (or mass.front_share)') * scale
        if not rear < cg_x < front:
            check.fail('mass.cg_x', f'the centre of gravity at x = {cg_x:g} mm is outside the '
                       f'wheelbase (rear axle x = {rear:g} mm, front axle x = {front:g} mm)')
        problem = RANGE['front_share'].problem((cg_x - rear) / (front - rear))
        if problem:
            check.fail('mass.cg_x', f'the centre of gravity at x = {cg_x:g} mm puts a share '
                       f'of the sprung mass on the front axle of {problem} (rear axle x = '
                       f'{rear:g} mm, front axle x = {front:g} mm; {RANGES_DOC})')
    cg_height = _cg_height(check, data, block, scale, axles)
    unsprung = _per_axle(check, block, 'unsprung', 'mass.unsprung', _ranged('unsprung_mass'))
    heights = {a: math.nan for a in AXLES}
    if block.get('unsprung_cg_height') is not None:
        heights = _per_axle(check, block, 'unsprung_cg_height', 'mass.unsprung_cg_height',
                            _ranged('height'))
    if not isinstance(data.get('tyre_rate'), dict):
        check.fail('tyre_rate', 'missing: ride rate and ride frequency need the vertical rate '
                   "of each axle's tyres, {front: N/unit, rear: N/unit}"
                   if data.get('tyre_rate') is None else
                   f'expected a mapping {{front, rear}}, got {shown(data["tyre_rate"])}')
    rates = _per_axle(check, data, 'tyre_rate', 'tyre_rate', _ranged('tyre_rate'))
    return MassData(sprung, cg_x, cg_height, unsprung, heights, rates)


def _cg_height(check, data, block, scale, axles):
    """Return mass.cg_height (mm), else the file's cg_height; refuse two that differ."""
    given = axles.cg_height if axles is not None else math.nan
    if block.get('cg_height') is None:
        if math.isnan(given):
            check.fail('mass.cg_height', 'missing: the roll moment arm, the roll gradient and '
                       'the load transfer need the height of the centre of gravity')
        return given
    height = check.ranged(block, 'cg_height', 'mass.cg_height', 'height')
    if not math.isnan(given) and abs(height - given) > 1e-9 * max(1.0, height):
        check.fail('mass.cg_height', f'{height:g} mm differs from cg_height {given:g} mm: give '
                   'one of them')
    return height


def _per_axle(check, block, key, where, read):
    """Return {front: value, rear: value} of block[key], each read by read(check, ...)."""
    values = block.get(key)
    if not isinstance(values, dict):
        check.fail(where, 'missing (required): {front: ..., rear: ...}' if values is None
                   else f'expected a mapping {{front, rear}}, got {shown(values)}')
    check.keys(values, AXLES, where)
    return {a: read(check, values, a, f'{where}.{a}') for a in AXLES}


def _ranged(kind):
    """Return a reader of a value of block[key] within the stated range kind (core units)."""
    def read(check, block, key, where):
        if block.get(key) is None:
            check.fail(where, 'missing (required)')
        return check.ranged(block, key, where, kind)
    return read
