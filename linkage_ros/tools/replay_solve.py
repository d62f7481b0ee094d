"""
Solve a stream of wheel-travel commands as suspension_node answers them, into sinks.

    solve_commands(commands, scene, method, sinks, topic)   the answers and /diagnostics
    benchmark(commands, scene, method)                     us per command, with each sink

The answering is the node's own (linkage_ros.protocol.Responder, with the node's parameter
defaults); time is the recording's: each command at its receive time, a diagnostics report
every period of it. As the node with TF on (its default), the recording also carries
/tf_static and /robot_description once, at the first command's time, and /tf per solved
command (linkage_ros.ros.tf, built without tf2_msgs); a scene with elements, their JointState
per solved command (ros/element_outputs.py), as the node publishes it.
"""

import math
from pathlib import Path
import sys
import time

from .replay_commands import DEFAULT_TOPIC, FLOAT64, stamp_of
from ..core.base import LinkageError
from ..protocol import Responder

DIAGNOSTIC_ARRAY = 'diagnostic_msgs/msg/DiagnosticArray'
JOINT_STATE = 'sensor_msgs/msg/JointState'
DIAGNOSTICS_TOPIC = '/diagnostics'
DESCRIPTION_TOPIC = '/robot_description'


def latched_topics():
    """Return {topic: QoS in rosbag2's form} of the latched topics a replay writes."""
    from ..record.interfaces import DEFAULT_QOS
    from ..ros.tf import TF_STATIC_TOPIC
    latched = {**DEFAULT_QOS, 'depth': 1, 'durability': 'transient_local'}
    return {TF_STATIC_TOPIC: latched, DESCRIPTION_TOPIC: dict(latched)}


def node_defaults():
    """Return the node's defaults that replay answers with: {parameter name: value}."""
    from ..ros.node import PARAMETERS
    names = ('frame_id', 'max_step_mm', 'condition_warn', 'diagnostic_period')
    return {name: PARAMETERS[name][0] for name in names}


def status_name(scene):
    """Return the name of the DiagnosticStatus the node (default name) gives scene's corner."""
    from ..ros.messages import status_name as named
    from ..ros.node import NODE_NAME
    return named('/' + NODE_NAME, scene.name)


