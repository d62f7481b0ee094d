# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Where a loaded command's time goes: its pieces timed apart (linkage-bench statics --parts).

A loaded command along the sine (statics.commands) is, in the compiled call: the views of
the Model and the work, for each of the zero-load and the loaded solve a chord step (a
residual assembly and a solve with the kept factorisation) and one Newton step (an exact
assembly, a factorisation, a solve), the loaded solve's residual (one more residual
assembly), the pickup forces; then the Python around it (Statics.solve: checks, the call,
the Loaded). Each piece is timed in a compiled loop at the last loaded equilibrium of the
sine, CPU time, and counted as often as a command does it.
"""

from __future__ import annotations

import time

from numba import njit
import numpy as np

from ..core.statics import kernels

command, forces, kernel = kernels.command, kernels.forces, kernels.kernel
kkt, newton = kernels.kkt, kernels.newton

jit = njit(cache=False)   # compiles in the core's kernels: cached apart, it could go stale
REPEAT = 2000


@jit
def _views(ints, reals, floats, integers, count):
    total = 0.0
    for _ in range(count):
        model = kernel.model_of(ints, reals)
        w = newton.work_of(model, floats, integers)
        total += w.grad[0] + model.consts[0]
    return total


@jit
def _last_loaded(model, state, io):
    """Return the views of the last loaded equilibrium and its command's Inputs."""
    done = command.views(state, len(model.b_kind), model.m, 1)
    x_load = np.empty(3)
    command.load_point(model, command.views(state, len(model.b_kind), model.m, 0).r[0],
                       io[command.AT_CP] != 0.0, x_load)
    return done, kernel.Inputs(done.head[0], done.head[1], x_load,
                               io[command.FORCE:command.FORCE + 3],
                               io[command.MOMENT:command.MOMENT + 3])


@jit
def _assemble(ints, reals, state, io, floats, integers, what, count):
    model = kernel.model_of(ints, reals)
    w = newton.work_of(model, floats, integers)
    done, inputs = _last_loaded(model, state, io)
    for _ in range(count):
        kernel.assemble(model, done.c, done.r, done.lam, inputs, what, w)
    return w.grad[0]


@jit
def _factorise(ints, reals, state, io, floats, integers, count):
    model = kernel.model_of(ints, reals)
    w = newton.work_of(model, floats, integers)
    _assemble(ints, reals, state, io, floats, integers, kernel.EXACT, 1)
    mode = 0
    for _ in range(count):
        mode, _ = newton.factorise(model, w)
    return mode


@jit
def _solve(ints, reals, state, io, floats, integers, count):
    model = kernel.model_of(ints, reals)
    w = newton.work_of(model, floats, integers)
    mode = _factorise(ints, reals, state, io, floats, integers, 1)
    for i in range(model.n + model.m):
        w.rhs[i] = 1.0
    for _ in range(count):
        kkt.solve_full(w, model.perm, model.bounds, mode)
    return w.sol[0]


@jit
def _pickups(ints, reals, state, io, floats, integers, count):
    model = kernel.model_of(ints, reals)
    w = newton.work_of(model, floats, integers)
    done, inputs = _last_loaded(model, state, io)
    out = np.empty(len(io))
    for _ in range(count):
        forces.pickups(model, done.c, done.r, done.lam, inputs, out, w.scratch)
    return out[0]


def _per_call(run, *args) -> float:
    """Return the best of 3 CPU times (us) per call of a compiled loop of REPEAT calls."""
    run(*args, 1)
    best = float('inf')
    for _ in range(3):
        start = time.process_time()
        run(*args, REPEAT)
        best = min(best, (time.process_time() - start) / REPEAT * 1e6)
    return best


def parts(scene, sine, more) -> dict:
    """
    Return {piece: CPU us per command} of a loaded command.

    sine, more: (travels, loads) of commands along the sine, more going on from sine: the
    first solved by Statics.solve, the second by its compiled call alone (the load written
    into its input first, not timed).
    """
    from ..core.statics import Statics
    statics = Statics(scene)
    travels, loads = sine
    statics.solve(travels[0], loads[0])
    start = time.process_time()
    for travel, load in zip(travels, loads):
        statics.solve(travel, load)
    whole = (time.process_time() - start) / len(travels) * 1e6
    io, state = statics._io, statics._state
    ints, reals = statics.packed.ints, statics.packed.reals
    floats, integers = statics._work
    compiled = 0
    for travel, load in zip(*more):
        io[command.FORCE:command.FORCE + 3] = load.force_n
        io[command.MOMENT:command.MOMENT + 3] = [1000.0 * m for m in load.moment_nm]
        io[command.Z] = statics._z0 + travel
        io[command.ZERO_FROM] = io[command.LOADED_FROM] = command.WARM
        start = time.perf_counter_ns()
        command.solve(ints, reals, state, io, floats, integers)
        compiled += time.perf_counter_ns() - start
    compiled /= 1e3 * len(more[0])
    io, state = io.copy(), state.copy()   # the pieces' loops: at the last equilibrium
    floats, integers = floats.copy(), integers.copy()
    args = (ints, reals, state, io, floats, integers)
    out = {'Statics.solve': whole, 'its compiled call': compiled,
           'Python around it': whole - compiled,
           'views of Model and work': _per_call(_views, ints, reals, floats, integers)}
    out['exact assembly (x2)'] = 2 * _per_call(_assemble, *args, kernel.EXACT)
    out['residual assembly (x3)'] = 3 * _per_call(_assemble, *args, kernel.RESIDUAL)
    out['factorisation (x2)'] = 2 * _per_call(_factorise, *args)
    out['KKT solve (x4)'] = 4 * _per_call(_solve, *args)
    out['pickup forces (x1)'] = _per_call(_pickups, *args)
    out['rest of the compiled call'] = compiled - sum(
        value for name, value in out.items() if '(x' in name or name.startswith('views'))
    return out
