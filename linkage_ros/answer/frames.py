# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
TF of a solved corner: /tf per answer, /tf_static of the design-fixed frames, as CDR bytes.

    frames = CornerFrames(scene, frame_id='base_link', prefix='')
    frames.tf_cdr(solution, stamp)        tf2_msgs/TFMessage: every moving body's frame
    static_cdr([frames, ...], stamp)      tf2_msgs/TFMessage: every corner's wheel frame
    tf2_msgs_missing()                    why live /tf cannot be published here ('' if it can)

Frames (linkage_ros.core.measure.bodies): per corner the carrier '<prefix>wheel_carrier' (the
wheel_carrier_pose the node answers: its transform from frame_id is that pose, bit for bit),
one frame per link, arm and strut '<prefix><constraint name>', all children of frame_id, and
the wheel '<prefix>wheel', fixed to the carrier, on /tf_static, with a corner's body pickups
'<prefix>pickup/<name>' where statics is on (answer/pickups.py: its pickup wrenches name them).
prefix: '' for a node of one scene, 'front_left/' for a vehicle's corner.

The messages are built by linkage_ros.answer.cdr without tf2_msgs (which has no wheel on the
package index), so that every recording carries /tf; live publishing needs tf2_msgs installed (any
full ROS 2 install, or linkage-tf2-msgs). ROS-free: the node and linkage-replay share it; it
is imported only when TF is on.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

import numpy as np

from .cdr import tf_message_cdr
from ..core.base import M_PER_MM, quaternion_from_matrix
from ..core.measure import body_poses, corner_bodies

if TYPE_CHECKING:
    from ..core.model import Scene
    from ..core.solve import Solution

TF_TYPE = 'tf2_msgs/msg/TFMessage'
TF_TOPIC, TF_STATIC_TOPIC = '/tf', '/tf_static'


class CornerFrames:
    """The TF frames of one corner: their names, and their transforms at a solved pose."""

    def __init__(self, scene: Scene, frame_id: str = 'base_link', prefix: str = '',
                 pickups: dict | None = None) -> None:
        """
        Name the frames of scene's bodies under prefix, children of frame_id.

        pickups: {frame name: point (3,) mm} of the body pickups (statics on:
        answer/pickups.CornerStatics.frame_points), static frames of frame_id's orientation.
        """
        self.frame_id = frame_id
        self.bodies = corner_bodies(scene, prefix, taken=(frame_id,))
        self.names = self.bodies.names
        self._parents = (frame_id,) * len(self.names)
        self.pickups = dict(pickups or {})

    def tf_cdr(self, solution: Solution, stamp: tuple[int, int]) -> bytes:
        """Return the TFMessage of every moving frame at a solved pose, stamped (sec, nanosec)."""
        return tf_message_cdr(stamp, self._parents, self.names,
                              body_poses(self.bodies, solution, M_PER_MM).tolist())

    def static_transforms(self) -> list[tuple[str, str, tuple, tuple]]:
        """
        Return the design-fixed transforms [(parent, child, translation m, quaternion)].

        The wheel on the carrier, and each body pickup (if any) on frame_id at its point,
        unrotated.
        """
        q = quaternion_from_matrix(self.bodies.wheel_rotation)
        return [(self.bodies.carrier, self.bodies.wheel, (0.0, 0.0, 0.0), tuple(q.tolist())),
                *((self.frame_id, name, tuple((np.asarray(point) * M_PER_MM).tolist()),
                   (0.0, 0.0, 0.0, 1.0)) for name, point in self.pickups.items())]


def static_cdr(corners: list[CornerFrames], stamp: tuple[int, int]) -> bytes:
    """
    Return one TFMessage of every corner's design-fixed transforms (for /tf_static).

    One message for all: /tf_static keeps the last message only (transient local, depth 1).
    """
    transforms = [t for corner in corners for t in corner.static_transforms()]
    return tf_message_cdr(stamp, [t[0] for t in transforms], [t[1] for t in transforms],
                          [t[2] for t in transforms], [t[3] for t in transforms])


def tf2_msgs_missing() -> str:
    """Return why tf2_msgs/msg/TFMessage cannot be published here, or '' if it can."""
    try:
        importlib.import_module('tf2_msgs.msg').TFMessage
    except (ImportError, AttributeError):
        return ('tf2_msgs cannot be imported (it has no wheel on the package index): /tf and '
                '/tf_static are recorded but not published; `linkage-tf2-msgs` builds it into '
                'this environment (needs a C/C++ compiler and the Python headers)')
    return ''


def tf_message_class():
    """Return tf2_msgs.msg.TFMessage (call only where tf2_msgs_missing() is '')."""
    return importlib.import_module('tf2_msgs.msg').TFMessage
