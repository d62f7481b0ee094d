"""
Continuation over wheel travel: the public entry points of the kinematics core.

    Continuation(scene, method='fast').solve(travel_mm) -> Solution   (stateful; the node)
    sweep(scene, travels_mm, method='fast') -> Sweep                   (a table of positions)

Each position starts from the previous one (the paper's continuation), which keeps the
carrier on the assembly branch of the design position. Steps longer than max_step are
walked in substeps; a step whose Newton iteration fails, or whose answer lands farther from
the tangent prediction than a branch change allows, is halved and retried; when the step
falls below min_step, the travel is out of reach and the reachable limit found is reported.
Nothing here raises for numerics: a Solution or Sweep carries success and a message.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
import math
from typing import Any, NamedTuple, TYPE_CHECKING

import numpy as np

from . import arclength
from . import kernel
from . import paper_method
from . import pose_newton
from .errors import LinkageError
from .geometry import camber_toe, quaternion_from_matrix
from .mechanism import carrier_points, compile_scene, length_errors, linearize
from .status import Status

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from .scene import Scene

METHODS = ('paper', 'fast')
ARC_TOL = 1e-9   # mm: residual tolerance on the arclength path to a travel limit
ROUND_OFF = 64 * np.finfo(float).eps   # tolerance floor per mm of scene size


@dataclass(frozen=True)
class Settings:
    """Solver settings. Lengths in mm."""

    method: str = 'fast'
    # paper: largest coordinate change in the last iteration (eqs. 11-12); fast: largest
    # constraint residual (a length)
    tol: float = 1e-10
    max_iter: int = 25        # Newton iterations per step
    max_step: float = 5.0     # longest continuation step
    min_step: float = 0.005   # below this a failing step means out of reach (limit to 0.01)
    knot_step: float = 40.0   # fast sweeps: continuation step between the knots of a batch
    knot_tol: float = 1e-6    # fast sweeps: knots only start the batch, which converges to tol


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


@dataclass(frozen=True)
class Sweep:
    """A table of solved positions, in the order asked for. Arrays over n positions."""

    travel: np.ndarray           # (n,) mm
    wheel_center: np.ndarray     # (n, 3) mm
    rotation: np.ndarray         # (n, 3, 3)
    camber: np.ndarray           # (n,) rad
    toe: np.ndarray              # (n,) rad
    iterations: np.ndarray       # (n,)
    residual: np.ndarray         # (n,) mm
    success: bool = True
    message: str = ''
    joints: np.ndarray | None = field(default=None, repr=False)   # (n, m, 3) carrier points, mm
    rack: float = 0.0            # steering rack travel of the sweep (mm)
    quaternion: np.ndarray | None = field(default=None, repr=False)   # (n, 4) xyzw, w >= 0
    status: Status = Status.OK   # why the table ends early (success False)


class Continuation:
    """
    Solves wheel travels one after another, each from the last good pose.

    The last solved position is state, packed for the compiled kernels (kernel.STATE_SIZE:
    travel and rack in mm, wheel centre, rotation, Jacobian and what it reports). Each
    accepted step replaces the array and nothing writes into it (it is made read-only), so
    views of it, such as a Solution's arrays, stay valid.
    """

    def __init__(self, scene: Scene, settings: Settings | None = None,
                 **overrides: Any) -> None:
        self.scene = scene
        settings = settings or Settings(**overrides)
        # Float64 round-off of coordinates of size L is about eps * L: a tolerance below it
        # can never be met and would read as a false travel limit, so it is floored there.
        self.floor = ROUND_OFF * scene.size
        self.settings = replace(settings, tol=max(settings.tol, self.floor),
                                knot_tol=max(settings.knot_tol, self.floor))
        if self.settings.method not in METHODS:
            raise LinkageError('method', f'unknown value {self.settings.method!r} (expected '
                               f"one of: {', '.join(METHODS)})")
        self.mech = compile_scene(scene)
        self._paper = (paper_method.build(scene, self.mech) if self.settings.method == 'paper'
                       else None)
        cfg, mech = self.settings, self.mech
        # kernel.walk's arguments that never change, looked up once: the one-command path
        # is a few microseconds, attribute lookups included.
        self._walk_setup = (mech.equations, mech.spin_axis, scene.side_sign,
                            float(mech.design_center[2]), cfg.tol, cfg.max_iter, 10 * cfg.tol,
                            cfg.max_step, cfg.min_step)
        self.reset()

    @property
    def center(self) -> np.ndarray:
        """Wheel centre (3,) mm of the last solved position."""
        return self.state[kernel.CENTER:kernel.CENTER + 3]

    @property
    def rotation(self) -> np.ndarray:
        """Carrier orientation (3, 3) relative to design at the last solved position."""
        return self.state[kernel.ROTATION:kernel.ROTATION + 9].reshape(3, 3)

    @property
    def jacobian(self) -> np.ndarray:
        """Jacobian (5, 6) of the guidance equations at the last solved position."""
        return self.state[kernel.JACOBIAN:kernel.JACOBIAN + 30].reshape(5, 6)

    def reset(self) -> None:
        """Go back to the design position (travel 0, rack 0): eq. 9's initial solution."""
        center, rotation = self.mech.design_center, np.eye(3)
        self._commit(self._pack(0.0, 0.0, center, rotation))
        self.reachable = (0.0, 0.0)

    def solve(self, travel: float, rack: float | None = None) -> Solution:
        """
        Solve the pose at travel (mm) and steering rack (mm; None = unchanged).

        Continuation starts from the current state, and the new pose is committed if it
        succeeds.
        """
        rack = self.rack if rack is None else rack
        if not (is_finite_number(travel) and is_finite_number(rack)):
            name, value = ('rack', rack) if is_finite_number(travel) else ('travel', travel)
            return self._failure(travel, Status.NOT_FINITE,
                                 f'{name} {value!r} mm is not a finite number', 0)
        saved = self.state, self.reachable
        if rack != self.rack:
            self.reachable = (self.travel, self.travel)   # the range explored at this rack
        steps, iterations, status, error = self._walk(float(travel), float(rack))
        if status:
            explored = self.reachable
            self._commit(saved[0])
            self.reachable = explored if rack == self.rack else saved[1]
            return self._failure(travel, status, error, steps, explored)
        return self._solution(iterations, steps)

    def _walk(self, target, rack):
        """
        Advance the state to (target travel, rack) along a straight line.

        Substeps are at most max_step long, halved on failure. Returns (steps, iterations,
        Status, error message or '').
        """
        start, start_rack = self.travel, self.rack
        if self._paper is None:
            state, steps, iterations, stalled, low, high = kernel.walk(
                *self._walk_setup, self.state, target, rack, *self.reachable)
            self._commit(state)
            self.reachable = (low, high)
        else:
            steps, iterations, stalled = self._paper_walk(target, rack)
        if not stalled:
            return steps, iterations, Status.OK, ''
        if rack == start_rack:
            return self._walk_arclength(start, target, steps)
        return steps, iterations, Status.OUT_OF_REACH, (
            f'travel {target:g} mm at rack {rack:g} mm is out of reach: continuation from '
            f'travel {start:g} mm, rack {start_rack:g} mm stops at travel {self.travel:.3f} mm, '
            f'rack {self.rack:.3f} mm')

    def _paper_walk(self, target, rack):
        """
        Walk as kernel.walk does, with the paper's corrector (_paper_step), in Python.

        The same line, the same step control (kernel.next_step, kernel.after_step). Returns
        (steps, iterations, stalled).
        """
        cfg = self.settings
        start, start_rack = self.travel, self.rack
        length = max(abs(target - start), abs(rack - start_rack))
        done, step_length, steps, iterations = 0.0, min(cfg.max_step, length), 0, 0
        while done < length:
            step_length, fraction = kernel.next_step(length, done, step_length)
            state, iterations, accepted = self._paper_step(
                start + fraction * (target - start), start_rack + fraction * (rack - start_rack))
            if accepted:
                self._commit(state)
                self._extend_reachable(self.travel)
                steps += 1
            done, step_length = kernel.after_step(accepted, length, done, step_length, fraction,
                                                  cfg.max_step)
            if not accepted and step_length < cfg.min_step:
                return steps, iterations, True
        return steps, iterations, False

    def _walk_arclength(self, start, target, steps):
        """
        Follow the curve by arclength, once continuation in travel has stalled.

        The walk goes to the target, or to the travel limit (turning point) that comes first.
        """
        cfg = self.settings
        status, found = arclength.walk(self.mech, self.center, self.rotation, self.travel,
                                       target, max(ARC_TOL, self.floor), cfg.max_iter,
                                       rack=self.rack)
        if status == 'reached':
            (near_center, near_rotation, _), length = found
            center, rotation, iterations, ok, jac = pose_newton.correct(
                self.mech, target, near_center, near_rotation,
                max(min(cfg.tol, ARC_TOL), self.floor), cfg.max_iter, self.rack)
            if ok and kernel.carrier_shift(self.mech.equations, center, rotation, near_center,
                                           near_rotation) <= 2 * length:   # the last arc step
                self._commit(self._pack(target, self.rack, center, rotation, jac))
                self._extend_reachable(target)
                return steps + 1, iterations, Status.OK, ''
            found = self.travel
        direction = math.copysign(1.0, target - start)
        limit = found if status == 'limit' else self.travel
        self._extend_reachable(limit)
        low, high = self.reachable
        what = ('a turning point, located to 0.01 mm' if status == 'limit'
                else 'the solution curve could not be followed further')
        kind = Status.OUT_OF_REACH if status == 'limit' else Status.CURVE_LOST
        return steps, 0, kind, (
            f'travel {target:g} mm is out of reach: continuation from {start:g} mm ends at the '
            f'{"bump" if direction > 0 else "rebound"} limit {limit:.3f} mm ({what}); reachable '
            f'range found: [{low:.3f}, {high:.3f}] mm')

    def _extend_reachable(self, travel):
        low, high = self.reachable
        self.reachable = (min(low, travel), max(high, travel))

    def _paper_step(self, travel, rack):
        """
        Take one step with the paper's corrector.

        The corrector starts from the last pose (eq. 9's continuation) and its answer is
        checked against the same tangent prediction as kernel.step's. Returns (state,
        iterations, accepted).
        """
        cfg, mech = self.settings, self.mech
        h, h_rack = travel - self.travel, rack - self.rack
        guess = pose_newton.predict(mech, self.center, self.rotation, self.jacobian, h, h_rack,
                                    self.rack)
        if guess is None:
            return None, 0, False
        center, rotation, iterations, ok, _ = paper_method.correct(
            self._paper, travel, self.center, self.rotation, cfg.tol, cfg.max_iter, rack)
        if not ok or not kernel.on_branch(mech.equations, *guess, center, rotation,
                                          max(abs(h), abs(h_rack)), 10 * cfg.tol):
            return None, iterations, False
        return self._pack(travel, rack, center, rotation), iterations, True

    def _pack(self, travel, rack, center, rotation, jacobian=None):
        """Pack a solved position as a reported kernel state (Jacobian computed if not given)."""
        if jacobian is None:
            jacobian = linearize(self.mech, center, rotation, rack)[1]
        state = np.zeros(kernel.STATE_SIZE)
        state[kernel.TRAVEL], state[kernel.RACK] = travel, rack
        state[kernel.CENTER:kernel.CENTER + 3] = center
        state[kernel.ROTATION:kernel.ROTATION + 9] = np.ravel(rotation)
        state[kernel.JACOBIAN:kernel.JACOBIAN + 30] = np.ravel(jacobian)
        kernel.report(self.mech.equations, self.mech.spin_axis, self.scene.side_sign, state)
        return state

    def _commit(self, state):
        state.flags.writeable = False
        self.state = state
        self.travel, self.rack = float(state[kernel.TRAVEL]), float(state[kernel.RACK])

    def _solution(self, iterations, steps):
        state = self.state
        residual, condition, camber, toe = state[kernel.RESIDUAL:kernel.TOE + 1].tolist()
        # Positional, in the order Solution declares its fields: keywords would cost about
        # a microsecond on the node's path, a tenth of a command.
        return Solution(self.travel, True, 'ok', state[kernel.CENTER:kernel.CENTER + 3],
                        state[kernel.ROTATION:kernel.ROTATION + 9].reshape(3, 3), camber, toe,
                        iterations, residual, steps, condition, self.reachable, self.rack,
                        state[kernel.QUATERNION:kernel.QUATERNION + 4])

    def _failure(self, travel, status, message, steps, reachable=None):
        return Solution(travel=travel, success=False, message=message, substeps=steps,
                        reachable=reachable or tuple(self.reachable), rack=self.rack,
                        status=status)

    def joints(self, solution: Solution) -> dict[str, np.ndarray]:
        """Carrier joint positions {name: (3,) mm} of a solved position."""
        pts = carrier_points(self.mech, solution.wheel_center, solution.rotation)
        return dict(zip(self.mech.point_names, pts))


