# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The packed state of a solved position: the one array the compiled kernels take and return.

A state is a float64 array (kernel.STATE_SIZE,), or (..., STATE_SIZE) for many positions:
travel and rack (mm), wheel centre M (3,) mm, carrier rotation R (3, 3) relative to design,
Jacobian (5, 6) of the guidance equations at the pose, then what kernel.report fills in:
residual (mm), condition number, camber and toe (rad), quaternion (x, y, z, w) of R.

The layout is kernel.py's (compiled code reads it there, kernel.views); this module is the
one place where Python code reads or writes it. The readers return views, not copies; those
of one state are plain slices, a few hundred ns each on the node's one-command path.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from . import kernel
from .kernel import (CENTER, JACOBIAN, QUATERNION, RACK, RESIDUAL, ROTATION, STATE_SIZE,
                     TOE, TRAVEL)

if TYPE_CHECKING:
    from numpy.typing import ArrayLike


def empty(*shape: int) -> np.ndarray:
    """Return uninitialised states, shape (*shape, STATE_SIZE)."""
    return np.empty(shape + (STATE_SIZE,))


def pack(travel: float, rack: float, center: ArrayLike, rotation: ArrayLike,
         jacobian: ArrayLike) -> np.ndarray:
    """Return the state of a solved position (mm), its report not filled in (zeros)."""
    state = np.zeros(STATE_SIZE)
    state[TRAVEL], state[RACK] = travel, rack
    state[CENTER:CENTER + 3] = center
    state[ROTATION:ROTATION + 9] = np.ravel(rotation)
    state[JACOBIAN:JACOBIAN + 30] = np.ravel(jacobian)
    return state


def travel(one: np.ndarray) -> float:
    """Return a state's travel, mm."""
    return one.item(TRAVEL)


def rack(one: np.ndarray) -> float:
    """Return a state's steering rack travel (mm)."""
    return one.item(RACK)


def center(one: np.ndarray) -> np.ndarray:
    """Return a state's wheel centre, (3,) mm."""
    return one[CENTER:CENTER + 3]


def rotation(one: np.ndarray) -> np.ndarray:
    """Return a state's carrier rotation relative to design, (3, 3)."""
    return one[ROTATION:ROTATION + 9].reshape(3, 3)


def jacobian(one: np.ndarray) -> np.ndarray:
    """Return a state's Jacobian of the guidance equations, d/d(M, omega), (5, 6)."""
    return one[JACOBIAN:JACOBIAN + 30].reshape(kernel.N_EQUATIONS, 6)


def report(one: np.ndarray) -> list[float]:
    """Return a reported state's [residual (mm), condition number, camber, toe (rad)]."""
    return one[RESIDUAL:TOE + 1].tolist()   # the four are adjacent, in this order


def quaternion(one: np.ndarray) -> np.ndarray:
    """Return a reported state's rotation as a quaternion, (4,): x, y, z, w."""
    return one[QUATERNION:QUATERNION + 4]


# --- many states: (..., STATE_SIZE) -> (...) ----------------------------------------------

def travels(many: np.ndarray) -> np.ndarray:
    """Return the travel of each of states (..., STATE_SIZE), (...,) mm."""
    return many[..., TRAVEL]


def centers(many: np.ndarray) -> np.ndarray:
    """Return the wheel centre of each of states (..., STATE_SIZE), (..., 3) mm."""
    return many[..., CENTER:CENTER + 3]


def rotations(many: np.ndarray) -> np.ndarray:
    """Return the carrier rotation of each of states (..., STATE_SIZE), (..., 3, 3)."""
    return many[..., ROTATION:ROTATION + 9].reshape(many.shape[:-1] + (3, 3))
