# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A load case on a vehicle: each corner at its loaded ride height, and the forces it carries.

    Loads(vehicle).solve(case) -> CaseAnswer

For each axle: the tyre loads of the case (transfer.py) at the corners' contact patches, each
corner held at a travel and solved by the statics (corner.py), the travels found where the
holding forces are zero (ride_height.py): the springs, stops and the anti-roll bar (bar.py)
carry the load. Left and right are solved together where a bar couples them. A wheel whose
vertical load is not above zero lifts off: its axle is not solved (status NOT_CARRIED). mm,
N, N m, vehicle frame.
"""

from __future__ import annotations

from dataclasses import dataclass, field
import math
from typing import TYPE_CHECKING

import numpy as np

from .bar import bar_state, DROP_LINK
from .cases import resolve_corner
from .corner import corner_load, CornerStatics, kinematic_pose, pivot_forces
from .ride_height import find_travels
from .transfer import tyre_loads
from .vehicle_data import LoadsVehicle, prepare
from ..axle.axle import axle_of
from ..base.errors import LinkageError
from ..base.status import Status
from ..measure.elements import element_values
from ..solve.continuation import Continuation

if TYPE_CHECKING:
    from .cases import LoadCase
    from .transfer import CornerTyre, TyreLoads
    from ..model.scene import Scene
    from ..model.vehicle import Vehicle
    from ..statics.loaded import Load, Loaded


@dataclass(frozen=True)
class CornerAnswer:
    """One corner in a case: its travel, its loaded equilibrium, the load it was given."""

    corner: str
    status: Status
    message: str
    tyre: CornerTyre
    travel_mm: float = math.nan
    loaded: Loaded | None = None     # the statics' answer at the travel (OK corners)
    load: Load | None = None         # the tyre and unsprung load as the statics took it
    pose: object = None              # corner.KinematicPose at the travel
    scene: Scene | None = None       # the corner as solved (with its drop link, if any)
    drop_tension_n: float = math.nan  # the anti-roll bar's drop link, + = tension
    holding_n: float = math.nan      # the holding force at the travel, N (+ = up)


@dataclass(frozen=True)
class BarAnswer:
    """An axle's anti-roll bar in a case: twist, torque, its bushings' forces on the body."""

    twist_rad: float
    torque_nm: float
    points_mm: np.ndarray      # (2, 3) the bushings (the bar's axis points)
    forces_n: np.ndarray       # (2, 3) their forces on the body
    ends_mm: np.ndarray        # (2, 3) the drop links' tops
    drop_forces_n: np.ndarray  # (2, 3) the drop links' forces on the bar


@dataclass(frozen=True)
class CaseAnswer:
    """A load case solved: its tyre loads, every corner's answer, each bar's."""

    case: LoadCase
    tyres: TyreLoads
    corners: dict                           # corner -> CornerAnswer
    bars: dict = field(default_factory=dict)   # axle -> BarAnswer

    @property
    def status(self) -> Status:
        """Return OK when every corner is solved, else the first corner's failure."""
        for answer in self.corners.values():
            if answer.status != Status.OK:
                return answer.status
        return Status.OK


