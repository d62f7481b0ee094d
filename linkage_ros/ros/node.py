"""
suspension_node: wheel travel in; wheel-carrier pose, camber, toe and solver health out.

A thin adapter over the kinematics core (linkage_ros.core.kinematics.Continuation): each command
is solved from the last good pose (large jumps walked in substeps of max_step_mm), turned
into SI messages by linkage_ros.ros.messages, and published. Outputs answer a stamped input
(JointState) with its header stamp, a Float64 with the node clock's time of receipt (simulated
time with use_sim_time). A bad command (NaN, inf, out of reach) publishes no pose, only an
ERROR diagnostic saying why; the core keeps the last good state.

Topics (names relative to the node's namespace, /diagnostics absolute):
    sub wheel_travel        std_msgs/Float64            m, + = bump
    sub joint_states        sensor_msgs/JointState      position of joint travel_joint (m, + =
                                                        bump); only if travel_joint is set
    pub wheel_carrier_pose  geometry_msgs/PoseStamped   wheel centre (m) in frame_id, carrier
                                                        orientation relative to design
    pub camber, toe         std_msgs/Float64            rad (+ = top outboard, + = toe-in)
    sub steering_rack       std_msgs/Float64            m, + = rack to the left; solved at the
                                                        last travel; only if the scene has a
                                                        steer: rack link
    pub /diagnostics        diagnostic_msgs/DiagnosticArray  one status per corner every
                                                        diagnostic_period s (the diagnostic_updater
                                                        convention), and at once for a bad
                                                        command or a change of level
    pub alignment           std_msgs/Float64MultiArray  messages.ALIGNMENT_FIELDS in SI, each
                                                        named by its layout dim label; only if
                                                        parameter alignment is true
    pub markers             visualization_msgs/MarkerArray  links and joints (m, frame_id); only
                                                        if parameter markers is true
All reliable, keep-last QOS_DEPTH (1000), so a burst of 1000 commands is not lost.

With parameter vehicle (a vehicle file, linkage_ros.core.vehicle) the node serves every corner:
each Corner has its own Continuation and the topics above under its name (front_left/
wheel_travel, front_left/camber, ...; steering_rack only where the corner steers), one
diagnostic status per corner named after it; parameter scene is then not used. Corners whose
vehicle entry names a travel_joint (and rack_joint) are also answered from one joint_states
topic: every named corner of a message in one callback, at the message's header stamp.
record_mcap records every corner; rerun_rrd writes one file showing the whole vehicle, each
corner's entities under its name (front_left/suspension/..., plots/front_left/camber_deg).

Sinks (recorders, viewers) receive every command and every published message; the MCAP and
Rerun modules are imported only when record_mcap or rerun_rrd is set.
"""

import contextlib
import difflib
import math
from pathlib import Path
import signal
import sys
import textwrap
import time

from builtin_interfaces.msg import Time
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import PoseStamped
from rcl_interfaces.msg import ParameterDescriptor
import rclpy
from rclpy.exceptions import ParameterException
from rclpy.executors import ExternalShutdownException
from rclpy.experimental import EventsExecutor
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64, Float64MultiArray
from visualization_msgs.msg import MarkerArray

from . import messages
from .health import Health
from ..cdr import float64_of, to_cdr, type_name
from ..cli import held_stderr, missing_package, writable_file
from ..core.errors import LinkageError
from ..core.kinematics import Continuation
from ..core.scene import load_scene

NODE_NAME = 'suspension_kinematics'
QOS_DEPTH = 1000
BAD_COMMAND_PERIOD = 5.0   # s: the console names each kind of bad command at most this often
QOS = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=QOS_DEPTH,
                 reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.VOLATILE)
OUTPUTS = {'wheel_carrier_pose': PoseStamped, 'camber': Float64, 'toe': Float64}

