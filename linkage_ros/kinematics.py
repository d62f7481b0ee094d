"""Continuation over wheel travel: the public entry points of the kinematics core.

    Continuation(scene, method='fast').solve(travel_mm) -> Solution   (stateful; the node)
    sweep(scene, travels_mm, method='fast') -> Sweep                   (a table of positions)

Each position starts from the previous one (the paper's continuation), which keeps the
carrier on the assembly branch of the design position. Steps longer than max_step are
walked in substeps; a step whose Newton iteration fails, or whose answer lands farther from
the tangent prediction than a branch change allows, is halved and retried; when the step
falls below min_step, the travel is out of reach and the reachable limit found is reported.
Nothing here raises for numerics: a Solution or Sweep carries success and a message.
"""

from dataclasses import dataclass, field, replace
import math

import numpy as np

from . import arclength, paper_method, pose_newton
from .geometry import camber_toe, quaternion_from_matrix
from .mechanism import carrier_points, compile_scene, length_errors, linearize, rack_derivative

METHODS = ('paper', 'fast')
ARC_TOL = 1e-9   # mm: residual tolerance on the arclength path to a travel limit
ROUND_OFF = 64 * np.finfo(float).eps   # tolerance floor per mm of scene size


@dataclass(frozen=True)
class Settings:
    """Solver settings. Lengths in mm."""

    method: str = 'fast'
    tol: float = 1e-10        # paper: largest coordinate change in the last iteration (eqs.
                              # 11-12); fast: largest constraint residual (a length)
    max_iter: int = 25        # Newton iterations per step
    max_step: float = 5.0     # longest continuation step
    min_step: float = 0.005   # below this a failing step means out of reach (limit to 0.01)
    knot_step: float = 40.0   # fast sweeps: continuation step between the knots of a batch
    knot_tol: float = 1e-6    # fast sweeps: knots only start the batch, which converges to tol


@dataclass(frozen=True)
class Solution:
    """One solved position, vehicle frame, mm and rad. On failure the pose fields are None."""

    travel: float                # imposed wheel-centre z change, + = bump (mm)
    success: bool
    message: str
    wheel_center: np.ndarray = None   # (3,) mm
    rotation: np.ndarray = None       # (3, 3) carrier orientation relative to design
    camber: float = math.nan     # rad, + = top of the wheel outboard
    toe: float = math.nan        # rad, + = toe-in
    iterations: int = 0          # Newton iterations of the last step
    residual: float = math.nan   # largest constraint violation (mm)
    substeps: int = 0            # continuation steps walked for this position
    condition: float = math.nan  # condition number of the Jacobian at the solution
    reachable: tuple = (0.0, 0.0)   # travel range (mm) known to be reachable so far
    rack: float = 0.0            # steering rack travel (mm), + = rack to the left

    @property
    def quaternion(self):
        """(x, y, z, w) of the carrier rotation relative to design."""
        return quaternion_from_matrix(self.rotation)


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
    joints: np.ndarray = field(default=None, repr=False)   # (n, m, 3) carrier points, mm
    rack: float = 0.0            # steering rack travel of the sweep (mm)

    @property
    def quaternion(self):
        return np.array([quaternion_from_matrix(r) for r in self.rotation]).reshape(-1, 4)


