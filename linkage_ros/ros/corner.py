# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
One wheel of suspension_node: its solver, its health, its topics, and how it answers.

A Corner subscribes its inputs and creates its outputs on the node that owns it, and reports
through an Outlet (the node): every input it receives, every message it publishes, a bad
command for the console, a status to publish at once. It never reaches into the node
otherwise, and the node calls it only to answer (answer, refuse) and for its status.

Inputs, under the corner's prefix ('' or 'front_left/'):
    wheel_travel   std_msgs/Float64 (m, + = bump)
    steering_rack  std_msgs/Float64 (m, + = to the left), only if the scene steers
    joint_states   sensor_msgs/JointState, position of joint travel_joint (m), if it is set
    contact_wrench geometry_msgs/WrenchStamped, the tyre's force (N) and moment (N m) at the
                   contact patch, vehicle frame: with statics on (a scene with bushings, or
                   parameter statics), each answer is the loaded pose at the last one
All come raw (CDR bytes): a Float64 is read in place, a fraction of the cost of an rclpy
message, and bytes that do not decode (linkage_ros.answer.cdr.CdrError) are an ERROR status naming
the topic and the byte count, with no pose, instead of an exception in the executor.

While the node runs, its parameters may change (ros/runtime.py): the corner then takes new
solver settings at the pose it holds (configure), a new scene from that scene's design
position (set_scene), or turns its alignment, markers, pickups, camber and toe (angles) and
elements on or off (set_outputs); its topics stay, and its elements topic follows the scene (a
scene with elements has one, unless parameter elements is false). With TF
on, the node gives it frames (ros/tf.CornerFrames): every answer then also sends the frames of its
bodies to the outlet's transforms().