# name: (default, description). Numbers accept integers too (a YAML 5 means 5.0).
PARAMETERS = {
    'scene': ('five_link', 'bundled scene name or path to a scene YAML file'),
    'frame_id': ('base_link', "frame of wheel_carrier_pose (the scene's vehicle frame)"),
    'method': ('fast', 'solver: fast (pose Newton) or paper (Gauss-Jordan, Alexandru 2018)'),
    'max_step_mm': (5.0, 'longest continuation substep, mm (> 0)'),
    'condition_warn': (1e4, 'Jacobian condition number above which diagnostics say WARN'),
    'diagnostic_period': (1.0, 'seconds between /diagnostics reports, on the node clock (> 0)'),
    'record_mcap': ('', 'path of an MCAP file recording commands and outputs; empty = off'),
    'rerun_rrd': ('', 'path of a Rerun .rrd file mirroring the poses; empty = off'),
    'travel_joint': ('', 'joint of sensor_msgs/JointState on joint_states whose position is '
                     'the wheel travel (m, + = bump); empty = joint_states not subscribed'),
    'alignment': (False, 'publish the alignment set (std_msgs/Float64MultiArray) per answer'),
    'markers': (False, 'publish links and joints (visualization_msgs/MarkerArray) per answer'),
    'vehicle': ('', 'vehicle file (bundled name or path): one corner per wheel, topics under '
                'the corner name; empty = the single scene of parameter scene'),
}


def corner_topics(scene, params, prefix=''):
    """
    Return the relative names of a corner's topics (prefix: '' or 'front_left/').

    /diagnostics and the vehicle's joint_states are not among them.
    """
    names = ['wheel_travel', *OUTPUTS]
    if params['travel_joint']:
        names.append('joint_states')
    if steered(scene):
        names.append('steering_rack')
    names += [name for name in ('alignment', 'markers') if params[name]]
    return [prefix + name for name in names]


def steered(scene):
    """Tell whether the scene has a steer: rack link (then it takes steering_rack commands)."""
    return any(c.steer == 'rack' for c in scene.constraints)


def load_corners(params):
    """
    Load the scenes the parameters name: {topic prefix: (Scene, travel joint, rack joint)}.

    The one scene under no prefix, or every corner of the vehicle parameter under
    'corner_name/' with the joint_states joints its vehicle file names ('' where none).
    """
    if not params['vehicle']:
        return {'': (load_scene(params['scene']), '', '')}
    from ..core.vehicle import load_vehicle
    vehicle = load_vehicle(params['vehicle'])
    return {f'{name}/': (scene, *vehicle.joints.get(name, ('', '')))
            for name, scene in vehicle.corners.items()}


