# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A corner under load: the load, and the loaded equilibrium's pose and forces (doc/kc.md).

The travel is held (the wheel centre's z), the rack too; the load is a force (N, fixed
direction, vehicle frame) at the contact patch or the wheel centre and a moment (N m, fixed
in space). statics.py solves them (Statics, solve_loaded). Numerics that fail are a result
with Status.NOT_CARRIED, naming the load and the last residual, with no pose; bad input (a
load at the contact patch without a wheel radius, a load that is not finite) raises
LinkageError (check_load).
"""

from __future__ import annotations

from dataclasses import dataclass
import math
from typing import NamedTuple, TYPE_CHECKING

import numpy as np

from ..base.errors import LinkageError
from ..base.finite import all_finite
from ..base.status import Status

if TYPE_CHECKING:
    from .pickups import Pickups

PLACES = ('cp', 'wc')


@dataclass(frozen=True)
class Load:
    """A force (N, vehicle frame) at the contact patch ('cp') or wheel centre ('wc'), a moment."""

    force_n: tuple = (0.0, 0.0, 0.0)
    at: str = 'wc'
    moment_nm: tuple = (0.0, 0.0, 0.0)

    def __str__(self) -> str:
        """Say the load in words for messages: 'F (0, 4000, 0) N at cp, M (0, 0, 0) N m'."""
        force = ', '.join(f'{float(v):g}' for v in self.force_n)
        moment = ', '.join(f'{float(v):g}' for v in self.moment_nm)
        return f'F ({force}) N at {self.at}, M ({moment}) N m'

    def said(self) -> str:
        """Say the load as a NOT_CARRIED message does: 'load (0.0, 4000.0, 0.0) N at cp, ...'."""
        return (f'load {tuple(float(f) for f in self.force_n)} N at {self.at}, moment '
                f'{tuple(float(m) for m in self.moment_nm)} N m')


class Loaded(NamedTuple):
    """
    A loaded equilibrium (mm, deg, N, vehicle frame); pose fields None (NaN) unless OK.

    A NamedTuple (cheap to make: one per command) over the solve's answer (pickups: the
    array the compiled solve wrote, and its slots' names): the pose, the holding force and
    the forces are read from it when asked for, the force dicts made anew at each read.
    """

    status: Status
    message: str
    travel_mm: float
    rack_mm: float = 0.0
    residual: float = math.nan
    iterations: int = 0
    pickups: Pickups | None = None

    @property
    def camber_deg(self) -> float:
        """Camber of the loaded wheel to the body, deg, + = top outboard."""
        return self.pickups.camber_deg() if self.pickups else math.nan

    @property
    def toe_deg(self) -> float:
        """Toe of the loaded wheel to the body, deg, + = toe-in."""
        return self.pickups.toe_deg() if self.pickups else math.nan

    @property
    def wheel_center_mm(self) -> np.ndarray | None:
        """Return the loaded wheel centre (3,) mm, vehicle frame (z: the held height)."""
        return self.pickups.wheel_center() if self.pickups else None

    @property
    def rotation(self) -> np.ndarray | None:
        """Return the carrier's turn (3, 3) from its design orientation."""
        return self.pickups.rotation() if self.pickups else None

    @property
    def holding_force_n(self) -> float:
        """Return the vertical force at the wheel centre holding the travel, N, + = up."""
        return self.pickups.holding_force() if self.pickups else math.nan

    @property
    def load_point_mm(self) -> np.ndarray | None:
        """Where the load acts, (3,) mm: the wheel centre, or the patch as a carrier point."""
        return self.pickups.load_point() if self.pickups else None

    @property
    def link_forces_n(self) -> dict:
        """Each link's force along itself, N, + = tension; both ends of one carrying a spring."""
        return self.pickups.link_forces() if self.pickups else {}

    @property
    def pivot_forces_n(self) -> dict:
        """Each arm's force on the body at its pivots ('<arm>_axis0', ...), (3,) N."""
        return self.pickups.pivot_forces() if self.pickups else {}

    @property
    def ball_joint_forces_n(self) -> dict:
        """Each constraint's force on the carrier at its carrier point, (3,) N."""
        return self.pickups.ball_joint_forces() if self.pickups else {}

    @property
    def spring_forces_n(self) -> dict:
        """Each spring's force, N, + = compressed."""
        return self.pickups.spring_forces() if self.pickups else {}

    @property
    def body_forces_n(self) -> dict:
        """Each body pickup's force on the body, (3,) N: pivots, link bases, spring ends, tops."""
        return self.pickups.body_forces() if self.pickups else {}

    @property
    def body_points_mm(self) -> dict:
        """Where each body pickup's force acts, (3,) mm."""
        return self.pickups.body_points() if self.pickups else {}

    @property
    def body_moments_nm(self) -> dict:
        """Each bushing's couple on the body at its point, (3,) N m (offset and rotation)."""
        return self.pickups.body_moments() if self.pickups else {}


def check_load(scene, load: Load) -> tuple[np.ndarray, np.ndarray]:
    """Return force (3,) N and moment (3,) N mm of a load; LinkageError for bad input."""
    if load.at not in PLACES:
        raise LinkageError('load.at', f'unknown value {load.at!r} (expected cp or wc)')
    if load.at == 'cp' and not scene.wheel_radius > 0:
        raise LinkageError(scene.source, 'a load at the contact patch (cp) needs wheel_radius '
                           'in the scene')
    values = []
    for name, given in (('force_n', load.force_n), ('moment_nm', load.moment_nm)):
        if len(given) != 3 or not all_finite(given):
            raise LinkageError(f'load.{name}', f'expected 3 finite numbers, got {given!r}')
        values.append(np.array(given, dtype=float))
    with np.errstate(over='ignore'):   # beyond 1.8e305 N m the moment is inf N mm: a
        return values[0], values[1] * 1000.0   # numerical failure (not carried), not input