def is_finite_number(value: object) -> bool:
    """Tell whether value is a finite int or float (numpy floats included)."""
    return isinstance(value, (int, float, np.floating)) and math.isfinite(value)


def sweep(scene: Scene, travels: ArrayLike, method: str = 'fast', rack: float = 0.0,
          **settings: Any) -> Sweep:
    """
    Solve the travels (mm, in the given order) at a steering rack position (mm).

    By continuation; returns a Sweep. The paper method walks the positions one after
    another. The fast method solves knots every knot_step mm by continuation and then every
    position at once by batched Newton, each from the tangent at its nearest knot; a position
    that fails there is walked.
    """
    travels = np.asarray(travels, dtype=float).ravel()
    cont = Continuation(scene, method=method, **settings)
    if rack:
        first = cont.solve(0.0, rack)   # steer at design travel first, then sweep
        if not first.success:
            return _table(cont, [], rack, success=False, message=first.message,
                          status=first.status)
    if method == 'fast' and len(travels) > 2 and np.all(np.isfinite(travels)):
        batch = _batched(cont, travels)
        if batch is not None:
            return batch
    return _sequential(cont, travels)


def _sequential(cont, travels):
    rows = []
    for travel in travels:
        sol = cont.solve(travel)
        if not sol.success:
            return _table(cont, rows, cont.rack, success=False, message=sol.message,
                          status=sol.status)
        rows.append(sol)
    return _table(cont, rows, cont.rack)


