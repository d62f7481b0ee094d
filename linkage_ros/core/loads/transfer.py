# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The four tyre loads of a load case, from the vehicle's masses and axles (doc/loads.md).

    tyre_loads(data, case) -> TyreLoads

Pure functions on floats and arrays. Forces N, lengths mm, masses kg, accelerations in g
(multiples of balance.G); the roll gradient and the lateral paths are balance.py's (SI), so
that the transfer is the setup sheet's. Vehicle frame, ISO 8855 (x forward, y left, z up).

- Vertical: each axle carries vertical_g times its static load, and the longitudinal
  transfer m g a_x h / L goes from the front to the rear axle (Gillespie, Fundamentals of
  Vehicle Dynamics, ch. 2; m every mass, h the height of their centre, L the wheelbase).
- Lateral: each axle's force is its static share of m g a_y (the car does not yaw), and
  under braking or drive in a turn the share that balances the yaw moment of the sprung
  centre's sideways shift in roll; split between its wheels in proportion to their vertical
  loads. Its lateral load transfer is the sheet's three paths (geometric, elastic,
  unsprung: Barton and Fieldhouse sec. 3.6, RCVD ch. 18), the roll gradient taken at the
  case's vertical load factor.
- Longitudinal: braking (a_x < 0) by the axles' brake shares, at the contact patch with
  outboard brakes and at the wheel centre with inboard ones; drive (a_x > 0) by the drive
  shares, at the wheel centre (doc/axle.md); equal on the two wheels of an axle.
