# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A corner under load: its equilibrium pose and the force at every pickup (STATICS_SPEC.md).

    solve_loaded(scene, travel_mm, load, rack_mm) -> Loaded

The travel is held (the wheel centre's z), the rack too; the load is a force (N, fixed
direction, vehicle frame) at the contact patch or the wheel centre and a moment (N m). The
zero-load equilibrium is solved first from the kinematic pose (it holds the springs'
preload), then the loaded one from it (newton.py). Numerics that fail are a result with
Status.NOT_CARRIED, naming the load and the last residual, with no pose.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
import math
from typing import NamedTuple

import numpy as np

from . import newton
from .forces import item_places, pickup_forces
from .pack import pack
from .rotation import log_so3
from .system import build, initial_pose, Pose, System
from ..base.errors import LinkageError
from ..base.finite import all_finite, is_finite_number
from ..base.geometry import camber_toe
from ..base.status import Status
from ..measure.alignment import patch_offset
from ..solve.continuation import Continuation
from ..solve.mechanism import compile_scene

PLACES = ('cp', 'wc')
# The model's validity (STATICS_SPEC.md): beyond these a load is not carried
MAX_DEFLECTION_MM = 10.0
MAX_CONICAL_DEG = 5.0
# trace 1 + 2 cos(angle) of a rotation surely within MAX_CONICAL_DEG (_beyond_validity)
QUICK_TRACE = 1.0 + 2.0 * math.cos(math.radians(0.999 * MAX_CONICAL_DEG))


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


@dataclass(frozen=True)
class Loaded:
    """A loaded equilibrium (mm, deg, N, vehicle frame); pose fields None unless OK."""

    status: Status
    message: str
    travel_mm: float
    camber_deg: float = math.nan
    toe_deg: float = math.nan
    wheel_center_mm: np.ndarray | None = None
    rotation: np.ndarray | None = None
    holding_force_n: float = math.nan
    link_forces_n: dict = field(default_factory=dict)
    pivot_forces_n: dict = field(default_factory=dict)
    ball_joint_forces_n: dict = field(default_factory=dict)
    spring_forces_n: dict = field(default_factory=dict)
    body_points_mm: dict = field(default_factory=dict)
    body_forces_n: dict = field(default_factory=dict)
    body_moments_nm: dict = field(default_factory=dict)
    load_point_mm: np.ndarray | None = None
    residual: float = math.nan
    iterations: int = 0
    rack_mm: float = 0.0


class Unloaded(NamedTuple):
    """The zero-load equilibrium at a travel and rack, and what later solves need of it."""

    status: Status
    message: str
    system: System | None = None
    eq: newton.Equilibrium | None = None
    lever: float = 1.0
    model: object = None    # kernel.Model of system (None: solved by newton_python)


# where a Scene keeps its statics Systems and packed Models, by rack (as compile_scene does)
PREPARED = '_statics'
RACKS_KEPT = 16
LAST = '_statics_last'   # the last zero-load equilibrium solved: key, it, kinematic (M, R)
# a last zero-load equilibrium at most this far in travel (same rack) starts the next Newton
# (a node at 1 kHz, a sweep): fewer iterations, and no arm poses to set up from the kinematics
WARM_MM = 5.0


def prepared(scene, rack_mm: float, z: float, load_x0: np.ndarray, compiled: bool = True):
    """
    Return (System, kernel.Model or None) of a scene at rack, held height z, load point x0.

    Built and packed once per scene and rack (kept on the Scene); each call sets the height
    and the load point in copies of the two arrays that hold them.
    """
    cache = scene.__dict__.setdefault(PREPARED, {})
    if rack_mm not in cache:
        if len(cache) >= RACKS_KEPT:   # a steered node's racks: keep the last few only
            cache.clear()
        system = build(scene, rack_mm, 0.0, np.zeros(3))
        cache[rack_mm] = (system, pack(system))
    template, model = cache[rack_mm]
    name, kind, items, _ = template.constraints[-1]   # the travel row, the last constraint
    system = replace(template, z=z, load_item=template.load_item._replace(x0=load_x0),
                     constraints=template.constraints[:-1] + [(name, kind, items, z)])
    if not compiled or _has_force_table(scene):
        return build(scene, rack_mm, z, load_x0), None
    data, x0 = model.t_data.copy(), model.it_x0.copy()
    data[model.m - 1, 0] = z            # the travel row, the last constraint
    x0[len(x0) - 1, 0] = load_x0        # the load, the last term
    return system, model._replace(t_data=data, it_x0=x0)