class Continuation:
    """Solves wheel travels one after another, each from the last good pose."""

    def __init__(self, scene, settings=None, **overrides):
        self.scene = scene
        settings = settings or Settings(**overrides)
        # Float64 round-off of coordinates of size L is about eps * L: a tolerance below it
        # can never be met and would read as a false travel limit, so it is floored there.
        self.floor = ROUND_OFF * scene.size
        self.settings = replace(settings, tol=max(settings.tol, self.floor),
                                knot_tol=max(settings.knot_tol, self.floor))
        if self.settings.method not in METHODS:
            raise ValueError(f"method: unknown value {self.settings.method!r} "
                             f"(expected one of: {', '.join(METHODS)})")
        self.mech = compile_scene(scene)
        if self.settings.method == 'paper':
            model = paper_method.build(scene, self.mech)
            self._correct = lambda *args: paper_method.correct(model, *args)
        else:
            self._correct = lambda *args: pose_newton.correct(self.mech, *args)
        self.reset()

    def reset(self):
        """Back to the design position (travel 0, rack 0), the paper's eq. 9 initial solution."""
        self.travel, self.rack = 0.0, 0.0
        self.center = self.mech.design_center.copy()
        self.rotation = np.eye(3)
        self._jac = linearize(self.mech, self.center, self.rotation)[1]
        self.reachable = [0.0, 0.0]

    def solve(self, travel, rack=None):
        """Solve the pose at travel (mm) and steering rack (mm; None = unchanged) from the
        current state; commit it if it succeeds."""
        rack = self.rack if rack is None else rack
        for name, value in (('travel', travel), ('rack', rack)):
            if not isinstance(value, (int, float, np.floating)) or not math.isfinite(value):
                return self._failure(travel, f'{name} {value!r} is not a finite number', 0)
        state = (self.travel, self.rack, self.center, self.rotation, self._jac,
                 list(self.reachable))
        if rack != self.rack:
            self.reachable = [self.travel, self.travel]   # the range explored at this rack
        steps, iterations, error = self._walk(float(travel), float(rack))
        if error:
            explored = tuple(self.reachable)
            (self.travel, self.rack, self.center, self.rotation, self._jac,
             self.reachable) = state
            if rack == self.rack:      # what was explored still holds at this rack
                self.reachable = list(explored)
            return self._failure(travel, error, steps, explored)
        return self._solution(iterations, steps)

    def _walk(self, target, rack=None, trace=None):
        """Advance the state to (target travel, rack) along a straight line; returns (steps,
        iterations, error message or '').

        trace, if a list, receives (travel, center, rotation) of every accepted step.
        """
        cfg = self.settings
        rack = self.rack if rack is None else rack
        start, start_rack, steps, iterations = self.travel, self.rack, 0, 0
        length = max(abs(target - start), abs(rack - start_rack))
        done = 0.0          # distance walked along the line (mm)
        step = min(cfg.max_step, length)
        while done < length:
            step = min(step, length - done)
            fraction = 1.0 if step == length - done else (done + step) / length
            ok, iterations = self._step(start + fraction * (target - start),
                                        start_rack + fraction * (rack - start_rack))
            if ok:
                steps += 1
                done = length if fraction == 1.0 else done + step
                if trace is not None:
                    trace.append((self.travel, self.center, self.rotation))
                self._extend_reachable(self.travel)
                step = min(2 * step, cfg.max_step)
            else:
                step /= 2
                if step < cfg.min_step:
                    if rack == start_rack:
                        return self._walk_arclength(start, target, steps)
                    return steps, iterations, (
                        f'travel {target:g} mm at rack {rack:g} mm is out of reach: '
                        f'continuation from travel {start:g} mm, rack {start_rack:g} mm stops '
                        f'at travel {self.travel:.3f} mm, rack {self.rack:.3f} mm')
        return steps, iterations, ''

    def _walk_arclength(self, start, target, steps):
        """Continuation in travel stalled: follow the curve by arclength to the target, or
        to the travel limit (turning point) that comes first."""
        cfg = self.settings
        status, found = arclength.walk(self.mech, self.center, self.rotation, self.travel,
                                       target, max(ARC_TOL, self.floor), cfg.max_iter,
                                       rack=self.rack)
        if status == 'reached':
            (near_center, near_rotation, _), length = found
            center, rotation, iterations, ok, jac = pose_newton.correct(
                self.mech, target, near_center, near_rotation,
                max(min(cfg.tol, ARC_TOL), self.floor), cfg.max_iter, self.rack)
            shift = carrier_shift(self.mech, (center, rotation), (near_center, near_rotation))
            if ok and shift <= 2 * length:   # within the last arc step
                self.travel, self.center, self.rotation, self._jac = (target, center,
                                                                      rotation, jac)
                self._extend_reachable(target)
                return steps + 1, iterations, ''
            found = self.travel
        direction = math.copysign(1.0, target - start)
        limit = found if status == 'limit' else self.travel
        self._extend_reachable(limit)
        low, high = self.reachable
        what = ('a turning point, located to 0.01 mm' if status == 'limit'
                else 'the solution curve could not be followed further')
        return steps, 0, (f'travel {target:g} mm is out of reach: continuation from {start:g} mm '
                          f'ends at the {"bump" if direction > 0 else "rebound"} limit '
                          f'{limit:.3f} mm ({what}); reachable range found: '
                          f'[{low:.3f}, {high:.3f}] mm')

    def _extend_reachable(self, travel):
        self.reachable[0] = min(self.reachable[0], travel)
        self.reachable[1] = max(self.reachable[1], travel)

    def _step(self, travel, rack):
        """One continuation step: tangent prediction, Newton correction, branch check."""
        cfg = self.settings
        h, h_rack = travel - self.travel, rack - self.rack
        d_center, d_omega = pose_newton.slope_of(self._jac)
        d_center, d_omega = d_center * h, d_omega * h
        if h_rack:
            column = rack_derivative(self.mech, self.center, self.rotation, self.rack)
            r_center, r_omega = pose_newton.rack_slope_of(self._jac, column)
            d_center, d_omega = d_center + r_center * h_rack, d_omega + r_omega * h_rack
        guess = pose_newton.predict(self.center, self.rotation, (d_center, d_omega), 1.0)
        start = guess if cfg.method == 'fast' else (self.center, self.rotation)
        center, rotation, iterations, ok, jac = self._correct(travel, *start, cfg.tol,
                                                              cfg.max_iter, rack)
        if not ok or not on_branch(self.mech, guess, (center, rotation),
                                   max(abs(h), abs(h_rack)), 10 * cfg.tol):
            return False, iterations
        if jac is None:
            jac = linearize(self.mech, center, rotation, rack)[1]
        self.travel, self.rack, self.center, self.rotation, self._jac = (travel, rack, center,
                                                                         rotation, jac)
        return True, iterations

    def _solution(self, iterations, steps):
        camber, toe = camber_toe(self.rotation @ self.mech.spin_axis, self.scene.side_sign)
        return Solution(
            travel=self.travel, success=True, message='ok', wheel_center=self.center.copy(),
            rotation=self.rotation.copy(), camber=float(camber), toe=float(toe),
            iterations=iterations, residual=float(length_errors(self.mech, self.center,
                                                                self.rotation, self.rack)),
            rack=self.rack,
            substeps=steps, condition=float(np.linalg.cond(self._jac[:, pose_newton.FREE])),
            reachable=tuple(self.reachable))

    def _failure(self, travel, message, steps, reachable=None):
        return Solution(travel=travel, success=False, message=message, substeps=steps,
                        reachable=reachable or tuple(self.reachable), rack=self.rack)

    def joints(self, solution):
        """Carrier joint positions {name: (3,) mm} of a solved position."""
        pts = carrier_points(self.mech, solution.wheel_center, solution.rotation)
        return dict(zip(self.mech.point_names, pts))


