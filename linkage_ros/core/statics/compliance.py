# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Compliance at one travel: first-order rates from the factorised KKT system (doc/kc.md).

At the zero-load equilibrium (which holds the springs' preload), a generalized load Q moves
the coordinates and multipliers by the implicit function theorem:

    [ H  J^T ] [ dq      ]   [ Q ]
    [ J   0  ] [ dlambda ] = [ 0 ]

one factorisation for all the loads (command.rates, compiled; Statics.rates). The carrier's
dq is its move dM (mm) and turn w (rad); the holding force changes by -dlambda of the travel
row. Rates as the quantity registry names them (measure/quantities.py, groups kc_...); the
6x6 matrix is the wheel centre's [dx, dy, dz mm, rx, ry, rz deg] per [Fx, Fy, Fz kN, Mx,
My, Mz kN m] (its SI twin per N and N m in m and rad: symmetric, Maxwell-Betti). Its z row
and column are exactly zero: the travel is held (kkt.py). Zeros the model knows are exact:
a rigid scene's pose rates are 0, not round-off.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from .command import MATRIX, MATRIX_SI, RATES_SIZE
from ..base.status import Status
from ..measure.quantities import names

RATE_COLUMNS = tuple(names('kc_fy_cp', 'kc_fx_cp', 'kc_fx_wc', 'kc_mz'))


class Compliance(NamedTuple):
    """
    The rates at one travel and rack (registry units), the 6x6 matrices; NaN on failure.

    A NamedTuple over its own array of values (command.RATES_SIZE floats, as command.rates
    writes them: the rates in RATE_COLUMNS' order, NaN where the scene has none, the 6x6
    matrix in the table's units, then in SI; cheap to make, one per command). The rates
    dict and the matrices are read from it when asked for: the dict made anew at each
    read, the matrices views into the values.
    """

    status: Status
    message: str
    travel_mm: float
    values: np.ndarray     # (RATES_SIZE,)

    @property
    def rates(self) -> dict:
        """Return {name (RATE_COLUMNS): value} of the rates the scene has; {} on failure."""
        return {k: v for k, v in zip(RATE_COLUMNS, self.values[:MATRIX].tolist())
                if not math.isnan(v)}

    @property
    def matrix(self) -> np.ndarray:
        """Return the (6, 6) compliance, mm, deg per kN, kN m."""
        return self.values[MATRIX:MATRIX_SI].reshape(6, 6)

    @property
    def matrix_si(self) -> np.ndarray:
        """Return the (6, 6) compliance, m, rad per N, N m."""
        return self.values[MATRIX_SI:RATES_SIZE].reshape(6, 6)


def failed(status: Status, message: str, travel_mm: float) -> Compliance:
    """Return the Compliance of a position that failed: no rates, matrices of NaN."""
    return Compliance(status, message, float(travel_mm), np.full(RATES_SIZE, math.nan))
