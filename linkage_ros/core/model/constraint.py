# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
One guidance constraint of a scene as its file declares it (sphere, circle, line).

Its own module so that the parts of a scene that name constraints (elements, mounts, the
kingpin) read the type without the scene's parser, which reads them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .bushing import Bushing

EQUATIONS_PER_TYPE = {'sphere': 1, 'circle': 2, 'line': 2}


@dataclass(frozen=True)
class Constraint:
    """
    One guidance constraint of the carrier, in mm, vehicle frame, design position.

    type 'sphere': carrier point keeps its distance to base[0] (binary link, eq. 2).
    type 'circle': carrier point turns about the axis base[0]-base[1] (revolute arm, eqs. 3-4).
    type 'line': the carrier-fixed line through the carrier point and base[0] keeps passing
    through base[0] (MacPherson strut top mount).
    bushing: None for a rigid constraint; an arm's or a link's bushing (bushing.Bushing).
    """

    name: str
    type: str             # noqa: A003 (the scene files' key; public field of Constraint)
    base: np.ndarray      # (k, 3): k = 1 for sphere and line, 2 for circle
    carrier: np.ndarray   # (3,)
    steer: str = ''
    bushing: Bushing | None = None

    @property
    def equations(self) -> int:
        """How many guidance equations the constraint gives: sphere 1, circle 2, line 2."""
        return EQUATIONS_PER_TYPE[self.type]
