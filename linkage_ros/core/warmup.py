# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The first compile of the numerical kernels: tell whether it is due, say so once, do it.

numba compiles the kernels (KERNEL_MODULES: linkage_ros.core.base.so3, force_table,
jacobian_kernel, kernel, element_kernel, body_kernel) on first use (about 20 s) and keeps the
machine code in its on-disk cache (NUMBA_CACHE_DIR, else __pycache__ beside each module);
later processes load it in well under a second. A program calls, before its first solve:

    cold() -> bool                   numba's cache lacks a kernel: the next solve compiles
    say_if_cold(prog, file=stderr)   print 'prog: compiling the numerical kernels, once, about
                                     20 s' once per process if cold(); returns cold()
                                     (with statics=True and those kernels cold, it names
                                     them: message())
    compile_if_cold(prog)            say_if_cold, then compile_in_child: what a program
                                     calls (the next process is warm, whatever it solves)
    compile_kernels()                solve once along every path (both methods, a rack, a
                                     travel out of reach, a sweep, the alignment set, the
                                     elements (one answer and a batch), the carrier's
                                     motion, an axle, roll-centre slopes, the bodies' TF
                                     frames): every kernel
                                     compiled, hence cached
    compile_in_child() -> bool       compile_kernels in a child process (python -m
                                     linkage_ros.core.warmup) while this one waits: the wait
                                     is interruptible, where a compile in this process holds
                                     it for seconds at a time inside LLVM; the child is
                                     killed if the wait is interrupted

Each takes statics=False: True adds the statics kernels (STATICS_MODULES: compiled by
solve_loaded and compliance), for a program or node whose scene has bushings or that is asked
for statics (wants_statics); the others neither check nor compile them.

`python -m linkage_ros.core.warmup [--statics]` compiles ahead of time (after an install, say).
"""

import importlib
import os
import subprocess
import sys

# The modules of numba-compiled functions (each one's own cache files).
KERNEL_MODULES = ('linkage_ros.core.base.so3', 'linkage_ros.core.base.force_table',
                  'linkage_ros.core.solve.jacobian_kernel',
                  'linkage_ros.core.solve.kernel', 'linkage_ros.core.solve.element_kernel',
                  'linkage_ros.core.solve.body_kernel')
# The statics' (only for a scene with bushings, or when statics is asked for).
STATICS_MODULES = tuple(f'linkage_ros.core.statics.{name}' for name in (
    'rotation', 'kernel', 'kkt', 'newton', 'forces', 'command'))
MESSAGE = 'compiling the numerical kernels, once, about 20 s'
# The statics kernels take about as long again (66 s after 83 s for the others, both measured
# on one busy machine: python -m linkage_ros.core.warmup, then with --statics).
STATICS_MESSAGE = 'compiling the statics kernels, once, about 20 s'
BOTH_MESSAGE = 'compiling the numerical kernels and the statics kernels, once, about 40 s'
STATICS_FLAG = '--statics'
_said = False


def wants_statics(scene, asked: bool = False) -> bool:
    """Tell whether a program on a scene solves statics: asked to, or the scene has bushings."""
    return bool(asked or scene.has_bushings)


def uncached_kernels(statics: bool = False) -> list:
    """Return the names (module.function) of kernels numba's on-disk cache lacks (yet)."""
    return _uncached(KERNEL_MODULES + (STATICS_MODULES if statics else ()))


def _uncached(modules) -> list:
    """Return the names (module.function) of the kernels of modules the cache lacks."""
    from numba.core.dispatcher import Dispatcher

    return [f'{module.rsplit(".", 1)[1]}.{name}' for module in modules
            for name, value in vars(importlib.import_module(module)).items()
            if isinstance(value, Dispatcher) and value.py_func.__module__ == module
            and not _in_cache(value)]   # each kernel in its own module, not where imported


def _in_cache(dispatcher) -> bool:
    """
    Tell whether numba's on-disk cache holds a compiled version of a kernel.

    numba has no public call for this: its cache index (the .nbi file, read as numba reads it:
    empty when absent, of another numba version or older than the source) is the one place.
    Should numba's internals move, the answer is True: never say a compile is coming when it
    is not known (test_warmup pins that this works with the installed numba).
    """
    try:
        return bool(dispatcher._cache._cache_file._load_index())
    except Exception:  # (numba's private layout changed: not known, so not cold)
        return True


def cold(statics: bool = False) -> bool:
    """Tell whether the next solve compiles kernels (about 20 s) instead of loading them."""
    return bool(uncached_kernels(statics))


def message(statics: bool = False) -> str:
    """
    Return what is said of the compile due, or '' if none is.

    MESSAGE (the kernels), STATICS_MESSAGE (statics asked for, only their kernels cold) or
    BOTH_MESSAGE: a program that solves statics says the time its compile takes.
    """
    kinematic = bool(_uncached(KERNEL_MODULES))
    more = statics and bool(_uncached(STATICS_MODULES))
    return (BOTH_MESSAGE if kinematic else STATICS_MESSAGE) if more else \
        (MESSAGE if kinematic else '')