class Corner:
    """
    One wheel of the node.

    Its scene, its Continuation (solved independently of the other corners), its Health, its
    input subscriptions and output publishers, topics under prefix ('' or 'front_left/').
    """

    def __init__(self, node, scene, params, prefix='', travel_joint='', rack_joint=''):
        self.node, self.scene = node, scene
        self.solver = Continuation(scene, method=params['method'],
                                   max_step=params['max_step_mm'])
        self.health = Health(params['condition_warn'])
        self.status_name = f'{node.get_name()}: {scene.name}'
        self.travel_joint, self.rack_joint = travel_joint, rack_joint   # vehicle joint_states
        self.publishers = {name: node.create_publisher(kind, prefix + name, QOS)
                           for name, kind in OUTPUTS.items()}
        # Float64 commands come raw (CDR): reading the 8 bytes in place costs a fraction of
        # building the rclpy message.
        self.travel_sub = node.create_subscription(Float64, prefix + 'wheel_travel',
                                                   self.on_travel, QOS, raw=True)
        self.joint = params['travel_joint']
        if self.joint:   # off by default: no subscription, no discovery traffic
            self.joint_sub = node.create_subscription(JointState, prefix + 'joint_states',
                                                      self.on_joint_states, QOS)
        if steered(scene):
            self.rack_sub = node.create_subscription(Float64, prefix + 'steering_rack',
                                                     self.on_rack, QOS, raw=True)
        self.extras = []   # (publisher, function(solution, stamp) -> message)
        if params['alignment']:
            from ..core.alignment import alignment
            self.extras.append((
                node.create_publisher(Float64MultiArray, prefix + 'alignment', QOS),
                lambda solution, stamp: messages.alignment_array(alignment(
                    scene, self.solver.mech, solution.wheel_center, solution.rotation,
                    solution.rack))))
        if params['markers']:
            from .markers import marker_array
            self.extras.append((
                node.create_publisher(MarkerArray, prefix + 'markers', QOS),
                lambda solution, stamp: marker_array(scene, solution, Time(
                    sec=stamp[0], nanosec=stamp[1]), node.frame_id)))

    def on_travel(self, data):
        stamp = self.node.received(self.travel_sub, data)
        self.answer(messages.command_mm(data), None, stamp,
                    lambda: f'{self.travel_sub.topic_name} {float64_of(data)!r} m')

    def on_rack(self, data):
        # A new rack at the last travel: Continuation keeps the travel it was last solved at.
        stamp = self.node.received(self.rack_sub, data)
        self.answer(None, messages.command_mm(data), stamp,
                    lambda: f'{self.rack_sub.topic_name} {float64_of(data)!r} m')

    def on_joint_states(self, msg):
        stamp = self.node.received(self.joint_sub, msg, msg.header.stamp)
        travel_mm = messages.joint_travel_mm(msg, self.joint)
        if travel_mm is not None:   # other joints' messages are not commands: no answer
            self.answer(travel_mm, None, stamp, lambda: joints_sent(
                self.joint_sub.topic_name, msg, [self.joint]))

    def answer(self, travel_mm, rack_mm, stamp, sent):
        """
        Solve a command and publish the answer.

        travel_mm and rack_mm: the command (None = unchanged); stamp: (sec, nanosec) of the
        answer; sent: a function that says what was sent where (e.g. '/wheel_travel 0.5 m'),
        called for the messages about a bad command. A failure or a change of level goes to
        /diagnostics at once, and a failure to the console too (once per kind of mistake and
        throttle period), with the value sent in the unit it was sent in (m).
        """
        travel = self.solver.travel if travel_mm is None else travel_mm
        solution = self.solver.solve(travel, rack_mm)
        if solution.success:
            for name, data in messages.answer(solution, stamp, self.node.frame_id):
                self.node.publish(self.publishers[name], data)
            for publisher, build in self.extras:
                self.node.publish(publisher, build(solution, stamp))
            said = ''
        else:
            said = sent()
            self.node.bad_command(said, solution)
        if self.health.add(solution, said):
            self.node.report([self])

    def status(self):
        return messages.health_status(self.health, self.status_name, self.scene.name,
                                      self.node.method)


