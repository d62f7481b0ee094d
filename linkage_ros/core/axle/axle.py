# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
An axle: two corners moved together in heave, roll and steer, and what they give together.

    solve_axle(axle, heave_mm, roll_rad, rack_mm) -> AxleResult    arrays over n positions

Motions (doc/axle.md): in heave both wheels travel by the heave; in roll by phi (ISO 8855:
+ = right side down) the right wheel goes to bump +s and the left to rebound -s, with
s = (t / 2) tan(phi) and t the design track at the contact patches; the rack (mm, + = to the
left) moves every steer: rack link of both corners. Each corner is solved by continuation
(kinematics.sweep), each run of positions at one rack in one sweep per corner.

Quantities at every position, from the exact velocities of the implicit function theorem
(pose_newton.slope_of, compiled for a batch: jacobian_kernel.slope_many), no finite differences:
  roll centre     the front-view intersection of the two lines through the contact patches
                  square to the patches' velocities under their own wheel's travel (the
                  patch taken as a point of the carrier; roll_centre.py, which the node and
                  the maps use too); its vehicle-frame y and its height above the ground (the
                  line through the two contact patches)
  camber, toe     of each wheel relative to the body and to the ground (body rolled by phi)
  track           between the contact patches
  anti-dive, -lift, -squat (%): 100 sign (v_x / v_z) (L / h) share (Milliken and Milliken,
                  Race Car Vehicle Dynamics, ch. 17), v the velocity under travel of the
                  contact patch (outboard brakes) or the wheel centre (inboard brakes,
                  drive), sign + front, - rear; the mean of the two wheels
  Ackermann (%)   100 (d_i - d_o) / (d_i - d_o*), d_o* = atan(L / (L / tan(d_i) + t)); NaN
                  below ACKERMANN_MIN_STEER (1 deg) of mean steer
  anti-roll bar   its twist, ratios and roll stiffness, for an axle that has one
                  (anti_roll_bar.py, imported only then)
Units: mm, rad, vehicle frame (x forward, y left, z up). Arrays (n,) or (n, 2) with column 0
the left wheel and 1 the right.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
import math
from typing import Any, TYPE_CHECKING

import numpy as np

from .roll_centre import height_above_ground, patch_motion, roll_centre
from ..base.geometry import camber_toe
from ..base.status import Status
from ..measure.alignment import contact_patch
from ..model.yaml_file import SceneError
from ..solve import jacobian_kernel
from ..solve.kinematics import sweep
from ..solve.mechanism import compile_scene, linearize

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from ..model.scene import Scene
    from ..model.vehicle import Vehicle
    from ..solve.mechanism import Mechanism

SIDES = ('left', 'right')
# Mean steer (rad) below which Ackermann is NaN. Its denominator, the ideal difference
# delta_i - delta_o*, is about (t / L) delta_i^2: 0.009 deg at 1 deg, where bump and roll steer
# (toe from wheel travel alone, up to a 0.7 deg mean on the demo front axle within its travel
# limits) would pass for steering and give thousands of percent (-15347 % at 4 deg of roll).
ACKERMANN_MIN_STEER = math.radians(1.0)
# Relative slack of the travel limits: a few hundred ulps, far below any travel that matters.
TRAVEL_LIMIT_ROUNDING = 1e-12


