# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node's parameters while it runs: a SetParameters request checked, then applied.

    RuntimeParameters(node, params)   registers the node's on-set and post-set callbacks

A request (rcl_interfaces SetParameters; `ros2 param set` in a full install) is taken whole
or not at all: rclpy's SetParameters service sets each parameter of a request on its own, so
the node answers it itself (set_whole): every parameter is checked first, then all are set in
one step, and a refusal refuses each of them with the same reason. A request naming a scene
is answered once the scene is loaded: it is read, parsed and checked in a thread (SceneLoad)
while the executor goes on answering commands, and the response waits (the services'
send_response holds it back) until the executor, polling every LOAD_POLL s on the steady
clock, finds the scene ready and sets the request whole. One such request at a time: another
request meanwhile is refused, to be sent again. Refused, with the reason
and the old values kept: a parameter the node does not have (named, with the closest name), a
value out of its range or of the wrong type (ros/parameters.checked, the wording of the
node's start), a method that does not exist, a scene that does not load (the loader's line,
any OSError of the file system included), a change of a FIXED parameter (vehicle,
record_mcap, rerun_rrd, frame_id, ...: why it is fixed), scene on a vehicle node.

Applied, once rclpy has stored the values (the post-set callback):
    method, max_step_mm, condition_warn   every corner's solver, at the pose it holds
    diagnostic_period                     the report timer, from now on
    alignment, markers, pickups, angles,  the outputs, made or removed
    elements
    roll_centres                          each axle's roll-centre topic, made or removed
    tf                                    /tf, /tf_static, robot_description on or off
    scene                                 the corner serves the new scene from its design
                                          position, its topics kept; /diagnostics says so at
                                          once, and /tf_static and robot_description are sent
                                          again
