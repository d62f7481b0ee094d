# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The commands linkage-replay works on: read from a bag, or made for a sweep.

    read_commands(path, topic)      -> Commands: the decoded commands, the bag, what was lost
    sweep_commands(scene, ...)      -> [Command] of a travel sweep on a timeline
    parameter_changes(bag)          -> [Change]: the node's run-time parameter changes
    load_changed_scenes(changes)    -> the scenes they name, and the first that does not load
    stored_scene(bag, topic)        -> the scene a recording stores, or None

A command is std_msgs/msg/Float64 in CDR, in m: wheel travel on the command topic, and the
steering rack on steering_rack in its namespace (/front_left/wheel_travel:
/front_left/steering_rack), both in the recorded order, as the node answered them. Beside
them, the contact wrenches the node took on contact_wrench in that namespace
(geometry_msgs/msg/WrenchStamped, kind WRENCH, its CDR kept): replayed in their place among
the commands, answering nothing, as the node took them; and the requests its solve service
took, recorded on solve in that namespace (linkage_ros_interfaces/srv/Solve_Request, kind
SOLVE, its CDR kept), each one command of travel and rack (and its wrench). A message
that does not decode (too short, not CDR) is lost and named; messages of another type on a
command topic are skipped with a line. Times are ns since the epoch, the recording's receive
(log) time.
"""

from __future__ import annotations

from dataclasses import dataclass, field
import math
from pathlib import Path
import time

from ..core.base import is_finite_number, LinkageError
from ..core.solve import travel_range
from ..record.stored import RECORD as METADATA

FLOAT64 = 'std_msgs/msg/Float64'
PARAMETER_EVENT = 'rcl_interfaces/msg/ParameterEvent'
PARAMETER_EVENTS = '/parameter_events'
DEFAULT_TOPIC = '/wheel_travel'
RACK_TOPIC = 'steering_rack'    # the rack commands' name, in the command topic's namespace
WRENCH_TOPIC = 'contact_wrench'  # the contact wrenches', beside the command topic
WRENCH_TYPE = 'geometry_msgs/msg/WrenchStamped'
SOLVE_TOPIC = 'solve'    # the solve service's requests, recorded beside the command topic
TRAVEL, RACK, WRENCH, SOLVE = 'travel', 'rack', 'wrench', 'solve'
# The run-time parameters that change what the node answers (ros/runtime.py): replayed
REPLAYED = ('scene', 'method', 'max_step_mm', 'condition_warn', 'diagnostic_period')
SWEEP_HZ = 50.0
# A sweep's commands are held in memory (about 240 bytes each, measured) and solved one by
# one (some 0.1 ms each, recording included): a million is 240 MB and a few minutes.
MAX_SWEEP_COMMANDS = 1_000_000
# ROS 2 stamps hold int32 seconds: the last time they can say is 2038-01-19 03:14:07 UTC.
LAST_STAMP_S = 2**31 - 1


class ReplayError(LinkageError):
    """A bag cannot be replayed: ReplayError(file or option, problem)."""


@dataclass(frozen=True)
class Command:
    """
    One command: receive (log) and publish time in ns, its value in m, and its kind.

    kind: TRAVEL (wheel travel, the value's name for history), RACK (steering rack) or
    WRENCH (a contact wrench: travel 0.0, data its WrenchStamped CDR as recorded) or SOLVE
    (a solve service request: travel its travel, data its Solve_Request CDR as recorded).
    """

    log_time: int
    publish_time: int
    travel: float
    kind: str = TRAVEL
    data: bytes = b''


@dataclass(frozen=True)
class Change:
    """A run-time change of the node's parameters: log time (ns), {name: new value}, the CDR."""

    log_time: int
    values: dict
    data: bytes


@dataclass
class Commands:
    """
    What read_commands found: the commands, the bag, and what is not among the commands.

    commands: travel and rack commands in the order they were received. lost: messages on
    the command topics that do not decode, [(BagMessage, CdrError)]; skipped: {(topic, type
    name): count} of messages of another type on them.
    """

    commands: list
    bag: object                 # record.mcap_reader.Bag
    topic: str                  # the travel topic, qualified
    lost: list = field(default_factory=list)
    skipped: dict = field(default_factory=dict)

    @property
    def rack_topic(self):
        """Return the steering-rack topic beside the travel topic (qualified)."""
        return rack_topic(self.topic)

    @property
    def wrench_topic(self):
        """Return the contact-wrench topic beside the travel topic (qualified)."""
        return wrench_topic(self.topic)

    def warnings(self):
        """Return the lines (without the program's name) that say what was not used."""
        lines = []
        path = self.bag.path
        from ..answer.cdr import SOLVE_REQUEST
        needs = {self.wrench_topic: f'contact wrenches are {WRENCH_TYPE}',
                 beside(self.topic, SOLVE_TOPIC): f'solve requests are {SOLVE_REQUEST}'}
        for (topic, type_name), count in self.skipped.items():
            lines.append(f'{path}: {count} message{"s" if count > 1 else ""} of '
                         f'{type_name or "no schema"} on {topic} skipped: '
                         f'{needs.get(topic, f"commands are {FLOAT64}")}')
        if self.lost:
            message, error = self.lost[0]
            total = len(self.lost) + len(self.commands)
            topics = ' and '.join(sorted({m.topic for m, _ in self.lost}))
            lines.append(f'{path}: {len(self.lost)} of the {total} commands on {topics} do '
                         f'not decode and are lost (the first at {seconds(message.log_time)} '
                         f's: {error})')
        return lines


def rack_topic(topic):
    """Return the steering-rack topic in the namespace of a travel topic (qualified)."""
    return topic.rsplit('/', 1)[0] + '/' + RACK_TOPIC


def wrench_topic(topic):
    """Return the contact-wrench topic in the namespace of a travel topic (qualified)."""
    return topic.rsplit('/', 1)[0] + '/' + WRENCH_TOPIC


def beside(topic, name):
    """Return the topic name in the namespace of a travel topic (qualified)."""
    return topic.rsplit('/', 1)[0] + '/' + name


def seconds(time_ns):
    """Say a time in ns as seconds with every digit: '1700000000.010000000'."""
    return f'{time_ns // 10**9}.{time_ns % 10**9:09d}'


def stamp_of(time_ns):
    """Return a time in ns as a builtin_interfaces/msg/Time (a ROS 2 stamp)."""
    from builtin_interfaces.msg import Time
    return Time(sec=int(time_ns // 10**9), nanosec=int(time_ns % 10**9))


def read_commands(path, topic=DEFAULT_TOPIC):
    """
    Read the travel commands on topic and the rack commands beside it, in the order received.

    The order is the receive (log) time's, file order where times tie: the order the node
    answered them in.

    Raises ReplayError (a mistake) if an intact bag has no such topic, or the topic carries
    no std_msgs/msg/Float64 in CDR; RecordingError if the path is not a bag. From a damaged
    bag that does not hold the topic among what could be read, no commands: the damage is
    the caller's warning.
    """
    from ..answer.cdr import CdrError, float64_of, SOLVE_REQUEST, solve_request_of, wrench_of
    from ..record.interfaces import qualified
    from ..record.mcap_reader import read_bag
    bag = read_bag(path)
    name = qualified(topic)
    result = Commands([], bag, name)
    served = beside(name, SOLVE_TOPIC) in bag.topics   # a run driven by the solve service
    if name not in bag.topics and not served:
        if bag.truncated:   # the damage may have taken it: what was read is used (nothing)
            return result
        raise ReplayError(path, f'no topic {name} (topics present: {topic_list(bag)}); '
                          'choose the wheel-travel topic with --topic')
    if name in bag.topics and (bag.encodings.get(name) != 'cdr' or (
            bag.topics[name] != FLOAT64 and not any(
                m.type_name == FLOAT64 for m in bag.messages if m.topic == name))):
        raise ReplayError(path, f'topic {name} carries {bag.topics[name] or "no schema"} '
                          f"('{bag.encodings.get(name)}' encoding), but wheel-travel commands "
                          f'must be {FLOAT64} in cdr (topics present: {topic_list(bag)})')
    kinds = {name: TRAVEL, result.rack_topic: RACK, result.wrench_topic: WRENCH,
             beside(name, SOLVE_TOPIC): SOLVE}
    types = {WRENCH: WRENCH_TYPE, SOLVE: SOLVE_REQUEST}
    for m in bag.messages:
        kind = kinds.get(m.topic)
        if kind is None:
            continue
        if not m.carries(types.get(kind, FLOAT64)):
            key = (m.topic, m.type_name)
            result.skipped[key] = result.skipped.get(key, 0) + 1
            continue
        try:
            if kind == WRENCH:
                wrench_of(m.data)       # that it decodes: the node refuses what does not
                value, data = 0.0, bytes(m.data)
            elif kind == SOLVE:
                value, data = solve_request_of(m.data)[1], bytes(m.data)
            else:
                value, data = float64_of(m.data), b''
        except CdrError as exc:
            result.lost.append((m, exc))
            continue
        result.commands.append(Command(m.log_time, m.publish_time, value, kind, data))
    # in the order the node took them (file order where times tie)
    result.commands.sort(key=lambda c: c.log_time)
    return result


def parameter_changes(bag):
    """
    Return the run-time parameter changes a recording holds, [Change] in time order.

    The node records each change it applies as the rcl_interfaces/msg/ParameterEvent it
    publishes on /parameter_events (ros/runtime.py); only the parameters that change its
    answers (REPLAYED) are kept, and events without any are left out. A bag with the events
    of several nodes (rosbag2 records every node's) keeps those of nodes named
    suspension_kinematics (in any namespace). Raises ReplayError naming the time of an event
    that does not decode: the run cannot be replayed past it.
    """
    from rclpy.parameter import parameter_value_to_python

    from ..answer.cdr import CdrError, from_cdr
    from ..ros.node import NODE_NAME
    changes, nodes = [], set()
    for m in bag.messages:
        if m.topic != PARAMETER_EVENTS or not m.carries(PARAMETER_EVENT):
            continue
        try:
            event = from_cdr(PARAMETER_EVENT, m.data)
        except CdrError as exc:
            raise ReplayError(bag.path, f'the parameter event at {seconds(m.log_time)} s '
                              f'does not decode ({exc}): the run cannot be replayed past '
                              'it') from None
        values = {p.name: parameter_value_to_python(p.value)
                  for p in (*event.new_parameters, *event.changed_parameters)
                  if p.name in REPLAYED}
        if values:
            changes.append((event.node, Change(m.log_time, values, bytes(m.data))))
            nodes.add(event.node)
    if len(nodes) > 1:
        changes = [(n, c) for n, c in changes if n.rsplit('/', 1)[-1] == NODE_NAME]
    return sorted((c for _, c in changes), key=lambda c: c.log_time)


def topic_list(bag):
    """Say the topics of a bag with their types: '/a (std_msgs/msg/Float64), ...'."""
    return ', '.join(f'{t} ({kind})' for t, kind in bag.topics.items()) or 'none'


def sweep_commands(scene, start=None, stop=None, step=None, hz=SWEEP_HZ, t0=None):
    """
    Return the commands of a travel sweep at hz from t0 (ns; default now).

    start, stop, step in mm (default: the scene's travel block). Raises ReplayError naming
    the option for a request that cannot be carried out: more than MAX_SWEEP_COMMANDS
    commands, a rate faster than the 1 ns of a stamp, or stamps beyond the last a ROS 2
    time can hold.
    """
    low, high, default_step = scene.travel
    start = low if start is None else start
    stop = high if stop is None else stop
    step = default_step if step is None else step
    if not (step > 0 and hz > 0 and all(is_finite_number(v) for v in (start, stop, step, hz))):
        raise ReplayError('--travel, --hz', f'must be finite, STEP and --hz > 0 '
                          f'(got {start:g}, {stop:g}, {step:g}, {hz:g})')
    count = abs(stop - start) / step + 1      # float: may be far beyond any integer in use
    if not count <= MAX_SWEEP_COMMANDS:
        raise ReplayError('--travel', f'{step:g} mm from {start:g} to {stop:g} mm '
                          f'makes {count:.3g} commands, more than the {MAX_SWEEP_COMMANDS:,} a '
                          'sweep may have (choose a larger STEP)')
    if hz > 1e9:
        raise ReplayError('--hz', f'{hz:g} Hz is a command every {1e9 / hz:.3g} ns, faster than '
                          'the 1 ns resolution of ROS 2 times (at most 1e+09 Hz)')
    t0 = time.time_ns() if t0 is None else t0
    span = (math.floor(count) - 1) / hz                  # s, from the first command to the last
    if not t0 / 1e9 + span <= LAST_STAMP_S:
        raise ReplayError('--hz', f'{hz:g} Hz spreads the {math.floor(count):,} commands over '
                          f'{span:.3g} s, so their stamps would run past 2038-01-19 03:14:07 '
                          'UTC, the last time a ROS 2 stamp (int32 seconds) can hold')
    period = int(round(1e9 / hz))
    return [Command(t0 + i * period, t0 + i * period, float(travel) / 1000.0)
            for i, travel in enumerate(travel_range(start, stop, step))]


def load_changed_scenes(changes):
    """
    Load the scenes that changes ([Change]) name, in order, up to the first that fails.

    Returns ({scene parameter value: Scene}, None), or with (Change, error) for the first
    change whose scene does not load here (a file of the recording's machine, say).
    """
    from ..core.model import load_scene
    scenes = {}
    for change in changes:
        name = change.values.get('scene')
        if name is None or name in scenes:
            continue
        try:
            scenes[name] = load_scene(name)
        except (LinkageError, OSError) as exc:
            return scenes, (change, exc)
    return scenes, None


def stored_scene(bag, topic):
    """
    Return the scene a recording stores for topic's corner, or None if it stores none.

    The scene file's content (record.stored), or for a vehicle the corner of the topic's
    namespace (/front_left/wheel_travel: front_left). Raises SceneError naming the bag for
    stored content that does not load.
    """
    from ..core.model import SceneError
    from ..record.stored import load_stored
    loaded = load_stored(bag.metadata, str(bag.path))
    if loaded is None or loaded.vehicle is None:
        return loaded and loaded.scene
    corner = topic.strip('/').rpartition('/')[0].rpartition('/')[2]
    if corner not in loaded.corners:
        raise SceneError(f'{bag.path} (its vehicle_yaml)', 'corners', f'no corner '
                         f'{corner or "(none: the topic has no namespace)"} for {topic} '
                         f'(corners: {", ".join(loaded.corners)}); choose one with --scene')
    return loaded.corners[corner]


def stored_text(scene, stored=None):
    """Return the metadata to store a scene in a recording: {'linkage_ros': {key: YAML}}."""
    if stored and (stored.get('scene_yaml') or stored.get('vehicle_yaml')):
        return {METADATA: dict(stored)}
    try:
        return {METADATA: {'scene_yaml': Path(scene.source).read_text()}}
    except (OSError, UnicodeDecodeError):   # a scene not from a file: nothing to store
        return {}