def solve_commands(commands, scene, method, sinks, topic=DEFAULT_TOPIC, progress=None,
                   frame_id=None, period_s=None):
    """
    Solve each command as the node does; hand it and what the node publishes to each sink.

    Sinks: McapRecorder, RerunRecorder (.record(topic, type, CDR, t, t_pub)). On the recorded
    timeline: pose, camber and toe for a solved command, at its receive time; /diagnostics
    as the node sends them (Responder): a report every period_s of recorded time (default:
    the node's diagnostic_period), at once for a failed command or a change of level, and a
    last one after the last command (a gap in the commands gives one report, not one per
    period). Outputs are in the command topic's namespace; frame_id defaults to the node's.

    Frames: those of the node's corner in the command topic's namespace ('' for /wheel_travel,
    'front_left/' for /front_left/wheel_travel), in frame_id.

    Returns the number of commands that could not be solved.
    """
    from ..cdr import float64_cdr, string_cdr, to_cdr
    from ..record.interfaces import qualified
    from ..robot_description import robot_description
    from ..ros import messages
    from ..ros.element_outputs import TOPIC as ELEMENTS_TOPIC
    from ..ros.tf import CornerFrames, static_cdr, TF_STATIC_TOPIC, TF_TOPIC, TF_TYPE
    defaults = node_defaults()
    topic = qualified(topic)
    namespace = topic.rsplit('/', 1)[0]
    period_s = defaults['diagnostic_period'] if period_s is None else period_s
    frame_id = frame_id or defaults['frame_id']
    prefix = namespace.strip('/') + '/' if namespace.strip('/') else ''
    frames = CornerFrames(scene, frame_id, prefix)
    responder = Responder(scene, method=method, max_step_mm=defaults['max_step_mm'],
                          condition_warn=defaults['condition_warn'], frame_id=frame_id,
                          status_name=status_name(scene),
                          period_ns=int(round(period_s * 1e9)))

    elements = None
    if scene.elements:     # the node's elements topic (ros/element_outputs.py)
        from ..ros.element_outputs import elements_builder
        elements = elements_builder(scene, responder.solver.mech, frame_id,
                                    lambda: responder.solver.jacobian)

    def emit(name, type_name, data, time_ns, publish_ns=None):
        for sink in sinks:
            sink.record(name, type_name, data, time_ns,
                        time_ns if publish_ns is None else publish_ns)

    def report(time_ns):
        status = messages.health_status(responder.health, responder.status_name, scene.name,
                                        method)
        emit(DIAGNOSTICS_TOPIC, DIAGNOSTIC_ARRAY,
             to_cdr(messages.diagnostics([status], stamp_of(time_ns))), time_ns)

    failures, t = 0, 0
    if commands:     # what the node sends at start, latched
        start = commands[0].log_time
        emit(TF_STATIC_TOPIC, TF_TYPE, static_cdr([frames], divmod(start, 10**9)), start)
        emit(DESCRIPTION_TOPIC, 'std_msgs/msg/String', string_cdr(robot_description(
            {prefix: scene}, frame_id, scene.name)), start)
    for i, command in enumerate(commands):
        t = command.log_time
        due = responder.due(t)
        if due is not None:           # the period ended before this command
            report(due)
            responder.health.reset_period()
        emit(topic, FLOAT64, float64_cdr(command.travel), t, command.publish_time)
        reply = responder.answer(command.travel * 1000.0, None, divmod(t, 10**9),
                                 lambda: f'{topic} {command.travel!r} m')
        for name, type_name, data in reply.outputs:
            emit(f'{namespace}/{name}', type_name, data, t)
        if reply.solution.success and elements is not None:
            emit(f'{namespace}/{ELEMENTS_TOPIC}', JOINT_STATE,
                 elements(reply.solution, divmod(t, 10**9)), t)
        if reply.solution.success:
            emit(TF_TOPIC, TF_TYPE, frames.tf_cdr(reply.solution, divmod(t, 10**9)), t)
        failures += not reply.solution.success
        if reply.report:
            report(t)
        if progress:
            progress.update(i + 1)
    if commands:
        report(t)
    return failures


def benchmark(commands, scene, method, repeat=3, stream=None):
    """
    Time solving the commands alone and with each sink; print a table (us per command).

    'no recording' solves and builds the messages (as the node does to publish them); the
    other rows add McapRecorder, RerunRecorder or both, file closing included. Best of repeat.
    """
    import tempfile

    from ..record.mcap_writer import McapRecorder
    from ..record.rerun_view import RerunRecorder
    if not commands:
        raise LinkageError('bench', 'no commands to time')
    stream = stream or sys.stdout
    modes = {'no recording': lambda d: [],
             'McapRecorder': lambda d: [McapRecorder(d / 'bench.mcap', qos=latched_topics())],
             'RerunRecorder': lambda d: [RerunRecorder(d / 'bench.rrd', scene)],
             'both': lambda d: [McapRecorder(d / 'bench.mcap', qos=latched_topics()),
                                RerunRecorder(d / 'bench.rrd', scene)]}
    messages = 5 * len(commands)   # the command, pose, camber, toe, tf (diagnostics: a few)
    print('mode,commands,us_per_command,ratio,extra_us_per_message', file=stream)
    base = None
    for mode, make in modes.items():
        best = math.inf
        for _ in range(repeat):
            with tempfile.TemporaryDirectory() as folder:
                start = time.perf_counter()
                sinks = make(Path(folder))
                solve_commands(commands, scene, method, sinks)
                for sink in sinks:
                    sink.close()
                best = min(best, time.perf_counter() - start)
        per_command = 1e6 * best / len(commands)
        base = per_command if base is None else base
        extra = 1e6 * best / messages - base * len(commands) / messages
        print(f'{mode},{len(commands)},{per_command:.1f},{per_command / base:.3f},{extra:.1f}',
              file=stream)
