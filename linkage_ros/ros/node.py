# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node: wheel travel in; wheel-carrier pose, camber, toe and solver health out.

A thin adapter over the kinematics core (linkage_ros.core.solve.kinematics.Continuation): each
command is solved from the last good pose (large jumps walked in substeps of max_step_mm),
turned into SI messages by linkage_ros.ros.messages, and published. Outputs answer a stamped
input (JointState) with its header stamp, a Float64 with the node clock's time of receipt
(with use_sim_time, the time of the last /clock message received before it). A bad command
(NaN, inf, out of reach, bytes that do not decode) publishes no pose, only an ERROR diagnostic
saying why; the core keeps the last good state.

Its topics, their types and what they hold: linkage_ros.answer.topics (the table of
doc/node.md#topics, generated from it). All reliable, keep-last qos_depth (ros/qos.py),
/tf_static and robot_description transient local, depth 1; each takes
qos_overrides.<topic>... parameters. TF (ros/tf_outputs.py) is imported only while parameter tf
is true; /tf and /tf_static are published where tf2_msgs imports, and recorded everywhere.

With parameter vehicle (a vehicle file, linkage_ros.core.model.vehicle) the node serves every
corner: each Corner (ros/corner.py) has its own Continuation and the topics above under its name
(front_left/wheel_travel, ...; steering_rack only where the corner steers), one diagnostic
status per corner named after it; parameter scene is then not used. Corners whose vehicle entry
names a travel_joint (and rack_joint) are also answered from one joint_states topic: every
named corner of a message in one callback, at the message's header stamp.

The node owns its corners and is their Outlet: it records what they receive and publish into
the sinks (ros/sinks.py), stamps their answers, throttles their bad commands on the console and
publishes their statuses. Parameters: ros/parameters.py, their changes while the node runs
ros/runtime.py; process entry: ros/entry.py.
"""

from __future__ import annotations

import contextlib
from functools import partial
import math
import time
from typing import Callable, NamedTuple

from diagnostic_msgs.msg import DiagnosticArray
from rclpy.node import Node
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState

from . import messages, parameters
from .corner import Corner, corner_outputs, JOINT_STATE, joints_sent
from .inbox import Inbox
from .parameters import PARAMETERS
from .qos import clock_qos, latched_qos, offered, publisher, QOS, QOS_DEPTH, subscription, \
    topic_qos, unknown_overrides
from .runtime import RuntimeParameters
from .sinks import check_outputs, open_sinks, recording_metadata, Sinks
from .solve_service import serve_corners
from ..answer.cdr import CdrError, joint_state_of, to_cdr, type_name
from ..core.base import LinkageError
from ..core.model import load_target
from ..core.warmup import wants_statics

__all__ = ['NODE_NAME', 'PARAMETERS', 'QOS', 'QOS_DEPTH', 'SuspensionNode']

NODE_NAME = 'suspension_kinematics'
BAD_COMMAND_PERIOD = 5.0   # s: the console names each kind of bad command at most this often
S = 1_000_000_000          # ns per s


class Corners(NamedTuple):
    """The scenes the parameters name, and the files they were read from."""

    scenes: dict     # topic prefix ('' or 'front_left/') -> (Scene, travel joint, rack joint)
    files: dict      # recording custom_data key ('scene_yaml', ...) -> path of the file
    inputs: dict     # what ('scene file', ...) -> path, for the outputs to stay clear of
    name: str = ''   # the scene's or the vehicle's name (the robot description's)
    axles: object = None   # the vehicle file's VehicleAxles, if it has axles


def load_corners(params: dict) -> Corners:
    """
    Load the scenes the parameters name.

    The one scene under no prefix, or every corner of the vehicle parameter under
    'corner_name/' with the joint_states joints its vehicle file names ('' where none).
    """
    if not params['vehicle']:
        scene = load_target(params['scene'], 'scene').scene
        return Corners({'': (scene, '', '')}, {'scene_yaml': scene.source},
                       {'scene file': scene.source}, scene.name)
    vehicle = load_target(params['vehicle'], 'vehicle').vehicle
    scenes = {f'{name}/': (scene, *vehicle.joints.get(name, ('', '')))
              for name, scene in vehicle.corners.items()}
    files = {'vehicle_yaml': vehicle.source,
             **{f'scene_yaml/{name}': scene.source for name, scene in vehicle.corners.items()}}
    inputs = {'vehicle file': vehicle.source,
              **{f'scene file of {name}': scene.source
                 for name, scene in vehicle.corners.items()}}
    axles = vehicle.axles if vehicle.axles is not None and vehicle.axles.axles else None
    return Corners(scenes, files, inputs, vehicle.name, axles)


class SuspensionNode(Node):
    """
    Wheel travel (m) in; wheel-carrier pose (m), camber and toe (rad), diagnostics out.

    One scene, or every corner of a vehicle (parameter vehicle), each a Corner.
    """

    def __init__(self, sinks=(), before_solving: Callable[..., None] | None = None,
                 **kwargs) -> None:
        """
        Declare the parameters, load the scenes and open the sinks, topics and timer.

        sinks: extra objects with record(topic, type_name, cdr_bytes, receive_ns, publish_ns)
        and close(), after those the parameters turn on. before_solving: called once the
        parameters, scenes and outputs are checked and before the first solve, as
        before_solving(statics=...): True when a corner answers loaded poses (the process
        entry compiles the kernels there, interruptibly, and the statics kernels with them
        when told). kwargs go to rclpy Node. A mistake
        raises LinkageError (a ValueError) naming the parameter, file or field.
        """
        self._begin(kwargs)
        try:
            params = self._wire(sinks, before_solving)
        except BaseException:
            self.sinks.close()
            super().destroy_node()
            raise
        self._start(params)
        self.runtime = RuntimeParameters(self, params)

    def _begin(self, kwargs):
        """Make the rclpy node, with nothing of the node's own yet (no sinks, no corners)."""
        super().__init__(NODE_NAME, **{
            **kwargs, 'automatically_declare_parameters_from_overrides': True})
        self.sinks = Sinks([], self._sink_failed, self.get_logger().error)
        self.faults, self._bad_said, self.corners = [], {}, {}
        self.taking_commands = True
        self.clock = self.get_clock()
        self.tf_outputs = None
        self.roll_centres, self._axles, self._said_axles = None, None, False

    def _wire(self, sinks, before_solving, clock=True):
        """
        Read the parameters, load the scenes, open the sinks and make the corners' topics.

        Returns the parameters' values; a mistake raises LinkageError, with whatever was made
        left for the caller to release. clock: take /clock in order (once per node).
        """
        params = parameters.declare(self)
        if clock:
            self._take_clock_in_order(params['qos_depth'])
        corners = load_corners(params)
        check_outputs(params, corners.inputs)
        scenes = {prefix: scene for prefix, (scene, _, _) in corners.scenes.items()}
        self.qos = topic_qos(params['qos_depth'])
        self.sinks.active = open_sinks(
            params, scenes, self._offered_qos(corners, params),
            recording_metadata(params, corners.files), self.get_logger().warning) + list(sinks)
        if before_solving is not None:   # the statics kernels too if a corner answers loaded
            before_solving(statics=any(wants_statics(scene, params['statics'])
                                       for scene in scenes.values()))
        self.frame_id = params['frame_id']
        self.diagnostics_pub = publisher(self, DiagnosticArray, '/diagnostics', self.qos)
        self.corners = {prefix.rstrip('/'): Corner(self, self, scene, params, prefix, *joints)
                        for prefix, (scene, *joints) in corners.scenes.items()}
        # made anew (a managed node's configure after a cleanup, whose entities are gone)
        self.roll_centres, self._axles = None, corners.axles
        self.set_roll_centres(params['roll_centres'])
        self.robot_name, self.tf_outputs = corners.name, None
        self.joint_corners = [c for c in self.corners.values()
                              if c.travel_joint or c.rack_joint]
        if self.joint_corners:   # losses and failures are each named corner's (ros/inbox.py)
            inbox = Inbox(self.on_vehicle_joint_states, self._joints_lost, self._joints_failed)
            joint_states = subscription(self, JointState, 'joint_states', inbox, self.qos,
                                        raw=True)
            self.joint_states_topic = joint_states.topic_name
        self._check_overrides(corners, params)
        self.set_tf(params['tf'])
        self._say_pickup_frames()
        self.solve_services = serve_corners(self, self.corners)
        return params

    def _start(self, params):
        """Start the diagnostics timer and say what the node serves."""
        self.timer = self.create_timer(params['diagnostic_period'], self.on_diagnostic_period)
        for corner in self.corners.values():
            self.get_logger().info(
                f'scene {corner.scene.name} ({corner.scene.source}), method '
                f'{corner.method}, frame {self.frame_id}; listening on '
                f'{", ".join(self._listening(corner))}')
        for line in dict.fromkeys(w for c in self.corners.values() for w in c.scene.warnings):
            self.get_logger().warning(line)   # the scenes' (Scene.warnings), each once

    def _listening(self, corner):
        joints = [joint for joint in (corner.travel_joint, corner.rack_joint) if joint]
        vehicle = [f'{self.joint_states_topic} (joint{"s" * (len(joints) > 1)} '
                   f'{", ".join(joints)}, m)'] if joints else []
        return corner.listening + vehicle

    # --- the Outlet of the corners ---------------------------------------------------------

    def received(self, topic, type_name, data):
        """
        Take an input of a corner: record it; return the time of receipt (sec, nanosec).

        That is the node clock's (with use_sim_time, the time of the last /clock message
        taken before the input: see _take_clock_in_order). None once the node has stopped
        taking commands: the input is dropped before it is read.
        """
        if not self.taking_commands:
            return None
        now = self.clock.now().nanoseconds
        if self.sinks:   # the input's publish time is unknown: EventsExecutor gives no info
            self.sinks.record(topic, type_name, data, now, now)
        return divmod(now, S)

    def taking(self, topic, type_name, data):
        """
        Take an input whose time of receipt is not used: record it; False once stopping.

        A contact wrench answers nothing and is stamped by nothing, so the node clock is
        read only to record it (a few us a wrench, four a vehicle's step, without sinks).
        """
        if not self.taking_commands:
            return False
        if self.sinks:
            now = self.clock.now().nanoseconds
            self.sinks.record(topic, type_name, data, now, now)
        return True

    def publish(self, publisher, msg):
        """Publish msg (CDR bytes or an rclpy message) and hand it to the sinks."""
        # Recorded first: should publish() fail, the recording still holds the attempt.
        if self.sinks:
            published = self.clock.now().nanoseconds
            self.sinks.record(publisher.topic_name, type_name(publisher.msg_type), to_cdr(msg),
                              published, published)
        publisher.publish(msg)

    def sender(self, publisher):
        """
        Return send(msg): publish(publisher, msg); without sinks, publisher.publish itself.

        The sinks are opened before the corners (they never grow; a failed one is dropped),
        so a node without them records nothing: its answers skip publish()'s check, one
        Python call per message (ros/corner.py: 18 to 46 a bushed vehicle's step).
        """
        return partial(self.publish, publisher) if self.sinks else publisher.publish

    def bad_command(self, sent, kind, why):
        """
        Say on the console that a command could not be answered (kind: a Status, say).

        Once per kind of failure and BAD_COMMAND_PERIOD s, with the count of the same kind
        held back since: a stream of bad commands must not flood the console; /diagnostics
        reports every one.
        """
        now = time.monotonic()
        last, held = self._bad_said.get(kind, (-math.inf, 0))
        if now - last < BAD_COMMAND_PERIOD:
            self._bad_said[kind] = (last, held + 1)
            return
        more = f' ({held} more like it in the last {now - last:.0f} s)' if held else ''
        self.get_logger().error(f'{sent}: {why}{more}')
        self._bad_said[kind] = (now, 0)

    def report(self, corners):
        """Publish the status of each of corners on /diagnostics, stamped now."""
        self.publish(self.diagnostics_pub, messages.diagnostics(
            [corner.status() for corner in corners], self.clock.now().to_msg()))

    def record(self, topic, type_name, data):
        """Hand a message the node sends but cannot publish (no tf2_msgs) to the sinks."""
        if self.sinks:
            now = self.clock.now().nanoseconds
            self.sinks.record(topic, type_name, data, now, now)

    def transforms(self, data):
        """Send a corner's frames (TFMessage CDR bytes) on /tf (ros/tf_outputs.py)."""
        self.tf_outputs.send(data)

    # --- TF and the parameters that change while the node runs ------------------------------

    def set_tf(self, on):
        """
        Turn /tf, /tf_static and robot_description on (sent at once) or off.

        Off, nothing of it is imported or computed. Where tf2_msgs is missing the frames are
        recorded and not published, which the log says once.
        """
        if on and self.tf_outputs is None:
            from .tf_outputs import TfOutputs
            self.tf_outputs = TfOutputs(self, self, self.corners, self.frame_id,
                                        self.robot_name, self.qos.depth)
            if self.tf_outputs.missing and not getattr(self, '_said_tf', False):
                self.get_logger().warning(self.tf_outputs.missing)
                self._said_tf = True
            self.describe()
        elif not on and self.tf_outputs is not None:
            self.tf_outputs.close()
            self.tf_outputs = None

    def set_roll_centres(self, on):
        """
        Turn each axle's roll-centre topic on (made) or off (removed, none computed).

        A vehicle without axles imports none of it (ros/roll_centres.py). Turned on again,
        an axle's roll centre is published once both its corners have answered again.
        """
        if on and self.roll_centres is None and self._axles is not None:
            from .roll_centres import RollCentres
            self.roll_centres = RollCentres(     # an axle without patches: said once
                self, self, self._axles, self.corners, self.qos, self.frame_id,
                (lambda line: None) if self._said_axles else self.get_logger().warning)
            self._said_axles = True
        elif not on and self.roll_centres is not None:
            self.roll_centres.close()
            self.roll_centres = None

    def _say_pickup_frames(self):
        """Say once, with pickup forces published, when their TF frames are not."""
        if not any(c.statics is not None and c.responder.switches['pickups']
                   for c in self.corners.values()):
            return
        why = ('parameter tf is false' if self.tf_outputs is None else
               'tf2_msgs is missing' if self.tf_outputs.missing else '')
        if why:
            self.get_logger().warning(
                f'{why}: the pickup frames are unavailable; pickup/<name> wrenches are in '
                f'{self.frame_id}, each acting at its pickup point (doc/node.md)')

    def describe(self):
        """Send /tf_static and robot_description again (after a change of scene)."""
        if self.tf_outputs is not None:
            self.tf_outputs.attach()
            self.tf_outputs.robot_name = self.robot_name
            self.tf_outputs.describe(divmod(self.clock.now().nanoseconds, S))

    def set_diagnostic_period(self, period):
        """Report every period s from now on."""
        self.destroy_timer(self.timer)
        self.timer = self.create_timer(period, self.on_diagnostic_period)

    # --- the node's own inputs and timer ---------------------------------------------------

    def _take_clock_in_order(self, depth):
        """
        With use_sim_time, take every /clock message in turn, in order with the commands.

        rclpy's time source subscribes to /clock with depth 1: a node busy for a moment then
        finds only the newest of several /clock messages when it gets to the first, and
        stamps the commands that came between them all with that later time. Its
        subscription is replaced here by one of depth messages (best effort, to match any
        /clock publisher) that hands each message to rclpy's callback, so that the node
        clock reads, at each command, the last /clock time received before it.
        """
        theirs = [sub for sub in self.subscriptions if sub.topic_name == '/clock']
        if not theirs:   # use_sim_time is false: the node clock is the system clock
            return
        callbacks = [sub.callback for sub in theirs]
        for sub in theirs:
            self.destroy_subscription(sub)

        def on_clock(msg):
            for callback in callbacks:
                callback(msg)

        self.create_subscription(Clock, '/clock', on_clock, clock_qos(depth))

    def on_vehicle_joint_states(self, data):
        """Answer every corner whose joints a JointState (for the whole vehicle) names."""
        topic = self.joint_states_topic
        if self.received(topic, JOINT_STATE, data) is None:
            return
        try:     # in place: a fraction of rclpy's JointState (answer/cdr.py)
            msg = joint_state_of(data)
        except CdrError as exc:
            for corner in self.joint_corners:
                corner.refuse(topic, exc)
            return
        stamp = msg.stamp
        # The axles' roll centres once per step, after all of its corners' answers.
        with self.roll_centres.step() if self.roll_centres else contextlib.nullcontext():
            for corner in self.joint_corners:
                travel_mm = messages.joint_travel_mm(msg, corner.travel_joint)
                rack_mm = messages.joint_travel_mm(msg, corner.rack_joint) \
                    if corner.rack_joint else None
                if travel_mm is None and rack_mm is None:
                    continue
                try:     # one corner's failure is its own: the others are answered
                    corner.answer(travel_mm, rack_mm, stamp, lambda corner=corner: joints_sent(
                        topic, msg, [corner.travel_joint, corner.rack_joint]))
                except Exception as exc:  # noqa: B902 (no exception may leave a callback)
                    corner.fail(topic, exc)

    def _joints_lost(self, count):
        for corner in self.joint_corners:
            corner.lose(self.joint_states_topic, count)

    def _joints_failed(self, exc):
        for corner in self.joint_corners:
            corner.fail(self.joint_states_topic, exc)

    def on_diagnostic_period(self):
        try:
            self.sinks.check()     # a recorder writing in the background may have failed
            self.report(self.corners.values())
        except Exception as exc:  # noqa: B902 (no exception may leave a callback)
            self.get_logger().error(f'the diagnostics report failed ({type(exc).__name__}: '
                                    f'{exc}); the node goes on')
        for corner in self.corners.values():
            corner.health.reset_period()

    # --- sinks and shutdown ----------------------------------------------------------------

    def _sink_failed(self, sink, reason):
        """
        Say, until the node stops, that a sink failed and was dropped.

        Every corner's status turns ERROR, naming the file, the reason and the time, at once
        and in every report after it: data is no longer being recorded. The node goes on
        answering commands.
        """
        when = self.clock.now().nanoseconds / S
        fault = (f'{type(sink).__name__} {getattr(sink, "path", "")} stopped at t = '
                 f'{when:.3f} s ({time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime(when))}):'
                 f' {reason}; nothing is recorded since')
        self.get_logger().error(fault)
        self.faults.append(fault)
        for corner in self.corners.values():
            corner.health.set_fault('; '.join(self.faults))
        if self.corners:
            self.report(self.corners.values())

    def stop_taking_commands(self):
        """Drop every input from now on (shutting down): the queued ones are not answered."""
        self.taking_commands = False

    def close_sinks(self):
        """Close every sink once (files are finished here); later calls do nothing."""
        self.sinks.close()

    def close_services(self):
        """Answer REFUSED every solve request still waiting (the node stops: none unanswered)."""
        for answers in getattr(self, 'solve_services', {}).values():
            answers.close()

    def destroy_node(self):
        self.stop_taking_commands()
        self.close_services()
        self.close_sinks()
        super().destroy_node()

    def _topics(self, corners, params, every=False):
        """
        Return {resolved topic: (entity, default QoS)} of the node's topics.

        corners as load_corners gives them; every: also those the node may make while it runs
        (alignment, markers, pickups, camber and toe, elements, roll centres, TF,
        steering_rack), whatever the parameters say now.
        """
        if every:
            params = {**params, 'alignment': True, 'markers': True, 'pickups': True,
                      'angles': True, 'elements': True, 'roll_centres': True}
        names = {'/diagnostics': 'publisher'}
        for prefix, (scene, *joints) in corners.scenes.items():
            names.update(corner_outputs(scene, params, prefix))
            if every:
                names[prefix + 'steering_rack'] = 'subscription'
            if any(joints):
                names['joint_states'] = 'subscription'
        if corners.axles is not None and params['roll_centres']:
            from .roll_centres import roll_centre_topics
            names.update(dict.fromkeys(roll_centre_topics(corners.axles, {
                prefix.rstrip('/'): scene for prefix, (scene, *_) in corners.scenes.items()}),
                'publisher'))
        topics = {self.resolve_topic_name(name): (entity, self.qos)
                  for name, entity in names.items()}
        if params['tf'] or every:
            topics.update({'/tf': ('publisher', self.qos),
                           '/tf_static': ('publisher', latched_qos()),
                           self.resolve_topic_name('robot_description'):
                               ('publisher', latched_qos())})
        return topics

    def _offered_qos(self, corners, params):
        """Return {resolved topic: QoS, its overrides applied} for the recording's metadata."""
        return {topic: offered(self, topic, entity, profile)
                for topic, (entity, profile) in self._topics(corners, params).items()}

    def _check_overrides(self, corners, params):
        """Refuse a qos_overrides parameter that names no topic of the node (LinkageError)."""
        known = {(topic, entity) for topic, (entity, _) in
                 self._topics(corners, params, every=True).items()}
        for name, problem in unknown_overrides(self, known).items():
            raise LinkageError(f'parameter {name}', problem)