class SuspensionNode(Node):
    """
    Wheel travel (m) in; wheel-carrier pose (m), camber and toe (rad), diagnostics out.

    One scene, or every corner of a vehicle (parameter vehicle), each a Corner.
    """

    def __init__(self, sinks=(), **kwargs):
        """
        Declare the parameters, load the scenes and open the sinks, topics and timer.

        sinks: extra objects with record(topic, type_name, cdr_bytes, receive_ns, publish_ns)
        and close(), after those the parameters turn on. kwargs go to rclpy Node.
        """
        super().__init__(NODE_NAME, **kwargs)
        self.sinks, self.faults, self._bad_said = [], [], {}
        self.clock = self.get_clock()
        try:
            params = self._declare_parameters()
            corners = load_corners(params)
            scenes = {prefix: scene for prefix, (scene, _, _) in corners.items()}
            self.sinks = open_sinks(params, scenes,
                                    self._offered_qos(corners, params)) + list(sinks)
            self.frame_id, self.method = params['frame_id'], params['method']
            self.diagnostics_pub = self.create_publisher(DiagnosticArray, '/diagnostics', QOS)
            self.corners = {prefix.rstrip('/'): Corner(self, scene, params, prefix, *joints)
                            for prefix, (scene, *joints) in corners.items()}
        except BaseException:
            self.close_sinks()
            super().destroy_node()
            raise
        self.joint_corners = [c for c in self.corners.values()
                              if c.travel_joint or c.rack_joint]
        if self.joint_corners:
            self.joint_states_sub = self.create_subscription(
                JointState, 'joint_states', self.on_vehicle_joint_states, QOS)
        self.create_timer(params['diagnostic_period'], self.on_diagnostic_period)
        for corner in self.corners.values():
            self.get_logger().info(
                f'scene {corner.scene.name} ({corner.scene.source}), method {self.method}, '
                f'frame {self.frame_id}; waiting on {corner.travel_sub.topic_name} (m)')

    def received(self, subscription, msg, stamp=None):
        """
        Record an input that came on subscription (if recording); return its answer's stamp.

        The stamp (sec, nanosec) is stamp's (a builtin_interfaces/Time), or the node clock's
        time of receipt.
        """
        if stamp is None or self.sinks:
            now = self.clock.now()
            if self.sinks:   # the input's publish time is unknown: EventsExecutor gives no info
                self._record(subscription.topic_name, subscription.msg_type,
                             to_cdr(msg), now.nanoseconds, now.nanoseconds)
            if stamp is None:
                return now.seconds_nanoseconds()
        return stamp.sec, stamp.nanosec

    def on_vehicle_joint_states(self, msg):
        """Answer every corner whose joints a JointState (for the whole vehicle) names."""
        stamp = self.received(self.joint_states_sub, msg, msg.header.stamp)
        for corner in self.joint_corners:
            travel_mm = messages.joint_travel_mm(msg, corner.travel_joint)
            rack_mm = messages.joint_travel_mm(msg, corner.rack_joint) if corner.rack_joint \
                else None
            if travel_mm is not None or rack_mm is not None:
                corner.answer(travel_mm, rack_mm, stamp, lambda corner=corner: joints_sent(
                    self.joint_states_sub.topic_name, msg,
                    [corner.travel_joint, corner.rack_joint]))

    def on_diagnostic_period(self):
        for sink in list(self.sinks):      # a recorder writing in the background may fail
            if getattr(sink, 'error', None):
                self._drop(sink, sink.error)
        self.report(self.corners.values())
        for corner in self.corners.values():
            corner.health.reset_period()

    def bad_command(self, sent, solution):
        """
        Say on the console that a command could not be answered (solution: its failure).

        Once per kind of failure (solution.status) and BAD_COMMAND_PERIOD s, with the count of
        the same kind held back since: a stream of bad commands must not flood the console;
        /diagnostics reports every one.
        """
        kind, why = solution.status, solution.message
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

    def publish(self, publisher, msg):
        """Publish msg (CDR bytes or an rclpy message) and hand it to the sinks."""
        # Recorded first: a SIGINT can surface as KeyboardInterrupt inside publish() after
        # the message left, and the recording must still hold what subscribers got.
        if self.sinks:
            published = self.clock.now().nanoseconds
            self._record(publisher.topic_name, publisher.msg_type, to_cdr(msg),
                         published, published)
        publisher.publish(msg)

    def _record(self, topic, msg_type, data, receive_ns, publish_ns):
        for sink in list(self.sinks):
            try:
                sink.record(topic, type_name(msg_type), data, receive_ns, publish_ns)
            except Exception as exc:  # a broken recorder must not stop the node
                self._drop(sink, getattr(sink, 'error', None) or str(exc))

    def _drop(self, sink, reason):
        """
        Stop feeding a sink that failed, and say so until the node stops.

        Every corner's status turns ERROR, naming the file, the reason and the time, at once
        and in every report after it: data is no longer being recorded. The node goes on
        answering commands.
        """
        self.sinks.remove(sink)
        self._close(sink)
        when = self.clock.now().nanoseconds / 1e9
        fault = (f'{type(sink).__name__} {getattr(sink, "path", "")} stopped at t = '
                 f'{when:.3f} s ({time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime(when))}):'
                 f' {reason}; nothing is recorded since')
        self.get_logger().error(fault)
        self.faults.append(fault)
        for corner in self.corners.values():
            corner.health.set_fault('; '.join(self.faults))
        self.report(self.corners.values())

    def close_sinks(self):
        """Close every sink once (files are finished here); later calls do nothing."""
        sinks, self.sinks = self.sinks, []
        for sink in sinks:
            self._close(sink)

    def _close(self, sink):
        try:
            sink.close()
        except Exception as exc:  # one failing sink must not keep the others open
            self.get_logger().error(f'closing {type(sink).__name__}: {exc}')

    def destroy_node(self):
        self.close_sinks()
        super().destroy_node()

    def _offered_qos(self, corners, params):
        """
        Return {resolved topic: QoS} of every topic, for the recording's metadata.

        corners as load_corners gives them.
        """
        names = ['/diagnostics']
        for prefix, (scene, *joints) in corners.items():
            names += corner_topics(scene, params, prefix)
            if any(joints):
                names.append('joint_states')
        return {self.resolve_topic_name(name): QOS for name in dict.fromkeys(names)}

    def _declare_parameters(self):
        values = {}
        for name, (default, description) in PARAMETERS.items():
            numeric = isinstance(default, float)
            descriptor = ParameterDescriptor(description=description, read_only=True,
                                             dynamic_typing=numeric)
            value = self.declare_parameter(name, default, descriptor).value
            values[name] = positive_number(name, value) if numeric else value
        # rclpy ignores an override of a parameter nobody declares: a misspelt -p would be
        # silently without effect. rclpy keeps the overrides only in this attribute.
        for name in self._parameter_overrides:
            if not self.has_parameter(name) and not name.startswith('qos_overrides.'):
                raise LinkageError(f'parameter {name}', unknown_parameter(name))
        return values


