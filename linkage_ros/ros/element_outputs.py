"""
A corner's springs, dampers and lengths on suspension_node: lengths and motion ratios per answer.

    pub elements   sensor_msgs/JointState   one message per answered command, only for a scene
                                            with elements (linkage_ros.core.elements):
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

from sensor_msgs.msg import JointState

from ..cdr import joint_state_cdr
from ..core.elements import prepare, values_at
from ..core.geometry import M_PER_MM

if TYPE_CHECKING:
    from rclpy.node import Node
    from rclpy.publisher import Publisher
    from rclpy.qos import QoSProfile

    from ..core.kinematics import Continuation, Solution
    from ..core.scene import Scene

TOPIC = 'elements'


def elements_output(node: Node, prefix: str, qos: QoSProfile, scene: Scene,
                    solver: Continuation, frame_id: str
                    ) -> tuple[Publisher, Callable[[Solution, tuple[int, int]], bytes]]:
    """
    Return (publisher, build) of a corner's elements topic: a Corner extra.

    build(solution, stamp) returns the JointState (CDR bytes) of a solution that solver has
    just solved (its Jacobian is the solver's last); stamp (sec, nanosec).
    """
    model = prepare(scene, solver.mech)
    names = tuple(e.name for e in scene.elements)

    def build(solution: Solution, stamp: tuple[int, int]) -> bytes:
        values = values_at(model, solution.wheel_center, solution.rotation, solution.rack,
                           solver.jacobian)
        return joint_state_cdr(stamp, frame_id, names, (values[0] * M_PER_MM).tolist(),
                               values[1].tolist())

    return node.create_publisher(JointState, prefix + TOPIC, qos), build
