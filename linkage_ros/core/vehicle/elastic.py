# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
An axle's elastic parts as one energy of its two wheel travels: rates and roll stiffness.

Each part (a spring, the anti-roll bar; later the bushings' torsion and the bump stops) gives,
at n solved axle positions, its stored energy V(z_L, z_R) (N mm), its gradient g = dV/dz, the
vertical wheel loads it carries (N, + = holding the body up), and its Hessian H = d2V/dz dz^T
(N/mm), z = (left, right) wheel travels (mm, + = bump). ELASTIC_PARTS lists the functions
that give them; a new part (bushing torsion, issue of the statics branch; bump stops, the
Chrono branch) is one function more there, and enters every rate and stiffness below.

  springs   V = sum k (L0 - L)^2 / 2 over the springs of each corner, so g_k = W_k = -F ratio
            and H_kk = k ratio^2 - F ratio_rate (measure/elements.py: exact, the preload term
            included), H_LR = 0
  bar       V = k_b tau^2 / 2, tau = theta_L(z_L) - theta_R(z_R) the twist (axle/anti_roll_bar.py),
            k_b in N mm/rad: g = k_b tau (theta_L', -theta_R'), H = k_b (grad tau grad tau^T +
            tau diag(theta_L'', -theta_R''))

From them (Milliken and Milliken, Race Car Vehicle Dynamics, ch. 16 and 18):
  wheel rate in heave, per wheel      K_w = (H 1)_k (both wheels travel together; a bar whose
                                      arms turn alike adds nothing)
  roll moment                          M = dV/dphi = g . z'            (N mm per rad)
  roll stiffness                       K_phi = d2V/dphi^2 = z'^T H z' + g . z''
with the body rolled over the ground by phi (axle.py): z = (h - s, h + s), s = (t/2) tan phi,
t the design track, so z' = s' (-1, 1), z'' = s'' (-1, 1), s' = (t/2) sec^2 phi,
s'' = t sec^2 phi tan phi. mm, N, rad; reported in N m/deg.
"""

from __future__ import annotations

from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from ..base.geometry import N_MM_PER_NM_DEG
from ..measure.elements import element_values

if TYPE_CHECKING:
    from ..axle.axle import Axle, AxleResult

# N mm per rad -> N m per deg
NMM_PER_RAD_TO_NM_PER_DEG = 1.0 / N_MM_PER_NM_DEG


class Elastic(NamedTuple):
    """One elastic part of an axle at n positions (N, mm); arrays over the positions."""

    name: str
    energy: np.ndarray     # (n,) N mm
    gradient: np.ndarray   # (n, 2) dV/dz_L, dV/dz_R: the wheel loads carried, N
    hessian: np.ndarray    # (n, 2, 2) N/mm


def springs(axle: Axle, result: AxleResult) -> Elastic | None:
    """Return the springs of both corners (those with a rate) as one part; None if none."""
    n = len(result.heave)
    energy, gradient, hessian = np.zeros(n), np.zeros((n, 2)), np.zeros((n, 2, 2))
    found = False
    for k, scene in enumerate(axle.scenes):
        rated = [j for j, e in enumerate(scene.elements) if e.has_rate]
        if not rated:
            continue
        found = True
        values = element_values(scene, result.wheel_center[:, k], result.rotation[:, k],
                                result.rack)
        for j in rated:
            # k (L0 - L)^2 / 2, or a force table's work from its free length (a stop)
            spring = scene.elements[j].spring_at
            energy += np.array([spring(length)[2] for length in values.length[:, j]])
            gradient[:, k] += -values.force[:, j] * values.ratio[:, j]
            hessian[:, k, k] += values.wheel_rate[:, j]
    return Elastic('springs', energy, gradient, hessian) if found else None


def bar(axle: Axle, result: AxleResult) -> Elastic | None:
    """Return the anti-roll bar as a part; None without a bar or without its rate."""
    if result.bar is None or not axle.anti_roll_bar.has_rate:
        return None
    k = axle.anti_roll_bar.rate * N_MM_PER_NM_DEG
    values = result.bar
    tau = values.twist
    grad = values.ratio_travel                                    # (theta_L', -theta_R')
    curve = np.stack((values.angle_rate2[:, 0], -values.angle_rate2[:, 1]), axis=1)
    hessian = k * (grad[:, :, None] * grad[:, None, :]
                   + tau[:, None, None] * (np.eye(2) * curve[:, None, :]))
    return Elastic('bar', 0.5 * k * tau ** 2, k * tau[:, None] * grad, hessian)


# The elastic parts of an axle, in order. Bushing torsion and bump stops join here.
ELASTIC_PARTS = (springs, bar)


def elastic_parts(axle: Axle, result: AxleResult) -> dict[str, Elastic]:
    """Return {name: Elastic} of the axle's parts at a result's positions."""
    found = (part(axle, result) for part in ELASTIC_PARTS)
    return {p.name: p for p in found if p is not None}


def roll_derivatives(track: float, roll: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return s' and s'' (mm/rad, mm/rad^2) of s = (t/2) tan(phi), t mm, phi rad (n,)."""
    secant2 = 1.0 / np.cos(roll) ** 2
    return 0.5 * track * secant2, track * secant2 * np.tan(roll)


def roll_moment(part: Elastic, track: float, roll: np.ndarray) -> np.ndarray:
    """Return dV/dphi (n,) N mm: the roll moment the part resists with."""
    s1, _ = roll_derivatives(track, roll)
    return s1 * (part.gradient[:, 1] - part.gradient[:, 0])


def roll_stiffness(part: Elastic, track: float, roll: np.ndarray) -> np.ndarray:
    """Return d2V/dphi^2 (n,) N m/deg of a part, the body rolled over the ground by roll."""
    s1, s2 = roll_derivatives(track, roll)
    h = part.hessian
    quadratic = s1 ** 2 * (h[:, 0, 0] - h[:, 0, 1] - h[:, 1, 0] + h[:, 1, 1])
    return (quadratic + s2 * (part.gradient[:, 1] - part.gradient[:, 0])) \
        * NMM_PER_RAD_TO_NM_PER_DEG


def heave_rate(part: Elastic) -> np.ndarray:
    """Return each wheel's rate when both travel together, (n, 2) N/mm: (H 1)_k."""
    return part.hessian.sum(axis=2)


def textbook_roll_stiffness(wheel_rate: float, track: float) -> float:
    """Return 0.5 k t^2 (N m/deg) of a wheel rate k (N/mm) per side and a track t (mm)."""
    return 0.5 * wheel_rate * track ** 2 * NMM_PER_RAD_TO_NM_PER_DEG


def series(rate: np.ndarray, other: np.ndarray) -> np.ndarray:
    """Return two rates in series, k1 k2 / (k1 + k2) (same unit)."""
    return rate * other / (rate + other)