def say_if_cold(prog: str, file=None, statics: bool = False) -> bool:
    """If cold(), say once per process on file (stderr) what is being compiled (message())."""
    global _said
    said = message(statics)
    if not said:
        return False
    if not _said:
        print(f'{prog}: {said}', file=file or sys.stderr, flush=True)
        _said = True
    return True


def compile_if_cold(prog: str, statics: bool = False) -> bool:
    """
    If cold(), say so once (say_if_cold) and compile every kernel in a child process.

    Every kernel, not only those this program needs: else the next program would be cold
    again, and say so again. The wait is interruptible (compile_in_child). Returns cold().
    """
    if not say_if_cold(prog, statics=statics):
        return False
    compile_in_child(statics)
    return True


def compile_kernels(statics: bool = False) -> None:
    """Solve along every path the programs take, so that every kernel is compiled and cached."""
    import numpy as np

    from .measure.alignment import alignment
    from .model.scene import load_scene
    from .solve.kinematics import Continuation, sweep
    steered = load_scene('double_wishbone')     # a steer: rack link: the rack paths too
    for method in ('fast', 'paper'):
        for scene in (load_scene('five_link'), steered):
            cont = Continuation(scene, method=method)
            cont.solve(10.0)
            cont.solve(1000.0)                  # out of reach: the arclength walk
            cont.solve(float('nan'))
        cont.solve(10.0, 5.0)
        solution = cont.solve(12.0)
        alignment(steered, cont.mech, solution.wheel_center, solution.rotation, solution.rack)
        sweep(steered, np.linspace(-20.0, 20.0, 5), method=method, rack=2.0)
    _compile_elements_and_axles(load_scene('five_link'))
    if statics:
        _compile_statics(load_scene('five_link'))


def _compile_elements_and_axles(scene) -> None:
    """Solve the elements of a scene that has some, its carrier's motion, an axle, its frames."""
    import numpy as np

    from .axle.axle import axle_of, slopes, solve_axle
    from .base.force_table import table_force
    from .measure.bodies import body_poses, corner_bodies
    from .measure.elements import element_values, prepare, values_at
    from .measure.motion import carrier_motion, guidance_rows, pose_batch
    from .measure.mounts import mount_motion, mount_table
    from .model.mounts import Mount
    from .model.vehicle import load_vehicle
    from .solve.kinematics import Continuation, sweep
    result = sweep(scene, np.linspace(-20.0, 20.0, 5))
    element_values(scene, result.wheel_center, result.rotation)
    cont = Continuation(scene)
    solution = cont.solve(5.0)
    model = prepare(scene, cont.mech)
    values_at(model, solution.wheel_center, solution.rotation, solution.rack, cont.jacobian)
    center, rotation = np.array(solution.wheel_center), np.array(solution.rotation)
    element_values(scene, center[None], rotation[None], solution.rack, model=model)  # one answer
    slopes(np.array(cont.jacobian)[None])   # the node's roll centres
    mech = cont.mech
    rows, poses = guidance_rows(scene, mech), pose_batch(mech, result.wheel_center,
                                                         result.rotation)
    carrier_motion(rows, poses)
    mount_motion(rows, mount_table(scene, [Mount('carrier', scene.constraints[0].carrier)]),
                 poses)
    solve_axle(axle_of(load_vehicle('demo_vehicle'), 'front'), [-10.0, 0.0, 10.0])
    body_poses(corner_bodies(scene), solution)     # the node's /tf (TF is on by default)
    table_force(np.array([0.0, 1.0]), np.array([0.0, 1.0]), 0.5)   # Element.spring_at's


def _compile_statics(scene) -> None:
    """Solve a loaded equilibrium and the rates of a scene given bushings on every joint."""
    from dataclasses import replace

    from .model.bushing import Bushing
    from .statics import compliance, Load, solve_loaded
    bushed = replace(scene, constraints=[
        c if c.type == 'line' else replace(c, bushing=Bushing(2000.0, 5000.0, 1.0, 5.0))
        for c in scene.constraints])
    compliance(bushed, 5.0)   # a zero-load state from the kinematics, then continued
    solve_loaded(bushed, 6.0, Load((0.0, 1000.0, 0.0), 'cp', (0.0, 0.0, 10.0)))


def compile_in_child(statics: bool = False) -> bool:
    """
    Run compile_kernels in a child process and wait for it; True if it finished well.

    The child has its own session, so that a Ctrl-C in the terminal reaches only this
    process, which then kills it: any exception in the wait (KeyboardInterrupt, a signal
    handler's) kills the child and is raised on. False if the child failed: the compile then
    happens in this process, at the first solve.
    """
    flags = [STATICS_FLAG] if statics else []
    child = subprocess.Popen([sys.executable, '-m', __name__, *flags], stdin=subprocess.DEVNULL,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                             start_new_session=True, env=os.environ.copy())
    try:
        return child.wait() == 0
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()


if __name__ == '__main__':
    compile_kernels(STATICS_FLAG in sys.argv[1:])