def _table(cont, rows, rack, success=True, message='ok', status=Status.OK):
    n = len(rows)
    center = np.array([r.wheel_center for r in rows]).reshape(n, 3)
    rotation = np.array([r.rotation for r in rows]).reshape(n, 3, 3)
    return _sweep_of(cont, np.array([r.travel for r in rows], dtype=float), center, rotation,
                     np.array([r.iterations for r in rows], dtype=int), rack, success, message,
                     status)


def _sweep_of(cont, travel, center, rotation, iterations, rack, success=True, message='ok',
              status=Status.OK):
    mech = cont.mech
    camber, toe = camber_toe(rotation @ mech.spin_axis, cont.scene.side_sign)
    return Sweep(travel=travel, wheel_center=center, rotation=rotation, camber=camber, toe=toe,
                 iterations=iterations, residual=length_errors(mech, center, rotation, rack),
                 success=success, message=message, rack=rack, status=status,
                 joints=carrier_points(mech, center, rotation),
                 quaternion=quaternion_from_matrix(rotation))


def _batched(cont, travels):
    """
    Sweep fast: knots by continuation, then every position in one compiled loop.

    The knots are walked from the state at travel 0; each position is a continuation step
    from its nearest knot. Returns None when a knot cannot be reached (the sequential walk
    then finds the limit).
    """
    cfg, mech, rack = cont.settings, cont.mech, cont.rack
    knots = _knots(cont, min(travels.min(), 0.0), max(travels.max(), 0.0))
    if knots is None:
        return None
    nearest = np.argmin(np.abs(travels[:, None] - knots[:, kernel.TRAVEL][None, :]), axis=1)
    n = len(travels)
    states = np.empty((n, kernel.STATE_SIZE))
    iterations, good = np.empty(n, dtype=np.int64), np.empty(n, dtype=np.bool_)
    # Knots hold to knot_tol only, so a position at a knot may move by about that much.
    kernel.step_many(mech.equations, mech.design_center[2], cfg.tol, cfg.max_iter,
                     1e3 * cfg.knot_tol, nearest, knots, travels, rack, states, iterations,
                     good)
    center = states[:, kernel.CENTER:kernel.CENTER + 3]
    rotation = states[:, kernel.ROTATION:kernel.ROTATION + 9].reshape(n, 3, 3)
    origin = cont.state
    for i in np.flatnonzero(~good):    # rare: walk it from travel 0
        cont._commit(origin)
        sol = cont.solve(travels[i])
        if not sol.success:
            return None
        center[i], rotation[i], iterations[i] = sol.wheel_center, sol.rotation, sol.iterations
    return _sweep_of(cont, travels, center, rotation, iterations, rack)