def _has_force_table(scene) -> bool:
    # The compiled kernel's springs are linear (rate, free length); a spring with a force table
    # (a Chrono curve, a bump stop) takes the numpy path, which evaluates Element.spring_at.
    return any(e.force_table is not None for e in scene.elements)


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
    return values[0], values[1] * 1000.0


def unloaded(scene, travel_mm: float, rack_mm: float = 0.0,
             continuation: Continuation | None = None, compiled: bool = True) -> Unloaded:
    """
    Solve the zero-load equilibrium at travel and rack (mm), from the kinematic pose.

    Or from the last one solved at the same rack within WARM_MM of travel (_predicted), when
    that converges.
    compiled False: by newton_python (numpy), the check of the compiled kernel. The last
    one solved is kept on the Scene and returned again for the same travel and rack (a rig
    or a node loading one position with many loads; rates and loads at one travel).
    """
    if not (is_finite_number(travel_mm) and is_finite_number(rack_mm)):
        return Unloaded(Status.NOT_FINITE, f'travel {travel_mm!r} and rack {rack_mm!r} must be '
                        'finite numbers')
    key = (float(travel_mm), float(rack_mm), compiled)
    last = scene.__dict__.get(LAST)
    if last is not None and last[0] == key:
        return last[1]
    cont = continuation or Continuation(scene)
    kin = cont.solve(float(travel_mm), float(rack_mm) if scene.steered else None)
    if not kin.success:
        return Unloaded(kin.status, kin.message)
    mech = compile_scene(scene)
    z = float(mech.design_center[2] + travel_mm)
    system, model = prepared(scene, float(rack_mm), z, mech.design_center, compiled)
    lever = mech.lever
    center, rotation = np.asarray(kin.wheel_center), np.asarray(kin.rotation)
    eq = None
    if (last is not None and last[0][1:] == key[1:]
            and abs(last[0][0] - key[0]) <= WARM_MM):
        eq = newton.loaded(system, model, _predicted(last, center, rotation), np.zeros(3),
                           np.zeros(3), lever)
    if eq is None or not eq.ok:   # a cold start, or the warm one failed: from the kinematics
        pose = initial_pose(system, scene, center, rotation)
        eq = newton.loaded(system, model, newton.Equilibrium(
            True, pose, np.zeros(len(system.constraints)), None, None, 0.0, 0), np.zeros(3),
            np.zeros(3), lever)
    if not eq.ok:
        return Unloaded(Status.NOT_CARRIED, f'the zero load is not carried at travel '
                        f'{travel_mm:g} mm: no convergence (residual {eq.residual:.3g} N)')
    done = Unloaded(Status.OK, 'ok', system, eq, lever, model)
    scene.__dict__[LAST] = (key, done, (center.copy(), rotation.copy()))
    return done


def _predicted(last, center: np.ndarray, rotation: np.ndarray) -> newton.Equilibrium:
    """
    Return a Newton start from the last zero-load equilibrium (a 'last' entry of LAST).

    Its carrier is moved as the kinematic pose moved since (the deflection carried over);
    the other bodies and the multipliers are kept.
    """
    _, done, (center0, rotation0) = last
    pose = done.eq.pose
    c, r = pose.c.copy(), pose.r.copy()
    c[0] = pose.c[0] + center - center0
    r[0] = rotation @ rotation0.T @ pose.r[0]
    return newton.Equilibrium(True, Pose(c, r), done.eq.multipliers.copy(), None, None, 0.0, 0)


def load_point(scene, base: Unloaded, at: str) -> np.ndarray:
    """Return the load point's design-frame carrier position x0 (3,) mm (cp: module doc)."""
    center0 = compile_scene(scene).design_center
    if at == 'wc':
        return center0.copy()
    c, r = base.eq.pose.c[0], base.eq.pose.r[0]
    axis = r @ compile_scene(scene).spin_axis
    patch = c + np.array(patch_offset(axis[0], axis[1], axis[2], scene.wheel_radius))
    return center0 + r.T @ (patch - c)