def carrier_shift(mech, pose, other):
    """Largest displacement (mm) of any carrier point between two poses (center, rotation);
    batched over leading axes."""
    moved = carrier_points(mech, *pose) - carrier_points(mech, *other)
    return np.abs(moved).max(axis=(-2, -1))


def on_branch(mech, guess, found, travel_step, slack):
    """True where the converged pose is where continuation along the branch predicts it.

    A tangent prediction misses by O(step^2); a jump to another assembly branch moves the
    carrier by a link-length scale. Half the step (plus a slack for the tolerance the poses
    hold to) separates the two. Batched: travel_step (n,) with poses of n.
    """
    return carrier_shift(mech, guess, found) <= 0.5 * np.abs(travel_step) + slack


def sweep(scene, travels, method='fast', rack=0.0, **settings):
    """Solve the travels (mm, in the given order) at a steering rack position (mm) by
    continuation; returns a Sweep.

    The paper method walks the positions one after another. The fast method solves knots
    every knot_step mm by continuation and then every position at once by batched Newton,
    each from the tangent at its nearest knot; a position that fails there is walked.
    """
    travels = np.asarray(travels, dtype=float).ravel()
    cont = Continuation(scene, method=method, **settings)
    if rack:
        first = cont.solve(0.0, rack)   # steer at design travel first, then sweep
        if not first.success:
            return _table(cont, [], rack, success=False, message=first.message)
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
            return _table(cont, rows, cont.rack, success=False, message=sol.message)
        rows.append(sol)
    return _table(cont, rows, cont.rack)


def _table(cont, rows, rack, success=True, message='ok'):
    n = len(rows)
    center = np.array([r.wheel_center for r in rows]).reshape(n, 3)
    rotation = np.array([r.rotation for r in rows]).reshape(n, 3, 3)
    return _sweep_of(cont, np.array([r.travel for r in rows]), center, rotation,
                     np.array([r.iterations for r in rows], dtype=int), rack, success, message)


