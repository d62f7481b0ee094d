# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Statics of a corner for suspension_node: the loaded pose, and each pickup's force.

The loaded pose at the last contact wrench, each body pickup's force as a
geometry_msgs/WrenchStamped:

    statics = CornerStatics(scene, frame_id='base_link', prefix='', continuation=None)
    statics.set_wrench(force_n, moment_nm)   the tyre's wrench at the contact patch (vehicle
                                             frame, N and N m); zero until one is set
    statics.use_frames(on)                   pickups in their own TF frames (on) or frame_id
    loaded, outputs = statics.load(solution, stamp)
        loaded: the kinematic Solution with the loaded pose put in its place (wheel centre,
        rotation, quaternion, camber, toe), or a failed Solution (Status.NOT_CARRIED) with no
        pose; outputs: [('pickup/<name>', WRENCH_TYPE, CDR bytes)], one per body pickup
    statics.reset()                          forget the last equilibrium (after a failure)
    pickup_points(scene) -> {name: point (3,) mm}   the body pickups, design, vehicle frame
    pickup_frame(prefix, name)                      the TF frame of a pickup

The loaded pose is that of the corner's core.statics.Statics, made once per scene (a new
scene makes a new CornerStatics) with the corner's kinematic Continuation (continuation: the
one that solved each command's travel, whose pose the long way starts from), at the travel
and rack that continuation solved, for a load at the contact patch (at='cp'): one compiled
call per command, from the last loaded equilibrium. The node's answers are those of a
Statics given the same commands, bit for bit, and those of a fresh solve_loaded to the
statics' round-off (1e-9 deg, 1e-8 mm, 1e-9 of the forces). A pickup's wrench is the
force on the body at that pickup (N, vehicle frame orientation), its torque the bushing's
couple there (N m, Loaded.body_moments_nm; zero at a ball joint, a rigid pivot or a spring
end). Its header names the pickup's frame (static TF at the design pickup point, orientation of the
vehicle frame; answer/frames.py publishes it on /tf_static), so that RViz's and Foxglove's wrench
displays draw the arrow at the pickup; where those frames are not published (tf off, or
tf2_msgs missing) it names the vehicle frame, and the pickup point is that of
pickup_points (doc/node.md).

ROS-free (cdr only). The statics core is imported by CornerStatics and pickup_points, only
where statics is on: a scene without bushings and without parameter statics loads none of
it.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .cdr import wrench_stamped_cdr
from ..core.base import LinkageError, quaternion_from_matrix, Status

if TYPE_CHECKING:
    from ..core.model import Scene
    from ..core.solve import Continuation, Solution

WRENCH_TYPE = 'geometry_msgs/msg/WrenchStamped'
PICKUP = 'pickup'          # the topics' folder: <corner>/pickup/<name>
ZERO = (0.0, 0.0, 0.0)


def pickup_points(scene: Scene, rack_mm: float = 0.0) -> dict[str, np.ndarray]:
    """
    Return {pickup name: body point (3,) mm, vehicle frame} of the body pickups.

    The statics core's names and points (Loaded.body_forces_n, body_points_mm: a link's
    '<link>_base', an arm's '<arm>_axis0' and '<arm>_axis1' or '<arm>_centre', a strut's
    '<strut>_top', a spring's '<spring>_body') at travel 0 and rack_mm (mm), with no load.
    The points are fixed to the body but for a rack link's base, which the rack moves.
    """
    from ..core.statics import Load, solve_loaded
    loaded = solve_loaded(scene, travel_mm=0.0, rack_mm=rack_mm,
                          load=Load(force_n=ZERO, at='wc', moment_nm=ZERO))
    if loaded.status != Status.OK:
        raise LinkageError(f'scene {scene.name} ({scene.source})',
                           f'no statics at design: {loaded.message}')
    return {name: np.array(point, dtype=float)
            for name, point in loaded.body_points_mm.items()}