def unknown_parameter(name):
    """Say that a parameter name is unknown, suggest the closest, list the known ones."""
    close = difflib.get_close_matches(name, PARAMETERS, n=1)
    guess = f'did you mean {close[0]}? ' if close else ''
    return f'not a parameter of suspension_node ({guess}known: {", ".join(PARAMETERS)})'


def joints_sent(topic, msg, joints):
    """Say what a JointState sent for joints: '/joint_states front_left_travel 0.02 m'."""
    positions = dict(zip(msg.name, msg.position))
    return f'{topic} ' + ', '.join(f'{joint} {positions[joint]!r} m' for joint in joints
                                   if joint in positions)


def positive_number(name, value):
    """Return value as a float if finite and > 0, else raise a ValueError naming the parameter."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise LinkageError(name, f'expected a number, got {value!r}')
    if not (math.isfinite(value) and value > 0):
        raise LinkageError(name, f'must be a finite number above 0, got {value!r}')
    return float(value)


@contextlib.contextmanager
def named(parameter):
    """Say which parameter a recorder that cannot start came from (/dev/full, say)."""
    try:
        yield
    except LinkageError as exc:
        raise LinkageError(parameter, str(exc)) from None


def open_sinks(params, scenes, qos):
    """
    Open the sinks the parameters turn on; their modules are imported only then.

    scenes: {topic prefix: Scene} of load_corners. qos: {topic: QoSProfile} the node offers,
    stored in the MCAP channel metadata. With a vehicle, the one Rerun recording draws every
    corner under its name. An output that cannot be written or a missing package raises
    LinkageError naming the parameter, before any command is taken.
    """
    for name in ('record_mcap', 'rerun_rrd'):
        problem = params[name] and writable_file(params[name])
        if problem:
            raise LinkageError(name, problem)
    sinks = []
    try:
        if params['record_mcap']:
            try:
                from ..record.mcap_writer import McapRecorder
            except ImportError as exc:
                raise LinkageError('record_mcap',
                                   missing_package(exc, 'recording to MCAP')) from None
            about = {k: str(params[k])
                     for k in ('scene', 'vehicle', 'method', 'frame_id', 'max_step_mm')}
            with named('record_mcap'):
                sinks.append(McapRecorder(params['record_mcap'], qos=qos, custom_data=about))
        if params['rerun_rrd']:
            try:
                from ..record.rerun_view import RerunRecorder
            except ImportError as exc:   # pyarrow comes with rerun-sdk: name the package
                raise LinkageError('rerun_rrd', missing_package(exc, 'mirroring to Rerun')) \
                    from None
            with named('rerun_rrd'):
                if '' in scenes:
                    sinks.append(RerunRecorder(params['rerun_rrd'], scenes['']))
                else:
                    sinks.append(RerunRecorder(params['rerun_rrd'], corners={
                        prefix.rstrip('/'): scene for prefix, scene in scenes.items()}))
    except BaseException:
        for sink in sinks:
            sink.close()
        raise
    return sinks


def spin_until_shutdown(executor):
    """Spin until SIGINT (KeyboardInterrupt) or SIGTERM (ExternalShutdownException)."""
    # Finite timeouts on purpose: with rclpy 7.1.6, EventsExecutor.spin() and spin_once()
    # without a timeout busy-wait holding the GIL and never run a callback.
    while True:
        executor.spin_once(timeout_sec=3600.0)


HELP = """usage: suspension_node [--help] [--ros-args -p NAME:=VALUE ... --params-file FILE]

