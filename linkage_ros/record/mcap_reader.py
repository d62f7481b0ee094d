# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Reading a recording back: every readable message of an MCAP file, and what is damaged.

    bag = read_bag('run.mcap')        # or a rosbag2 bag folder holding one .mcap
    bag.messages                      # BagMessage: topic, type name, CDR bytes, times (ns),
                                      # message encoding, schema as stored
    bag.truncated, bag.describe()     # damage found, named with its byte offset
    m.carries('std_msgs/msg/Float64') # the type a consumer expects, in CDR?
    bag.decode(m, cdr.float64_of)     # the value, or None: counted lost, named by losses()

The records are walked by mcap_scan.Scan (sizes checked before anything is read); this module
turns what it found into a Bag: the messages of known channels in file order, each topic's
type, encoding, offered QoS and schema text, the metadata records and the 'rosbag2'
metadata's custom data. A file whose records are intact may still hold a message whose bytes
do not decode (a 5-byte Float64): Bag.decode counts it, so that a consumer can go on, say
what was lost, and end with exit status 1 (Bag.complete is then false).
"""

import collections
from dataclasses import dataclass, field
import os
from pathlib import Path
from typing import NamedTuple

import yaml

from .errors import RecordingError
from .interfaces import MESSAGE_ENCODING, qualified, SCHEMA_ENCODING
from .mcap_scan import MCAP_MAGIC, Scan
from ..answer.cdr import CdrError, from_cdr


class BagSchema(NamedTuple):
    """A schema as stored: name (the type), encoding ('ros2msg', 'ros2idl', ...), data."""

    name: str
    encoding: str
    data: bytes


@dataclass(frozen=True)
class BagMessage:
    """
    One message as stored: topic, type name, bytes, log (receive) and publish time (ns).

    encoding: its channel's message encoding ('cdr' for ROS 2); schema: its channel's
    BagSchema (None for a channel without one), to copy as it is (McapRecorder.record's
    schema=). type_name is the schema's name ('' without one).
    """

    topic: str
    type_name: str
    data: bytes
    log_time: int
    publish_time: int
    encoding: str = MESSAGE_ENCODING
    schema: BagSchema | None = None

    def carries(self, type_name):
        """Tell whether the message is a type_name ('pkg/msg/Type') in CDR."""
        return self.type_name == type_name and self.encoding == MESSAGE_ENCODING


@dataclass
class Bag:
    """
    What read_bag() found.

    truncated: the file is cut short or damaged, so something it held may be lost; problem
    says what was found (each item of damage, '; ' between them); lost: how many messages
    the file's own statistics count beyond those read (None when the statistics are lost).
    undecoded: {topic: (count, the first one's CdrError text)} of the messages decode()
    found undecodable; losses() says them.
    """

    path: str
    profile: str = ''
    topics: dict = field(default_factory=dict)    # topic -> type name
    encodings: dict = field(default_factory=dict)  # topic -> message encoding ('cdr')
    qos: dict = field(default_factory=dict)       # topic -> first offered QoS profile (dict)
    definitions: dict = field(default_factory=dict)   # type name -> 'ros2msg' schema text
    custom_data: dict = field(default_factory=dict)   # from the 'rosbag2' metadata record
    metadata: dict = field(default_factory=dict)  # name -> {key: value} of each record
    messages: list = field(default_factory=list)  # BagMessage, in file order
    truncated: bool = False
    problem: str = ''                             # what is damaged ('' for an intact file)
    damage: list = field(default_factory=list)    # Damage, in the order found
    lost: object = None                           # int or None
    undecoded: dict = field(default_factory=dict)  # topic -> (count, first problem)

    @property
    def cut(self):
        """Tell whether the only damage is that the file ends early (a hard kill)."""
        return bool(self.damage) and all(d.kind == 'cut' for d in self.damage)

    def describe(self):
        """Return a phrase for a warning: 'bag truncated after N messages (cut at ...)'."""
        read = f'{len(self.messages)} message{"" if len(self.messages) == 1 else "s"}'
        lost = f', {self.lost} lost' if self.lost else ''
        if self.cut:
            return f'bag truncated after {read}{lost} ({self.problem})'
        return f'bag damaged: {read} read{lost} ({self.problem})'

    @property
    def complete(self):
        """Tell whether nothing was found lost: no damage, no message that did not decode."""
        return not self.truncated and not self.undecoded

    def decode(self, message, read=None):
        """
        Return what read(message.data) reads, or None if the bytes do not decode.

        read: a reader of CDR bytes that raises cdr.CdrError (cdr.float64_of, cdr.pose_of);
        by default cdr.from_cdr of the message's type (the rclpy message; LinkageError if
        no class of that type is installed). A message that does not decode is counted in
        undecoded under its topic, with the first one's reason, and is left to the caller
        to skip.
        """
        try:
            return read(message.data) if read else from_cdr(message.type_name, message.data)
        except CdrError as exc:
            count, first = self.undecoded.get(message.topic, (0, str(exc)))
            self.undecoded[message.topic] = (count + 1, first)
            return None

    def losses(self):
        """
        Return one line per topic whose messages did not decode (decode), naming them.

        'N messages on /camber do not decode, left out (the first: std_msgs/Float64 of 5
        bytes: too short: it needs 12 bytes)'.
        """
        return [f'{count} message{"s" if count > 1 else ""} on {topic} do'
                f'{"" if count > 1 else "es"} not decode, left out (the first: {first})'
                for topic, (count, first) in self.undecoded.items()]


def read_bag(path, topics=None):
    """
    Read every readable message of an MCAP file (ROS 2 profile), naming any damage.

    path: an .mcap file, or a rosbag2 bag folder holding one. topics: keep only these.

    A complete file is read to its end. In a file cut short (hard kill) or damaged every
    record that is still intact is read: the chunks before the damage, and those after it
    that the file still locates (records that follow in order, or the chunk index of an
    intact summary). Bag.truncated, Bag.problem and Bag.damage say what was found. Sizes
    declared in the file are checked against the file size and RECORD_LIMIT before any is
    read. Raises RecordingError if the file cannot be opened or is not MCAP at all.
    """
    path = bag_file(Path(path))
    try:
        stream = open(path, 'rb')
    except OSError as exc:
        raise RecordingError(path, f'cannot read ({exc.strerror or exc})') from None
    with stream:
        size = os.fstat(stream.fileno()).st_size
        start = stream.read(len(MCAP_MAGIC))
        if not start:
            raise RecordingError(path, 'not an MCAP file (it is empty)')
        if start != MCAP_MAGIC[:len(start)]:
            raise RecordingError(path, 'not an MCAP file (it does not start with the MCAP '
                                 'magic bytes)')
        scan = Scan(stream, size)
        if len(start) < len(MCAP_MAGIC):
            scan.note('cut', size, f'cut at byte {size} (the file ends inside the magic bytes)')
        else:
            scan.run()
    return _bag(scan, str(path), topics)


def _bag(scan, path, topics):
    """Return the Bag of a Scan: messages of known channels (in file order), topics, damage."""
    bag = Bag(path, profile=scan.profile, custom_data=_custom_data(scan.metadata),
              metadata=scan.metadata)
    wanted = None if topics is None else {qualified(t) for t in topics}
    stored = {}     # channel id -> (type name, BagSchema or None)
    for channel in scan.channels.values():
        schema = scan.schemas.get(channel.schema_id)
        type_name = schema.name if schema else ''
        stored[channel.id] = (type_name, BagSchema(schema.name, schema.encoding,
                                                   bytes(schema.data)) if schema else None)
        bag.topics.setdefault(channel.topic, type_name)
        bag.encodings.setdefault(channel.topic, channel.message_encoding)
        qos = _offered_qos(channel.metadata.get('offered_qos_profiles', ''))
        if qos:
            bag.qos.setdefault(channel.topic, qos)
        if schema and schema.encoding == SCHEMA_ENCODING:
            try:
                bag.definitions.setdefault(type_name, bytes(schema.data).decode())
            except UnicodeDecodeError:
                pass
    orphans, first = collections.Counter(), {}
    for channel_id, log_time, publish_time, data, offset in scan.raw:
        channel = scan.channels.get(channel_id)
        if channel is None:
            orphans[channel_id] += 1
            first.setdefault(channel_id, offset)
        elif wanted is None or channel.topic in wanted:
            type_name, schema = stored[channel_id]
            bag.messages.append(BagMessage(channel.topic, type_name, data, log_time,
                                           publish_time, channel.message_encoding, schema))
    for channel_id, count in sorted(orphans.items()):
        scan.note('channel', first[channel_id], f'{count} message'
                  f'{"s" if count > 1 else ""} of channel {channel_id}, which the file '
                  f'does not define, left out (the first in the record at byte '
                  f'{first[channel_id]})')
    named = scan.chunks_read | {d.offset for d in scan.damage}   # said once, where it is
    for offset in sorted({c.chunk_start_offset for c in scan.chunk_indexes} - named):
        # a byte that turned a chunk's opcode into another record's: read past, not as a chunk
        scan.note('record', offset, f'the chunk that the summary indexes at byte {offset} is '
                  'not there (the record at that byte is not a chunk): its messages are lost')
    if scan.statistics is not None:
        stored = scan.statistics.message_count
        bag.lost = max(0, stored - (len(scan.raw) - sum(orphans.values())))
    bag.damage = list(scan.damage)
    bag.truncated = bool(bag.damage)
    bag.problem = '; '.join(d.message for d in bag.damage)
    return bag


def bag_file(path):
    """Return the .mcap of a rosbag2 bag folder (metadata.yaml beside one), or path itself."""
    if not path.is_dir():
        return path
    files = sorted(path.glob('*.mcap'))
    if len(files) != 1:
        found = ', '.join(f.name for f in files) or 'none'
        raise RecordingError(path, f'a bag folder must hold exactly one .mcap file (found: '
                             f'{found})')
    return files[0]


def _offered_qos(text):
    try:
        profiles = yaml.safe_load(text) if text else None
    except (yaml.YAMLError, RecursionError):
        return None
    if isinstance(profiles, list) and profiles and isinstance(profiles[0], dict):
        return profiles[0]
    return None


def _custom_data(metadata):
    try:
        data = yaml.safe_load(metadata.get('rosbag2', {}).get('serialized_metadata', '')) or {}
        return {str(k): str(v) for k, v in (data.get('custom_data') or {}).items()}
    except (yaml.YAMLError, RecursionError, AttributeError):
        return {}