def pickup_frame(prefix: str, name: str) -> str:
    """Return the TF frame of a pickup: '<prefix>pickup/<name>' ('front_left/pickup/...')."""
    return f'{prefix}{PICKUP}/{name}'


class CornerStatics:
    """The contact wrench of one corner and its loaded answers (module docstring)."""

    def __init__(self, scene: Scene, frame_id: str = 'base_link', prefix: str = '',
                 continuation: Continuation | None = None) -> None:
        from ..core.statics import Load, Statics
        self._make_load = Load
        self.statics = Statics(scene, continuation)
        self.scene, self.frame_id, self.prefix = scene, frame_id, prefix
        self.points = pickup_points(scene)
        self.names = list(self.points)
        self.force, self.moment = ZERO, ZERO
        self._load = Load(force_n=ZERO, at='cp', moment_nm=ZERO)
        self.frames = [frame_id] * len(self.names)

    def set_wrench(self, force_n: tuple, moment_nm: tuple) -> None:
        """Take the tyre's wrench at the contact patch: force N, moment N m, vehicle frame."""
        self.force, self.moment = tuple(force_n), tuple(moment_nm)
        self._load = self._make_load(force_n=self.force, at='cp', moment_nm=self.moment)

    def take(self, old: CornerStatics | None) -> None:
        """Go on with the wrench of old (the corner's statics before a change), if any."""
        if old is not None:
            self.set_wrench(old.force, old.moment)

    def frame_points(self) -> dict[str, np.ndarray]:
        """Return {TF frame: point (3,) mm} of the pickups (ros/tf.CornerFrames' pickups)."""
        return {pickup_frame(self.prefix, name): point for name, point in self.points.items()}

    def use_frames(self, on: bool) -> None:
        """Name each pickup's own TF frame (on) or the vehicle frame in the pickup wrenches."""
        self.frames = [pickup_frame(self.prefix, n) if on else self.frame_id
                       for n in self.names]

    def reset(self) -> None:
        """Forget the last equilibrium: the next command starts from the kinematic pose."""
        self.statics.reset()

    def load(self, solution: Solution, stamp: tuple[int, int],
             pickups: bool = True) -> tuple[Solution, list]:
        """
        Return (the loaded answer, its pickup outputs) of a solved kinematic command.

        pickups: False leaves the pickup outputs out ([]): their forces are then neither
        read from the solve's answer nor built into messages (the node's parameter pickups).

        solution: the corner's continuation's (the one given at construction) answer to the
        command: the equilibrium continues from the last one, or where there is none near
        enough from that continuation's pose (the same assembly branch, no walk from design).

        The loaded pose replaces the kinematic one in solution (travel, rack, the solver's
        counts kept); a load the linkage cannot carry gives a failed Solution
        (Status.NOT_CARRIED, the core's message naming the load and its last residual) and
        no outputs.
        """
        loaded = self.statics.solve(solution.travel, self._load, solution.rack)
        if loaded.status != Status.OK:
            failed = solution._replace(
                success=False, message=loaded.message, wheel_center=None, rotation=None,
                camber=math.nan, toe=math.nan, quaternion=None, status=loaded.status)
            return failed, []
        rotation = np.asarray(loaded.rotation)
        answer = solution._replace(
            wheel_center=np.asarray(loaded.wheel_center_mm), rotation=rotation,
            quaternion=quaternion_from_matrix(rotation),
            camber=math.radians(loaded.camber_deg), toe=math.radians(loaded.toe_deg))
        if not pickups:
            return answer, []
        forces, moments = loaded.body_forces_n, loaded.body_moments_nm
        outputs = [(f'{PICKUP}/{name}', WRENCH_TYPE, wrench_stamped_cdr(
                    stamp, frame, forces[name].tolist(),
                    moments[name].tolist() if name in moments else ZERO))
                   for name, frame in zip(self.names, self.frames)]
        return answer, outputs