- The unsprung masses' weight and inertia, -m_u g (a_x, a_y, vertical_g), act on their
  corners at the unsprung centre (the wheel centre's x and y, its height above the ground).
"""

from __future__ import annotations

import math
from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from ..base.errors import LinkageError
from ..vehicle import balance

if TYPE_CHECKING:
    from .cases import LoadCase
    from .vehicle_data import LoadsVehicle

G = balance.G
SHARE_TOLERANCE = 1e-9   # brake and drive shares must sum to 1 within this


class CornerTyre(NamedTuple):
    """One corner's tyre load (N, N m, vehicle frame)."""

    force_n: np.ndarray    # (3,) the ground's force on the tyre
    couple_nm: np.ndarray  # (3,) a couple of the ground on the tyre (a given wrench's moment)
    centre_n: np.ndarray   # (3,) the part of force_n that reaches the carrier at the wheel centre
    shaft: bool            # centre_n's couple is a shaft's (inboard brake, drive): the ground's
    #                        force stays at the patch; else the ground's force acts there
    unsprung_n: np.ndarray  # (3,) the unsprung mass's weight and inertia, at its centre
    given: bool            # the case gave this corner's load (LoadCase.corners)


class TyreLoads(NamedTuple):
    """A case's four tyre loads and what they balance."""

    corners: dict          # corner -> CornerTyre
    derived: dict          # corner -> CornerTyre from the body's accelerations (before the
    #                        case's own corner loads replaced some)
    axle_vertical_n: dict  # axle -> its two wheels' vertical load, N
    longitudinal_transfer_n: float   # onto the rear axle, N (+ under drive)
    lateral: dict          # axle -> balance.Transfer (N, + = onto the right wheel)
    roll_rad: float        # the body's roll angle (+ = right side down)
    body_shift_mm: np.ndarray   # (3,) the sprung centre's move in that roll


def static_axle_loads(data: LoadsVehicle) -> dict[str, float]:
    """Return each axle's static vertical load at 1 g (N): its share of every mass."""
    weight = data.mass_kg * G
    x = data.cg_mm[0]
    front, rear = data.axles['front'].x_mm, data.axles['rear'].x_mm
    return {'front': weight * (x - rear) / (front - rear),
            'rear': weight * (front - x) / (front - rear)}


def longitudinal_transfer(weight_n: float, longitudinal_g: float, height_mm: float,
                          wheelbase_mm: float) -> float:
    """Return m g a_x h / L (N): the vertical load onto the rear axle (+ under drive)."""
    return weight_n * longitudinal_g * height_mm / wheelbase_mm


def roll_angle(data: LoadsVehicle, lateral_g: float, vertical_g: float) -> float:
    """
    Return the body's roll angle (rad, + = right side down) at lateral_g and vertical_g.

    balance.roll_gradient with gravity vertical_g x G (the overturning moment of the sprung
    centre's shift grows with the load factor); NaN where the body has no stiffness left.
    """
    stiffness = sum(a.roll_stiffness_nm_per_deg for a in data.axles.values()) * 180.0 / math.pi
    gradient = balance.roll_gradient(data.sprung_kg, data.roll_moment_arm_mm / 1000.0,
                                     stiffness, vertical_g * G)
    return gradient * lateral_g * G


def lateral_transfer(data: LoadsVehicle, lateral_g: float, roll: float) -> dict:
    """Return {axle: balance.Transfer} (N, + = onto the right wheel) at lateral_g and roll."""
    return {name: balance.load_transfer(
        lateral_g * G, a.sprung_kg, a.roll_centre_mm / 1000.0,
        a.roll_stiffness_nm_per_deg * 180.0 / math.pi, roll, 2.0 * a.unsprung_kg,
        a.unsprung_height_mm / 1000.0, a.track_mm / 1000.0) for name, a in data.axles.items()}


def shares(data: LoadsVehicle, longitudinal_g: float) -> tuple[dict, str]:
    """Return ({axle: share of the longitudinal force}, 'brake' or 'drive') for a case."""
    kind = 'brake' if longitudinal_g < 0 else 'drive'
    given = {n: getattr(a, f'{kind}_share') for n, a in data.axles.items()}
    if longitudinal_g != 0 and abs(sum(given.values()) - 1.0) > SHARE_TOLERANCE:
        said = ' + '.join(f'{n} {v:g}' for n, v in given.items())
        raise LinkageError(data.vehicle.source, f'axles.*.{kind}_share: a case with '
                           f'longitudinal_g {longitudinal_g:g} needs {kind} shares that sum '
                           f'to 1 ({said} = {sum(given.values()):g})')
    return given, kind


def tyre_loads(data: LoadsVehicle, case: LoadCase, corner_keys: dict | None = None) -> TyreLoads:
    """
    Return the four tyre loads of a case (doc/loads.md, 'The tyre loads').

    corner_keys: {case corner key: vehicle corner} of the case's own corner loads
    (cases.resolve_corner); LinkageError for brake or drive shares that do not sum to 1, or a
    body that has no roll stiffness left.
    """
    ax, ay, nz = case.accelerations_g
    weight = data.mass_kg * G
    static = static_axle_loads(data)
    moved = longitudinal_transfer(weight, ax, data.height_mm, data.wheelbase_mm)
    vertical = {'front': nz * static['front'] - moved, 'rear': nz * static['rear'] + moved}
    roll = roll_angle(data, ay, nz)
    if math.isnan(roll):
        raise LinkageError(f'case {case.name}', f'at vertical_g {nz:g} the body has no roll '
                           'stiffness left (K <= m_s g d): it falls over')
    lateral = lateral_transfer(data, ay, roll)
    split, kind = shares(data, ax)
    shift = np.array([0.0, -data.roll_moment_arm_mm * roll, 0.0])
    # the sprung centre, shifted sideways in roll, turns the longitudinal inertia force into
    # a yaw moment (N mm) that the axles' lateral forces balance: the front's grows by it / L
    yaw = data.sprung_kg * G * float(np.cross(shift, case.accelerations_g)[2])
    axle_lateral = {'front': ay * static['front'] + yaw / data.wheelbase_mm,
                    'rear': ay * static['rear'] - yaw / data.wheelbase_mm}
    derived = {}
    for name, axle in data.axles.items():
        long_force = weight * ax * split[name] / 2.0
        shaft = kind == 'drive' or axle.inboard
        for side, corner in enumerate(axle.corners):
            fz = 0.5 * vertical[name] + (1.0 if side else -1.0) * lateral[name].total
            fy = axle_lateral[name] * fz / vertical[name]
            force = np.array([long_force, fy, fz])
            centre = np.array([long_force if shaft else 0.0, 0.0, 0.0])
            derived[corner] = CornerTyre(force, np.zeros(3), centre, shaft,
                                         unsprung_force(axle.unsprung_kg, case), False)
    corners = dict(derived)
    for key, given in case.corners.items():
        corner = (corner_keys or {}).get(key, key)
        corners[corner] = given_tyre(data, corner, given, static, case)
    return TyreLoads(corners, derived, vertical, moved, lateral, roll, shift)


def unsprung_force(mass_kg: float, case: LoadCase) -> np.ndarray:
    """Return -m_u g (a_x, a_y, vertical_g) (N): an unsprung mass's weight and inertia."""
    return -mass_kg * G * np.array(case.accelerations_g)


def given_tyre(data: LoadsVehicle, corner: str, given, static: dict,
               case: LoadCase) -> CornerTyre:
    """Return a corner's tyre load as the case gives it (cases.CornerLoad)."""
    axle, _ = data.corner_axle(corner)
    unsprung = unsprung_force(axle.unsprung_kg, case)
    if given.g is None:
        force = np.array(given.force_n)
        centre = force.copy() if given.at == 'wc' else np.zeros(3)
        return CornerTyre(force, np.array(given.moment_nm), centre, False, unsprung, True)
    long_g, lat_g, vert_g = given.g
    wheel = 0.5 * static[axle.name]   # the corner's static tyre load, N
    force = wheel * np.array([long_g, lat_g, vert_g])
    centre = np.array([force[0] if given.at == 'wc' else 0.0, 0.0, 0.0])
    return CornerTyre(force, np.zeros(3), centre, False, unsprung, True)


def ground_moment(tyre: CornerTyre, centre: np.ndarray, patch: np.ndarray) -> np.ndarray:
    """Return the ground's moment on the tyre about the contact patch (N m); centre, patch mm."""
    moment = np.array(tyre.couple_nm, dtype=float)
    if not tyre.shaft:
        moment = moment + np.cross(centre - patch, tyre.centre_n) / 1000.0
    return moment
