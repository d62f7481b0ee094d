# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A vehicle's setup sheet: per axle and for the vehicle, from the exact kinematics and its masses.

    setup_sheet(vehicle, scale=1) -> SetupSheet

Each axle is solved at design, over heave (HEAVE_SHARE of its left corner's travel block),
over roll (+-ROLL_DEG) and, if it steers, over the rack (+-RACK_MM); scale multiplies the
number of positions of each table. The sheet (doc/vehicle.md) has a row per axle (front,
rear) and one for the vehicle, the quantity registry's names as columns (mm, deg, N, kg, Hz):
rates and stiffnesses of the axle's elastic parts (elastic.py), the roll axis, roll gradient,
load transfer and pitch (balance.py). A table that stops at a corner's travel limits, or
out of reach, gives status 1 and its message; the sheet is computed from what was solved.
"""

from __future__ import annotations

from dataclasses import dataclass, field
import math
from typing import TYPE_CHECKING

import numpy as np

from . import balance, elastic
from ..axle.axle import axle_of, solve_axle
from ..axle.roll_centre import meet
from ..base.status import Status
from ..measure.elements import element_values

if TYPE_CHECKING:
    from ..axle.axle import Axle, AxleResult
    from ..model.vehicle import Vehicle

HEAVE_SHARE = 0.75          # of the left corner's travel block
ROLL_DEG = 3.0              # the roll table, +-
RACK_MM = 30.0              # the rack table of a steered axle, +-
POINTS = {'heave': 31, 'roll': 25, 'rack': 61}   # positions per table at scale 1
AXLES = ('front', 'rear')
# the anti quantities under braking and under drive, per axle (axle.py's names)
BRAKING = {'front': 'anti_dive', 'rear': 'anti_lift'}
DRIVE = {'front': 'anti_lift', 'rear': 'anti_squat'}


@dataclass
class AxleSheet:
    """One axle's solves and its elastic parts at them."""

    axle: Axle
    design: AxleResult
    heave: AxleResult
    roll: AxleResult
    rack: AxleResult | None
    row: dict = field(default_factory=dict)       # the axle's row of the sheet
    tables: dict = field(default_factory=dict)    # 'heave', 'roll', 'rack' -> {column: (n,)}


@dataclass
class SetupSheet:
    """The setup sheet of a vehicle: rows (axle -> {column: value}), tables, status."""

    name: str
    rows: dict
    axles: dict
    status: Status = Status.OK
    messages: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()


def setup_sheet(vehicle: Vehicle, scale: int = 1) -> SetupSheet:
    """Return the setup sheet of a vehicle with mass data (Vehicle.mass), tables x scale."""
    mass = vehicle.mass
    sheets = {name: solve_tables(axle_of(vehicle, name), scale) for name in AXLES}
    x = {name: float(s.design.contact_patch[0, :, 0].mean()) for name, s in sheets.items()}
    sprung = {'front': mass.sprung * (mass.cg_x - x['rear']) / (x['front'] - x['rear'])}
    sprung['rear'] = mass.sprung - sprung['front']
    notes = []
    for name, s in sheets.items():
        corner = 0.5 * sprung[name]
        s.row.update(axle_row(s, mass.tyre_rate[name], corner))
        s.row.update({'axle_x_mm': x[name], 'sprung_mass_kg': sprung[name],
                      'unsprung_mass_kg': 2.0 * mass.unsprung[name]})
        for what in ('heave', 'roll'):
            s.tables[what] = axle_columns(s.axle, getattr(s, what), mass.tyre_rate[name],
                                          corner)
        if s.rack is not None:
            s.tables['rack'] = steering_columns(s.rack)
            s.row.update(steering_row(s.tables['rack']))
        notes += s.design.notes
    rows = {name: s.row for name, s in sheets.items()}
    rows['vehicle'] = vehicle_row(vehicle, sheets, x, sprung)
    notes += falls_over(vehicle, rows['vehicle'])
    failed = [r for s in sheets.values() for r in (s.design, s.heave, s.roll, s.rack)
              if r is not None and not r.success]
    return SetupSheet(vehicle.name, rows, sheets,
                      Status.OUT_OF_REACH if failed else Status.OK,
                      tuple(r.message for r in failed), tuple(dict.fromkeys(notes)))


def solve_tables(axle: Axle, scale: int) -> AxleSheet:
    """Solve an axle at design and over its heave, roll and (if it steers) rack tables."""
    low, high, _ = axle.left.travel
    heave = np.linspace(HEAVE_SHARE * low, HEAVE_SHARE * high, POINTS['heave'] * scale)
    roll = np.radians(np.linspace(-ROLL_DEG, ROLL_DEG, POINTS['roll'] * scale))
    rack = None
    if axle.steered:
        rack = solve_axle(axle, 0.0, 0.0, np.linspace(-RACK_MM, RACK_MM, POINTS['rack'] * scale))
    return AxleSheet(axle, solve_axle(axle, 0.0), solve_axle(axle, heave),
                     solve_axle(axle, 0.0, roll), rack)


def axle_columns(axle: Axle, result: AxleResult, tyre_rate: float,
                 corner_mass: float) -> dict[str, np.ndarray]:
    """
    Return an axle's rate columns at a result's positions, {registry name: (n,)}.

    tyre_rate N/mm per tyre; corner_mass kg, the sprung mass on each of its wheels.
    """
    parts = elastic.elastic_parts(axle, result)
    wheel = sum((elastic.heave_rate(p) for p in parts.values()),
                np.zeros((len(result.heave), 2))).mean(axis=1)
    ride = elastic.series(wheel, tyre_rate)
    columns = {'heave_mm': result.heave, 'roll_deg': np.degrees(result.roll),
               'wheel_rate_N_per_mm': wheel, 'ride_rate_N_per_mm': ride,
               'ride_frequency_Hz': balance.ride_frequency(ride * 1000.0, corner_mass),
               'roll_centre_height_mm': result.roll_centre_height}
    total = np.zeros(len(result.heave))
    for name in ('springs', 'bar'):
        part = parts.get(name)
        value = (elastic.roll_stiffness(part, axle.design_track, result.roll)
                 if part is not None else np.zeros(len(result.heave)))
        columns[f'roll_stiffness_{name}_Nm_per_deg'] = value
        total = total + value
    columns['roll_stiffness_Nm_per_deg'] = total
    for name, _, _ in axle.anti_quantities():
        columns[f'{name}_pct'] = result.anti[name]
    scene = axle.left
    values = element_values(scene, result.wheel_center[:, 0], result.rotation[:, 0],
                            result.rack)
    for j, e in enumerate(scene.elements):
        if e.has_rate:
            columns[f'{e.name}_ratio'] = values.ratio[:, j]
            columns[f'{e.name}_wheel_rate_N_per_mm'] = values.wheel_rate[:, j]
    return columns


def axle_row(sheet: AxleSheet, tyre_rate: float, corner_mass: float) -> dict[str, float]:
    """Return an axle's row of the sheet: its columns at design, and the textbook stiffness."""
    axle, design = sheet.axle, sheet.design
    columns = axle_columns(axle, design, tyre_rate, corner_mass)
    row = {name: float(v[0]) for name, v in columns.items()
           if name not in ('heave_mm', 'roll_deg') and not name.endswith('_ratio')
           and not name.endswith('_wheel_rate_N_per_mm')}
    row['tyre_rate_N_per_mm'] = tyre_rate
    row['track_mm'] = float(design.track[0])
    row['roll_stiffness_textbook_Nm_per_deg'] = textbook(axle, design)
    return row


def textbook(axle: Axle, design: AxleResult) -> float:
    """
    Return the textbook roll stiffness (N m/deg) of an axle at design.

    Springs: 0.5 k_w t^2 with k_w = k MR^2 (constant motion ratio, no preload term) the mean
    of the two wheels; the bar at its design ratio to roll, k_b (d twist / d phi)^2.
    """
    rates = []
    for k, scene in enumerate(axle.scenes):
        values = element_values(scene, design.wheel_center[:, k], design.rotation[:, k],
                                design.rack)
        rates.append(sum(e.rate * values.ratio[0, j] ** 2
                         for j, e in enumerate(scene.elements) if e.has_rate))
    value = elastic.textbook_roll_stiffness(float(np.mean(rates)), axle.design_track)
    if design.bar is not None and axle.anti_roll_bar.has_rate:
        value += axle.anti_roll_bar.rate * float(design.bar.ratio_roll[0]) ** 2
    return value


def steering_columns(result: AxleResult) -> dict[str, np.ndarray]:
    """
    Return the steering table of a rack sweep at design height, {registry name: (n,)}.

    The steering ratio d(mean steer)/d(rack) (deg/mm) and its change with the rack (deg/mm^2)
    are the table's central differences (numpy.gradient, second order, also at the
    ends): the rack is no variable of the solve's implicit-function derivatives.
    """
    mean = np.degrees(result.mean_steer)
    nan = np.full(len(mean), np.nan)
    ratio = np.gradient(mean, result.rack, edge_order=2) if len(mean) > 2 else nan
    change = np.gradient(ratio, result.rack, edge_order=2) if len(mean) > 2 else nan
    return {'rack_mm': result.rack, 'left_steer_deg': np.degrees(result.steer[:, 0]),
            'right_steer_deg': np.degrees(result.steer[:, 1]), 'mean_steer_deg': mean,
            'ackermann_pct': result.ackermann, 'steering_ratio_deg_per_mm': ratio,
            'steering_ratio_change_deg_per_mm2': change}


def steering_row(table: dict[str, np.ndarray]) -> dict[str, float]:
    """Return the steering ratio and its change at rack 0 (interpolated in the table)."""
    rack = table['rack_mm']
    return {name: float(np.interp(0.0, rack, table[name])) if len(rack) > 1 else math.nan
            for name in ('steering_ratio_deg_per_mm', 'steering_ratio_change_deg_per_mm2')}


def vehicle_row(vehicle: Vehicle, sheets: dict, x: dict, sprung: dict) -> dict[str, float]:
    """Return the vehicle's row: roll axis, roll gradient, load transfer, pitch (SI inside)."""
    mass, g = vehicle.mass, balance.G
    rc = {n: float(s.design.roll_centre_height[0]) for n, s in sheets.items()}
    axis = balance.roll_axis_height(mass.cg_x, (x['front'], rc['front']),
                                    (x['rear'], rc['rear']))
    arm = mass.cg_height - axis
    per_rad = {n: s.row['roll_stiffness_Nm_per_deg'] * 180.0 / math.pi
               for n, s in sheets.items()}
    stiffness = sum(per_rad.values())
    gradient = balance.roll_gradient(mass.sprung, arm / 1000.0, stiffness)
    roll = gradient * g                                     # rad at 1 g
    heights = unsprung_heights(vehicle, sheets)
    transfer = {}
    for n, s in sheets.items():
        transfer[n] = balance.load_transfer(
            g, sprung[n], rc[n] / 1000.0, per_rad[n], roll, 2.0 * mass.unsprung[n],
            heights[n] / 1000.0, s.row['track_mm'] / 1000.0)
        s.row.update({'load_transfer_geometric_N': transfer[n].geometric,
                      'load_transfer_elastic_N': transfer[n].elastic,
                      'load_transfer_unsprung_N': transfer[n].unsprung,
                      'load_transfer_N': transfer[n].total})
    row = {'mass_kg': mass.total, 'sprung_mass_kg': mass.sprung, 'cg_x_mm': mass.cg_x,
           'cg_height_mm': mass.cg_height,
           'cg_height_total_mm': whole_cg_height(mass, heights),
           'wheelbase_mm': x['front'] - x['rear'],
           'roll_stiffness_Nm_per_deg': stiffness * math.pi / 180.0,
           'roll_axis_height_at_cg_mm': axis, 'roll_moment_arm_mm': arm,
           'roll_gradient_deg_per_g': math.degrees(roll),
           'lltd_front_pct': 100.0 * transfer['front'].total
           / (transfer['front'].total + transfer['rear'].total)}
    row.update(pitch(vehicle, sheets, x, row['cg_height_total_mm']))
    return row


def falls_over(vehicle: Vehicle, row: dict) -> list[str]:
    """
    Say why a vehicle's row has no roll gradient, if it has none ([] if it has one).

    Its roll stiffness K does not hold the sprung mass's overturning moment m_s g d
    (balance.roll_gradient: NaN where K <= m_s g d).
    """
    if not math.isnan(row['roll_gradient_deg_per_g']):
        return []
    moment = vehicle.mass.sprung * balance.G * row['roll_moment_arm_mm'] / 1000.0 * math.pi / 180.0
    return [f'the roll stiffness, {row["roll_stiffness_Nm_per_deg"]:.6g} N m/deg, does not hold '
            f'the body against its overturning moment m_s g d = {moment:.6g} N m/deg (it falls '
            'over in roll): no roll gradient, elastic load transfer or LLTD']


def unsprung_heights(vehicle: Vehicle, sheets: dict) -> dict[str, float]:
    """Return {axle: its unsprung masses' centre above the ground, mm} (default wheel radius)."""
    given = vehicle.mass.unsprung_cg_height
    return {n: given[n] if not math.isnan(given[n]) else s.axle.left.wheel_radius
            for n, s in sheets.items()}


def whole_cg_height(mass, heights: dict[str, float]) -> float:
    """
    Return the whole car's centre of gravity above the ground, mm.

    The sprung mass at cg_height and each axle's two unsprung masses at heights (mm), by
    their masses: the h of the pitch gradient's load transfer m g h / L (m the whole car).
    """
    return (mass.sprung * mass.cg_height + 2.0 * sum(
        mass.unsprung[n] * height for n, height in heights.items())) / mass.total


def pitch(vehicle: Vehicle, sheets: dict, x: dict, height: float) -> dict[str, float]:
    """Return the pitch centres and pitch gradients under braking and drive (height: mm)."""
    mass = vehicle.mass
    wheelbase = (x['front'] - x['rear']) / 1000.0
    row = {}
    for case, antis, sign in (('braking', BRAKING, 1.0), ('drive', DRIVE, -1.0)):
        axles = []
        for n, s in sheets.items():
            anti = s.design.anti.get(antis[n])
            axles.append((float(anti[0]) if anti is not None else 0.0,
                          2000.0 * s.row['wheel_rate_N_per_mm'],
                          2000.0 * s.row['tyre_rate_N_per_mm']))
        row[f'pitch_gradient_{case}_deg_per_g'] = sign * math.degrees(
            balance.pitch_gradient(mass.total, height / 1000.0, wheelbase, tuple(axles)))
        centre = pitch_centre(sheets, case)
        row[f'pitch_centre_{case}_x_mm'], row[f'pitch_centre_{case}_height_mm'] = centre
    return row


def pitch_centre(sheets: dict, case: str) -> tuple[float, float]:
    """
    Return the pitch centre (x mm, height mm above the ground) under braking or drive.

    The side-view lines through each axle's left contact patch (braking, outboard brakes) or
    wheel centre (inboard brakes, drive), square to that point's velocity under travel, meet
    there: the instant centre of the body over the ground, each wheel turning about its
    side-view instant centre (roll_centre.meet, in x-z).
    """
    lines = []
    for s in sheets.values():
        patch = case == 'braking' and s.axle.brakes == 'outboard'
        point = (s.design.contact_patch if patch else s.design.wheel_center)[0, 0]
        velocity = (s.design.patch_velocity if patch else s.design.center_velocity)[0, 0]
        lines.append((velocity[0], velocity[2], point[0], point[2]))
    px, pz = meet(*lines)
    ground = float(np.mean([s.design.contact_patch[0, :, 2].mean() for s in sheets.values()]))
    return float(px), float(pz) - ground
