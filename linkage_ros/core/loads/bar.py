# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
An anti-roll bar under load: its drop links' forces, and the bar's forces on the body.

The bar turns with the axle's corners as core/axle/anti_roll_bar.py has it (its arms' angles
from the drop links' lower ends D in the corners' kinematic poses at their travels); its
torque k twist (k the rate, N mm/rad) holds each arm, and each drop link carries it as an axial
force. The left arm's end E_L turns by theta_L about u; the link's force on E (tension N,
+ = pulling E towards D) has the moment -N (w . t) / l about u, w = E - D, t = u x (E - A0),
l the link's length; the bar's torque on the left arm is -k twist, on the right +k twist:

    N_left = -k twist l / (w_L . t_L),   N_right = k twist l / (w_R . t_R)

Each drop link reaches its corner as a spring of that constant force between E (held) and D
(on the arm, link or carrier that carries it: drop_element), so that the corner's statics
carries it through its pickups. The bar's two bushings (its axis points) take the drop links'
forces on the bar as a rigid revolute's pivots do (corner.pivot_forces). mm, N, rad.
"""

from __future__ import annotations

from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from ..axle.anti_roll_bar import arm_end, bar_values
from ..base.geometry import N_MM_PER_NM_DEG
from ..model.elements import Element

if TYPE_CHECKING:
    from ..axle.axle import Axle
    from ..model.anti_roll_bar import AntiRollBar, BarSide

DROP_LINK = 'arb_drop_link'   # the drop link's element in a corner's statics


class BarState(NamedTuple):
    """The bar at two corner poses: twist (rad), torque (N m), and each side's drop link."""

    twist_rad: float
    torque_nm: float          # k twist
    tension_n: np.ndarray     # (2,) each drop link's axial force, + = tension
    ends: np.ndarray          # (2, 3) each arm's end E, mm
    drops: np.ndarray         # (2, 3) each drop link's lower end D, mm
    stiffness_n_per_mm: np.ndarray   # (2, 2) k g g^T, g = d twist / d travels: the bar's
    #                                  first-order rate at the wheels (the ride height's start)


def bar_state(axle: Axle, bar: AntiRollBar, centres: np.ndarray,
              rotations: np.ndarray) -> BarState:
    """Return the bar at the corners' kinematic poses: centres (2, 3) mm, rotations (2, 3, 3)."""
    values = bar_values(axle.scenes, axle.mechanisms, axle.design_track, bar, np.zeros(1),
                        np.zeros(1), centres[None], rotations[None])
    twist = float(values.twist[0])
    torque = bar.rate * N_MM_PER_NM_DEG * twist   # N mm
    ends, drops, tension = np.empty((2, 3)), values.drop_point[0], np.empty(2)
    for k, (side, sign) in enumerate(zip(bar.sides, (-1.0, 1.0))):
        ends[k] = arm_end(bar, side, values.angle[0, k:k + 1])[0]
        w = ends[k] - drops[k]
        t = np.cross(bar.axis, ends[k] - bar.axis_point)
        tension[k] = sign * torque * side.link_length / float(w @ t)
    grad = values.ratio_travel[0]
    stiffness = bar.rate * N_MM_PER_NM_DEG * np.outer(grad, grad)
    return BarState(twist, torque / 1000.0, tension, ends, drops, stiffness)


def drop_element(side: BarSide, end: np.ndarray, tension: float) -> Element:
    """
    Return a drop link as a corner's element: a spring of constant force from E to its D.

    Its force table holds -tension (+ = compressed) at every deflection, so the statics
    carries the link's force along the line from E (a point held, as a body point) to D.
    """
    table = np.array([[0.0, -tension], [1.0, -tension]])
    return Element(name=DROP_LINK, type='spring', body=np.array(end, dtype=float),
                   mount=side.mount, free_length=side.link_length, force_table=table)
