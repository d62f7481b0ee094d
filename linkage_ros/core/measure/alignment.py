# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Exact derivatives and the alignment set of solved positions (beyond the paper).

At a solution the Jacobian gives, by the implicit function theorem, the carrier's velocity
per unit of travel (and per unit of rack) exactly to rounding: camber gain, bump steer, the
wheel-centre velocity ratio and the instantaneous screw axis follow without finite
differences. The instantaneous steer axis is the screw axis of the carrier's motion under
rack input at constant wheel-centre height; caster, kingpin inclination, scrub radius and
mechanical trail are read off it (scenes without a steer: rack link have none of these).

Frames and units: vehicle frame (x forward, y left, z up), mm, rad, rad/mm. Batched over
n positions: center (n, 3), rotation (n, 3, 3).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..base.geometry import cross
from ..base.patch import patch_offset
from ..solve.mechanism import linearize, rack_derivative
from ..solve.pose_newton import rack_slope_of, slope_of

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..model.scene import Scene
    from ..solve.mechanism import Mechanism


@dataclass(frozen=True)
class Alignment:
    """Per-position kinematic quantities, arrays (n,) or (n, 3). NaN where undefined."""

    camber_gain: np.ndarray            # d camber / d travel, rad/mm
    bump_steer: np.ndarray             # d toe / d travel, rad/mm
    wheel_center_velocity: np.ndarray  # (n, 3) d M / d travel, mm/mm (z = 1)
    screw_axis: np.ndarray             # (n, 3) unit direction of the bump screw axis
    screw_point: np.ndarray            # (n, 3) point of that axis nearest the wheel centre, mm
    screw_pitch: np.ndarray            # mm/rad
    steer_axis: np.ndarray             # (n, 3) instantaneous steer axis, unit, pointing up
    steer_point: np.ndarray            # (n, 3) its point nearest the wheel centre, mm
    caster: np.ndarray                 # rad, + = top of the steer axis rearward
    kingpin_inclination: np.ndarray    # rad, + = top of the steer axis inboard
    scrub_radius: np.ndarray           # mm, + = steer axis meets the ground inboard of the patch
    mechanical_trail: np.ndarray       # mm, + = steer axis meets the ground ahead of the patch
    contact_patch: np.ndarray          # (n, 3) mm: lowest point of the wheel (needs a radius)
    track_change: np.ndarray           # mm, 2 x outboard patch shift (both wheels in parallel)
    wheelbase_change: np.ndarray       # mm, forward shift of this wheel's contact patch
    lateral_shift: np.ndarray          # mm, outboard shift of the wheel centre
    longitudinal_shift: np.ndarray     # mm, forward shift of the wheel centre
    side_view_ic: np.ndarray           # (n, 2) instant centre (x, z) in the side view, mm
    front_view_ic: np.ndarray          # (n, 2) instant centre (y, z) in the front view, mm


def alignment(scene: Scene, mech: Mechanism, center: ArrayLike, rotation: ArrayLike,
              rack: float = 0.0) -> Alignment:
    """Compute the alignment set at n solved positions (see Alignment for units and signs)."""
    center, rotation = np.atleast_2d(center), np.asarray(rotation).reshape(-1, 3, 3)
    side = scene.side_sign
    _, jac = linearize(mech, center, rotation, rack)
    v_bump, w_bump = slope_of(jac)
    axis = rotation @ mech.spin_axis
    camber_gain, bump_steer = angle_rates(axis, cross(w_bump, axis), side)
    screw_axis, screw_point, screw_pitch = screw(center, v_bump, w_bump)

    nan3 = np.full_like(center, np.nan)
    steer_axis = steer_point = nan3
    if mech.steered:
        v_rack, w_rack = rack_slope_of(jac, rack_derivative(mech, center, rotation, rack))
        steer_axis, steer_point, _ = screw(center, v_rack, w_rack)
        steer_axis = steer_axis * np.sign(steer_axis[:, 2:3])   # pointing up
    caster = np.arctan2(-steer_axis[:, 0], steer_axis[:, 2])
    kingpin = np.arctan2(-side * steer_axis[:, 1], steer_axis[:, 2])

    patch = contact_patch(center, axis, scene.wheel_radius) if scene.wheel_radius else nan3
    design_patch = (contact_patch(mech.design_center[None], mech.spin_axis[None],
                                  scene.wheel_radius) if scene.wheel_radius else nan3[:1])
    ground = ground_point(steer_point, steer_axis, patch[:, 2])
    return Alignment(
        camber_gain=camber_gain, bump_steer=bump_steer, wheel_center_velocity=v_bump,
        screw_axis=screw_axis, screw_point=screw_point, screw_pitch=screw_pitch,
        steer_axis=steer_axis, steer_point=steer_point, caster=caster,
        kingpin_inclination=kingpin,
        scrub_radius=side * (patch[:, 1] - ground[:, 1]),
        mechanical_trail=ground[:, 0] - patch[:, 0],
        contact_patch=patch,
        track_change=2 * side * (patch[:, 1] - design_patch[:, 1]),
        wheelbase_change=patch[:, 0] - design_patch[:, 0],
        lateral_shift=side * (center[:, 1] - mech.design_center[1]),
        longitudinal_shift=center[:, 0] - mech.design_center[0],
        side_view_ic=np.column_stack((center[:, 0] + v_bump[:, 2] / w_bump[:, 1],
                                      center[:, 2] - v_bump[:, 0] / w_bump[:, 1])),
        front_view_ic=np.column_stack((center[:, 1] - v_bump[:, 2] / w_bump[:, 0],
                                       center[:, 2] + v_bump[:, 1] / w_bump[:, 0])))


def angle_rates(axis: np.ndarray, axis_rate: np.ndarray,
                side: float) -> tuple[np.ndarray, np.ndarray]:
    """Return the rates of camber and toe (rad per unit input) of spin axes (n, 3) at axis_rate."""
    ax, ay, az = axis[:, 0], axis[:, 1], axis[:, 2]
    dx, dy, dz = axis_rate[:, 0], axis_rate[:, 1], axis_rate[:, 2]
    h = np.hypot(ax, ay)
    dh = (ax * dx + ay * dy) / h
    camber_rate = -(h * dz - az * dh) / (h**2 + az**2)
    toe_rate = side * (ay * dx - ax * dy) / (ax**2 + ay**2)
    return camber_rate, toe_rate


def screw(center: np.ndarray, velocity: np.ndarray,
          omega: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """
    Return the instantaneous screw axis of a twist.

    The twist is given by the velocity of the wheel centre and the angular velocity. Returns
    the unit direction, the axis point nearest the centre and the pitch (mm/rad).
    """
    w2 = np.einsum('ij,ij->i', omega, omega)
    direction = omega / np.sqrt(w2)[:, None]
    point = center + cross(omega, velocity) / w2[:, None]
    return direction, point, np.einsum('ij,ij->i', omega, velocity) / w2


def contact_patch(center: np.ndarray, axis: np.ndarray, radius: float) -> np.ndarray:
    """Return the lowest point of a wheel of radius (mm) centred at center, spin axes (n, 3)."""
    return center + np.column_stack(patch_offset(axis[:, 0], axis[:, 1], axis[:, 2], radius))


def ground_point(point: np.ndarray, direction: np.ndarray, height: np.ndarray) -> np.ndarray:
    """Return where lines (point, direction) meet the horizontal planes z = height."""
    t = (height - point[:, 2]) / direction[:, 2]
    return point + t[:, None] * direction
