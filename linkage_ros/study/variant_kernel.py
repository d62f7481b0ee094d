"""
A compiled solve batched over mechanism variants: each variant from its design to n travels.

numba-compiled (njit, cache=True) like core/solve/kernel.py, whose step and walk it calls, and
so3.py's rotations: numba's disk cache follows each file alone, and would keep running an old
step after an edit of kernel.py, so the digests of both files are written here (KERNEL_DIGEST,
SO3_DIGEST; test_kernel says the values to set). One call solves V
variants, each its own equation table (equations.table), the way kinematics.sweep solves one
mechanism: knots every knot_step mm by continuation from the design position (to knot_tol),
then every travel as one continuation step from its nearest knot; a step that fails is
walked from the design position with halving substeps (kernel.walk). What still fails is
left to the caller (FAILED), which solves it by Continuation (arclength included) to tell
a travel out of reach from a hard step.

Quantities per (variant, travel), OUTPUTS: camber, toe (rad), wheel centre x, y, z (mm).
"""

import math
from typing import NamedTuple

from numba import njit
import numpy as np

from ..core.base.so3 import camber_toe, rotate
from ..core.solve import kernel

# sha256 of the files compiled in (test_kernel checks them)
KERNEL_DIGEST = 'aac551c5ae7e0ce7eefb2d02eae639375599903a43e8c3ba5170f5430657f31f'
SO3_DIGEST = '63b60c6921d8498a47cf8a0a86bdda0a2f05c7473f028ff5e6d7b18de31758ea'
OUTPUTS = 5            # camber, toe, M_x, M_y, M_z
SOLVED, FAILED = 0, 1  # status per (variant, travel)

jit = njit(cache=True, nogil=True, error_model='numpy')


class Variants(NamedTuple):
    """V variants of one mechanism: their equation tables and design data, mm."""

    equations: np.ndarray   # (V, 5, kernel.COLUMNS)
    spin_axis: np.ndarray   # (V, 3) design outboard spin-axis unit vectors
    center0: np.ndarray     # (V, 3) design wheel centres


class Controls(NamedTuple):
    """The solver settings (continuation.Settings resolved for the design), mm."""

    side_sign: float
    tol: float
    max_iter: int
    max_step: float
    min_step: float
    max_substeps: int
    knot_step: float
    knot_tol: float


@jit
def design_state(equations, center0):
    """Return the packed state of the design position (travel 0, R = I) of a table."""
    state = np.zeros(kernel.STATE_SIZE)
    center, rotation, jac = kernel.views(state)
    center[:] = center0
    for i in range(3):
        rotation[i, i] = 1.0
    f = np.empty(5)
    kernel.linearize(equations, center, rotation, 0.0, f, jac)
    return state


@jit
def knots(setup, start, low, high, knot_step, out):
    """
    Write continuation knots from start (travel 0) to high, then to low, into out (K, SIZE).

    Steps of at most knot_step mm with setup (its tol the knots' own). Returns the count,
    or -1 if a step fails or out is too short.
    """
    out[0] = start
    count = 1
    for end in (high, low):
        last = 0
        while out[last, kernel.TRAVEL] != end:
            travel = out[last, kernel.TRAVEL]
            target = end if abs(end - travel) <= knot_step else (
                travel + math.copysign(knot_step, end - travel))
            if count == out.shape[0]:
                return -1
            _, accepted = kernel.step(setup, out[last], target, 0.0, out[count])
            if not accepted:
                return -1
            last = count
            count += 1
    return count


@jit
def outputs(state, spin_axis, side_sign, out):
    """Write camber, toe (rad), M (mm) of a solved state into out (OUTPUTS,)."""
    center, rotation, _ = kernel.views(state)
    ax, ay, az = rotate(rotation, spin_axis[0], spin_axis[1], spin_axis[2])
    out[0], out[1] = camber_toe(ax, ay, az, side_sign)
    out[2], out[3], out[4] = center[0], center[1], center[2]


@jit
def solve_variants(variants, travels, controls, values, status):
    """
    Solve V variants at travels (T,) mm: values (V, T, OUTPUTS), status (V, T) SOLVED/FAILED.

    variants: tuple(Variants); controls: tuple(Controls). A failed entry's values are NaN.
    """
    equations, spin_axis, center0 = variants
    side_sign, tol, max_iter, max_step, min_step, max_substeps, knot_step, knot_tol = controls
    low, high = min(travels.min(), 0.0), max(travels.max(), 0.0)
    room = int((high - low) / knot_step) + 4
    chain = np.empty((room, kernel.STATE_SIZE))
    state = np.empty(kernel.STATE_SIZE)
    for v in range(equations.shape[0]):
        eqs = equations[v]
        z0 = center0[v, 2]
        setup = kernel.Setup(eqs, spin_axis[v], side_sign, z0, tol, max_iter, 10 * tol,
                             max_step, min_step, max_substeps)
        knot_setup = kernel.Setup(eqs, spin_axis[v], side_sign, z0, knot_tol, max_iter,
                                  1e3 * knot_tol, max_step, min_step, max_substeps)
        batch_setup = kernel.Setup(eqs, spin_axis[v], side_sign, z0, tol, max_iter,
                                   1e3 * knot_tol, max_step, min_step, max_substeps)
        start = design_state(eqs, center0[v])
        count = knots(knot_setup, start, low, high, knot_step, chain)
        for t in range(travels.shape[0]):
            travel = travels[t]
            accepted, result = False, state
            if count > 0:
                nearest, gap = 0, np.inf
                for k in range(count):
                    if abs(chain[k, kernel.TRAVEL] - travel) < gap:
                        nearest, gap = k, abs(chain[k, kernel.TRAVEL] - travel)
                _, accepted = kernel.step(batch_setup, chain[nearest], travel, 0.0, state)
                result = state
            if not accepted:
                walked = kernel.walk(setup, start, travel, 0.0, 0.0, 0.0)
                accepted = walked.outcome == kernel.REACHED
                result = walked.state
            if accepted:
                outputs(result, spin_axis[v], side_sign, values[v, t])
                status[v, t] = SOLVED
            else:
                values[v, t, :] = np.nan
                status[v, t] = FAILED