def _sweep_of(cont, travel, center, rotation, iterations, rack, success=True, message='ok'):
    mech = cont.mech
    camber, toe = camber_toe(rotation @ mech.spin_axis, cont.scene.side_sign)
    return Sweep(travel=travel, wheel_center=center, rotation=rotation, camber=camber, toe=toe,
                 iterations=iterations, residual=length_errors(mech, center, rotation, rack),
                 success=success, message=message, rack=rack,
                 joints=carrier_points(mech, center, rotation))


def _batched(cont, travels):
    """Fast sweep: knots by continuation from the state at travel 0, then all positions in
    one batched solve. Returns None when a knot cannot be reached (the sequential walk then
    finds the limit).
    """
    cfg, mech, rack = cont.settings, cont.mech, cont.rack
    knots = _knots(cont, min(travels.min(), 0.0), max(travels.max(), 0.0))
    if knots is None:
        return None
    knot_travel, knot_center, knot_rotation = knots
    nearest = np.argmin(np.abs(travels[:, None] - knot_travel[None, :]), axis=1)
    h = travels - knot_travel[nearest]
    slopes = pose_newton.slope_of(linearize(mech, knot_center, knot_rotation, rack)[1])
    guess_center, guess_rotation = pose_newton.predict(
        knot_center[nearest], knot_rotation[nearest], [s[nearest] for s in slopes], h)
    center, rotation, iterations, converged = pose_newton.correct_batch(
        mech, travels, guess_center, guess_rotation, cfg.tol, cfg.max_iter, rack)
    # Knots hold to knot_tol only, so a position at a knot may move by about that much.
    good = converged & on_branch(mech, (guess_center, guess_rotation), (center, rotation), h,
                                 1e3 * cfg.knot_tol)
    origin = (cont.travel, cont.rack, cont.center, cont.rotation, cont._jac)
    for i in np.flatnonzero(~good):    # rare: walk it from travel 0
        cont.travel, cont.rack, cont.center, cont.rotation, cont._jac = origin
        sol = cont.solve(travels[i])
        if not sol.success:
            return None
        center[i], rotation[i], iterations[i] = sol.wheel_center, sol.rotation, sol.iterations
    return _sweep_of(cont, travels, center, rotation, iterations, rack)


def _knots(cont, low, high):
    """Poses every knot_step mm from the current state (travel 0) to low and to high (mm):
    the bump and rebound continuation chains, walked side by side as one batch, each step
    from its tangent prediction and checked for a branch change. Knots hold to knot_tol only
    (they start the batched solve). Returns arrays (k,), (k, 3), (k, 3, 3), or None if a
    step fails (the caller then walks, halving steps, and finds any limit)."""
    cfg, mech = cont.settings, cont.mech
    ends = np.array([end for end in (high, low) if end != cont.travel])
    travel = np.full(len(ends), cont.travel)
    center = np.repeat(cont.center[None], len(ends), axis=0)
    rotation = np.repeat(cont.rotation[None], len(ends), axis=0)
    jac = np.repeat(cont._jac[None], len(ends), axis=0)
    trace = [(cont.travel, cont.center, cont.rotation)]
    while len(ends):
        h = np.clip(ends - travel, -cfg.knot_step, cfg.knot_step)
        guess = pose_newton.predict(center, rotation, pose_newton.slope_of(jac), h)
        center, rotation, _, converged = pose_newton.correct_batch(
            mech, travel + h, *guess, cfg.knot_tol, cfg.max_iter, cont.rack)
        if not np.all(converged & on_branch(mech, guess, (center, rotation), h,
                                            1e3 * cfg.knot_tol)):
            return None
        travel = np.where(np.abs(ends - travel) <= cfg.knot_step, ends, travel + h)
        trace += list(zip(travel, center, rotation))
        going = travel != ends
        ends, travel, center, rotation = ends[going], travel[going], center[going], rotation[going]
        jac = linearize(mech, center, rotation, cont.rack)[1]
    return (np.array([t[0] for t in trace]), np.array([t[1] for t in trace]),
            np.array([t[2] for t in trace]))


def travel_range(start, stop, step):
    """Travels from start to stop (mm) inclusive at step, either direction."""
    count = int(math.floor(abs(stop - start) / step + 1e-9))
    values = start + math.copysign(step, stop - start) * np.arange(count + 1)
    return values if values[-1] == stop else np.append(values, stop)
