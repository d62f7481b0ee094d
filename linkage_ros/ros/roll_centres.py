# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Each axle's roll centre on suspension_node, for a vehicle file with axles.

    pub <axle>/roll_centre   geometry_msgs/PointStamped   (front/roll_centre, rear/roll_centre)
        header   the answer's stamp, frame_id (the vehicle frame)
        point    the roll centre in m: y and z where the front-view lines through the two
                 contact patches, square to the patches' velocities under their own wheel's
                 travel, meet (linkage_ros.core.axle.axle.roll_centre, doc/axle.md); x midway
                 between the two contact patches

When it is published: once both of the axle's corners have been answered with a pose (each
at least once), after every answer that gives one of them a new pose, from the last pose of
each corner:
    - a Float64 command (wheel_travel, steering_rack of one corner): after its answer;
    - a JointState step (the vehicle's joint_states): once, after every corner the step names
      has been answered, if it gave one of the axle's corners a new pose and neither of them
      failed (no roll centre that mixes a pose of this step with an older one in its place).
A failed command publishes none; nor does an axle whose lines are parallel (the roll centre at
infinity, never NaN). An axle whose corners lack wheel_radius (no contact patch) has no topic,
and the node says so once at start. A vehicle without axles never imports this module. With
parameter roll_centres false there are none (RollCentres.close: the publishers destroyed, the
corners no longer listened to, nothing computed).
"""

from __future__ import annotations

from contextlib import contextmanager
import math
from typing import Callable, Iterator, TYPE_CHECKING

from geometry_msgs.msg import PointStamped
import numpy as np

from .qos import publisher
from ..answer.cdr import point_stamped_cdr
from ..core.axle import roll_centre_of_states
from ..core.base import M_PER_MM

if TYPE_CHECKING:
    from rclpy.node import Node
    from rclpy.qos import QoSProfile

    from .corner import Corner, Outlet
    from ..core.model import VehicleAxles
    from ..core.solve import Solution

TOPIC = 'roll_centre'


def roll_centre_topics(axles: VehicleAxles, scenes: dict) -> list[str]:
    """Return the relative names of the roll-centre topics; scenes: {corner name: Scene}."""
    return [f'{name}/{TOPIC}' for name, spec in axles.axles.items()
            if has_patches(scenes[spec.left], scenes[spec.right])]


def has_patches(*scenes) -> bool:
    """Tell whether every scene has a wheel_radius (a contact patch)."""
    return all(scene.wheel_radius > 0 for scene in scenes)


class AxleRollCentre:
    """One axle's corners, its publisher, and which corners have had a pose yet."""

    def __init__(self, name: str, left: Corner, right: Corner, publisher) -> None:
        self.name, self.corners, self.publisher = name, (left, right), publisher
        self.posed: set[int] = set()     # 0 left, 1 right: answered with a pose
        self.radius = np.array([c.scene.wheel_radius for c in self.corners], dtype=float)
        self.spin_axis = np.array([c.solver.mech.spin_axis for c in self.corners], dtype=float)
        self.out = np.empty(3)     # written into: a new array costs more

    def point_mm(self) -> np.ndarray:
        """
        Return the roll centre (3,) mm of the corners' last kinematic poses (NaN: at infinity).

        One compiled call on the corners' Continuation states (core.axle); the array
        returned is overwritten by the next call.
        """
        left, right = self.corners
        roll_centre_of_states(self.radius, self.spin_axis, left.solver.state,
                              right.solver.state, self.out)
        return self.out


class RollCentres:
    """
    The roll-centre topics of a vehicle's axles: a listener of the axles' Corners.

    node: where the publishers are made; outlet: what publishes (the node: recorded too);
    axles: the vehicle file's; corners: {corner name: Corner}; say: a function that logs a
    line (an axle without contact patches).
    """

    def __init__(self, node: Node, outlet: Outlet, axles: VehicleAxles,
                 corners: dict[str, Corner], qos: QoSProfile, frame_id: str,
                 say: Callable[[str], None]) -> None:
        self.node, self.outlet, self.frame_id = node, outlet, frame_id
        self.axles = []
        self._listening: list[tuple[Corner, Callable]] = []    # (corner, its listener)
        self._step: dict | None = None     # during a JointState step: {axle: [posed, failed]}
        for name, spec in axles.axles.items():
            left, right = corners[spec.left], corners[spec.right]
            if not has_patches(left.scene, right.scene):
                say(f'{name} axle: no roll centre: {spec.left} or {spec.right} has no '
                    'wheel_radius (no contact patch)')
                continue
            axle = AxleRollCentre(name, left, right, publisher(
                node, PointStamped, f'{name}/{TOPIC}', qos))
            self.axles.append(axle)
            for k, corner in enumerate(axle.corners):
                listener = (lambda corner, solution, stamp, axle=axle, k=k:
                            self.answered(axle, k, solution, stamp))
                corner.listeners.append(listener)
                self._listening.append((corner, listener))

    def close(self) -> None:
        """Stop: no corner listened to, every roll-centre publisher destroyed."""
        for corner, listener in self._listening:
            corner.listeners.remove(listener)
        self._listening = []
        for axle in self.axles:
            self.node.destroy_publisher(axle.publisher)
        self.axles = []

    def answered(self, axle: AxleRollCentre, k: int, solution: Solution,
                 stamp: tuple[int, int]) -> None:
        """Take the answer of corner k (0 left, 1 right) of axle: publish now, or at step end."""
        if solution.success:
            axle.posed.add(k)
        if self._step is not None:
            state = self._step.setdefault(axle, [False, False, stamp])
            state[0 if solution.success else 1] = True
        elif solution.success:
            self.publish(axle, stamp)

    @contextmanager
    def step(self) -> Iterator[None]:
        """Hold the roll centres of the answers inside; publish each axle's once at the end."""
        self._step = {}
        try:
            yield
            held = self._step
        finally:
            self._step = None
        for axle, (posed, failed, stamp) in held.items():
            if posed and not failed:
                self.publish(axle, stamp)

    def publish(self, axle: AxleRollCentre, stamp: tuple[int, int]) -> None:
        """Publish axle's roll centre at stamp, once both corners have a pose and it is finite."""
        if len(axle.posed) < 2:
            return
        x, y, z = axle.point_mm().tolist()
        if not (math.isfinite(x) and math.isfinite(y) and math.isfinite(z)):
            return
        self.outlet.publish(axle.publisher, point_stamped_cdr(
            stamp, self.frame_id, (x * M_PER_MM, y * M_PER_MM, z * M_PER_MM)))
