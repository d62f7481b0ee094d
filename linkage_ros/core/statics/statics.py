# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A corner's statics, one command after another: Statics(scene).

Statics is for the statics what Continuation is for the kinematics:

    statics = Statics(scene)
    statics.solve(travel_mm, load, rack_mm) -> Loaded        the loaded pose and forces
    statics.rates(travel_mm, rack_mm) -> Compliance          the compliance rates there
    solve_loaded(scene, ...), compliance(scene, ...)          one command, a Statics each

A Statics owns its last zero-load and its last loaded equilibrium (nothing is kept in the
frozen Scene). Each command is one compiled call (command.py): the loaded equilibrium by
Newton from the last loaded one (and, for a load at the contact patch, whose point the
unloaded pose sets, the zero-load one from the last zero-load one). Where there is no last
equilibrium near enough (command.WARM_MM), or a solve from it fails, the command falls back
to the long way: the kinematic pose (the Continuation), the zero-load equilibrium from it,
then the load in increments. Both ways solve the same equations to the same tolerance: the
answers agree to round-off (test_statics_speed).

Nothing here raises for numerics: a command that is not carried, not finite or out of reach
is a Loaded (Compliance) with its Status and a message. Bad input (a load at the contact
patch without a wheel radius, a load that is not finite) raises LinkageError.
"""

from __future__ import annotations

from math import isfinite
from typing import TYPE_CHECKING

import numpy as np

from . import command, forces, kernel
from .compliance import Compliance, failed
from .loaded import check_load, Load, Loaded
from .pack import pack
from .pickups import Pickups
from .system import build, initial_pose
from ..base.finite import is_finite_number
from ..base.status import Status
from ..solve.continuation import Continuation
from ..solve.mechanism import compile_scene

if TYPE_CHECKING:
    from ..model.scene import Scene

NO_LOAD = Load()


class Statics:
    """
    Solves a scene's statics command after command, each from its last equilibrium.

    continuation: the solve.Continuation to take kinematic poses from (the node's own, which
    has solved each command's travel already); by default one of its own.
    """

    def __init__(self, scene: Scene, continuation: Continuation | None = None) -> None:
        self.scene = scene
        self.continuation = continuation or Continuation(scene)
        mech = compile_scene(scene)
        self.system = build(scene)
        self.packed = packed = pack(self.system, scene, mech)
        self._z0 = float(mech.design_center[2])
        bodies, m = len(self.system.bodies), len(self.system.constraints)
        model = kernel.unpack(packed.ints, packed.reals)
        state, floats, ints = command.sizes(model)
        # the state (the last equilibria and their factorisations) and the work of a command
        self._state = np.zeros(state)
        self._work = (np.zeros(floats), np.zeros(ints, dtype=np.int64))
        self._zero = command.state_offset(bodies, model.n, m, len(model.perm), 0)
        names = packed.names
        size = forces.answer_offsets(len(names.pickups), len(names.balls), len(names.links),
                                     len(names.springs))[-1]
        self._io = np.zeros(command.ANSWER + max(size, command.RATES_SIZE))
        self._answer_size = size
        self._ints, self._reals, self._names = packed.ints, packed.reals, packed.names
        self._load = None   # the last Load given: its numbers are in io
        self._patch = scene.wheel_radius > 0   # a load at the contact patch is possible
        self.long_ways = 0   # commands that started from the kinematic pose (_kinematic)

    def reset(self) -> None:
        """Forget the last equilibria: the next command starts from the kinematic pose."""
        self._state[:] = 0.0

    def spring_in_place(self, name: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """
        Return writable views of spring name in this Statics' packed model: (x0, point, forces).

        x0 (3,) mm: its first end as packed (its it_x0); point (3,) mm: its body end's pickup;
        forces (k,) N: its force table's forces. Written between commands, they change the
        spring as pack() would for a scene with it so moved or loaded, without a new Statics
        (core/loads: a drop link whose end and force follow the travels); the next command
        still starts from the last equilibrium.
        """
        model = kernel.unpack(self._ints, self._reals)   # views into the packed arrays
        s = self._names.springs.index(name)
        term = [t for t, kind in enumerate(model.t_kind) if kind == kernel.SPRING][s]
        start, stop = model.t_table[term]
        return (model.it_x0[term, 0], model.p_point[model.s_body[s]],
                model.table[start:stop, 1])

    def solve(self, travel_mm: float, load: Load = NO_LOAD, rack_mm: float = 0.0) -> Loaded:
        """
        Solve the loaded equilibrium at travel and rack (mm); returns a Loaded.

        Bad input raises LinkageError (check_load); numerics never raise: a load not carried
        is Status.NOT_CARRIED, naming the load and the last residual, with no pose.
        """
        io = self._io
        if load is not self._load:   # a node keeps one Load for many commands
            self._take_load(load)
        if not (is_finite_number(travel_mm) and is_finite_number(rack_mm)):
            return Loaded(Status.NOT_FINITE, self._not_finite(travel_mm, rack_mm), travel_mm)
        travel, rack = float(travel_mm), float(rack_mm)
        io[command.Z], io[command.RACK] = self._z0 + travel, rack
        io[command.ZERO_FROM] = io[command.LOADED_FROM] = command.WARM
        code = command.solve(self._ints, self._reals, self._state, io, *self._work)
        if code == command.COLD or code == command.ZERO_FAILED or code == command.LOADED_FAILED:
            kin = self._kinematic(travel, rack)   # the long way
            if kin is not None:
                return Loaded(kin.status, kin.message, travel, rack)
            io[command.LOADED_FROM] = command.ZERO
            code = command.solve(self._ints, self._reals, self._state, io, *self._work)
        if code == command.OK:
            answer = io[command.ANSWER:command.ANSWER + self._answer_size].copy()
            return Loaded(Status.OK, 'ok', travel, rack, float(answer[forces.RESIDUAL]),
                          int(answer[forces.ITERATIONS]), Pickups(self._names, answer))
        return self._not_carried(code, load, travel, rack)

    def rates(self, travel_mm: float, rack_mm: float = 0.0) -> Compliance:
        """Return the Compliance (the rates and the 6x6 matrix) at travel and rack (mm)."""
        if not (is_finite_number(travel_mm) and is_finite_number(rack_mm)):
            return failed(Status.NOT_FINITE, self._not_finite(travel_mm, rack_mm), travel_mm)
        travel, rack = float(travel_mm), float(rack_mm)
        io = self._io
        io[command.Z], io[command.RACK] = self._z0 + travel, rack
        io[command.ZERO_FROM] = command.WARM
        code = command.rates(self._ints, self._reals, self._state, io, *self._work)
        if code != command.OK:
            kin = self._kinematic(travel, rack)
            if kin is not None:
                return failed(kin.status, kin.message, travel)
            code = command.rates(self._ints, self._reals, self._state, io, *self._work)
        if code != command.OK:
            return failed(Status.NOT_CARRIED, self._zero_message(travel), travel)
        return Compliance(Status.OK, 'ok', travel,
                          io[command.ANSWER:command.ANSWER + command.RATES_SIZE].copy())

    def _take_load(self, load: Load) -> None:
        """
        Write a load into io: force N, moment N mm, where (check_load's; LinkageError).

        A load of six finite floats (a node's, each command) is taken at once; anything
        else is check_load's (it names what is wrong, or takes ints and numpy numbers).
        """
        io = self._io
        try:
            fx, fy, fz = load.force_n
            mx, my, mz = load.moment_nm
        except (TypeError, ValueError):
            fx = None
        at = load.at
        if (type(fx) is float and type(fy) is float and type(fz) is float
                and type(mx) is float and type(my) is float and type(mz) is float
                and isfinite(fx) and isfinite(fy) and isfinite(fz) and isfinite(mx)
                and isfinite(my) and isfinite(mz)
                and (at == 'wc' or (at == 'cp' and self._patch))):
            io[command.FORCE], io[command.FORCE + 1], io[command.FORCE + 2] = fx, fy, fz
            # beyond 1.8e305 N m the moment is inf N mm: a numerical failure (NOT_CARRIED)
            io[command.MOMENT] = mx * 1000.0
            io[command.MOMENT + 1] = my * 1000.0
            io[command.MOMENT + 2] = mz * 1000.0
        else:
            force, moment = check_load(self.scene, load)
            io[command.FORCE:command.FORCE + 3] = force
            io[command.MOMENT:command.MOMENT + 3] = moment
        io[command.AT_CP] = 1.0 if at == 'cp' else 0.0
        self._load = load

    @staticmethod
    def _not_finite(travel_mm, rack_mm) -> str:
        """Say what is wrong with a travel and rack (mm) that are not both finite numbers."""
        return f'travel {travel_mm!r} and rack {rack_mm!r} must be finite numbers'

    def _kinematic(self, travel, rack):
        """
        Write the kinematic pose at travel and rack into the zero-load state (the long way).

        Returns None, or the failed kinematic Solution (out of reach, not finite).
        """
        scene = self.scene
        self.long_ways += 1
        kin = self.continuation.solve(travel, rack if scene.steered else None)
        if not kin.success:
            return kin
        pose = initial_pose(self.system, scene, np.asarray(kin.wheel_center),
                            np.asarray(kin.rotation))
        bodies, m = len(self.system.bodies), len(self.system.constraints)
        o = self._zero   # the zero-load equilibrium's place: head, c, r, lambda
        self._state[o:o + 3] = 0.0
        self._state[o + 3:o + 3 + 3 * bodies] = pose.c.ravel()
        self._state[o + 3 + 3 * bodies:o + 3 + 12 * bodies] = pose.r.ravel()
        self._state[o + 3 + 12 * bodies:o + 3 + 12 * bodies + m] = 0.0
        self._io[command.ZERO_FROM] = command.KINEMATIC
        return None

    def _zero_message(self, travel) -> str:
        return (f'the zero load is not carried at travel {travel:g} mm: no convergence '
                f'(residual {self._io[command.RESIDUAL]:.3g} N)')

    def _not_carried(self, code, load, travel, rack) -> Loaded:
        """Return the NOT_CARRIED Loaded of a command's code (io), naming load and residual."""
        io = self._io
        residual = float(io[command.RESIDUAL])
        if code == command.ZERO_FAILED:
            return Loaded(Status.NOT_CARRIED, self._zero_message(travel), travel, rack,
                          residual)
        if code == command.BEYOND:
            answer = io[command.ANSWER:]
            key = self.system.bushings[int(answer[forces.VALIDITY_BUSHING])].key
            value = answer[forces.VALIDITY_VALUE]
            why = (f"bushing {key} deflects {value:.3g} mm, beyond the model's "
                   f'{forces.MAX_DEFLECTION_MM:g} mm'
                   if answer[forces.VALIDITY] == forces.DEFLECTS else
                   f"bushing {key} turns {value:.3g} deg conically, beyond the model's "
                   f'{forces.MAX_CONICAL_DEG:g} deg')
            why += f' (residual {residual:.3g} N)'
        else:
            why = f'no convergence (last residual {residual:.3g} N)'
        return Loaded(Status.NOT_CARRIED, f'{load.said()} is not carried at travel '
                      f'{travel:g} mm: {why}', travel, rack, residual,
                      int(io[command.ITERATIONS]))


def solve_loaded(scene: Scene, travel_mm: float = 0.0, load: Load = NO_LOAD,
                 rack_mm: float = 0.0, continuation: Continuation | None = None) -> Loaded:
    """
    Solve the loaded equilibrium of a scene at travel and rack (mm); returns a Loaded.

    One solve, the long way (a Statics made for it; continuation: a solve.Continuation of
    the scene to take the kinematic pose from). A caller with many commands keeps a Statics.
    Bad input raises LinkageError; a load not carried is Status.NOT_CARRIED with no pose.
    """
    return Statics(scene, continuation).solve(travel_mm, load, rack_mm)


def compliance(scene: Scene, travel_mm: float = 0.0, rack_mm: float = 0.0,
               continuation: Continuation | None = None) -> Compliance:
    """Return the Compliance of a scene at travel and rack (mm): one Statics.rates."""
    return Statics(scene, continuation).rates(travel_mm, rack_mm)