class Loads:
    """The load cases of one vehicle: its data from the setup sheet, its corners' solvers."""

    def __init__(self, vehicle: Vehicle | LoadsVehicle) -> None:
        self.data = vehicle if isinstance(vehicle, LoadsVehicle) else prepare(vehicle)
        self.vehicle = self.data.vehicle
        self.axles = {name: axle_of(self.vehicle, name) for name in self.data.axles}
        self.kinematics = {c: Continuation(s) for c, s in self.vehicle.corners.items()}
        self.statics = {}   # {corner: CornerStatics}, made at its first solve, then reused

    def corner_keys(self, case: LoadCase) -> dict[str, str]:
        """Return {case corner key: vehicle corner}; LinkageError for a key naming none."""
        keys = {}
        for key in case.corners:
            corner = resolve_corner(key, self.vehicle.corners, self.vehicle.axles.axles)
            if not corner:
                raise LinkageError(f'case {case.name}', f'corners.{key}: {self.vehicle.name} '
                                   f'has no such corner (corners: '
                                   f'{", ".join(self.vehicle.corners)})')
            keys[key] = corner
        return keys

    def solve(self, case: LoadCase) -> CaseAnswer:
        """Return the CaseAnswer of a case (LinkageError for a case the vehicle cannot take)."""
        tyres = tyre_loads(self.data, case, self.corner_keys(case))
        corners, bars = {}, {}
        for name, axle in self.data.axles.items():
            answers, bar = self.solve_axle(name, tyres)
            corners.update(answers)
            if bar is not None:
                bars[name] = bar
        return CaseAnswer(case, tyres, corners, bars)

    def solve_axle(self, name: str, tyres: TyreLoads):
        """Return ({corner: CornerAnswer}, BarAnswer or None) of an axle under a case's loads."""
        data = self.data.axles[name]
        corners = data.corners
        loads = [tyres.corners[c] for c in corners]
        lifted = [(c, t.force_n[2]) for c, t in zip(corners, loads) if not t.force_n[2] > 0]
        if lifted:
            said = ', '.join(f'{c} ({fz:.6g} N)' for c, fz in lifted)
            why = (f'the {name} axle is not solved: a wheel lifts off, its vertical tyre load '
                   f'not above 0: {said}')
            return {c: CornerAnswer(c, Status.NOT_CARRIED, why, t)
                    for c, t in zip(corners, loads)}, None
        scenes = [self.vehicle.corners[c] for c in corners]
        drops = [self.data.centres[c][2] - self.data.ground_z_mm - data.unsprung_height_mm
                 for c in corners]
        # a bar couples the two corners: solved together; else each corner on its own
        groups = [(0, 1)] if data.bar is not None else [(0,), (1,)]
        answers, bar = {}, None
        for group in groups:
            got, state, results = self._solve_group(name, group, scenes, loads, drops)
            answers.update(got)
            if data.bar is not None and state is not None:
                bar = self._bar_answer(data.bar, state, [r[2] for r in results])
        return answers, bar

    def _solve_group(self, name, group, scenes, loads, drops):
        """Return ({corner: CornerAnswer}, bar state, results) of corners solved together."""
        corners = [self.data.axles[name].corners[k] for k in group]
        mine = [scenes[k] for k in group]
        low = np.array([s.travel[0] for s in mine])
        high = np.array([s.travel[1] for s in mine])

        def evaluate(z):
            return self._evaluate(name, group, scenes, loads, drops, z)

        z0 = np.zeros(len(group))
        first, _, why = self._poses(corners, mine, z0)
        if first is None:
            return {c: CornerAnswer(c, Status.OUT_OF_REACH, why, loads[k])
                    for c, k in zip(corners, group)}, None, None
        found = find_travels(evaluate, z0, self._jacobian(name, mine, first), low, high,
                             corners)
        if found.status != Status.OK or found.payload is None:
            return {c: CornerAnswer(c, found.status, found.message, loads[k], float(z),
                                    holding_n=float(h))
                    for c, k, z, h in zip(corners, group, found.travel_mm, found.holding_n)
                    }, None, None
        poses, results, state = found.payload
        answers = {}
        for j, (corner, k) in enumerate(zip(corners, group)):
            statics, load, loaded, tension, end = results[j]
            scene = statics.scene if end is None else statics.with_drop(end, tension)
            answers[corner] = CornerAnswer(corner, Status.OK, 'ok', loads[k],
                                           float(found.travel_mm[j]), loaded, load, poses[j],
                                           scene, tension, loaded.holding_force_n)
        return answers, state, results

    def _poses(self, corners, scenes, z):
        """Return the kinematic poses of the corners at travels z, or (None, None, why)."""
        poses = []
        for corner, scene, travel in zip(corners, scenes, z):
            solution = self.kinematics[corner].solve(float(travel))
            if not solution.success:
                return None, None, f'{corner}: {solution.message}'
            poses.append(kinematic_pose(scene, solution))
        return poses, None, ''

    def _evaluate(self, name, group, scenes, loads, drops, z):
        """
        Return (holding forces (n,) N, payload, '') of corners group at travels z.

        Or (None, None, why) where a corner cannot be solved there. group: the axle's corner
        indices solved together, (0, 1) with a bar.
        """
        data = self.data.axles[name]
        corners = [data.corners[k] for k in group]
        poses, _, why = self._poses(corners, [scenes[k] for k in group], z)
        if poses is None:
            return None, None, why
        bar = None
        if data.bar is not None:
            bar = bar_state(self.axles[name], data.bar,
                            np.array([p.centre for p in poses]),
                            np.array([p.rotation for p in poses]))
        results, held = [], np.empty(len(group))
        for j, (k, pose) in enumerate(zip(group, poses)):
            statics = self._statics(corners[j], scenes[k], data.bar.sides[k] if bar else None)
            end, tension = (bar.ends[k], float(bar.tension_n[k])) if bar else (None, math.nan)
            load = corner_load(loads[k], pose, drops[k])
            loaded = statics.solve(z[j], load, end, tension)
            if loaded.status != Status.OK:
                return None, None, f'{corners[j]}: {loaded.message}'
            held[j] = loaded.holding_force_n
            results.append((statics, load, loaded, tension, end))
        return held, (poses, results, bar), ''

    def _statics(self, corner, scene, side):
        """Return the corner's CornerStatics (with its bar's drop link, side), made once."""
        statics = self.statics.get(corner)
        if statics is None:
            statics = self.statics[corner] = CornerStatics(scene, side)
        return statics

    def _jacobian(self, name, scenes, poses):
        """
        Return the start of d holding / d travel (n, n) N/mm: the kinematic wheel rates.

        The holding force (+ = up, doc/kc.md) is what the springs leave: a wheel further in
        bump is pushed down harder by them, so less is left to hold up: it grows by the
        wheel rate.
        """
        rates = []
        for scene, pose in zip(scenes, poses):
            values = element_values(scene, pose.centre[None], pose.rotation[None])
            rates.append(sum(float(values.wheel_rate[0, j])
                             for j, e in enumerate(scene.elements) if e.has_rate))
        jac = np.diag(rates)
        data = self.data.axles[name]
        if data.bar is not None and len(poses) == 2:
            values = bar_state(self.axles[name], data.bar,
                               np.array([p.centre for p in poses]),
                               np.array([p.rotation for p in poses]))
            jac += values.stiffness_n_per_mm
        return jac

    def _bar_answer(self, bar, state, loaded) -> BarAnswer | None:
        """Return the BarAnswer of a solved axle (None without a bar)."""
        if bar is None:
            return None
        key = f'{DROP_LINK}_body'
        forces = np.array([r.body_forces_n[key] for r in loaded])   # on the bar, at E
        points = np.array(bar.axis_points, dtype=float)
        on_body = pivot_forces(points, list(zip(state.ends, forces)))
        return BarAnswer(state.twist_rad, state.torque_nm, points, on_body, state.ends, forces)
