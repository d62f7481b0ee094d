# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The moving bodies of a corner and their frames: the carrier, the wheel, each link, arm, strut.

    bodies = corner_bodies(scene, prefix='')      -> Bodies: names, kinds, design frames
    positions, quaternions = body_poses(bodies, solution)   every body's frame at a pose

A frame is an origin (mm, vehicle frame) and a rotation (columns: the frame's x, y, z axes in
the vehicle frame). The bodies, in this order, one frame each:

    '<prefix>wheel_carrier'  origin the wheel centre M, rotation R (the carrier's rotation
                             relative to design): identity at design, so that this frame is
                             the node's wheel_carrier_pose
    '<prefix><name>'         one per constraint, in the scene's order:
        link (sphere)        origin the body end A (moved along +y by the rack for a steer:
                             rack link), z along the link towards its carrier joint B, turned
                             from design by the smallest rotation that takes the design
                             direction to the present one (a ball-jointed link's spin about
                             its own line is free: it is taken as none)
        arm (circle)         origin the first axis point, z along the axis (towards the
                             second), x towards the ball joint square to the axis: the arm's
                             rotation about its fixed axis
        strut (line)         origin the top mount T, z along the strut towards the carrier
                             point at design, turning with the carrier (a MacPherson strut's
                             tube is fixed to the knuckle and slides through the top mount)
    '<prefix>wheel'          fixed to the carrier (design_static): origin M, z along the spin
                             axis outboard

prefix is '' for a node of one scene and 'front_left/' for a vehicle's corners. A name
already taken (wheel_carrier, wheel, a repeated constraint name, the parent frame) gets
'_<constraint index>' appended. Pure numpy, no ROS: the node's /tf and the URDF share it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..base.geometry import perpendicular, unit
from ..solve import body_kernel

if TYPE_CHECKING:
    from ..model.scene import Scene
    from ..solve.kinematics import Solution

CARRIER, WHEEL = 'wheel_carrier', 'wheel'
KINDS = {'sphere': 'link', 'circle': 'arm', 'line': 'strut'}
CODES = {'carrier': body_kernel.CARRIER, 'link': body_kernel.LINK, 'arm': body_kernel.ARM,
         'strut': body_kernel.STRUT}


@dataclass(frozen=True)
class Bodies:
    """
    The bodies of one corner (scene) and their frames at design, mm, vehicle frame.

    names (1 + m,): the carrier then one per constraint; kinds: 'carrier', 'link', 'arm',
    'strut'; origins (1 + m, 3) and rotations (1 + m, 3, 3) at design; wheel: the name of the
    wheel's frame, fixed to the carrier with rotation wheel_rotation (3, 3) (in the carrier
    frame) at the wheel centre. table: the same for the compiled kernel (body_kernel).
    """

    scene: Scene
    names: tuple[str, ...]
    kinds: tuple[str, ...]
    origins: np.ndarray
    rotations: np.ndarray
    wheel: str
    wheel_rotation: np.ndarray
    table: np.ndarray
    offsets: np.ndarray      # (m, 3) the carrier joints minus the design wheel centre

    @property
    def carrier(self) -> str:
        """Return the name of the carrier's frame."""
        return self.names[0]


def corner_bodies(scene: Scene, prefix: str = '', taken: tuple[str, ...] = ()) -> Bodies:
    """
    Return the bodies of a scene with their design frames (module docstring).

    prefix: put before every frame name ('' or 'front_left/'); taken: names that are not
    free (the parent frame, say), which a constraint's frame must not take.
    """
    used = set(taken)
    names = [_free(prefix + CARRIER, used, 0)]
    wheel = _free(prefix + WHEEL, used, 0)
    kinds, origins, rotations = ['carrier'], [scene.wheel_center], [np.eye(3)]
    for index, c in enumerate(scene.constraints):
        kind = KINDS[c.type]
        names.append(_free(prefix + c.name, used, index))
        kinds.append(kind)
        origins.append(c.base[0])
        if kind == 'arm':      # z along the fixed axis, x towards the joint
            rotations.append(frame_along(c.base[1] - c.base[0], c.carrier - c.base[0]))
        else:                  # z along the link or strut, towards the carrier joint
            rotations.append(frame_along(c.carrier - c.base[0]))
    table = np.zeros((len(names), body_kernel.COLUMNS))
    table[:, body_kernel.KIND] = [CODES[kind] for kind in kinds]
    table[1:, body_kernel.JOINT] = np.arange(len(scene.constraints))
    table[1:, body_kernel.STEER] = [c.steer == 'rack' for c in scene.constraints]
    table[:, body_kernel.ORIGIN:body_kernel.ORIGIN + 3] = origins
    table[:, body_kernel.AXES:body_kernel.AXES + 9] = np.reshape(rotations, (-1, 9))
    spin = unit(scene.wheel_center - scene.spin_axis_point)     # outboard
    return Bodies(scene, tuple(names), tuple(kinds), np.array(origins), np.array(rotations),
                  wheel, frame_along(spin, [1.0, 0.0, 0.0]), table, scene.carrier_offsets)


def _free(name: str, used: set, index: int) -> str:
    """Return name, or name_<index> (then _<index>_2, ...) if it is taken; mark it taken."""
    candidate, n = name, 1
    while candidate in used:
        candidate = f'{name}_{index}' if n == 1 else f'{name}_{index}_{n}'
        n += 1
    used.add(candidate)
    return candidate


def frame_along(z: np.ndarray, toward: np.ndarray | None = None) -> np.ndarray:
    """
    Return a right-handed frame (columns x, y, z) whose z is along z.

    x points towards toward (its part square to z), or is geometry.perpendicular(z).
    """
    z = unit(z)
    if toward is None:
        x = perpendicular(z)
    else:
        x = np.asarray(toward, dtype=float)
        x = unit(x - (x @ z) * z)
    return np.column_stack((x, np.cross(z, x), z))


def body_poses(bodies: Bodies, solution: Solution, scale: float = 1.0) -> np.ndarray:
    """
    Return every body's frame at a solved pose: (1 + m, 7), each row origin then quaternion.

    Origins in mm times scale (M_PER_MM: in m), quaternions (x, y, z, w) of the frames'
    rotations in the vehicle frame, in the order of bodies.names. The carrier's row is the
    solution's wheel centre and its own quaternion, so that the carrier frame is the
    PoseStamped the node answers. Compiled (body_kernel.frames): a few us for a corner.
    """
    out = np.empty((len(bodies.names), 7))
    body_kernel.frames(bodies.table, bodies.offsets, solution.wheel_center, solution.rotation,
                       solution.quaternion, float(solution.rack), scale, out)
    return out