def _knots(cont, low, high):
    """
    Return states every knot_step mm from the current state (travel 0) to high and low (mm).

    These are the bump and rebound continuation chains, each step from its tangent prediction
    and checked for a branch change. Knots hold to knot_tol only (they start the batched
    solve). Returns an array (k, kernel.STATE_SIZE), or None if a step fails (the caller then
    walks, halving steps, and finds any limit).
    """
    cfg, mech = cont.settings, cont.mech
    knots = [cont.state]
    for end in (high, low):
        state = knots[0]
        while state[kernel.TRAVEL] != end:
            travel = state[kernel.TRAVEL]
            target = end if abs(end - travel) <= cfg.knot_step else (
                travel + math.copysign(cfg.knot_step, end - travel))
            new = np.empty(kernel.STATE_SIZE)
            _, ok = kernel.step(mech.equations, mech.design_center[2], cfg.knot_tol,
                                cfg.max_iter, 1e3 * cfg.knot_tol, state, target, cont.rack, new)
            if not ok:
                return None
            new.flags.writeable = False   # as committed states are: one kernel specialization
            state = new
            knots.append(state)
    return np.array(knots)


def travel_range(start: float, stop: float, step: float) -> np.ndarray:
    """Return the travels from start to stop (mm) inclusive at step, either direction."""
    count = int(math.floor(abs(stop - start) / step + 1e-9))
    values = start + math.copysign(step, stop - start) * np.arange(count + 1)
    return values if values[-1] == stop else np.append(values, stop)