What a solved command publishes is its Responder's list (protocol.OUTPUTS, outputs_of: the
pose, camber and toe unless angles is off, then the extras turned on), published in that
order, each on the corner's
publisher of that name ('/tf' through the outlet's transforms()).
"""

from __future__ import annotations

from typing import Callable, Protocol, TYPE_CHECKING

from geometry_msgs.msg import PoseStamped, WrenchStamped
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64, Float64MultiArray
from visualization_msgs.msg import MarkerArray

from . import messages
from .inbox import Inbox
from .qos import publisher, subscription, topic_qos
from ..answer.cdr import CdrError, float64_of, joint_state_of, JointStateRead, \
    wrench_of
from ..answer.protocol import ANSWER_TYPES, CONTACT_WRENCH, outputs_of, Reply, Responder, \
    wrench_problem, WRENCH_TYPE
from ..core.warmup import wants_statics

if TYPE_CHECKING:
    from rclpy.node import Node
    from rclpy.publisher import Publisher

    from ..core.model import Scene

FLOAT64 = 'std_msgs/msg/Float64'
JOINT_STATE = 'sensor_msgs/msg/JointState'
# the message classes of the outputs' publishers (protocol.OUTPUTS; /tf: ros/tf_outputs.py)
MESSAGES = {'geometry_msgs/msg/PoseStamped': PoseStamped, 'std_msgs/msg/Float64': Float64,
            'std_msgs/msg/Float64MultiArray': Float64MultiArray,
            'visualization_msgs/msg/MarkerArray': MarkerArray,
            'sensor_msgs/msg/JointState': JointState, WRENCH_TYPE: WrenchStamped}
TF = '/tf'
PICKUP = 'pickup'             # the output of the pickups' forces: one topic pickup/<name> each
UNDECODABLE = 'undecodable'   # the kind of a bad command whose bytes do not decode
BAD_WRENCH = 'bad wrench'     # the kind of a contact wrench refused (not finite, too big, ...)
LOST = 'lost messages'        # inputs lost before the node took them (a queue overflowed)
INTERNAL = 'internal error'   # an input whose handling raised: refused, the node goes on


class Outlet(Protocol):
    """What a Corner reports to: the node that owns it."""

    def received(self, topic: str, type_name: str, data: bytes) -> tuple[int, int] | None:
        """
        Take an input (CDR bytes, as it came on topic), before it is even decoded.

        Returns the node clock's time of receipt (sec, nanosec), or None once the node takes
        no more commands (it is shutting down): the input is then dropped unread.
        """

    def taking(self, topic: str, type_name: str, data: bytes) -> bool:
        """
        Take an input whose time of receipt is not used (a contact wrench), as received().

        False once the node takes no more commands (the input is then dropped unread).
        """

    def publish(self, publisher: Publisher, msg: bytes | object) -> None:
        """Publish msg (CDR bytes or an rclpy message) on publisher."""

    def sender(self, publisher: Publisher) -> Callable[[bytes | object], None]:
        """Return send(msg): publish(publisher, msg), or as cheap a function that does it."""

    def bad_command(self, sent: str, kind: object, why: str) -> None:
        """Say on the console that a command sent as sent could not be answered, and why."""

    def report(self, corners: list[Corner]) -> None:
        """Publish the status of corners on /diagnostics now."""

    def transforms(self, data: bytes) -> None:
        """Send a corner's TF (tf2_msgs/TFMessage CDR bytes) on /tf, or record it only."""


class Corner:
    """
    One wheel: its scene, its Continuation (independent of the other corners), its Health.

    Its input subscriptions and output publishers are created on node, topics under prefix
    ('' or 'front_left/'); it reports to outlet. params: the node's parameter values.
    travel_joint, rack_joint: the joints of the vehicle's joint_states that command it ('' =
    none), which the node reads and hands to answer.
    """

    def __init__(self, node: Node, outlet: Outlet, scene: Scene, params: dict, prefix: str = '',
                 travel_joint: str = '', rack_joint: str = '') -> None:
        self.node, self.outlet, self.scene, self.prefix = node, outlet, scene, prefix
        self.frame_id, self.method = params['frame_id'], params['method']
        self.responder = self._responder(scene, params)
        self.travel_joint, self.rack_joint = travel_joint, rack_joint   # vehicle joint_states
        self.qos = topic_qos(params['qos_depth'])
        self.publishers = {}    # output name -> its publisher, for the outputs on
        self.sends = {}         # output name -> function(message): publishes it
        self.listening = []     # what it takes, for the start-up line
        self.travel_topic = self._subscribe(Float64, 'wheel_travel', self.on_travel)
        self.listening.append(f'{self.travel_topic} (m)')
        self.joint = params['travel_joint']
        if self.joint:   # off by default: no subscription, no discovery traffic
            self.joints_topic = self._subscribe(JointState, 'joint_states',
                                                self.on_joint_states)
            self.listening.append(f'{self.joints_topic} (joint {self.joint}, m)')
        self.rack_topic = self.wrench_topic = None
        self._listen_to_rack()
        self._listen_to_wrench(params)
        # function(corner, solution, stamp) called after every answer, solved or not (the
        # vehicle's axles: ros/roll_centres.py)
        self.listeners = []
        self.set_outputs(params)

    @property
    def frames(self):
        """Return the corner's CornerFrames (answer/frames.py) while TF is on, else None."""
        return self.responder.frames

    @frames.setter
    def frames(self, frames) -> None:
        # the node's TF (ros/tf_outputs.py) gives and takes them: /tf is published with them
        self.responder.set_outputs(frames=frames)
        self._set_publishers()

    @property
    def statics(self):
        """Return the corner's answer/pickups.CornerStatics while statics is on, else None."""
        return self.responder.statics

    def _responder(self, scene: Scene, params: dict) -> Responder:
        # The node's answering protocol, shared with linkage-replay; the node's own timer
        # sends the periodic reports, so the responder's period clock is not used here.
        responder = Responder(
            scene, method=params['method'], max_step_mm=params['max_step_mm'],
            condition_warn=params['condition_warn'], frame_id=self.frame_id,
            status_name=messages.status_name(self.node.get_fully_qualified_name(), scene.name),
            period_ns=round(params['diagnostic_period'] * 1e9),
            statics=wants_statics(scene, params['statics']), prefix=self.prefix,
            builders=messages.BUILDERS)
        self.solver, self.health = responder.solver, responder.health
        self.status_name = responder.status_name
        return responder

    def _listen_to_rack(self) -> None:
        """Subscribe steering_rack if the scene steers and it is not subscribed yet."""
        if self.scene.steered and self.rack_topic is None:
            self.rack_topic = self._subscribe(Float64, 'steering_rack', self.on_rack)
            self.listening.append(f'{self.rack_topic} (m)')

    def _listen_to_wrench(self, params: dict) -> None:
        """Subscribe contact_wrench if statics is on and it is not subscribed yet."""
        if wants_statics(self.scene, params['statics']) and self.wrench_topic is None:
            self.wrench_topic = self._subscribe(WrenchStamped, CONTACT_WRENCH, self.on_wrench)
            self.listening.append(f'{self.wrench_topic} (N, N m at the contact patch, '
                                  f'{self.frame_id})')

    def _subscribe(self, kind: type, name: str, take: Callable[[bytes], None]) -> str:
        """
        Subscribe the input name (under the corner's prefix) raw; return its resolved topic.

        Through an Inbox (ros/inbox.py): the messages lost before each one are counted
        (lose), and an exception of take is the refusal of that message (fail), never the
        executor's.
        """
        where = {}
        inbox = Inbox(take, lambda count: self.lose(where['topic'], count),
                      lambda exc: self.fail(where['topic'], exc))
        where['topic'] = subscription(self.node, kind, self.prefix + name, inbox, self.qos,
                                      raw=True).topic_name
        return where['topic']

    def configure(self, params: dict) -> None:
        """
        Take new solver settings (method, max_step_mm, condition_warn) at the present pose.

        The new solver starts at the pose the old one holds (Responder.follow); the health
        goes on counting.
        """
        self._follow(self.scene, params)
        self.method = params['method']

    def set_scene(self, scene: Scene, params: dict) -> None:
        """
        Serve a new scene from its design position, its topics kept; the health says so.

        steering_rack is subscribed if the new scene steers (and stays, if the old one did).
        """
        self.scene = scene
        self._follow(scene, params)
        self._listen_to_rack()
        self._listen_to_wrench(params)
        self._set_publishers()

    def _follow(self, scene: Scene, params: dict) -> None:
        """Answer with a new Responder for scene and params, as linkage-replay does."""
        old = self.responder
        self.responder = self._responder(scene, params)
        self.responder.follow(old)
        self.health = self.responder.health

    def set_outputs(self, params: dict) -> None:
        """Turn the outputs other than the pose on or off, as params (the node's) say."""
        self.responder.set_outputs(alignment=params['alignment'], markers=params['markers'],
                                   pickups=params['pickups'], angles=params['angles'],
                                   elements=params['elements'])
        self._set_publishers()

    def _set_publishers(self) -> None:
        """
        Have a publisher for each output of the responder's, and none for any other.

        A publisher kept (the elements of a new scene with elements) keeps its subscribers
        matched; /tf goes to the outlet's transforms().
        """
        outputs = {o.name: o for o in self.responder.outputs}
        if PICKUP in outputs:      # one topic per pickup of the scene
            outputs.update({f'{PICKUP}/{name}': outputs[PICKUP]
                            for name in self.responder.statics.names})
            del outputs[PICKUP]
        for name in [n for n in self.publishers if n not in outputs]:
            self.node.destroy_publisher(self.publishers.pop(name))
        for name, output in outputs.items():
            if name != TF and name not in self.publishers:
                self.publishers[name] = publisher(self.node, MESSAGES[output.type_name],
                                                  self.prefix + name, self.qos)
        self.sends = {name: self.outlet.transforms if name == TF
                      else self.outlet.sender(self.publishers[name])
                      for name in outputs}

    def on_travel(self, data: bytes) -> None:
        self._float64_command(self.travel_topic, data, rack=False)

    def on_rack(self, data: bytes) -> None:
        # A new rack at the last travel: Continuation keeps the travel it was last solved at.
        # A scene without a rack link (subscribed for an earlier one) refuses it (Responder).
        self._float64_command(self.rack_topic, data, rack=True)

    def _float64_command(self, topic: str, data: bytes, rack: bool) -> None:
        stamp = self.outlet.received(topic, FLOAT64, data)
        if stamp is None:
            return
        try:
            value_mm = messages.command_mm(data)
        except CdrError as exc:
            self.refuse(topic, exc)
            return
        self.answer(value_mm if not rack else None, value_mm if rack else None, stamp,
                    lambda: f'{topic} {float64_of(data)!r} m')

    def on_wrench(self, data: bytes) -> None:
        """Take the tyre's wrench at the contact patch for the next answers; answer nothing."""
        topic = self.wrench_topic
        if not self.outlet.taking(topic, WRENCH_TYPE, data):   # no clock read: not stamped
            return
        try:
            frame_id, force, torque = wrench_of(data)
        except CdrError as exc:
            self.refuse(topic, exc)
            return
        problem = wrench_problem(frame_id, force, torque, self.frame_id)
        if self.responder.statics is None:   # subscribed for an earlier scene
            problem = (f'scene {self.scene.name} has no bushings and parameter statics is '
                       'false: a contact wrench moves nothing')
        if problem:
            self.refuse(topic, problem, BAD_WRENCH)
            return
        self.responder.statics.set_wrench(force, torque)

    def on_joint_states(self, data: bytes) -> None:
        # Answered at the message's header stamp, not at the time of receipt.
        topic = self.joints_topic
        if self.outlet.received(topic, JOINT_STATE, data) is None:
            return
        try:
            msg = joint_state_of(data)
        except CdrError as exc:
            self.refuse(topic, exc)
            return
        travel_mm = messages.joint_travel_mm(msg, self.joint)
        if travel_mm is not None:   # other joints' messages are not commands: no answer
            self.answer(travel_mm, None, msg.stamp, lambda: joints_sent(topic, msg, [self.joint]))

    def answer(self, travel_mm: float | None, rack_mm: float | None, stamp: tuple[int, int],
               sent: Callable[[], str]) -> Reply:
        """
        Solve a command, publish the answer, count it into the health; return the Reply.

        travel_mm and rack_mm: the command (None = unchanged); stamp: (sec, nanosec) of the
        answer; sent: a function that says what was sent where (e.g. '/wheel_travel 0.5 m'),
        called for the messages about a bad command. A solved command publishes the
        Responder's outputs in its order (the pose, then camber, toe and the extras turned
        on); a failed one publishes nothing and goes to the console (the outlet throttles it).
        A failure or a change of level goes to /diagnostics at once. The Reply (protocol.py)
        holds the Solution and the outputs published (the solve service reads them back).
        """
        reply = self.responder.answer(travel_mm, rack_mm, stamp, sent)
        solution, sends = reply.solution, self.sends
        for name, _, data in reply.outputs:
            sends[name](data)
        if not solution.success:
            self.outlet.bad_command(reply.sent, solution.status, solution.message)
        for listener in self.listeners:
            listener(self, solution, stamp)
        if reply.report:
            self.outlet.report([self])
        return reply

    def refuse(self, topic: str, error: CdrError | str, kind: str = UNDECODABLE) -> None:
        """Count an input that cannot be answered (bytes that do not decode): ERROR, no pose."""
        self.outlet.bad_command(topic, kind, str(error))
        self.health.refuse(f'{topic}: {error}')
        self.outlet.report([self])

    def lose(self, topic: str, count: int) -> None:
        """Count count inputs of topic lost before the node took them; say so on the console."""
        self.health.lose(count)
        self.outlet.bad_command(topic, LOST, f'{count} message{"s" * (count > 1)} lost before '
                                f'this one: its queue (qos_depth {self.qos.depth}) overflowed '
                                '(/diagnostics counts them: lost, lost_total)')

    def fail(self, topic: str, exc: BaseException) -> None:
        """Refuse an input of topic whose handling raised exc: ERROR, and the node goes on."""
        text = ' '.join(str(exc).split())[:300]
        self.refuse(topic, f'internal error ({type(exc).__name__}: {text}): the message is '
                    'dropped, the corner keeps its last good pose', INTERNAL)

    def status(self):
        """Return the DiagnosticStatus of this corner."""
        return messages.health_status(self.health, self.status_name, self.scene.name,
                                      self.method)


def corner_topics(scene: Scene, params: dict, prefix: str = '') -> list[str]:
    """
    Return the relative names of a corner's topics (prefix: '' or 'front_left/').

    /diagnostics and the vehicle's joint_states are not among them.
    """
    outputs = [o.name for o in outputs_of(scene, params) if o.name != TF]
    answer = [name for name in outputs if name in ANSWER_TYPES]   # the pose, camber, toe
    names = ['wheel_travel', *answer]
    if params['travel_joint']:
        names.append('joint_states')
    if scene.steered:
        names.append('steering_rack')
    if wants_statics(scene, params.get('statics')):
        names.append(CONTACT_WRENCH)
    names += [name for name in outputs if name not in answer and name != PICKUP]
    if PICKUP in outputs:
        from ..answer.pickups import pickup_points
        names += [f'{PICKUP}/{name}' for name in pickup_points(scene)]
    return [prefix + name for name in names]


def corner_outputs(scene: Scene, params: dict, prefix: str = '') -> dict[str, str]:
    """Return {relative name: 'publisher' or 'subscription'} of a corner's topics."""
    inputs = {prefix + name for name in ('wheel_travel', 'joint_states', 'steering_rack',
                                         CONTACT_WRENCH)}
    return {name: 'subscription' if name in inputs else 'publisher'
            for name in corner_topics(scene, params, prefix)}


def joints_sent(topic: str, msg: JointStateRead | JointState, joints: list[str]) -> str:
    """
    Say what a JointState sent for joints: '/joint_states front_left_travel 0.02 m'.

    msg: as answer/cdr.joint_state_of reads it, or an rclpy JointState.
    """
    positions = dict(zip(msg.name, msg.position))
    return f'{topic} ' + ', '.join(f'{joint} {positions[joint]!r} m' for joint in joints
                                   if joint in positions)