def solve_loaded(scene, travel_mm: float = 0.0, load: Load = Load(), rack_mm: float = 0.0,
                 continuation: Continuation | None = None, compiled: bool = True) -> Loaded:
    """
    Solve the loaded equilibrium of a scene at travel and rack (mm); returns a Loaded.

    Bad input (a load at cp without wheel_radius, a non-finite load) raises LinkageError;
    a load not carried is Status.NOT_CARRIED with no pose. continuation: a solve.Continuation
    of the scene to take the kinematic pose from (kept between calls: the node's). compiled
    False: by newton_python (numpy), the compiled kernel's check.
    """
    force, moment = check_load(scene, load)
    base = unloaded(scene, travel_mm, rack_mm, continuation, compiled)
    if base.status != Status.OK:
        return Loaded(base.status, base.message, float(travel_mm))
    x0 = load_point(scene, base, load.at)
    system = replace(base.system, load_item=base.system.load_item._replace(x0=x0))
    model = base.model
    if model is not None:
        it_x0 = model.it_x0.copy()
        it_x0[len(it_x0) - 1, 0] = x0
        model = model._replace(it_x0=it_x0)
    eq = newton.loaded(system, model, base.eq, force, moment, base.lever)
    if not eq.ok:
        return _not_carried(load, travel_mm, eq, 'no convergence (last residual '
                            f'{eq.residual:.3g} N)')
    at = item_places(system, model, eq.pose)
    forces = pickup_forces(scene, system, eq, force, at)
    beyond = _beyond_validity(system, eq, at)
    if beyond:
        return _not_carried(load, travel_mm, eq, f'{beyond} (residual {eq.residual:.3g} N)')
    mech = compile_scene(scene)
    c, r = eq.pose.c[0], eq.pose.r[0]
    camber, toe = camber_toe(r @ mech.spin_axis, scene.side_sign)
    return Loaded(Status.OK, 'ok', float(travel_mm), math.degrees(camber), math.degrees(toe),
                  c.copy(), r.copy(), holding_force_n=-float(eq.multipliers[-1]),
                  load_point_mm=at[-1, 0].copy(),
                  residual=eq.residual, iterations=eq.iterations, rack_mm=float(rack_mm),
                  **forces)


def _not_carried(load: Load, travel_mm: float, eq, why: str) -> Loaded:
    """Return the NOT_CARRIED Loaded of a load at a travel, naming the load and why."""
    said = (f'load {tuple(float(f) for f in load.force_n)} N at {load.at}, moment '
            f'{tuple(float(m) for m in load.moment_nm)} N m')
    return Loaded(Status.NOT_CARRIED, f'{said} is not carried at travel {travel_mm:g} mm: '
                  f'{why}', float(travel_mm), residual=eq.residual, iterations=eq.iterations)


def _beyond_validity(system, eq, at: np.ndarray) -> str:
    """Say which bushing deflects beyond the model's validity, '' if none does; at: places."""
    bushes = system.bushings
    if not bushes:
        return ''
    first = len(system.constraints) + len(system.springs)   # the bushings' terms (pack.py)
    d = at[first:first + len(bushes), 0] - np.array([b.at for b in bushes])
    sizes = np.sqrt((d * d).sum(axis=1))
    # the usual answer at once: no deflection beyond, and no arm turned beyond the conical
    # limit in all (a rotation's conical part is at most its angle; the margin covers
    # round-off); else (or a NaN) each bushing in turn, to name the first beyond
    arms = {b.body for b in bushes if system.bodies[b.body].kind == 'arm'}
    if sizes.max() <= MAX_DEFLECTION_MM and all(
            _trace(eq.pose.r[k]) >= QUICK_TRACE for k in arms):
        return ''
    sizes = sizes.tolist()
    turns = {}   # per arm body: its rotation vector (its bushings share it)
    for b, size in zip(bushes, sizes):
        if size > MAX_DEFLECTION_MM:
            return (f'bushing {b.key} deflects {size:.3g} mm, beyond the '
                    f"model's {MAX_DEFLECTION_MM:g} mm")
        if system.bodies[b.body].kind == 'arm':
            if b.body not in turns:
                turns[b.body] = log_so3(eq.pose.r[b.body])
            phi = turns[b.body]
            across = phi - (phi @ b.axis) * b.axis
            conical = math.degrees(math.sqrt(across @ across))
            if conical > MAX_CONICAL_DEG:
                return (f'bushing {b.key} turns {conical:.3g} deg conically, beyond the '
                        f"model's {MAX_CONICAL_DEG:g} deg")
    return ''


def _trace(rotation: np.ndarray) -> float:
    """Return the trace of a rotation matrix (3, 3): 1 + 2 cos(its angle)."""
    return float(rotation[0, 0] + rotation[1, 1] + rotation[2, 2])
