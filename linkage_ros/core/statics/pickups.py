# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The forces of one loaded answer, by pickup name (a Loaded's dicts; doc/kc.md).

The compiled solve writes every force into one array (forces.answer_offsets); Pickups keeps
that array and pack.Names, and makes the dicts a Loaded gives when they are read.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from . import forces
from .forces import answer_offsets
from .pack import Names


class Pickups(NamedTuple):
    """One answer (its own array) and the names of its slots."""

    names: Names
    answer: np.ndarray

    def camber_deg(self) -> float:
        """Camber, deg (+ = top outboard)."""
        return math.degrees(self.answer[forces.CAMBER])

    def toe_deg(self) -> float:
        """Toe, deg (+ = toe-in)."""
        return math.degrees(self.answer[forces.TOE])

    def wheel_center(self) -> np.ndarray:
        """Return the wheel centre (3,) mm."""
        return self.answer[forces.CENTER:forces.CENTER + 3]

    def rotation(self) -> np.ndarray:
        """Return the carrier's turn (3, 3) from design."""
        return self.answer[forces.ROTATION:forces.ROTATION + 9].reshape(3, 3)

    def holding_force(self) -> float:
        """Return the holding force, N, + = up."""
        return float(self.answer[forces.HOLDING])

    def load_point(self) -> np.ndarray:
        """Where the load acts (3,) mm."""
        return self.answer[forces.LOAD_POINT:forces.LOAD_POINT + 3]

    def _parts(self):
        """Return the answer's views: forces, moments, points, balls, links, ends, springs."""
        names = self.names
        p, q, links = len(names.pickups), len(names.balls), len(names.links)
        o = answer_offsets(p, q, links, len(names.springs))
        a = self.answer
        return (a[o[0]:o[1]].reshape(p, 3), a[o[1]:o[2]].reshape(p, 3),
                a[o[2]:o[3]].reshape(p, 3), a[o[3]:o[4]].reshape(q, 3), a[o[4]:o[5]],
                a[o[5]:o[6]].reshape(links, 2), a[o[6]:o[7]])

    def body_forces(self) -> dict:
        """Each body pickup's force on the body, (3,) N."""
        return dict(zip(self.names.pickups, self._parts()[0]))

    def body_moments(self) -> dict:
        """Each bushing's couple on the body, (3,) N m."""
        moments, names = self._parts()[1], self.names.pickups
        return {names[i]: moments[i] for i in self.names.bushings}

    def body_points(self) -> dict:
        """Where each body pickup's force acts, (3,) mm."""
        return dict(zip(self.names.pickups, self._parts()[2]))

    def ball_joint_forces(self) -> dict:
        """Each constraint's force on the carrier at its carrier point, (3,) N."""
        return dict(zip(self.names.balls, self._parts()[3]))

    def pivot_forces(self) -> dict:
        """Each arm's force on the body at a pivot, (3,) N."""
        forces, names = self._parts()[0], self.names.pickups
        return {names[i]: forces[i] for i in self.names.pivots}

    def spring_forces(self) -> dict:
        """Each spring's force, N, + = compressed."""
        return dict(zip(self.names.springs, self._parts()[6].tolist()))

    def link_forces(self) -> dict:
        """
        Each link's force along itself, N, + = tension.

        A link that carries a spring is loaded between its ends: its body end ('<link>_body_end',
        the force on its base along the link) and its carrier end ('<link>_carrier_end').
        """
        _, _, _, _, links, ends, _ = self._parts()
        out = {}
        for name, carries, axial, (body, carrier) in zip(
                self.names.links, self.names.carries, links.tolist(), ends.tolist()):
            if carries:
                out[f'{name}_body_end'], out[f'{name}_carrier_end'] = body, carrier
            else:
                out[name] = axial
        return out
