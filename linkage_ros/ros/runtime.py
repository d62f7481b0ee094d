"""
suspension_node's parameters while it runs: a SetParameters request checked, then applied.

    RuntimeParameters(node, params)   registers the node's on-set and post-set callbacks

A request (rcl_interfaces SetParameters; `ros2 param set` in a full install) is taken whole
or not at all. Refused, with the reason and the old values kept: a value out of its range or
of the wrong type (ros/parameters.checked, the wording of the node's start), a method that
does not exist, a scene that does not load (the loader's line), a change of a FIXED parameter
(vehicle, record_mcap, rerun_rrd, frame_id, ...: why it is fixed), scene on a vehicle node.

Applied, once rclpy has stored the values (the post-set callback):
    method, max_step_mm, condition_warn   every corner's solver, at the pose it holds
    diagnostic_period                     the report timer, from now on
    alignment, markers                    the outputs, made or removed
    tf                                    /tf, /tf_static, robot_description on or off
    scene                                 the corner serves the new scene from its design
                                          position, its topics kept; /diagnostics says so at
                                          once, and /tf_static and robot_description are sent
                                          again
Every applied change is recorded as the rcl_interfaces/msg/ParameterEvent the node publishes
on /parameter_events (the recordings go on across it).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from rcl_interfaces.msg import ParameterEvent, SetParametersResult

from .parameters import checked, FIXED, PARAMETERS
from ..cdr import to_cdr
from ..core.base import LinkageError

if TYPE_CHECKING:
    from rclpy.node import Node
    from rclpy.parameter import Parameter

PARAMETER_EVENT = 'rcl_interfaces/msg/ParameterEvent'
SOLVER = ('method', 'max_step_mm', 'condition_warn')


class RuntimeParameters:
    """The node's parameters as they are now, and how a change of them is taken."""

    def __init__(self, node: Node, params: dict) -> None:
        self.node, self.values = node, dict(params)
        self._pending = {}     # checked values of the request being set, and a loaded scene
        node.add_on_set_parameters_callback(self.check)
        node.add_post_set_parameters_callback(self.apply)

    def check(self, parameters: list[Parameter]) -> SetParametersResult:
        """Check a request whole: SetParametersResult refused with the reason, or accepted."""
        try:
            self._pending = self._checked(parameters)
        except LinkageError as exc:
            self._pending = {}
            return SetParametersResult(successful=False, reason=str(exc))
        return SetParametersResult(successful=True)

    def _checked(self, parameters):
        pending = {}
        for parameter in parameters:
            name, value = parameter.name, parameter.value
            if name.startswith('qos_overrides.'):
                continue            # declared by rclpy for a topic made now (read-only after)
            if name in FIXED:
                raise LinkageError(name, f'cannot change while the node runs: {FIXED[name]}; '
                                   'restart the node with the new value')
            if name not in PARAMETERS:
                continue            # rclpy's own (start_type_description_service: read-only)
            pending[name] = checked(name, value)
        if 'scene' in pending:
            if self.values['vehicle']:
                raise LinkageError('scene', f'not used by a node of vehicle '
                                   f'{self.values["vehicle"]}: each corner has its scene from '
                                   'the vehicle file')
            from ..core.model import load_scene
            pending['_scene'] = load_scene(pending['scene'])     # SceneError: the reason
        return pending

    def apply(self, parameters: list[Parameter]) -> None:
        """Apply the request check() accepted; record the ParameterEvent."""
        if all(p.name.startswith('qos_overrides.') for p in parameters):
            return      # rclpy declaring the QoS parameters of a topic made now
        pending, self._pending = self._pending, {}
        scene = pending.pop('_scene', None)
        changed = {k: v for k, v in pending.items() if v != self.values.get(k)}
        self.values.update(pending)
        node, values = self.node, self.values
        if not changed and scene is None:
            self._record(parameters)
            return
        if scene is not None:
            for corner in node.corners.values():
                corner.set_scene(scene, values)
            node.robot_name = scene.name
            node.get_logger().info(f'scene {scene.name} ({scene.source}): continuation '
                                   'restarts from its design position')
        elif any(name in changed for name in SOLVER):
            for corner in node.corners.values():
                corner.configure(values)
        if 'diagnostic_period' in changed:
            node.set_diagnostic_period(values['diagnostic_period'])
        if 'alignment' in changed or 'markers' in changed:
            for corner in node.corners.values():
                corner.set_outputs(values)
        if 'tf' in changed:
            node.set_tf(values['tf'])
        elif scene is not None:
            node.describe()
        self._record(parameters)
        if scene is not None:
            node.report(node.corners.values())

    def _record(self, parameters):
        """Hand the sinks the ParameterEvent of the change, as rclpy publishes it."""
        node = self.node
        if not node.sinks:
            return
        event = ParameterEvent(node=node.get_fully_qualified_name(),
                               changed_parameters=[p.to_parameter_msg() for p in parameters])
        event.stamp = node.clock.now().to_msg()
        node.record('/parameter_events', PARAMETER_EVENT, to_cdr(event))