Wheel travel in; wheel-carrier pose, camber, toe and solver health out (ROS 2, SI units).

parameters (-p NAME:=VALUE after --ros-args, or a params file under /**: ros__parameters:):
{parameters}
topics (relative names; a vehicle puts each corner's under its name, e.g. front_left/):
  in   wheel_travel        std_msgs/Float64           m, + = bump
  in   steering_rack       std_msgs/Float64           m, + = rack to the left (scenes with a
                                                      steer: rack link)
  in   joint_states        sensor_msgs/JointState     travel_joint's position, m (and the
                                                      joints a vehicle file names)
  out  wheel_carrier_pose  geometry_msgs/PoseStamped  wheel centre (m) in frame_id, rotation
                                                      relative to design
  out  camber, toe         std_msgs/Float64           rad, + = top outboard, + = toe-in
  out  /diagnostics        diagnostic_msgs/DiagnosticArray  every diagnostic_period, and at
                                                      once for a bad command or a new level
  out  alignment, markers  Float64MultiArray, MarkerArray (when turned on)

example:
  ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST suspension_node --ros-args -p scene:=macpherson \\
      -p record_mcap:=run.mcap

exit status: 0 stopped by Ctrl-C (SIGINT) or SIGTERM, recordings closed;
             2 a mistake: unknown parameter, bad value, bad scene or vehicle file, an output
               file that cannot be written, a missing optional package (one line on stderr)
"""


def help_text() -> str:
    """Return the text of suspension_node --help: the parameters with their defaults."""
    lines = []
    for name, (default, text) in PARAMETERS.items():
        lines += textwrap.wrap(f'{name:<18} {default!r:<12} {text}', 92,
                               initial_indent='  ', subsequent_indent=' ' * 34)
    return HELP.format(parameters='\n'.join(lines))


def main(args: list[str] | None = None) -> int:
    """Run suspension_node: 0 when stopped by SIGINT or SIGTERM, 2 for a mistake."""
    argv = sys.argv[1:] if args is None else list(args)
    own = argv[:argv.index('--ros-args')] if '--ros-args' in argv else argv
    if {'-h', '--help'} & set(own):          # before ROS starts
        print(help_text(), end='')
        return 0
    if own:
        print(f'suspension_node: unknown argument {own[0]!r}: parameters go after --ros-args, '
              'as -p name:=value (see suspension_node --help)', file=sys.stderr)
        return 2
    # A file-size limit (ulimit -f) would kill the process at the limit: make it an error of
    # the write instead, which stops the recording and is reported, while the node goes on.
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    try:
        init_ros(argv)
        node = SuspensionNode()
    except (ValueError, OSError, ImportError, ParameterException) as exc:
        # LinkageError (a ValueError): its message names the file, field or parameter.
        print(f'suspension_node: {exc}', file=sys.stderr)
        rclpy.try_shutdown()
        return 2
    return run(node)


def init_ros(argv):
    """
    Start rclpy with the user's arguments; a mistake in them is one LinkageError.

    A params file that is not there, one rcl cannot parse, a bad -p rule, an unknown ROS
    argument: rclpy raises RuntimeError after rcl logged a line of its own, which is held
    back (and shown if rclpy starts after all).
    """
    for option, value in zip(argv, argv[1:]):
        if option == '--params-file' and not Path(value).is_file():
            raise LinkageError(f'--params-file {value}', 'no such file')
    with held_stderr():
        try:
            rclpy.init(args=['suspension_node', *argv])
        except RuntimeError as exc:   # rclpy's RCLError, UnknownROSArgsError
            if type(exc).__name__ == 'UnknownROSArgsError':
                raise LinkageError('--ros-args', f'unknown ROS arguments {exc} (see '
                                   'suspension_node --help)') from None
            # 'failed to initialize rcl: Couldn't parse ...' + ', at /project/src/...'
            problem = ' '.join(str(exc).split(', at /')[0].split())
            raise LinkageError('--ros-args', problem.replace(
                'failed to initialize rcl: ', '')) from None


def run(node):
    """Spin node until SIGINT or SIGTERM, then destroy it and shut down; returns 0."""
    executor = EventsExecutor()
    executor.add_node(node)
    try:
        spin_until_shutdown(executor)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
    return 0


if __name__ == '__main__':
    sys.exit(main())
