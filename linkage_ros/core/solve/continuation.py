# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Continuation over wheel travel and steering rack: one command at a time, each from the last.

    Continuation(scene, method='fast').solve(travel_mm, rack_mm) -> Solution

Each command starts from the last good pose (the paper's continuation), which keeps the
carrier on the assembly branch of the design position. Commands longer than max_step are
walked in substeps along a straight line in (travel, rack); a substep whose Newton iteration
fails, or whose answer lands on the other side of a turning point or farther from the
tangent prediction than a branch change allows, is halved and retried (kernel.step). When a
substep falls below min_step the command is out of reach: at an unchanged rack the solution
curve is then followed by arclength (arclength.py) to the target or to the travel limit
(turning point) in between, which is reported and remembered for that rack, so that a
later command beyond it is refused at once. A walk never takes more than max_substeps.

Nothing here raises for numerics: a Solution carries success, a status
(status.Status) and a message.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
import math
import numbers
from typing import Any, NamedTuple, TYPE_CHECKING

import numpy as np

from . import arclength, jacobian_kernel, kernel, pose_newton, state
from .mechanism import (carrier_points, compile_scene, linearize, scaled_condition,
                        SINGULAR_CONDITION)
from .paper_method import build as build_paper_model, correct as paper_correct
from ..base.errors import LinkageError
from ..base.finite import is_finite_number
from ..base.ranges import RANGE, shown
from ..base.status import Status

if TYPE_CHECKING:
    from ..model.scene import Scene

METHODS = ('paper', 'fast')
ARC_TOL = 1e-9       # mm: residual tolerance on the arclength path to a travel limit
ROUND_OFF = 64 * np.finfo(float).eps   # tolerance floor per mm of scene size
# Defaults of the settings that follow the mechanism's size (length_scale): mm at scale 1.
MIN_STEP, KNOT_STEP, KNOT_TOL = 0.005, 40.0, 1e-6
LOCATED = 0.5 * arclength.RESOLUTION   # mm at scale 1: how closely a travel limit is located


@dataclass(frozen=True)
class Settings:
    """
    Solver settings. Lengths in mm.

    None: the default for this mechanism, MIN_STEP, KNOT_STEP or KNOT_TOL times its
    length_scale (1 for every road-vehicle corner). Given values are used as they are.
    """

    method: str = 'fast'
    # paper: largest coordinate change in the last iteration (eqs. 11-12); fast: largest
    # constraint residual (a length)
    tol: float = 1e-10
    max_iter: int = 25        # Newton iterations per step
    max_step: float = 5.0     # longest continuation substep
    min_step: float | None = None    # a failing substep below this means out of reach
    max_substeps: int = 10_000       # substeps one command may try; a longer walk is refused
    knot_step: float | None = None   # fast sweeps: continuation step between batch knots
    knot_tol: float | None = None    # fast sweeps: knots only start the batch (to tol)


class Solution(NamedTuple):
    """
    One solved position, vehicle frame, mm and rad. On failure the pose fields are None.

    Immutable (a NamedTuple: cheap to make, which matters on the node's one-command path);
    its arrays are read-only views of the solver's state.
    """

    travel: float                # imposed wheel-centre z change, + = bump (mm)
    success: bool
    message: str
    wheel_center: np.ndarray | None = None   # (3,) mm
    rotation: np.ndarray | None = None       # (3, 3) carrier orientation relative to design
    camber: float = math.nan     # rad, + = top of the wheel outboard
    toe: float = math.nan        # rad, + = toe-in
    iterations: int = 0          # Newton iterations of the last step
    residual: float = math.nan   # largest constraint violation (mm)
    substeps: int = 0            # continuation steps walked for this position
    condition: float = math.nan  # condition number of the Jacobian at the solution
    reachable: tuple[float, float] = (0.0, 0.0)   # travel range (mm) known reachable so far
    rack: float = 0.0            # steering rack travel (mm), + = rack to the left
    quaternion: np.ndarray | None = None     # (4,) (x, y, z, w) of rotation, w >= 0
    status: Status = Status.OK   # the kind of failure; branch on it, not on message


def length_scale(lever: float) -> float:
    """
    Return the factor of the mechanism-sized lengths for a carrier of lever mm.

    lever: the largest distance of a carrier point from the wheel centre (mechanism.lever).
    1 for carriers of 100 mm to 1 m (every road vehicle: 170-400 mm in the bundled scenes),
    and proportional to the lever beyond, so that a step or an arclength never spans a fair
    part of a small mechanism, nor a negligible part of a large one.
    """
    return max(min(1.0, lever / 100.0), lever / 1000.0)


def resolved(settings: Settings, scale: float, floor: float) -> Settings:
    """
    Return settings with every default filled in for a mechanism of length_scale scale.

    Tolerances are floored at the round-off of the scene's coordinates (floor, mm): float64
    round-off of coordinates of size L is about eps * L, and a tolerance below it could never
    be met and would read as a false travel limit. Bad values raise a LinkageError.
    """
    if settings.method not in METHODS:
        raise LinkageError('method', f'unknown value {settings.method!r} (expected one of: '
                                     f"{', '.join(METHODS)})")
    small = min(1.0, scale)   # tolerances only tighten: a larger scene keeps tol as given
    out = replace(settings, tol=max(settings.tol, floor),
                  min_step=MIN_STEP * scale if settings.min_step is None else settings.min_step,
                  knot_step=(KNOT_STEP * scale if settings.knot_step is None
                             else settings.knot_step),
                  knot_tol=max(KNOT_TOL * small if settings.knot_tol is None
                               else settings.knot_tol, floor))
    for name in ('tol', 'max_step', 'min_step', 'knot_step', 'knot_tol'):
        value = getattr(out, name)
        if not (is_finite_number(value) and value > 0):
            raise LinkageError(name, f'must be a finite number above 0 (mm), got {value!r}')
    for name in ('max_iter', 'max_substeps'):
        value = getattr(out, name)
        if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 1:
            raise LinkageError(name, f'must be a whole number of at least 1, got {value!r}')
    return replace(out, max_iter=int(out.max_iter), max_substeps=int(out.max_substeps))


def not_finite(name: str, value: object) -> str:
    """
    Say why a command (travel or rack, mm) is not solved: NaN, or an infinity.

    An infinity in mm is mostly a finite value in m beyond 1.8e305 (the node's 1e308 m): it is
    said as out of the range of a length, in m and mm, the value as given being the caller's
    to say (the node's message starts with it: '/wheel_travel 1e+308 m: ...').
    """
    if isinstance(value, float) and math.isinf(value):
        return (f'{name} outside {RANGE["coordinate"].said(1000.0)}, the range of a length: '
                'not a finite number of mm')
    return f'{name} {shown(value)} mm is not a finite number'


class Continuation:
    """
    Solves wheel travels one after another, each from the last good pose.

    The last solved position is state, packed for the compiled kernels (state.py). Each
    accepted step replaces the array and nothing writes into it (it is made read-only), so
    views of it, such as a Solution's arrays, stay valid.
    """

    def __init__(self, scene: Scene, settings: Settings | None = None,
                 **overrides: Any) -> None:
        self.scene = scene
        self.mech = mech = compile_scene(scene)
        self.scale = length_scale(mech.lever)
        self.floor = ROUND_OFF * scene.size
        self.settings = cfg = resolved(settings or Settings(**overrides), self.scale,
                                       self.floor)
        self.arc_tol = max(ARC_TOL * min(1.0, self.scale), self.floor)
        # how closely a travel limit is located (mm): only a command farther beyond a limit
        # found is refused from it, so that no reachable travel ever is
        self._located = LOCATED * self.scale
        self._paper = build_paper_model(scene, mech) if cfg.method == 'paper' else None
        self.setup = kernel.Setup(mech.equations, mech.spin_axis, float(scene.side_sign),
                                  float(mech.design_center[2]), cfg.tol, cfg.max_iter,
                                  10 * cfg.tol, cfg.max_step, cfg.min_step, cfg.max_substeps)
        # kernel.walk takes it as a plain tuple: numba types that in C (kernel.Setup says why)
        self._setup_fields = tuple(self.setup)
        self.reset()

    @property
    def center(self) -> np.ndarray:
        """Wheel centre (3,) mm of the last solved position."""
        return state.center(self.state)

    @property
    def rotation(self) -> np.ndarray:
        """Carrier orientation (3, 3) relative to design at the last solved position."""
        return state.rotation(self.state)

    @property
    def jacobian(self) -> np.ndarray:
        """Jacobian (5, 6) of the guidance equations at the last solved position."""
        return state.jacobian(self.state)

    def reset(self) -> None:
        """Go back to the design position (travel 0, rack 0): eq. 9's initial solution."""
        self._commit(self._pack(0.0, 0.0, self.mech.design_center, np.eye(3)))
        self.reachable = (0.0, 0.0)
        # Travel limits found, per rack (mm): [rebound, bump] (mm), -inf / inf until found.
        # Every state is on the design branch (a step never crosses a turning point), so a
        # limit found at a rack holds there for good. Keyed on the rack of the state (never
        # on a commanded rack: the walk's arithmetic may land an ulp away from it), and
        # read only through _limits_at, which makes the entry of the state's rack.
        self.limits = {}
        # (commanded rack, the state's rack it was reached at): the same command again is
        # the same rack, not a new walk of an ulp that forgets the limits found there
        self._asked_rack = (0.0, 0.0)
        self._limits_at(self.rack)

    def take_pose(self, other: Continuation) -> None:
        """
        Start from the pose another Continuation of the same scene holds (new settings).

        Its state, the travel range explored and the travel limits found are taken as they
        are: they belong to the mechanism, not to the settings. Raises ValueError for another
        scene's Continuation.
        """
        if other.scene is not self.scene:
            raise ValueError('take_pose: the other Continuation solves another scene')
        self._commit(other.state)
        self.reachable = other.reachable
        self.limits = {rack: list(limits) for rack, limits in other.limits.items()}
        self._asked_rack = other._asked_rack
        self._limits_at(other._limits_rack)

    def solve(self, travel: float, rack: float | None = None) -> Solution:
        """
        Solve the pose at travel (mm) and steering rack (mm; None = unchanged).

        Continuation starts from the current state, and the new pose is committed if it
        succeeds.
        """
        rack = self.rack if rack is None else rack
        if not (is_finite_number(travel) and is_finite_number(rack)):
            name, value = ('rack', rack) if is_finite_number(travel) else ('travel', travel)
            return self._failure(travel, Status.NOT_FINITE, not_finite(name, value), 0)
        travel, rack = float(travel), float(rack)
        if rack == self._asked_rack[0]:
            rack = self._asked_rack[1]
        low, high = self._refused_beyond
        if rack == self.rack and not low <= travel <= high:
            return self._beyond_known_limit(travel)
        saved, saved_rack, saved_reachable = self.state, self.rack, self.reachable
        if rack != saved_rack:
            self.reachable = (self.travel, self.travel)   # the range explored at this rack
        # The walk along the straight line to (travel, rack); it commits where it got to.
        if self._paper is None:
            walked = kernel.walk(self._setup_fields, saved, travel, rack, *self.reachable)
            self._commit(walked.state)
            self.reachable = (walked.low, walked.high)
        else:
            walked = self._paper_walk(travel, rack)
        if walked.outcome == kernel.REACHED:   # the usual case, first
            if rack != saved_rack:
                self._asked_rack = (rack, self.rack)
                self._limits_at(self.rack)
            return self._solution(walked.iterations, walked.steps)
        steps, iterations, status, error = self._stopped(walked, travel, rack, saved)
        if not status:   # reached by arclength
            return self._solution(iterations, steps)
        explored = self.reachable
        self._commit(saved)
        self.reachable = explored if rack == saved_rack else saved_reachable
        return self._failure(travel, status, error, steps, explored)

    def _stopped(self, walked, target, rack, saved):
        """
        Say why a walk from the state saved stopped short of (target, rack), or go on.

        At an unchanged rack, a walk that stalled goes on by arclength. Returns (steps,
        iterations, Status, error message or '').
        """
        steps, iterations = walked.steps, walked.iterations
        start, start_rack = state.travel(saved), state.rack(saved)
        at_rack = '' if rack == start_rack else f' at rack {rack:g} mm'
        if walked.outcome == kernel.SUBSTEP_LIMIT:
            return steps, iterations, Status.SUBSTEP_LIMIT, self._substep_limit(
                target, rack, start, start_rack, at_rack)
        singular = self._singular_here(target, at_rack)
        if singular:
            return steps, iterations, Status.SINGULAR, singular
        if rack == start_rack:
            return self._walk_arclength(start, target, steps)
        return steps, iterations, Status.OUT_OF_REACH, (
            f'travel {target:g} mm{at_rack} is out of reach: continuation from travel '
            f'{start:g} mm, rack {start_rack:g} mm stops at travel {self.travel:.3f} mm, '
            f'rack {self.rack:.3f} mm')

    def _substep_limit(self, target, rack, start, start_rack, at_rack):
        """Say why a walk was refused or stopped at max_substeps."""
        cfg = self.settings
        length = max(abs(target - start), abs(rack - start_rack))
        if length > cfg.max_step * cfg.max_substeps:   # as kernel.walk tells
            needed = length / cfg.max_step
            needed = f'{math.ceil(needed):d}' if needed < 1e9 else f'{needed:.3g}'   # not 300
            return (f'travel {target:g} mm{at_rack}: the walk of {length:g} mm from travel '
                    f'{start:g} mm needs {needed} substeps of max_step {cfg.max_step:g} mm, '
                    f'more than max_substeps {cfg.max_substeps}: raise max_step')
        return (f'travel {target:g} mm{at_rack} is not reached within max_substeps '
                f'{cfg.max_substeps} substeps (halved where they failed): continuation stops '
                f'at travel {self.travel:.3f} mm, rack {self.rack:.3f} mm')

    def _singular_here(self, target, at_rack):
        """Return a message if the Jacobian at the current state is singular, else ''."""
        condition = scaled_condition(self.mech, self.jacobian)
        if condition <= SINGULAR_CONDITION:   # False for NaN: a non-finite Jacobian is too
            return ''
        return (f'travel {target:g} mm{at_rack} is out of reach: the guidance equations are '
                f'singular at travel {self.travel:g} mm, rack {self.rack:g} mm (scaled '
                f'condition number {condition:.3g}): the links do not determine the '
                "carrier's motion there (two links alike?)")

    def _paper_walk(self, target, rack):
        """
        Walk as kernel.walk does, with the paper's corrector (_paper_step), in Python.

        The same line, the same step control (kernel.next_step, kernel.after_step) and
        substep bound. Returns a kernel.Walked (its state is the one committed).
        """
        cfg = self.settings
        start, start_rack = self.travel, self.rack
        length = max(abs(target - start), abs(rack - start_rack))

        def walked(outcome):
            return kernel.Walked(self.state, steps, iterations, outcome, *self.reachable)

        done, step_length, steps, iterations = 0.0, min(cfg.max_step, length), 0, 0
        if length > cfg.max_step * cfg.max_substeps:
            return walked(kernel.SUBSTEP_LIMIT)
        for _ in range(cfg.max_substeps):
            if done >= length:
                return walked(kernel.REACHED)
            step_length, fraction = kernel.next_step(length, done, step_length)
            new, iterations, accepted = self._paper_step(
                start + fraction * (target - start), start_rack + fraction * (rack - start_rack))
            if accepted:
                self._commit(new)
                self._extend_reachable(self.travel)
                steps += 1
            done, step_length = kernel.after_step(accepted, length, done, step_length, fraction,
                                                  cfg.max_step)
            if not accepted and step_length < cfg.min_step:
                return walked(kernel.STALLED)
        return walked(kernel.REACHED if done >= length else kernel.SUBSTEP_LIMIT)

    def _paper_step(self, travel, rack):
        """
        Take one step with the paper's corrector.

        The corrector starts from the last pose (eq. 9's continuation) and its answer is
        checked as kernel.step's is: against the tangent prediction, and for the side of the
        turning points. Returns (state, iterations, accepted).
        """
        cfg, mech = self.settings, self.mech
        h, h_rack = travel - self.travel, rack - self.rack
        guess = pose_newton.predict(mech, self.center, self.rotation, self.jacobian, h, h_rack,
                                    self.rack)
        if guess is None:
            return None, 0, False
        center, rotation, iterations, ok, _ = paper_correct(
            self._paper, travel, self.center, self.rotation, cfg.tol, cfg.max_iter, rack)
        if not ok:
            return None, iterations, False
        new = self._pack(travel, rack, center, rotation)
        if not kernel.on_branch(mech.equations, *guess, center, rotation,
                                max(abs(h), abs(h_rack)), 10 * cfg.tol,
                                self._orientation(state.jacobian(new))):
            return None, iterations, False
        return new, iterations, True

    def _orientation(self, jacobian):
        """Return det J_free at the state times at jacobian: > 0 on the same side of folds."""
        return (jacobian_kernel.determinant(self.jacobian)
                * jacobian_kernel.determinant(jacobian))

    def _walk_arclength(self, start, target, steps):
        """
        Follow the curve by arclength, once continuation in travel has stalled.

        The walk goes to the target, or to the travel limit (turning point) that comes first,
        which is then remembered for this rack.
        """
        cfg = self.settings
        status, found = arclength.walk(self.mech, self.center, self.rotation, self.travel,
                                       target, self.arc_tol, cfg.max_iter, rack=self.rack,
                                       scale=self.scale)
        if status == Status.OK:
            (near_center, near_rotation, _), length = found
            center, rotation, iterations, ok, jac = pose_newton.correct(
                self.mech, target, near_center, near_rotation,
                max(min(cfg.tol, self.arc_tol), self.floor), cfg.max_iter, self.rack)
            if ok and kernel.carrier_shift(self.mech.equations, center, rotation, near_center,
                                           near_rotation) <= 2 * length \
                    and self._orientation(jac) > 0.0:   # the last arc step, the same side
                self._commit(self._pack(target, self.rack, center, rotation, jac))
                self._extend_reachable(target)
                return steps + 1, iterations, Status.OK, ''
            status, found = Status.CURVE_LOST, self.travel
        if status == Status.SINGULAR:
            return steps, 0, status, self._singular_here(target, '') or (
                f'travel {target:g} mm is out of reach: the solution curve has no tangent at '
                f'travel {self.travel:g} mm (the guidance equations are singular there)')
        limit = found if status == Status.OUT_OF_REACH else self.travel
        if status == Status.OUT_OF_REACH:
            self.limits[self._limits_rack][target > start] = limit
            self._limits_at(self._limits_rack)
        return steps, 0, status, self._limit_message(start, target, limit, status)

    def _limit_message(self, start, target, limit, status):
        """Say that target is beyond limit (found going from start); extends reachable."""
        self._extend_reachable(limit)
        low, high = self.reachable
        what = (f'a turning point, located to {self._located:g} mm'
                if status == Status.OUT_OF_REACH
                else 'the solution curve could not be followed further')
        return (f'travel {target:g} mm is out of reach: continuation from {start:g} mm ends at '
                f'the {"bump" if target > start else "rebound"} limit {limit:.3f} mm ({what}); '
                f'reachable range found: [{low:.3f}, {high:.3f}] mm')

    def _limits_at(self, rack):
        """
        Take the travel limits known at rack (mm) as those of the current rack.

        A command farther than self._located beyond one is refused from it (_refused_beyond):
        the limit is located that closely, and no reachable travel may be refused.
        """
        low, high = self.limits.setdefault(rack, [-math.inf, math.inf])
        self._limits_rack = rack
        self._refused_beyond = (low - self._located, high + self._located)

    def _beyond_known_limit(self, travel):
        """Refuse at once a travel beyond a limit already found at this rack."""
        limit = self.limits[self._limits_rack][travel > self.travel]
        message = self._limit_message(self.travel, travel, limit, Status.OUT_OF_REACH)
        return self._failure(travel, Status.OUT_OF_REACH, message, 0)

    def _extend_reachable(self, travel):
        low, high = self.reachable
        self.reachable = (min(low, travel), max(high, travel))

    def _pack(self, travel, rack, center, rotation, jacobian=None):
        """Pack a solved position as a reported kernel state (Jacobian computed if not given)."""
        if jacobian is None:
            jacobian = linearize(self.mech, center, rotation, rack)[1]
        packed = state.pack(travel, rack, center, rotation, jacobian)
        kernel.report(self.setup, packed)
        return packed

    def _commit(self, new):
        new.setflags(write=False)   # half the time of flags.writeable = False
        self.state = new
        self.travel, self.rack = state.travel(new), state.rack(new)

    def _solution(self, iterations, steps):
        solved = self.state
        residual, condition, camber, toe = state.report(solved)
        # Positional, in the order Solution declares its fields: keywords would cost about
        # a microsecond on the node's path, a tenth of a command.
        return Solution(self.travel, True, 'ok', state.center(solved), state.rotation(solved),
                        camber, toe, iterations, residual, steps, condition, self.reachable,
                        self.rack, state.quaternion(solved))

    def _failure(self, travel, status, message, steps, reachable=None):
        return Solution(travel=travel, success=False, message=message, substeps=steps,
                        reachable=reachable or tuple(self.reachable), rack=self.rack,
                        status=status)

    def joints(self, solution: Solution) -> dict[str, np.ndarray]:
        """Carrier joint positions {name: (3,) mm} of a solved position."""
        pts = carrier_points(self.mech, solution.wheel_center, solution.rotation)
        return dict(zip(self.mech.point_names, pts))
