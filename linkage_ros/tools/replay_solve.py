# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Solve a stream of wheel-travel commands as suspension_node answers them, into sinks.

    solve_commands(commands, scene, method, sinks, topic)   the answers and /diagnostics

The answering is the node's own (linkage_ros.answer.protocol.Responder, with the node's
parameter defaults); time is the recording's: each command at its receive time, a diagnostics
report every period of it. As the node with TF on (its default), the recording also carries
/tf_static and /robot_description once, at the first command's time, and /tf per solved command
(linkage_ros.answer.frames, built without tf2_msgs); a scene with elements, their JointState
per solved command (answer/elements.py), as the node publishes it. Rack commands and the node's
run-time parameter changes (a new scene, new solver settings) are replayed in their recorded
order, as the node took them. What a solved command publishes is the Responder's list, as on
the node (protocol.OUTPUTS).
"""

from .replay_commands import DEFAULT_TOPIC, FLOAT64, stamp_of
from ..answer.protocol import Responder
from ..core.base import MM_PER_M

DIAGNOSTIC_ARRAY = 'diagnostic_msgs/msg/DiagnosticArray'
DIAGNOSTICS_TOPIC = '/diagnostics'
DESCRIPTION_TOPIC = '/robot_description'


def latched_topics():
    """Return {topic: QoS in rosbag2's form} of the latched topics a replay writes."""
    from ..answer.frames import TF_STATIC_TOPIC
    from ..record.interfaces import DEFAULT_QOS
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


class _Corner:
    """
    The corner a replay answers as: its Responder and TF frames, for its scene.

    change() takes the node's run-time parameter changes as ros/runtime.py applies them.
    """

    def __init__(self, scene, method, frame_id, prefix, period_s):
        self.settings = {**node_defaults(), 'method': method, 'frame_id': frame_id,
                         'diagnostic_period': period_s}
        self.prefix = prefix
        self.responder = None
        self._build(scene)

    def _build(self, scene):
        from ..answer.frames import CornerFrames, tf2_msgs_missing
        old, s = self.responder, self.settings
        self.scene = scene
        self.responder = Responder(scene, method=s['method'], max_step_mm=s['max_step_mm'],
                                   condition_warn=s['condition_warn'], frame_id=s['frame_id'],
                                   status_name=status_name(scene),
                                   period_ns=int(round(s['diagnostic_period'] * 1e9)),
                                   prefix=self.prefix)
        if old is not None:
            self.responder.follow(old)
        # the node's outputs with its defaults: TF on, alignment and markers off; the
        # scene's elements for a scene with elements (protocol.OUTPUTS); with statics, the
        # pickups' frames, which its pickup wrenches name (ros/tf_outputs.py)
        # (as ros/tf_outputs.py: only where tf2_msgs imports; else the wrenches name frame_id)
        statics = self.responder.statics
        pickups = statics is not None and not tf2_msgs_missing()
        self.frames = CornerFrames(scene, s['frame_id'], self.prefix,
                                   statics.frame_points() if pickups else None)
        self.responder.set_outputs(frames=self.frames)

    def take_wrench(self, data):
        """
        Take a recorded contact wrench as the node does (ros/corner.Corner.on_wrench).

        Returns '' if taken, else why it is refused (not finite, another frame, no statics):
        the caller counts the refusal into the health and reports at once, as the node does.
        """
        from ..answer.cdr import wrench_of
        return self._take(*wrench_of(data))

    def _take(self, frame_id, force, torque):
        from ..answer.protocol import wrench_problem
        problem = wrench_problem(frame_id, force, torque, self.settings['frame_id'])
        if self.responder.statics is None:
            problem = (f'scene {self.scene.name} has no bushings and parameter statics is '
                       'false: a contact wrench moves nothing')
        if not problem:
            self.responder.statics.set_wrench(force, torque)
        return problem

    def take_request(self, data, service):
        """
        Return (travel_mm, rack_mm, sent, problem) of a recorded solve request, its wrench taken.

        As ros/solve_service.SolveAnswers.solve takes it. The node records only the requests
        it takes; a recording that holds one whose wrench the node refuses (not finite,
        beyond the bound, no statics: a file not written by the node) gets the node's
        refusal: problem says why ('' if taken), and the request is not answered.
        """
        from ..answer.cdr import solve_request_of
        _, travel, rack, force, torque, use_wrench = solve_request_of(data)
        sent = f'{service} travel {travel!r} m, rack {rack!r} m'   # as the node says it
        if use_wrench:
            problem = self._take(self.settings['frame_id'], force, torque)
            if problem:
                return None, None, sent, problem
        travel_mm, rack_mm = travel * MM_PER_M, rack * MM_PER_M
        if not self.scene.steered and rack_mm == 0.0:
            rack_mm = None    # no rack link: the rack stays where it is (none)
        return travel_mm, rack_mm, sent, ''

    def change(self, values, scenes, time_ns):
        """
        Apply a change's values as the node does; return True if the scene changed.

        scenes: {scene parameter value: Scene} loaded for the changes.
        """
        solver = {k: v for k, v in values.items()
                  if k in ('method', 'max_step_mm', 'condition_warn')}
        self.settings.update(solver)
        if 'diagnostic_period' in values:    # the node's timer starts again at the change
            self.settings['diagnostic_period'] = values['diagnostic_period']
            self.responder.restart_period(round(values['diagnostic_period'] * 1e9), time_ns)
        if 'scene' in values:
            self._build(scenes[values['scene']])
            return True
        if solver:
            self._build(self.scene)
        return False


def solve_commands(commands, scene, method, sinks, topic=DEFAULT_TOPIC, progress=None,
                   frame_id=None, period_s=None, changes=(), scenes=None):
    """
    Solve each command as the node does; hand it and what the node publishes to each sink.

    Sinks: McapRecorder, RerunRecorder (.record(topic, type, CDR, t, t_pub)). On the recorded
    timeline: pose, camber and toe for a solved command, at its receive time; /diagnostics
    as the node sends them (Responder): a report every period_s of recorded time (default:
    the node's diagnostic_period), at once for a failed command or a change of level, and a
    last one after the last command (a gap in the commands gives one report, not one per
    period). Outputs are in the command topic's namespace; frame_id defaults to the node's.

    commands: travel and rack commands (replay_commands.Command) in the order received, rack
    ones solved at the last travel; contact wrenches among them (kind WRENCH) are taken as
    the node takes them (ros/corner.Corner.on_wrench: protocol.wrench_problem refuses a
    wrench not finite or in another frame, an ERROR reported at once) and held for the
    answers after them (the loaded pose, the pickups' forces); solve service requests (kind
    SOLVE) are answered as the service answers them, travel and rack at once (ros/
    solve_service.py). changes: the node's run-time parameter changes (replay_commands.Change),
    each applied at its time as ros/runtime.py applies it, and recorded on /parameter_events:
    new solver settings at the pose held; a new scene (scenes: {scene parameter value:
    Scene}) from its design position, with its /tf_static and robot_description sent again
    and /diagnostics at once, as the node does.

    Frames: those of the node's corner in the command topic's namespace ('' for /wheel_travel,
    'front_left/' for /front_left/wheel_travel), in frame_id.

    Returns the number of commands that could not be solved.
    """
    from .replay_commands import beside, PARAMETER_EVENT, PARAMETER_EVENTS, RACK, rack_topic, \
        SOLVE, SOLVE_TOPIC, WRENCH, WRENCH_TYPE, wrench_topic
    from ..answer.cdr import SOLVE_REQUEST
    from ..answer.cdr import float64_cdr, string_cdr, to_cdr
    from ..answer.frames import static_cdr, TF_STATIC_TOPIC, TF_TYPE
    from ..answer.robot_description import robot_description
    from ..record.interfaces import qualified
    from ..ros import messages
    defaults = node_defaults()
    topic = qualified(topic)
    rack, wrench, solve = rack_topic(topic), wrench_topic(topic), beside(topic, SOLVE_TOPIC)
    namespace = topic.rsplit('/', 1)[0]
    period_s = defaults['diagnostic_period'] if period_s is None else period_s
    frame_id = frame_id or defaults['frame_id']
    prefix = namespace.strip('/') + '/' if namespace.strip('/') else ''
    corner = _Corner(scene, method, frame_id, prefix, period_s)

    def emit(name, type_name, data, time_ns, publish_ns=None):
        for sink in sinks:
            sink.record(name, type_name, data, time_ns,
                        time_ns if publish_ns is None else publish_ns)

    def report(time_ns):
        responder = corner.responder
        status = messages.health_status(responder.health, responder.status_name,
                                        corner.scene.name, corner.settings['method'])
        emit(DIAGNOSTICS_TOPIC, DIAGNOSTIC_ARRAY,
             to_cdr(messages.diagnostics([status], stamp_of(time_ns))), time_ns)

    def describe(time_ns):     # what the node sends at start and after a scene change, latched
        emit(TF_STATIC_TOPIC, TF_TYPE, static_cdr([corner.frames], divmod(time_ns, 10**9)),
             time_ns)
        emit(DESCRIPTION_TOPIC, 'std_msgs/msg/String', string_cdr(robot_description(
            {prefix: corner.scene}, frame_id, corner.scene.name)), time_ns)

    pending = list(changes)

    def apply_changes(until):     # the changes recorded by time until (ns), as the node did
        while pending and pending[0].log_time <= until:
            change = pending.pop(0)
            emit(PARAMETER_EVENTS, PARAMETER_EVENT, change.data, change.log_time)
            if corner.change(change.values, scenes or {}, change.log_time):
                describe(change.log_time)
                report(change.log_time)

    failures, t = 0, 0
    if commands:
        describe(commands[0].log_time)
    for i, command in enumerate(commands):
        t = command.log_time
        apply_changes(t)
        responder = corner.responder
        due = responder.due(t)
        if due is not None:           # the period ended before this command
            report(due)
            responder.health.reset_period()
        if command.kind == WRENCH:     # taken for the answers that follow; answers nothing
            emit(wrench, WRENCH_TYPE, command.data, t, command.publish_time)
            problem = corner.take_wrench(command.data)
            if problem:               # refused as the node refuses it: ERROR, at once
                responder.health.refuse(f'{wrench}: {problem}')
                report(t)
            if progress:
                progress.update(i + 1)
            continue
        if command.kind == SOLVE:      # a solve service request: travel and rack at once
            travel_mm, rack_mm, sent, problem = corner.take_request(command.data,
                                                                    prefix + SOLVE_TOPIC)
            if problem:     # refused as the node refuses it: ERROR at once, not recorded
                responder.health.refuse(f'{solve}: {problem}')
                responder.health.refuse_request()
                report(t)
                if progress:
                    progress.update(i + 1)
                continue
            emit(solve, SOLVE_REQUEST, command.data, t, command.publish_time)
        else:
            name = rack if command.kind == RACK else topic
            emit(name, FLOAT64, float64_cdr(command.travel), t, command.publish_time)
            value_mm = command.travel * MM_PER_M      # as messages.command_mm reads it
            travel_mm, rack_mm = (None, value_mm) if command.kind == RACK else (value_mm, None)
            sent = lambda: f'{name} {command.travel!r} m'  # noqa: E731 (only on failure)
        reply = responder.answer(travel_mm, rack_mm, divmod(t, 10**9), sent)
        for output, type_name, data in reply.outputs:     # the node's list, in its order
            emit(output if output.startswith('/') else f'{namespace}/{output}', type_name,
                 data, t)
        failures += not reply.solution.success
        if reply.report:
            report(t)
        if progress:
            progress.update(i + 1)
    if commands:
        report(t)
        apply_changes(pending[-1].log_time if pending else t)   # those after the last command
    return failures