@dataclass(frozen=True)
class Axle:
    """Two corners of a vehicle (mm, vehicle frame) and what its anti quantities need."""

    left: Scene
    right: Scene
    name: str = 'axle'
    front: bool = True            # anti-dive and anti-lift signs: front + , rear -
    wheelbase: float = math.nan   # mm
    cg_height: float = math.nan   # mm above the ground
    brake_share: float = 0.0      # of the vehicle's braking force
    drive_share: float = 0.0      # of the vehicle's driving force
    brakes: str = 'outboard'      # outboard | inboard
    anti_roll_bar: Any = None     # anti_roll_bar.AntiRollBar, or None

    @property
    def scenes(self) -> tuple[Scene, Scene]:
        """Return the left and the right corner."""
        return self.left, self.right

    @property
    def has_patches(self) -> bool:
        """Whether both corners give a wheel_radius, so that contact patches are known."""
        return self.left.wheel_radius > 0 and self.right.wheel_radius > 0

    @property
    def steered(self) -> bool:
        """Whether a corner has a steer: rack link."""
        return any(s.steered for s in self.scenes)

    def design_patches(self) -> np.ndarray:
        """Return the contact patches at design (2, 3) mm; wheel centres without a radius."""
        return np.array([
            contact_patch(s.wheel_center[None], unit_axis(s)[None], s.wheel_radius)[0]
            if s.wheel_radius > 0 else s.wheel_center for s in self.scenes])

    @cached_property
    def mechanisms(self) -> tuple[Mechanism, Mechanism]:
        """Return the left and the right corner compiled (once per Axle)."""
        return compile_scene(self.left), compile_scene(self.right)

    @cached_property
    def design_track(self) -> float:
        """Track at the design contact patches (mm); between the wheel centres without one."""
        patches = self.design_patches()
        return float(patches[0, 1] - patches[1, 1])

    def anti_quantities(self) -> list[tuple[str, str, float]]:
        """Return (name, point, share) of the axle's anti quantities; point: patch or centre."""
        brake = 'anti_dive' if self.front else 'anti_lift'
        drive = 'anti_lift' if self.front else 'anti_squat'
        found = []
        if self.brake_share:
            found.append((brake, 'patch' if self.brakes == 'outboard' else 'centre',
                          self.brake_share))
        if self.drive_share:
            found.append((drive, 'centre', self.drive_share))
        return found


def unit_axis(scene: Scene) -> np.ndarray:
    """Return the design spin axis (3,), outboard."""
    axis = scene.wheel_center - scene.spin_axis_point
    return axis / np.linalg.norm(axis)


