# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A compiled solve batched over mechanism variants: each variant at n travels, from the design's.

Compiled (base/compiled.py's jit, one cache key for every kernel source) like
core/solve/kernel.py, whose step_many and walk it calls. One call solves V variants, each its own
equation table (mechanism.equation_table of mechanism.geometry_of, the one compile, batched),
with the kernel that solves the design's batched sweep (kernel.step_many): variant v at
travel t is one continuation step of length 0 from the design's solved state at t (Newton
from the nominal pose: a design 0.05 mm away converges in 2-3 iterations), branch-checked.
Where that fails, the variant is re-assembled at travel 0 from the design pose (a variant
with other lengths does not assemble there) and walked with halving substeps (kernel.walk).
What still fails is left to the caller (FAILED), which solves it by Continuation (arclength
included) to tell a travel out of reach from a hard step.

Quantities per (variant, travel), OUTPUTS: camber, toe (rad), wheel centre x, y, z (mm).
"""

from typing import NamedTuple

import numpy as np

from ..base.compiled import jit
from ..base.so3 import camber_toe, rotate
from ..measure.quantities import columns
from ..solve import kernel

# What out holds per (variant, travel), in order: the registry's 'wheel' quantities (camber,
# toe, wheel centre x, y, z; camber and toe in rad here, deg in tables)
QUANTITIES = tuple(columns('wheel'))
OUTPUTS = len(QUANTITIES)
SOLVED, FAILED = 0, 1  # status per (variant, travel)


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
    near: float   # a variant's pose within this of the nominal one is on its branch


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
def outputs(state, spin_axis, side_sign, out):
    """Write camber, toe (rad), M (mm) of a solved state into out (OUTPUTS,)."""
    center, rotation, _ = kernel.views(state)
    ax, ay, az = rotate(rotation, spin_axis[0], spin_axis[1], spin_axis[2])
    out[0], out[1] = camber_toe(ax, ay, az, side_sign)
    out[2], out[3], out[4] = center[0], center[1], center[2]


@jit
def solve_variants(variants, starts, travels, controls, values, status):
    """
    Solve V variants at travels (T,) mm: values (V, T, OUTPUTS), status (V, T) SOLVED/FAILED.

    variants: tuple(Variants); starts (T, kernel.STATE_SIZE): the design's solved states at
    the travels (Jacobians included); controls: tuple(Controls). A failed entry's values are
    NaN.
    """
    equations, spin_axis, center0 = variants
    side_sign, tol, max_iter, max_step, min_step, max_substeps, near = controls
    count = travels.shape[0]
    nearest = np.arange(count)
    states = np.empty((count, kernel.STATE_SIZE))
    assembled = np.empty(kernel.STATE_SIZE)
    iterations = np.empty(count, dtype=np.int64)
    accepted = np.empty(count, dtype=np.bool_)
    for v in range(equations.shape[0]):
        eqs, axis, z0 = equations[v], spin_axis[v], center0[v, 2]
        # from the nominal pose: a step of length 0 whose branch check allows `near` mm
        from_nominal = kernel.Setup(eqs, axis, side_sign, z0, tol, max_iter, near, max_step,
                                    min_step, max_substeps)
        kernel.step_many(from_nominal, nearest, starts, travels, 0.0, states, iterations,
                         accepted)
        setup = kernel.Setup(eqs, axis, side_sign, z0, tol, max_iter, 10 * tol, max_step,
                             min_step, max_substeps)
        ready = 0   # 0: not yet re-assembled at travel 0; 1: done; -1: it does not assemble
        for t in range(count):
            accepted_t, result = accepted[t], states[t]
            if not accepted_t and ready == 0:
                _, good = kernel.step(from_nominal, design_state(eqs, center0[v]), 0.0, 0.0,
                                      assembled)
                ready = 1 if good else -1
            if not accepted_t and ready == 1:
                walked = kernel.walk(setup, assembled, travels[t], 0.0, 0.0, 0.0)
                accepted_t, result = walked.outcome == kernel.REACHED, walked.state
            if accepted_t:
                outputs(result, axis, side_sign, values[v, t])
                status[v, t] = SOLVED
            else:
                values[v, t, :] = np.nan
                status[v, t] = FAILED