Every applied change is recorded as the rcl_interfaces/msg/ParameterEvent the node publishes
on /parameter_events (the recordings go on across it).
"""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING

from rcl_interfaces.msg import ParameterEvent, SetParametersResult
from rclpy.clock import Clock, ClockType
from rclpy.exceptions import ParameterException
from rclpy.parameter import Parameter

from .parameters import checked, FIXED, PARAMETERS, unknown_parameter
from ..answer.cdr import to_cdr
from ..answer.protocol import statics_problem
from ..core.base import LinkageError

if TYPE_CHECKING:
    from rclpy.node import Node

PARAMETER_EVENT = 'rcl_interfaces/msg/ParameterEvent'
SOLVER = ('method', 'max_step_mm', 'condition_warn')
OUTPUTS = ('alignment', 'markers', 'pickups', 'angles', 'elements')   # a corner's switches
LOAD_POLL = 0.01   # s: how often the executor looks whether a scene being loaded is ready


class RuntimeParameters:
    """The node's parameters as they are now, and how a change of them is taken."""

    def __init__(self, node: Node, params: dict) -> None:
        self.node, self.values = node, dict(params)
        self._pending = {}     # checked values of the request being set, and a loaded scene
        node.add_on_set_parameters_callback(self.check)
        node.add_post_set_parameters_callback(self.apply)
        # rclpy's services answer with the node's own handlers (see set_whole)
        self._load = None      # the request waiting for its scene (SceneLoad), if any
        self._preloaded = None   # (scene parameter, Scene or the error) for check()
        for service in node.services:
            if service.srv_name.endswith('/set_parameters'):
                self._answer_with(service, self.set_whole)
            elif service.srv_name.endswith('/set_parameters_atomically'):
                self._answer_with(service, self.set_atomically)

    def _answer_with(self, service, fill):
        """Answer service's requests with fill(parameters, result, response), maybe later."""
        send = service.send_response

        def answer(request, response):
            return self._answer(service, [Parameter.from_parameter_msg(p)
                                          for p in request.parameters], fill, response)

        def send_response(response, header):
            load = self._load
            if load is not None and response is load.response and load.header is None:
                load.header = header     # sent once the scene is loaded (_loaded)
                return
            send(response, header)

        service.callback, service.send_response, service.send_now = answer, send_response, send

    def _answer(self, service, parameters, fill, response):
        """Answer a request now, or, with a scene to load, once it is loaded off the executor."""
        scene = next((p.value for p in parameters if p.name == 'scene'), None)
        unknown = self._unknown(parameters)
        if self._load is not None:
            return fill(parameters, SetParametersResult(successful=False, reason=(
                'scene: an earlier request is loading a scene; send this one once that one '
                'is answered')), response)
        if not isinstance(scene, str) or self.values['vehicle'] or unknown is not None:
            return fill(parameters, unknown or self.set_all(parameters), response)
        # The scene is read, parsed and checked in a thread while the executor goes on
        # answering commands; the request is then set whole or refused (set_all), at once.
        self._load = SceneLoad(scene, service, parameters, fill, response)
        self._load.timer = self.node.create_timer(LOAD_POLL, self._loaded,
                                                  clock=Clock(clock_type=ClockType.STEADY_TIME))
        return response

    def _loaded(self):
        """Finish the request of a scene loaded: set it whole or refuse it, and answer."""
        load = self._load
        if not load.done.is_set() or load.header is None:
            return
        self.node.destroy_timer(load.timer)
        self._load, self._preloaded = None, (load.scene, load.outcome)
        try:
            load.fill(load.parameters, self.set_all(load.parameters), load.response)
        finally:
            self._preloaded = None
        load.service.send_now(load.response, load.header)

    def _unknown(self, parameters):
        """Return the refusal of a request naming a parameter the node has not, else None."""
        for parameter in parameters:   # rclpy's refusal would name none (rclpy 7.1)
            if not self.node.has_parameter(parameter.name):
                return SetParametersResult(successful=False, reason=(
                    f'{parameter.name}: {unknown_parameter(parameter.name)}'))
        return None

    @staticmethod
    def set_whole(parameters, result, response):
        """Fill rcl_interfaces SetParameters' response: each parameter, the one result."""
        response.results = [SetParametersResult(successful=result.successful,
                                                reason=result.reason)
                            for _ in parameters]
        return response

    @staticmethod
    def set_atomically(parameters, result, response):
        """Fill rcl_interfaces SetParametersAtomically's response."""
        response.result = result
        return response

    def set_all(self, parameters: list[Parameter]) -> SetParametersResult:
        """Set parameters in one step, or none of them: the SetParametersResult."""
        unknown = self._unknown(parameters)
        if unknown is not None:
            return unknown
        try:
            return self.node.set_parameters_atomically(parameters)
        except ParameterException as exc:
            return SetParametersResult(successful=False, reason=str(exc))

    def check(self, parameters: list[Parameter]) -> SetParametersResult:
        """Check a request whole: SetParametersResult refused with the reason, or accepted."""
        try:
            self._pending = self._checked(parameters)
        except (LinkageError, OSError) as exc:   # OSError: a scene path the system refuses
            self._pending = {}
            return SetParametersResult(successful=False, reason=' '.join(str(exc).split()))
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
            pending['_scene'] = self._scene(pending['scene'])   # SceneError: the reason
            problem = statics_problem(pending['_scene'], self.values['statics'])
            if problem:
                raise LinkageError('scene', problem)
        return pending

    def _scene(self, name):
        """Return the scene a request names: loaded by its SceneLoad, else loaded now."""
        if self._preloaded is not None and self._preloaded[0] == name:
            outcome = self._preloaded[1]
            if isinstance(outcome, BaseException):
                raise outcome
            return outcome
        return SceneLoad.load(name)

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
            for line in scene.warnings:   # as at start (a singular design, a unit slip)
                node.get_logger().warning(line)
        elif any(name in changed for name in SOLVER):
            for corner in node.corners.values():
                corner.configure(values)
        if 'diagnostic_period' in changed:
            node.set_diagnostic_period(values['diagnostic_period'])
        if any(name in changed for name in OUTPUTS):
            for corner in node.corners.values():
                corner.set_outputs(values)
        if 'roll_centres' in changed:
            node.set_roll_centres(values['roll_centres'])
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


class SceneLoad:
    """
    A scene read, parsed and checked in a thread, for the request that names it.

    outcome: the Scene, or the LinkageError or OSError that refuses it, once done is set.
    header: the request's, once the executor has handed over the response to send later.
    """

    def __init__(self, scene, service, parameters, fill, response):
        self.scene, self.service, self.parameters = scene, service, parameters
        self.fill, self.response, self.header, self.timer = fill, response, None, None
        self.outcome, self.done = None, threading.Event()
        threading.Thread(target=self._run, name='scene load', daemon=True).start()

    def _run(self):
        try:
            self.outcome = self.load(self.scene)
        except (LinkageError, OSError) as exc:
            self.outcome = exc
        except Exception as exc:  # noqa: B902 (any failure is the request's refusal)
            self.outcome = LinkageError('scene', f'cannot be loaded ({type(exc).__name__}: '
                                        f'{exc})')
        self.done.set()

    @staticmethod
    def load(name):
        """Load the scene of a name or path (core.model.load_scene, read when called)."""
        from ..core import model
        return model.load_scene(name)
