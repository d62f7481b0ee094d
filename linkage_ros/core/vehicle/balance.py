# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The vehicle's balance from its axles: roll axis, roll gradient, load transfer, pitch.

Pure functions on floats (SI: kg, m, N, rad, m/s^2), each a formula of doc/vehicle.md with
its source: Milliken and Milliken, Race Car Vehicle Dynamics (RCVD), ch. 18; Gillespie,
Fundamentals of Vehicle Dynamics, ch. 8 (roll) and ch. 7 (pitch); Barton and Fieldhouse,
Automotive Chassis Engineering (2018), sec. 3.6 with its worked example (test/core/
test_vehicle_setup.py reproduces it). Roll + = right side down under a lateral acceleration
+ = to the left (ISO 8855); pitch + = nose down.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

G = 9.80665   # m/s^2, standard gravity: the g of deg/g


def ride_frequency(ride_rate, mass: float):
    """Return sqrt(K / m) / 2 pi (Hz) of ride rates K (N/m, float or array) carrying m (kg)."""
    return np.sqrt(ride_rate / mass) / (2.0 * math.pi)


def roll_axis_height(x: float, front: tuple[float, float], rear: tuple[float, float]) -> float:
    """Return the height of the roll axis at x: the line through front and rear (x, height)."""
    (xf, zf), (xr, zr) = front, rear
    return zr + (zf - zr) * (x - xr) / (xf - xr)


def roll_gradient(sprung: float, arm: float, stiffness: float, g: float = G) -> float:
    """
    Return the roll gradient d phi / d a_y (rad per m/s^2), the overturning moment included.

    k_phi = m_s d / (K - m_s g d) (Barton and Fieldhouse eq. 3.18; RCVD ch. 18 without the
    last term): sprung mass m_s (kg), roll moment arm d (m: the sprung centre of gravity above
    the roll axis), total roll stiffness K (N m/rad). Times G: rad per g. NaN where the body
    has no stiffness left (K <= m_s g d: it falls over).
    """
    rest = stiffness - sprung * g * arm
    return sprung * arm / rest if rest > 0 else math.nan


class Transfer(NamedTuple):
    """The lateral load transfer of one axle (N; + = onto the outer wheel), by its three paths."""

    geometric: float   # sprung mass through the roll centre
    elastic: float     # through the roll stiffness
    unsprung: float    # the unsprung masses' own
    total: float


def load_transfer(accel: float, sprung_share: float, roll_centre: float, stiffness: float,
                  roll: float, unsprung: float, unsprung_height: float,
                  track: float) -> Transfer:
    """
    Return one axle's lateral load transfer (Barton and Fieldhouse sec. 3.6; RCVD ch. 18).

    geometric  m_s,i a z_i / t: the axle's share of the sprung mass m_s,i (kg) at the axle's
               roll centre height z_i (m)
    elastic    K_i phi / t: the axle's roll stiffness K_i (N m/rad) at the roll angle phi
               (rad) of a = accel (m/s^2), phi = roll_gradient a
    unsprung   m_u,i a h_u,i / t: the axle's two unsprung masses m_u,i (kg) at h_u,i (m)
    t the track (m). Over both axles, sum t_i (transfer_i) = m a h + m_s g d phi: the
    vehicle's overturning moment, the sprung mass's lateral shift d phi included.
    """
    geometric = sprung_share * accel * roll_centre / track
    elastic = stiffness * roll / track
    own = unsprung * accel * unsprung_height / track
    return Transfer(geometric, elastic, own, geometric + elastic + own)


def pitch_gradient(mass: float, cg_height: float, wheelbase: float,
                   axles: tuple[tuple[float, float, float], ...], g: float = G) -> float:
    """
    Return the pitch gradient (rad per g) under a longitudinal acceleration of 1 g.

    The load transfer dW = m g h / L (N; Gillespie ch. 7) goes through each axle's springs
    less the share its links take, (1 - anti / 100) dW / K_w, and all of it through the
    tyres, dW / K_t: axles ((anti %, K_w, K_t) of the axle's two wheels, N/m). The body's
    pitch is the sum of the front's and the rear's deflection over L: mass kg, cg_height and
    wheelbase m.
    """
    transfer = mass * g * cg_height / wheelbase
    deflection = sum((1.0 - anti / 100.0) * transfer / wheels + transfer / tyres
                     for anti, wheels, tyres in axles)
    return deflection / wheelbase