def wheel_travels(axle: Axle, heave: ArrayLike,
                  roll: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Return the (left, right) wheel travels (mm) of heaves (mm) and roll angles (rad)."""
    s = 0.5 * axle.design_track * np.tan(roll)
    return np.asarray(heave - s, dtype=float), np.asarray(heave + s, dtype=float)


@dataclass(frozen=True)
class AxleResult:
    """Solved axle positions (mm, rad), in the order asked for; NaN where undefined."""

    heave: np.ndarray            # (n,) mm
    roll: np.ndarray             # (n,) rad, + = right side down
    rack: np.ndarray             # (n,) mm, + = rack to the left
    travel: np.ndarray           # (n, 2) wheel travels, mm, + = bump
    wheel_center: np.ndarray     # (n, 2, 3) mm
    rotation: np.ndarray         # (n, 2, 3, 3) carrier orientation relative to design
    camber: np.ndarray           # (n, 2) rad relative to the body, + = top outboard
    toe: np.ndarray              # (n, 2) rad relative to the body, + = toe-in
    camber_ground: np.ndarray    # (n, 2) rad relative to the ground
    toe_ground: np.ndarray       # (n, 2) rad relative to the ground
    contact_patch: np.ndarray    # (n, 2, 3) mm
    patch_velocity: np.ndarray   # (n, 2, 3) the patch's velocity per mm of its wheel's travel
    center_velocity: np.ndarray  # (n, 2, 3) the wheel centre's, per mm of travel
    roll_centre: np.ndarray      # (n, 2) (y, z) mm, vehicle frame
    roll_centre_height: np.ndarray   # (n,) mm above the ground (the line through the patches)
    track: np.ndarray            # (n,) mm between the contact patches
    anti: dict[str, np.ndarray]  # anti_dive / anti_lift / anti_squat, (n,) percent
    steer: np.ndarray            # (n, 2) yaw of each wheel relative to the body, + = left
    mean_steer: np.ndarray       # (n,) rad
    ackermann: np.ndarray        # (n,) percent; NaN below ACKERMANN_MIN_STEER of mean steer
    success: bool = True
    status: Status = Status.OK
    message: str = 'ok'
    notes: tuple[str, ...] = field(default=())   # what could not be computed, and why
    bar: Any = None              # anti_roll_bar.BarValues of an axle with a bar, else None


def solve_axle(axle: Axle, heave: ArrayLike, roll: ArrayLike = 0.0, rack: ArrayLike = 0.0,
               method: str = 'fast', **settings: Any) -> AxleResult:
    """
    Solve an axle at n positions (heave mm, roll rad, rack mm, broadcast together).

    Runs of positions at one rack are swept together, in order; a position out of reach of
    either wheel, or beyond either corner's travel limits (its scene's travel block), ends the
    result there (success False, status OUT_OF_REACH, the limit in message), in heave, roll
    and steer alike.
    """
    heave, roll, rack = (np.ravel(a).astype(float)
                         for a in np.broadcast_arrays(heave, roll, rack))
    travels = np.stack(wheel_travels(axle, heave, roll), axis=1)
    inside, beyond = within_travel_limits(axle, travels)
    centers, rotations, done = [], [], 0
    status, message = Status.OK, 'ok'
    for start, stop in _runs(rack[:inside]):
        solved = [sweep(scene, travels[start:stop, k], method=method, rack=rack[start],
                        **settings) for k, scene in enumerate(axle.scenes)]
        count = min(len(s.travel) for s in solved)
        centers.append(np.stack([s.wheel_center[:count] for s in solved], axis=1))
        rotations.append(np.stack([s.rotation[:count] for s in solved], axis=1))
        done = start + count
        failed = [k for k, s in enumerate(solved) if not s.success]
        if failed:
            k, i = failed[0], done
            status, message = solved[k].status, (
                f'heave {heave[i]:g} mm, roll {math.degrees(roll[i]):g} deg, rack '
                f'{rack[i]:g} mm: the {SIDES[k]} wheel ({axle.scenes[k].name}): '
                f'{solved[k].message}')
            break
    else:
        if beyond:
            status, message = Status.OUT_OF_REACH, (
                f'heave {heave[done]:g} mm, roll {math.degrees(roll[done]):g} deg, rack '
                f'{rack[done]:g} mm: {beyond}')
    center = np.concatenate(centers) if centers else np.empty((0, 2, 3))
    rotation = np.concatenate(rotations) if rotations else np.empty((0, 2, 3, 3))
    values = axle_quantities(axle, heave[:done], roll[:done], rack[:done], center, rotation)
    return AxleResult(heave=heave[:done], roll=roll[:done], rack=rack[:done],
                      travel=travels[:done], wheel_center=center, rotation=rotation,
                      success=status == Status.OK, status=status, message=message,
                      **values)


def within_travel_limits(axle: Axle, travels: np.ndarray) -> tuple[int, str]:
    """
    Return how many positions come before the first beyond a corner's travel limits, and why.

    travels (n, 2) mm, left and right wheel. Each corner's limits are its scene's travel
    block (min, max), the range linkage-sweep sweeps by default: past them a table would give
    a wheel where its suspension does not go. A travel within TRAVEL_LIMIT_ROUNDING of a limit
    counts as at it: heave +- (t / 2) tan(roll) lands a few ulps beyond a limit asked for
    exactly. The reason is '' when every position is within.
    """
    first, reason = len(travels), ''
    for k, scene in enumerate(axle.scenes):
        low, high = scene.travel[:2]
        slack = TRAVEL_LIMIT_ROUNDING * max(1.0, abs(low), abs(high))
        out = np.flatnonzero((travels[:, k] < low - slack) | (travels[:, k] > high + slack))
        if len(out) and out[0] < first:
            first = int(out[0])
            reason = (f'the {SIDES[k]} wheel ({scene.name}) would travel '
                      f'{travels[first, k]:g} mm, beyond its travel limits {low:g} to '
                      f"{high:g} mm (the scene's travel block)")
    return first, reason


def _runs(rack):
    """Yield (start, stop) of the runs of equal rack values, in order."""
    edges = np.flatnonzero(np.diff(rack)) + 1
    bounds = np.concatenate(([0], edges, [len(rack)])) if len(rack) else np.array([0, 0])
    for start, stop in zip(bounds[:-1], bounds[1:]):
        if stop > start:
            yield int(start), int(stop)


def axle_quantities(axle: Axle, heave: np.ndarray, roll: np.ndarray, rack: np.ndarray,
                    center: np.ndarray, rotation: np.ndarray) -> dict[str, Any]:
    """
    Return the axle quantities of solved positions, as AxleResult's fields.

    center (n, 2, 3), rotation (n, 2, 3, 3): both wheels' poses (left, right); heave (mm),
    roll (rad), rack (mm) (n,).
    """
    n = len(heave)
    shape2, shape3 = (n, 2), (n, 2, 3)
    camber, toe = np.empty(shape2), np.empty(shape2)
    camber_ground, toe_ground = np.empty(shape2), np.empty(shape2)
    patch, v_patch = np.full(shape3, np.nan), np.full(shape3, np.nan)
    v_center, omega = np.empty(shape3), np.empty(shape3)
    rolled = np.any(roll != 0.0)
    jacobians = []
    for k, (scene, mech) in enumerate(zip(axle.scenes, axle.mechanisms)):
        wheel_center = np.ascontiguousarray(center[:, k])   # copied once, not per use
        wheel_rotation = np.ascontiguousarray(rotation[:, k])
        jacobians.append(linearize(mech, wheel_center, wheel_rotation, rack)[1])
        v_center[:, k], omega[:, k] = slopes(jacobians[-1])
        axis = wheel_rotation @ mech.spin_axis
        camber[:, k], toe[:, k] = camber_toe(axis, scene.side_sign)
        if rolled:
            camber_ground[:, k], toe_ground[:, k] = camber_toe(roll_about_x(axis, roll),
                                                               scene.side_sign)
        else:
            camber_ground[:, k], toe_ground[:, k] = camber[:, k], toe[:, k]
        if scene.wheel_radius > 0:
            patch[:, k], v_patch[:, k] = patch_motion(wheel_center, axis, scene.wheel_radius,
                                                      v_center[:, k], omega[:, k])
    track = patch[:, 0, 1] - patch[:, 1, 1]
    centre = roll_centre(patch, v_patch)
    steer = -np.array([s.side_sign for s in axle.scenes]) * toe   # yaw, + = to the left
    bar, notes = None, missing_radius_notes(axle)
    if axle.anti_roll_bar is not None:
        from .anti_roll_bar import bar_notes, bar_values
        bar = bar_values(axle.scenes, axle.mechanisms, axle.design_track, axle.anti_roll_bar,
                         roll, rack, center, rotation, tuple(jacobians))
        notes += bar_notes(axle.name, bar)
    return {
        'camber': camber, 'toe': toe, 'camber_ground': camber_ground, 'toe_ground': toe_ground,
        'contact_patch': patch, 'patch_velocity': v_patch, 'center_velocity': v_center,
        'roll_centre': centre, 'roll_centre_height': height_above_ground(centre, patch),
        'track': track,
        'anti': {name: anti_percent(v_patch if point == 'patch' else v_center, axle.front,
                                    axle.wheelbase, axle.cg_height, share)
                 for name, point, share in axle.anti_quantities()},
        'steer': steer, 'mean_steer': steer.mean(axis=1),
        'ackermann': ackermann(steer, axle.wheelbase, track),
        'notes': notes, 'bar': bar}


def slopes(jac: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """
    Return d(center)/d(travel) and d(omega)/d(travel), (n, 3) each, at n solutions.

    pose_newton.slope_of's answer from its compiled batch (jacobian_kernel.slope_many): numpy's
    batched solve costs about a microsecond per 5 x 5 system, as much as a solve of the pose.
    """
    free = np.empty((len(jac), 5))
    jacobian_kernel.slope_many(np.ascontiguousarray(jac), free)
    return np.column_stack((free[:, :2], np.ones(len(jac)))), free[:, 2:]


def roll_about_x(vector: np.ndarray, roll: np.ndarray) -> np.ndarray:
    """Return vectors (n, 3) turned about x by roll (n,) rad: body to ground, + = right down."""
    c, s = np.cos(roll), np.sin(roll)
    return np.column_stack((vector[:, 0], c * vector[:, 1] - s * vector[:, 2],
                            s * vector[:, 1] + c * vector[:, 2]))


def anti_percent(velocity: np.ndarray, front: bool, wheelbase: float, cg_height: float,
                 share: float) -> np.ndarray:
    """
    Return an axle's anti-dive, -lift or -squat (%) from its wheels' velocities (n, 2, 3).

    100 sign (v_x / v_z) (L / h) share for each wheel (sign + for the front axle, - for the
    rear), then the mean of the two: Milliken ch. 17 with tan(theta) = +-v_x / v_z, theta the
    side-view angle of the point's path normal (the line to the side-view instant centre).
    """
    sign = 1.0 if front else -1.0
    ratio = velocity[..., 0] / velocity[..., 2]
    return 100.0 * sign * ratio.mean(axis=1) * (wheelbase / cg_height) * share


def ackermann(steer: np.ndarray, wheelbase: float, track: np.ndarray) -> np.ndarray:
    """
    Return the Ackermann percentage of wheel yaws (n, 2) rad (left, right; + = to the left).

    The inner wheel is on the side the axle turns to (the sign of the mean yaw); with d_i
    and d_o the inner and outer steer angles, the ideal outer angle is d_o* = atan(L / (L /
    tan(d_i) + t)), t the track (mm), and the result 100 (d_i - d_o) / (d_i - d_o*): 100 =
    Ackermann, 0 = parallel, < 0 = anti-Ackermann. NaN where the mean yaw is below
    ACKERMANN_MIN_STEER (straight ahead included).
    """
    mean = steer.mean(axis=1)
    turn = np.where(np.abs(mean) >= ACKERMANN_MIN_STEER, np.sign(mean), 0.0)
    left_turn = turn > 0
    inner = np.where(left_turn, steer[:, 0], -steer[:, 1])
    outer = np.where(left_turn, steer[:, 1], -steer[:, 0])
    with np.errstate(divide='ignore', invalid='ignore'):
        ideal = np.arctan(wheelbase / (wheelbase / np.tan(inner) + track))
        return np.where(turn != 0, 100.0 * (inner - outer) / (inner - ideal), np.nan)


def missing_radius_notes(axle: Axle) -> tuple[str, ...]:
    """Say, once per corner, which quantities a corner without wheel_radius leaves out."""
    return tuple(f'{s.name} ({s.source}) has no wheel_radius: no contact patch, so no roll '
                 'centre, track, contact-patch anti-dive or Ackermann'
                 for s in axle.scenes if not s.wheel_radius > 0)


def axle_of(vehicle: Vehicle, name: str) -> Axle:
    """Return the named axle of a vehicle as an Axle, or raise SceneError naming the file."""
    data = vehicle.axles
    if data is None or name not in data.axles:
        known = ', '.join(data.axles) if data is not None and data.axles else 'none'
        raise SceneError(vehicle.source, 'axles', f'no axle {name!r} (axles: {known})')
    spec = data.axles[name]
    return Axle(left=vehicle.corners[spec.left], right=vehicle.corners[spec.right],
                name=name, front=name == 'front', wheelbase=data.wheelbase,
                cg_height=data.cg_height, brake_share=spec.brake_share,
                drive_share=spec.drive_share, brakes=spec.brakes,
                anti_roll_bar=spec.anti_roll_bar)
