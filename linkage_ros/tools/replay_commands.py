"""
The wheel-travel commands linkage-replay works on: read from a bag, or made for a sweep.

    read_commands(path, topic)      -> Commands: the decoded commands, the bag, what was lost
    sweep_commands(scene, ...)      -> [Command] of a travel sweep on a timeline
    stored_scene(bag, topic)        -> the scene a recording stores, or None

A command is std_msgs/msg/Float64 in CDR, travel in m. A message that does not decode (too
short, not CDR) is lost and named; messages of another type on the command topic are skipped
with a line. Times are ns since the epoch, the recording's receive (log) time.
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
DEFAULT_TOPIC = '/wheel_travel'
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
    """One wheel-travel command: receive (log) and publish time in ns, travel in m."""

    log_time: int
    publish_time: int
    travel: float


@dataclass
class Commands:
    """
    What read_commands found: the commands, the bag, and what is not among the commands.

    lost: messages on the topic that do not decode, [(BagMessage, CdrError)]; skipped:
    {type name: count} of messages of another type on the topic.
    """

    commands: list
    bag: object                 # record.mcap_reader.Bag
    topic: str                  # the topic, qualified
    lost: list = field(default_factory=list)
    skipped: dict = field(default_factory=dict)

    def warnings(self):
        """Return the lines (without the program's name) that say what was not used."""
        lines = []
        path, topic = self.bag.path, self.topic
        for type_name, count in self.skipped.items():
            lines.append(f'{path}: {count} message{"s" if count > 1 else ""} of '
                         f'{type_name or "no schema"} on {topic} skipped: commands are '
                         f'{FLOAT64}')
        if self.lost:
            message, error = self.lost[0]
            total = len(self.lost) + len(self.commands)
            lines.append(f'{path}: {len(self.lost)} of the {total} commands on {topic} do not '
                         f'decode and are lost (the first at {seconds(message.log_time)} s: '
                         f'{error})')
        return lines


def seconds(time_ns):
    """Say a time in ns as seconds with every digit: '1700000000.010000000'."""
    return f'{time_ns // 10**9}.{time_ns % 10**9:09d}'


def stamp_of(time_ns):
    """Return a time in ns as a builtin_interfaces/msg/Time (a ROS 2 stamp)."""
    from builtin_interfaces.msg import Time
    return Time(sec=int(time_ns // 10**9), nanosec=int(time_ns % 10**9))


def read_commands(path, topic=DEFAULT_TOPIC):
    """
    Read the commands on topic in a bag, in file order.

    Raises ReplayError (a mistake) if an intact bag has no such topic, or the topic carries
    no std_msgs/msg/Float64 in CDR; RecordingError if the path is not a bag. From a damaged
    bag that does not hold the topic among what could be read, no commands: the damage is
    the caller's warning.
    """
    from ..cdr import CdrError, float64_of
    from ..record.interfaces import qualified
    from ..record.mcap_reader import read_bag
    bag = read_bag(path)
    name = qualified(topic)
    result = Commands([], bag, name)
    if name not in bag.topics:
        if bag.truncated:   # the damage may have taken it: what was read is used (nothing)
            return result
        raise ReplayError(path, f'no topic {name} (topics present: {topic_list(bag)}); '
                          'choose the wheel-travel topic with --topic')
    on_topic = [m for m in bag.messages if m.topic == name]
    if bag.encodings.get(name) != 'cdr' or (bag.topics[name] != FLOAT64 and not any(
            m.type_name == FLOAT64 for m in on_topic)):
        raise ReplayError(path, f'topic {name} carries {bag.topics[name] or "no schema"} '
                          f"('{bag.encodings.get(name)}' encoding), but wheel-travel commands "
                          f'must be {FLOAT64} in cdr (topics present: {topic_list(bag)})')
    for m in on_topic:
        if m.type_name != FLOAT64:
            result.skipped[m.type_name] = result.skipped.get(m.type_name, 0) + 1
            continue
        try:
            travel = float64_of(m.data)
        except CdrError as exc:
            result.lost.append((m, exc))
            continue
        result.commands.append(Command(m.log_time, m.publish_time, travel))
    return result


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
        raise ReplayError('--from, --to, --step, --hz', f'must be finite, --step and --hz > 0 '
                          f'(got {start:g}, {stop:g}, {step:g}, {hz:g})')
    count = abs(stop - start) / step + 1      # float: may be far beyond any integer in use
    if not count <= MAX_SWEEP_COMMANDS:
        raise ReplayError('--from/--to/--step', f'{step:g} mm from {start:g} to {stop:g} mm '
                          f'makes {count:.3g} commands, more than the {MAX_SWEEP_COMMANDS:,} a '
                          'sweep may have (choose a larger --step)')
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


def stored_scene(bag, topic):
    """
    Return the scene a recording stores for topic's corner, or None if it stores none.

    The scene file's content (record.stored), or for a vehicle the corner of the topic's
    namespace (/front_left/wheel_travel: front_left). Raises SceneError naming the bag for
    stored content that does not load.
    """
    from ..core.model import Scene, SceneError
    from ..record.stored import load_stored
    loaded = load_stored(bag.metadata, str(bag.path))
    if loaded is None or isinstance(loaded, Scene):
        return loaded
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
