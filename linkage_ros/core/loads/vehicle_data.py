# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
What the load cases need of a vehicle: its masses and its axles, read from the setup sheet.

    prepare(vehicle) -> LoadsVehicle

The axles' x (the mean of their design contact patches), tracks, roll-centre heights, roll
stiffnesses, sprung shares and the roll moment arm are the setup sheet's (core/vehicle,
doc/vehicle.md), so that the load transfer here is the sheet's. mm, kg, N m/deg as the sheet.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..base.errors import LinkageError
from ..vehicle.sheet import setup_sheet, unsprung_heights, whole_cg_height

if TYPE_CHECKING:
    from ..model.anti_roll_bar import AntiRollBar
    from ..model.vehicle import Vehicle
    from ..vehicle.sheet import SetupSheet

AXLES = ('front', 'rear')
SIDES = ('left', 'right')


@dataclass(frozen=True)
class AxleData:
    """One axle as the load cases use it (mm, kg, N m/deg), from the setup sheet."""

    name: str
    corners: tuple[str, str]      # left, right corner names
    x_mm: float                   # mean x of the design contact patches
    track_mm: float
    roll_centre_mm: float         # height above the ground, design
    roll_stiffness_nm_per_deg: float
    sprung_kg: float              # the axle's share of the sprung mass
    unsprung_kg: float            # per corner
    unsprung_height_mm: float     # above the ground
    brake_share: float
    drive_share: float
    inboard: bool                 # inboard brakes (the torque goes into the body)
    bar: AntiRollBar | None       # with a rate, else None


@dataclass(frozen=True)
class LoadsVehicle:
    """A vehicle with masses, its axles and its corners' design contact patches (mm, kg)."""

    vehicle: Vehicle
    sheet: SetupSheet
    sprung_kg: float
    cg_x_mm: float                # the sprung mass's centre
    cg_height_mm: float           # the sprung mass's centre above the ground
    roll_moment_arm_mm: float     # the sprung centre above the roll axis
    ground_z_mm: float            # z of the ground: the mean of the design contact patches
    height_mm: float              # every mass's centre above the ground (the sheet's pitch)
    axles: dict                   # name -> AxleData
    patches: dict                 # corner -> (3,) design contact patch, mm
    centres: dict                 # corner -> (3,) design wheel centre, mm

    @property
    def mass_kg(self) -> float:
        """Return the vehicle's mass: sprung and four unsprung corners (kg)."""
        return self.sprung_kg + 2.0 * sum(a.unsprung_kg for a in self.axles.values())

    @property
    def cg_mm(self) -> np.ndarray:
        """Return the centre of every mass (x, 0, height above the ground), (3,) mm."""
        x = (self.sprung_kg * self.cg_x_mm + 2.0 * sum(
            a.unsprung_kg * a.x_mm for a in self.axles.values())) / self.mass_kg
        return np.array([x, 0.0, self.height_mm])

    @property
    def wheelbase_mm(self) -> float:
        """Return front axle x minus rear axle x (mm), the sheet's wheelbase."""
        return self.axles['front'].x_mm - self.axles['rear'].x_mm

    def corner_axle(self, corner: str) -> tuple[AxleData, int]:
        """Return the axle of a corner and its side (0 left, 1 right)."""
        for axle in self.axles.values():
            if corner in axle.corners:
                return axle, axle.corners.index(corner)
        raise KeyError(corner)


def prepare(vehicle: Vehicle) -> LoadsVehicle:
    """
    Return what the load cases need of a vehicle, from its setup sheet.

    LinkageError if the vehicle has no setup sheet: no mass block, no front and rear axle,
    a corner without a spring rate (the sheet's own requirements, doc/vehicle.md).
    """
    problem = sheet_problem(vehicle)
    if problem:
        raise LinkageError(vehicle.source, problem)
    sheet = setup_sheet(vehicle)
    mass, spec = vehicle.mass, vehicle.axles.axles
    heights = unsprung_heights(vehicle, sheet.axles)
    axles, patches, centres = {}, {}, {}
    for name in AXLES:
        row, solved = sheet.rows[name], sheet.axles[name]
        bar = spec[name].anti_roll_bar
        axles[name] = AxleData(
            name, (spec[name].left, spec[name].right), row['axle_x_mm'], row['track_mm'],
            row['roll_centre_height_mm'], row['roll_stiffness_Nm_per_deg'],
            row['sprung_mass_kg'], mass.unsprung[name], heights[name],
            spec[name].brake_share, spec[name].drive_share, spec[name].brakes == 'inboard',
            bar if bar is not None and bar.has_rate else None)
        for k, corner in enumerate(axles[name].corners):
            patches[corner] = np.array(solved.design.contact_patch[0, k], dtype=float)
            centres[corner] = np.array(solved.design.wheel_center[0, k], dtype=float)
    ground = float(np.mean([p[2] for p in patches.values()]))
    return LoadsVehicle(vehicle, sheet, mass.sprung, mass.cg_x, mass.cg_height,
                        sheet.rows['vehicle']['roll_moment_arm_mm'], ground,
                        whole_cg_height(mass, heights), axles, patches, centres)


def sheet_problem(vehicle: Vehicle) -> str:
    """Say in a few words why a vehicle has no setup sheet (so no load cases); '' if it has."""
    if vehicle.mass is None:
        return ('no mass block: load cases need the masses and tyre rates of the setup sheet '
                '(mass: sprung, front_share or cg_x, unsprung; tyre_rate: doc/vehicle.md)')
    for name in AXLES:
        spec = vehicle.axles.axles[name]
        for corner in (spec.left, spec.right):
            if not any(e.has_rate for e in vehicle.corners[corner].elements):
                return (f'corners.{corner}: its scene has no spring with a rate and '
                        'free_length: the loaded ride height needs one')
            if not vehicle.corners[corner].wheel_radius > 0:
                return (f'corners.{corner}: its scene has no wheel_radius: the tyre loads act '
                        'at the contact patch')
    return ''
