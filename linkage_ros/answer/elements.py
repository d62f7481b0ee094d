# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A corner's springs, dampers and lengths on suspension_node: lengths and motion ratios per answer.

    pub elements   sensor_msgs/JointState   one message per answered command, only for a scene
                                            with elements (linkage_ros.core.measure.elements):
        header     the answer's stamp, frame_id
        name       the scene's element names, in the scene's order
        position   each element's length, m
        velocity   each element's motion ratio d length / d wheel travel: dimensionless (m per
                   m of travel, + = the element lengthens in bump; a damper that shortens in
                   bump reads negative), not a speed
        effort     empty

The values come from the compiled kernel of one answer (elements.values_at) with the Jacobian
the solve already has (Continuation.jacobian), and the message is packed as CDR bytes
(cdr.joint_state_cdr, its layout cached per names): a few microseconds per answer.
"""

from __future__ import annotations

from typing import Callable, TYPE_CHECKING

from .cdr import joint_state_cdr
from ..core.base import M_PER_MM
from ..core.measure import prepare, values_at

if TYPE_CHECKING:
    import numpy as np

    from ..core.model import Scene
    from ..core.solve import Mechanism, Solution

TOPIC = 'elements'


def elements_builder(scene: Scene, mech: Mechanism, frame_id: str,
                     jacobian: Callable[[], np.ndarray]
                     ) -> Callable[[Solution, tuple[int, int]], bytes]:
    """
    Return build(solution, stamp): the JointState (CDR bytes) of a corner's elements topic.

    solution is what the corner's solver has just solved, and jacobian() that solver's last
    Jacobian (Continuation.jacobian, (5, 6)); stamp (sec, nanosec). A Corner extra: the corner
    owns the publisher (its QoS overrides) and asks for a new build when its scene changes.
    """
    model = prepare(scene, mech)
    names = tuple(e.name for e in scene.elements)

    def build(solution: Solution, stamp: tuple[int, int]) -> bytes:
        values = values_at(model, solution.wheel_center, solution.rotation, solution.rack,
                           jacobian())
        return joint_state_cdr(stamp, frame_id, names, (values[0] * M_PER_MM).tolist(),
                               values[1].tolist())

    return build
