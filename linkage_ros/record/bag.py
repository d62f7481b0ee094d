"""
MCAP recording in the layout rosbag2's MCAP storage plugin writes (Jazzy), and reading back.

    with McapRecorder('run.mcap') as rec:
        rec.record('/wheel_travel', 'std_msgs/msg/Float64', cdr_bytes, receive_ns, publish_ns)

The file has profile 'ros2'; one schema per type (encoding 'ros2msg', the type's .msg text
with every dependency appended, as rosbag2_storage_mcap's message_definition_cache does);
channels with 'cdr' encoding and the 'offered_qos_profiles' and 'topic_type_hash' metadata;
messages with log time = receive time and publish time; chunks compressed with zstd; and, at
close, a metadata record 'rosbag2' holding the bag metadata (version 9) as YAML.

Durability: a chunk is written (and handed to the OS) when it reaches chunk_size bytes or when
messages have waited flush_period seconds. close() (also on SIGINT/SIGTERM through the node's
shutdown) writes the summary and footer: the file is complete. After a hard kill (SIGKILL,
power loss) the file has no summary; every chunk written before the kill is intact and
read_bag() (used by linkage-replay and linkage-rerun) recovers it.
"""

import atexit
import collections
from dataclasses import dataclass, field
import functools
import io
import json
import os
from pathlib import Path
import re
import struct
import sys
import threading
import zlib

from mcap.data_stream import ReadDataStream
from mcap.exceptions import EndOfFile, McapError
from mcap.opcode import Opcode
from mcap.records import (Attachment, AttachmentIndex, Channel, Chunk, ChunkIndex, DataEnd,
                          Footer, Header, Message, MessageIndex, Metadata, MetadataIndex,
                          Schema, Statistics, SummaryOffset)
from mcap.stream_reader import breakup_chunk, CRCValidationError
from mcap.writer import CompressionType, Writer
import yaml

from ..cdr import to_cdr
from ..core.errors import LinkageError

MCAP_MAGIC = b'\x89MCAP0\r\n'
PROFILE = 'ros2'
SCHEMA_ENCODING = 'ros2msg'
MESSAGE_ENCODING = 'cdr'
METADATA_VERSION = 9           # rosbag2 Jazzy: QoS policies as words, QoS profiles as lists
CHUNK_SIZE = 64 * 1024         # bytes of uncompressed messages per chunk
FLUSH_PERIOD = 1.0             # s: longest a message waits in memory before its chunk is written
SEPARATOR = '=' * 80
INFINITE = {'sec': 9223372036, 'nsec': 854775807}   # RMW_DURATION_INFINITE as rosbag2 dumps it
DEFAULT_QOS = {'history': 'keep_last', 'depth': 10, 'reliability': 'reliable',
               'durability': 'volatile', 'deadline': INFINITE, 'lifespan': INFINITE,
               'liveliness': 'automatic', 'liveliness_lease_duration': INFINITE,
               'avoid_ros_namespace_conventions': False}
_PRIMITIVES = {'bool', 'byte', 'char', 'float32', 'float64', 'int8', 'uint8', 'int16', 'uint16',
               'int32', 'uint32', 'int64', 'uint64', 'string'}
# rosbag2_storage_mcap's MSG_FIELD_TYPE_REGEX: the first word of a line is a field type.
_FIELD_TYPE = re.compile(r'(?:^|\n)\s*([a-zA-Z0-9_/]+)(?:\[[^\]]*\])?\s+')
_TYPE_NAME = re.compile(r'^([a-zA-Z][a-zA-Z0-9_]*)/(?:msg/)?([a-zA-Z][a-zA-Z0-9_]*)$')


class RecordingError(LinkageError):
    """A recording cannot be written or read: RecordingError(file or type, problem)."""


# --- message definitions -------------------------------------------------------------------

def share_dirs():
    """Folders searched for <pkg>/msg/<Type>.msg: AMENT_PREFIX_PATH entries, then sys.prefix."""
    prefixes = [p for p in os.environ.get('AMENT_PREFIX_PATH', '').split(os.pathsep) if p]
    dirs = []
    for prefix in prefixes + [sys.prefix]:
        share = Path(prefix) / 'share'
        if share not in dirs:
            dirs.append(share)
    return dirs


def _split_type(type_name):
    """'pkg/msg/Type' or 'pkg/Type' -> (pkg, Type); RecordingError for anything else."""
    match = _TYPE_NAME.match(type_name)
    if not match:
        raise RecordingError(f'type {type_name!r}', 'expected a ROS 2 message type like '
                             "'std_msgs/msg/Float64'")
    return match.group(1), match.group(2)


def _interface_file(type_name, suffix):
    package, name = _split_type(type_name)
    for share in share_dirs():
        path = share / package / 'msg' / f'{name}{suffix}'
        if path.is_file():
            return path
    searched = ', '.join(str(s / package / 'msg') for s in share_dirs())
    raise RecordingError(f'type {type_name!r}', f'no {name}{suffix} found (searched '
                         f'{searched}); is the message package installed?')


def msg_dependencies(text, package):
    """Sorted dependency names ('pkg/Type') of a .msg text, as rosbag2_storage_mcap finds them."""
    deps = set()
    for match in _FIELD_TYPE.finditer(text):
        kind = match.group(1)
        if kind not in _PRIMITIVES:
            deps.add(kind if '/' in kind else f'{package}/{kind}')
    return sorted(deps)


def message_definition(type_name):
    """
    Return the full 'ros2msg' schema text of a type.

    That is its .msg text, then each dependency (depth first, once each) after a line of 80
    '=' and a line 'MSG: pkg/Type'.
    """
    seen = set()

    def append(name):
        package, _ = _split_type(name)
        text = _interface_file(name, '.msg').read_text()
        for dep in msg_dependencies(text, package):
            if dep not in seen:
                seen.add(dep)
                text += f'\n{SEPARATOR}\nMSG: {dep}\n' + append(dep)
        return text

    return append(type_name)


def type_hash(type_name):
    """Return the 'RIHS01_...' hash of a type, from its installed .json ('' if none)."""
    try:
        data = json.loads(_interface_file(type_name, '.json').read_text())
    except RecordingError:
        return ''
    package, name = _split_type(type_name)
    for entry in data.get('type_hashes', []):
        if entry.get('type_name') == f'{package}/msg/{name}':
            return entry.get('hash_string', '')
    return ''


def qos_profile_dict(profile=None):
    """
    Return a QoS profile as rosbag2 (metadata version 9) writes it.

    profile: an rclpy QoSProfile, a dict in rosbag2's form, or None (DEFAULT_QOS). Durations
    of 0 (rclpy's 'default') are written as rosbag2 records the DDS defaults: infinite.
    """
    if profile is None:
        return dict(DEFAULT_QOS)
    if isinstance(profile, dict):    # already in rosbag2's form (e.g. read from a bag)
        return dict(profile)

    def duration(value):
        ns = value.nanoseconds
        return dict(INFINITE) if ns == 0 else {'sec': ns // 10**9, 'nsec': ns % 10**9}

    return {'history': profile.history.name.lower(), 'depth': int(profile.depth),
            'reliability': profile.reliability.name.lower(),
            'durability': profile.durability.name.lower(),
            'deadline': duration(profile.deadline), 'lifespan': duration(profile.lifespan),
            'liveliness': profile.liveliness.name.lower(),
            'liveliness_lease_duration': duration(profile.liveliness_lease_duration),
            'avoid_ros_namespace_conventions': bool(profile.avoid_ros_namespace_conventions)}


class _PlainDumper(yaml.SafeDumper):
    """YAML as yaml-cpp dumps it for rosbag2: no anchors or aliases for repeated values."""

    def ignore_aliases(self, data):
        return True


def _dump(data):
    return yaml.dump(data, Dumper=_PlainDumper, sort_keys=False, default_flow_style=False)


def qualified(topic):
    """Topic name with a leading '/': recorded names are fully qualified, as rosbag2 records."""
    return topic if topic.startswith('/') else '/' + topic


# --- writer --------------------------------------------------------------------------------

class _RawFile:
    """
    Unbuffered file for mcap's Writer.

    Every finished chunk reaches the OS at once, so a hard kill loses only the chunk being
    built (mcap wraps RawIOBase in a buffer, so this is deliberately not one).
    """

    def __init__(self, path):
        self._file = open(path, 'wb', buffering=0)

    def write(self, data):
        view = memoryview(data)
        while view:
            view = view[self._file.write(view):]

    def tell(self):
        return self._file.tell()

    def flush(self):
        pass

    def close(self):
        self._file.close()


@dataclass
class _Topic:
    name: str
    type_name: str
    channel_id: int
    qos: dict
    type_hash: str
    count: int = 0


class McapRecorder:
    """
    Writes ROS 2 messages to an MCAP file that rosbag2, Foxglove and rosbags read.

    Thread-safe; a context manager; close() is idempotent. Times are ns since the epoch.
    qos: {topic: rclpy QoSProfile} offered by the publishers (DEFAULT_QOS for others).
    custom_data: {str: str} stored in the bag metadata (e.g. scene name, solver method).
    definitions: {type name: 'ros2msg' schema text} used instead of the installed .msg files
    (a copied bag keeps its own, read_bag's Bag.definitions).

    A write error (disk full, file-size limit, file gone) stops the recording: error holds
    the reason from then on, whichever thread met it, and record() raises RecordingError.
    The file keeps every chunk written before; close() does not raise for the lost end.
    """

    def __init__(self, path, *, qos=None, custom_data=None, chunk_size=CHUNK_SIZE,
                 flush_period=FLUSH_PERIOD, definitions=None):
        self.path = Path(path)
        self._file = None
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._file = _RawFile(self.path)
            self._writer = Writer(self._file, chunk_size=chunk_size,
                                  compression=CompressionType.ZSTD)
            self._writer.start(profile=PROFILE, library=_library())
        except OSError as exc:
            if self._file is not None:
                self._file.close()
            raise RecordingError(path, f'cannot write ({exc.strerror or exc})') from None
        self._qos = {qualified(k): qos_profile_dict(v) for k, v in (qos or {}).items()}
        self._custom = {str(k): str(v) for k, v in (custom_data or {}).items()}
        self._definitions = dict(definitions or {})
        self._schemas = {}
        self._topics = {}
        self._times = [None, None]     # first, last log time
        self._pending = 0
        self._lock = threading.Lock()
        self._closed = False
        self.error = ''          # why the recording stopped; '' while it records
        self._stop = threading.Event()
        self._flusher = None
        if flush_period:
            self._flusher = threading.Thread(target=self._flush_loop, args=(flush_period,),
                                             name='mcap-flush', daemon=True)
            self._flusher.start()
        atexit.register(self.close)

    @property
    def message_count(self):
        return sum(t.count for t in self._topics.values())

    def record(self, topic, type_name, data, receive_ns, publish_ns):
        """
        Write a message on topic with its ROS 2 type name.

        data is CDR bytes (as the node publishes them, or a raw subscription receives them)
        or an rclpy message.
        """
        data = to_cdr(data)
        with self._lock:
            if self._closed:
                raise RecordingError(self.path, 'recording is closed')
            if self.error:
                raise RecordingError(self.path, self.error)
            entry = self._topics.get(topic) or self._add_topic(topic, type_name)
            if entry.type_name != type_name:
                raise RecordingError(self.path, f'topic {entry.name} is recorded as '
                                     f'{entry.type_name}, got a {type_name}')
            entry.count += 1
            try:
                self._writer.add_message(entry.channel_id, log_time=int(receive_ns),
                                         data=data, publish_time=int(publish_ns),
                                         sequence=entry.count)
            except OSError as exc:
                raise RecordingError(self.path, self._failed(exc)) from None
            first, last = self._times
            self._times = [receive_ns if first is None else min(first, receive_ns),
                           receive_ns if last is None else max(last, receive_ns)]
            self._pending += 1

    def flush(self):
        """Write the chunk being built now (the node need not call this; a thread does)."""
        with self._lock:
            if not self._closed and self._pending and not self.error:
                try:
                    self._writer.flush()
                except OSError as exc:
                    raise RecordingError(self.path, self._failed(exc)) from None
                self._pending = 0

    def close(self):
        """Finish the file: last chunk, 'rosbag2' metadata, summary, footer. Idempotent."""
        with self._lock:
            if self._closed:
                return
            self._closed = True
        self._stop.set()
        if self._flusher is not None:
            self._flusher.join()
        atexit.unregister(self.close)
        try:
            if not self.error:
                self._writer.add_metadata('rosbag2', {'serialized_metadata': _dump(
                    self.bag_metadata())})
                self._writer.finish()
        except OSError as exc:      # the end is lost; what was written stays readable
            self._failed(exc)
        finally:
            self._file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def bag_metadata(self):
        """rosbag2 BagMetadata (version 9) of what has been written so far, as a dict."""
        first, last = self._times
        start = first or 0
        duration = (last - first) if first is not None else 0
        count = self.message_count
        return {
            'version': METADATA_VERSION, 'storage_identifier': 'mcap',
            'duration': {'nanoseconds': duration},
            'starting_time': {'nanoseconds_since_epoch': start},
            'message_count': count,
            'topics_with_message_count': [
                {'topic_metadata': {'name': t.name, 'type': t.type_name,
                                    'serialization_format': MESSAGE_ENCODING,
                                    'offered_qos_profiles': [t.qos],
                                    'type_description_hash': t.type_hash},
                 'message_count': t.count} for t in self._topics.values()],
            'compression_format': '', 'compression_mode': '',
            'relative_file_paths': [self.path.name],
            'files': [{'path': self.path.name,
                       'starting_time': {'nanoseconds_since_epoch': start},
                       'duration': {'nanoseconds': duration}, 'message_count': count}],
            'custom_data': dict(self._custom),
            'ros_distro': os.environ.get('ROS_DISTRO', 'jazzy'),
        }

    def _add_topic(self, topic, type_name):
        name = qualified(topic)
        if type_name not in self._schemas:
            self._schemas[type_name] = self._writer.register_schema(
                name=type_name, encoding=SCHEMA_ENCODING,
                data=(self._definitions.get(type_name)
                      or message_definition(type_name)).encode())
        qos = self._qos.get(name, dict(DEFAULT_QOS))
        digest = type_hash(type_name)
        channel_id = self._writer.register_channel(
            topic=name, message_encoding=MESSAGE_ENCODING, schema_id=self._schemas[type_name],
            metadata={'offered_qos_profiles': _dump([qos]), 'topic_type_hash': digest})
        self._topics[topic] = entry = _Topic(name, type_name, channel_id, qos, digest)
        return entry

    def _flush_loop(self, period):
        while not self._stop.wait(period) and not self.error:
            try:
                self.flush()
            except RecordingError:
                return          # self.error says why; the node reports it

    def _failed(self, exc):
        """Remember the first write error as the reason the recording stopped; return it."""
        self.error = self.error or f'cannot write ({exc.strerror or exc})'
        return self.error


def _library():
    from importlib.metadata import version, PackageNotFoundError
    try:
        return f'linkage_ros {version("linkage_ros")}, mcap-python {version("mcap")}'
    except PackageNotFoundError:
        return 'linkage_ros'


# --- reader --------------------------------------------------------------------------------
#
# An MCAP file is the magic bytes, then records (opcode: 1 byte, length: 8 bytes, content),
# then the magic bytes again. The reader below walks the records itself only to check each
# declared size against the file before anything is read or allocated; every record is then
# parsed by the mcap library (its record classes and breakup_chunk, which decompresses a
# chunk and checks its CRC). Whatever is damaged is named with its byte offset, and reading
# goes on wherever the file still says where the next record is.

RECORD_LIMIT = 4 * 2**30     # bytes: largest record or uncompressed chunk read (mcap's default)
# Most bytes one compressed byte can become: zstd's RLE block turns 4 bytes into 128 KiB;
# lz4 turns about 1 byte into 255.
EXPANSION = {'zstd': 2**15, 'lz4': 2**8, '': 1}
_NAMES = {op: op.name.lower().replace('_', ' ') for op in Opcode}
_FIXED_LENGTH = {Opcode.FOOTER: 20, Opcode.DATA_END: 4, Opcode.SUMMARY_OFFSET: 17}
_PARSERS = {Opcode.HEADER: Header.read, Opcode.FOOTER: Footer.read, Opcode.SCHEMA: Schema.read,
            Opcode.CHANNEL: Channel.read, Opcode.MESSAGE_INDEX: MessageIndex.read,
            Opcode.CHUNK_INDEX: ChunkIndex.read, Opcode.ATTACHMENT: Attachment.read,
            Opcode.ATTACHMENT_INDEX: AttachmentIndex.read, Opcode.STATISTICS: Statistics.read,
            Opcode.METADATA: Metadata.read, Opcode.METADATA_INDEX: MetadataIndex.read,
            Opcode.SUMMARY_OFFSET: SummaryOffset.read, Opcode.DATA_END: DataEnd.read}
# What mcap's parsers raise on malformed content (EndOfFile: a field runs past the record).
_MALFORMED = (McapError, struct.error, UnicodeDecodeError, ValueError, OverflowError)


@dataclass(frozen=True)
class BagMessage:
    """One message as stored: topic, type name, CDR bytes, log (receive) and publish time (ns)."""

    topic: str
    type_name: str
    data: bytes
    log_time: int
    publish_time: int


@dataclass(frozen=True)
class Damage:
    """
    One thing found wrong in a file: kind, the byte offset where it is, and what it is.

    kind: 'cut' (the file ends early), 'length' (a record's declared size is impossible),
    'record' (a record's content is malformed), 'crc' (a CRC does not match), 'decompress'
    (a chunk does not decompress), 'channel' (messages of a channel the file does not
    define), 'summary' or 'footer' (the index at the end of the file).
    """

    kind: str
    offset: int
    message: str


@dataclass
class Bag:
    """
    What read_bag() found.

    truncated: the file is cut short or damaged, so something it held may be lost; problem
    says what was found (each item of damage, '; ' between them); lost: how many messages
    the file's own statistics count beyond those read (None when the statistics are lost).
    """

    path: str
    profile: str = ''
    topics: dict = field(default_factory=dict)    # topic -> type name
    encodings: dict = field(default_factory=dict)  # topic -> message encoding ('cdr')
    qos: dict = field(default_factory=dict)       # topic -> first offered QoS profile (dict)
    definitions: dict = field(default_factory=dict)   # type name -> 'ros2msg' schema text
    custom_data: dict = field(default_factory=dict)   # from the 'rosbag2' metadata record
    messages: list = field(default_factory=list)  # BagMessage, in file order
    truncated: bool = False
    problem: str = ''                             # what is damaged ('' for an intact file)
    damage: list = field(default_factory=list)    # Damage, in the order found
    lost: object = None                           # int or None

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
    path = _bag_file(Path(path))
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
        scan = _Scan(stream, size)
        if len(start) < len(MCAP_MAGIC):
            scan.damage.append(Damage('cut', size, f'cut at byte {size} (the file ends inside '
                                      'the magic bytes)'))
        else:
            scan.run()
    return scan.bag(str(path), topics)


class _Stop(Exception):
    """The records cannot be followed past this damage."""

    def __init__(self, damage):
        super().__init__(damage.message)
        self.damage = damage


class _Scan:
    """One pass over an MCAP file: records checked, parsed by mcap, damage noted."""

    def __init__(self, stream, size):
        self.stream, self.size = stream, size
        self.damage = []
        self.profile = ''
        self.schemas, self.channels = {}, {}
        self.raw = []   # (channel id, log time, publish time, data, record offset), file order
        self.custom_data = {}
        self.statistics = None
        self.chunk_indexes, self.metadata_indexes = [], []

    # --- walking the records ---

    def run(self):
        """Read every record from the first to the footer and the closing magic bytes."""
        offset, previous = len(MCAP_MAGIC), None
        crc = zlib.crc32(MCAP_MAGIC)  # of the data section: every byte before the data end
        summary_start = None          # offset after the data end record
        while True:
            if offset == self.size:
                after = (f'after the {_record_name(previous[0])} record at byte {previous[1]}'
                         if previous else 'after the magic bytes')
                self._note('cut', offset, f'cut at byte {offset} (the file ends {after}, '
                           'before the footer)')
                return
            try:
                opcode, head, content = self._record_at(offset)
            except _Stop as stop:
                damage = stop.damage
                if summary_start is None:
                    self.damage.append(damage)
                    self._resync(offset)
                elif damage.kind == 'cut':
                    self.damage.append(damage)
                elif self._read_at(offset, 1) == bytes([Opcode.FOOTER]):
                    self._note('footer', damage.offset, f'bad footer: {damage.message}')
                else:
                    self._note('summary', damage.offset, f'bad summary: {damage.message}')
                return
            if opcode == Opcode.FOOTER:
                self._footer(offset, content, summary_start)
                return
            if summary_start is None and opcode == Opcode.DATA_END:
                self._data_end(offset, content, crc)
                summary_start = offset + len(head) + len(content)
            elif summary_start is None:
                crc = zlib.crc32(content, zlib.crc32(head, crc))
                self._handle(opcode, offset, content, summary=False)
            else:
                self._handle(opcode, offset, content, summary=True)
            previous = (opcode, offset)
            offset += len(head) + len(content)

    def _read_at(self, offset, length):
        self.stream.seek(offset)
        return self.stream.read(length)

    def _record_at(self, offset):
        """
        Return (opcode, 9 header bytes, content) of the record at offset.

        Its declared length is checked against the file size, RECORD_LIMIT and its own
        fields before it is read; _Stop says what is wrong.
        """
        head = self._read_at(offset, 9)
        name = f'the {_record_name(head[0])} record' if head else 'a record'
        if len(head) < 9:
            raise _Stop(Damage('cut', self.size, f'cut at byte {self.size} (the file ends '
                               f'inside {name} at byte {offset})'))
        opcode, length = struct.unpack('<BQ', head)
        if opcode == 0:
            raise _Stop(Damage('record', offset, f'a record at byte {offset} has opcode 0x00, '
                               'which no MCAP record has'))
        what = f'a record at byte {offset} ({_record_name(opcode)})'
        available = self.size - offset - 9
        if length > available:
            fields = _implied_length(opcode, self._read_at(offset + 9, min(available, 4096)),
                                     length)
            if length > RECORD_LIMIT or fields not in (None, length):
                raise _Stop(Damage('length', offset, f'{what} declares {length} bytes, beyond '
                                   f'the end of the file (size {self.size})'))
            raise _Stop(Damage('cut', self.size, f'cut at byte {self.size} (the file ends '
                               f'inside {name} at byte {offset})'))
        content = self.stream.read(length)
        fields = _implied_length(opcode, content, length)
        if fields is not None and fields != length:
            take = ('run past its end' if fields > length else f'take {fields}')
            raise _Stop(Damage('length', offset, f'{what} declares {length} bytes, but its '
                               f'fields {take}'))
        return opcode, head, content

    def _data_end(self, offset, content, crc):
        try:
            record = DataEnd.read(ReadDataStream(io.BytesIO(content)))
        except _MALFORMED:
            return    # its fixed length was checked: not reached
        if record.data_section_crc and record.data_section_crc != crc:
            if not any(d.kind in ('crc', 'decompress', 'record', 'channel')
                       for d in self.damage):
                self._note('crc', offset, 'CRC mismatch in the data section (checked by the '
                           f'data end record at byte {offset})')

    def _footer(self, offset, content, summary_start):
        footer = Footer.read(ReadDataStream(io.BytesIO(content)))   # 20 bytes: checked
        if summary_start is None:
            self._note('footer', offset, f'bad footer at byte {offset}: no data end record '
                       'comes before it')
        elif footer.summary_start == 0 and summary_start != offset:
            self._note('footer', offset, f'bad footer at byte {offset}: it says the file has '
                       f'no summary, but one starts at byte {summary_start}')
        elif footer.summary_start not in (0, summary_start):
            self._note('footer', offset, f'bad footer at byte {offset}: it says the summary '
                       f'starts at byte {footer.summary_start}, but it starts at byte '
                       f'{summary_start}')
        elif footer.summary_start and footer.summary_crc:
            data = self._read_at(summary_start, offset + 9 + 16 - summary_start)
            if zlib.crc32(data) != footer.summary_crc:   # says it all: no detail before
                self.damage = [d for d in self.damage if d.kind != 'summary']
                self._note('summary', summary_start, 'bad summary: CRC mismatch in the summary '
                           f'at byte {summary_start} (checked by the footer at byte {offset})')
        end = offset + 9 + 20
        magic = self._read_at(end, len(MCAP_MAGIC) + 1)
        if not magic:
            self._note('cut', self.size, f'cut at byte {self.size} (the file ends after the '
                       f'footer record at byte {offset}, before the closing magic bytes)')
        elif len(magic) < len(MCAP_MAGIC) and magic == MCAP_MAGIC[:len(magic)]:
            self._note('cut', self.size, f'cut at byte {self.size} (the file ends inside the '
                       'closing magic bytes)')
        elif magic[:len(MCAP_MAGIC)] != MCAP_MAGIC:
            self._note('footer', end, f'bad footer at byte {offset}: the MCAP magic bytes do '
                       f'not follow it at byte {end}')
        elif len(magic) > len(MCAP_MAGIC):
            extra = self.size - end - len(MCAP_MAGIC)
            self._note('footer', end + len(MCAP_MAGIC), f'{extra} bytes follow the closing '
                       f'magic bytes at byte {end}')

    def _resync(self, damaged):
        """
        Read on after damage at byte damaged of the data section, through the summary.

        The chunks and metadata records at or after it that an intact summary indexes are
        read (footer and summary checked by their CRC first). Nothing happens if the file
        has no intact footer and summary.
        """
        footer_at = self.size - len(MCAP_MAGIC) - 9 - 20
        if footer_at <= damaged or self._read_at(footer_at + 29, 8) != MCAP_MAGIC:
            return
        head = self._read_at(footer_at, 9)
        if head != struct.pack('<BQ', Opcode.FOOTER, 20):
            return
        footer = Footer.read(ReadDataStream(io.BytesIO(self._read_at(footer_at + 9, 20))))
        start = footer.summary_start
        if not damaged < start <= footer_at or (footer.summary_crc and zlib.crc32(
                self._read_at(start, footer_at + 9 + 16 - start)) != footer.summary_crc):
            return
        try:
            records = []
            offset = start
            while offset < footer_at:
                opcode, head, content = self._record_at(offset)
                records.append((opcode, offset, content))
                offset += len(head) + len(content)
        except _Stop:
            return
        if offset != footer_at:
            return
        for opcode, offset, content in records:
            self._handle(opcode, offset, content, summary=True)
        for index in sorted(self.chunk_indexes, key=lambda c: c.chunk_start_offset):
            self._indexed(index.chunk_start_offset, index.chunk_length, Opcode.CHUNK,
                          damaged, footer_at)
        for index in sorted(self.metadata_indexes, key=lambda m: m.offset):
            self._indexed(index.offset, index.length, Opcode.METADATA, damaged, footer_at)

    def _indexed(self, offset, length, opcode, damaged, limit):
        """Read a record the summary locates (at or after byte damaged, before limit)."""
        if not (damaged <= offset and 9 <= length and offset + length <= limit):
            return
        if self._read_at(offset, 1) != bytes([opcode]):
            return
        content = self._read_at(offset + 9, length - 9)   # the index's length, not the record's
        if _implied_length(opcode, content, len(content)) in (None, len(content)):
            self._handle(opcode, offset, content, summary=False)

    # --- records ---

    def _note(self, kind, offset, message):
        self.damage.append(Damage(kind, offset, message))

    def _handle(self, opcode, offset, content, summary):
        if opcode == Opcode.CHUNK:
            self._chunk(offset, content)
            return
        parse = _PARSERS.get(opcode)
        if opcode == Opcode.MESSAGE:
            parse = functools.partial(_read_message, length=len(content))
        if parse is None:
            return                    # a record type of a later MCAP version: skipped
        try:
            record = parse(ReadDataStream(io.BytesIO(content)))
        except _MALFORMED as exc:
            prefix = 'bad summary: ' if summary else ''
            self._note('summary' if summary else 'record', offset, f'{prefix}the '
                       f'{_NAMES[opcode]} record at byte {offset} is malformed ({_reason(exc)})')
            return
        self._take(record, offset)

    def _take(self, record, offset):
        if isinstance(record, Message):
            self.raw.append((record.channel_id, record.log_time, record.publish_time,
                             bytes(record.data), offset))
        elif isinstance(record, Channel):
            self.channels.setdefault(record.id, record)
        elif isinstance(record, Schema):
            self.schemas.setdefault(record.id, record)
        elif isinstance(record, Header):
            self.profile = record.profile
        elif isinstance(record, Metadata):
            if record.name == 'rosbag2':
                self.custom_data = _custom_data(record.metadata)
        elif isinstance(record, Statistics):
            self.statistics = record
        elif isinstance(record, ChunkIndex):
            self.chunk_indexes.append(record)
        elif isinstance(record, MetadataIndex):
            self.metadata_indexes.append(record)

    def _chunk(self, offset, content):
        """
        Decompress a chunk (mcap's breakup_chunk, CRC checked) and take its records.

        Its uncompressed size is checked first, against what its compression can produce.
        """
        where = f'the chunk at byte {offset}'
        usize, = struct.unpack_from('<Q', content, 16)
        clen, = struct.unpack_from('<I', content, 28)    # fields checked by _record_at
        data = content[40 + clen:]
        try:
            compression = content[32:32 + clen].decode()
        except UnicodeDecodeError:
            compression = repr(bytes(content[32:32 + clen]))
        problem = _size_problem(compression, usize, data)
        if problem:
            self._note('decompress', offset, f'{where} does not decompress ({problem})')
            return
        try:
            chunk = Chunk.read(ReadDataStream(io.BytesIO(content)))
            records = breakup_chunk(chunk, validate_crc=True)
        except CRCValidationError:
            self._note('crc', offset, f'CRC mismatch in {where}')
            return
        except _DECOMPRESSION_ERRORS as exc:
            self._note('decompress', offset, f'{where} does not decompress ({compression}: '
                       f'{_reason(exc)})')
            return
        except _MALFORMED as exc:
            self._note('record', offset, f'{where} holds a malformed record ({_reason(exc)})')
            return
        for record in records:
            self._take(record, offset)

    # --- result ---

    def bag(self, path, topics):
        """Return the Bag: messages of known channels (in file order), topics, damage."""
        bag = Bag(path, profile=self.profile, custom_data=self.custom_data)
        wanted = None if topics is None else {qualified(t) for t in topics}
        for channel in self.channels.values():
            schema = self.schemas.get(channel.schema_id)
            type_name = schema.name if schema else ''
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
        for channel_id, log_time, publish_time, data, offset in self.raw:
            channel = self.channels.get(channel_id)
            if channel is None:
                orphans[channel_id] += 1
                first.setdefault(channel_id, offset)
            elif wanted is None or channel.topic in wanted:
                bag.messages.append(BagMessage(channel.topic, bag.topics[channel.topic], data,
                                               log_time, publish_time))
        for channel_id, count in sorted(orphans.items()):
            self._note('channel', first[channel_id], f'{count} message'
                       f'{"s" if count > 1 else ""} of channel {channel_id}, which the file '
                       f'does not define, left out (the first in the record at byte '
                       f'{first[channel_id]})')
        if self.statistics is not None:
            stored = self.statistics.message_count
            bag.lost = max(0, stored - (len(self.raw) - sum(orphans.values())))
        bag.damage = list(self.damage)
        bag.truncated = bool(bag.damage)
        bag.problem = '; '.join(d.message for d in bag.damage)
        return bag


_DECOMPRESSION_ERRORS = (RuntimeError,)   # lz4.frame; zstandard.ZstdError added on import
try:
    import zstandard
    _DECOMPRESSION_ERRORS += (zstandard.ZstdError,)
except ImportError:   # mcap reads zstd chunks only with zstandard installed
    zstandard = None
try:
    import lz4.frame as lz4_frame
except ImportError:   # and lz4 chunks only with lz4
    lz4_frame = None


def _read_message(stream, length):
    return Message.read(stream, length)


def _record_name(opcode):
    return _NAMES.get(opcode, f'unknown (opcode 0x{opcode:02x})')


def _reason(exc):
    if isinstance(exc, EndOfFile):
        return 'a field runs past its end'
    return f'{type(exc).__name__}: {exc}' if str(exc) else type(exc).__name__


def _implied_length(opcode, content, length):
    """
    Return the content length that the fields at the start of a record imply.

    content: all or the first bytes of the record's content; length: its declared length.
    None if the fields do not say, or are not all there. Exact for chunks, message indexes
    and fixed-size records; for a chunk whose compression name runs past length, a lower
    bound above length.
    """
    if opcode in _FIXED_LENGTH:
        return _FIXED_LENGTH[opcode]
    if opcode == Opcode.CHUNK and length < 40:
        return 40
    if opcode == Opcode.CHUNK and len(content) >= 32:
        clen, = struct.unpack_from('<I', content, 28)
        if 40 + clen > length:
            return 40 + clen
        if len(content) < 40 + clen:
            return None
        rlen, = struct.unpack_from('<Q', content, 32 + clen)
        return 40 + clen + rlen
    if opcode == Opcode.MESSAGE_INDEX and length < 6:
        return 6
    if opcode == Opcode.MESSAGE_INDEX and len(content) >= 6:
        return 6 + struct.unpack_from('<I', content, 2)[0]
    if opcode == Opcode.MESSAGE:
        return None if len(content) >= 22 else 22
    return None


def _size_problem(compression, usize, data):
    """Why a chunk's declared uncompressed size (usize) cannot be right, or ''."""
    if compression not in EXPANSION:
        return f'unknown compression {compression!r}'
    if compression == '':
        if usize != len(data):
            return (f'it declares {usize} bytes uncompressed, but stores {len(data)} bytes '
                    'without compression')
        return ''
    if usize > RECORD_LIMIT or usize > EXPANSION[compression] * len(data):
        return (f'it declares {usize} bytes uncompressed from {len(data)} compressed bytes, '
                f'more than {compression} can make of them')
    if compression == 'zstd' and zstandard is not None:
        try:
            stored = zstandard.frame_content_size(data)
        except zstandard.ZstdError:
            return 'zstd: not a zstd frame'
        if stored >= 0 and stored != usize:
            return f'its zstd frame holds {stored} bytes, but the chunk declares {usize}'
    if compression == 'lz4' and lz4_frame is not None:
        try:
            stored = lz4_frame.get_frame_info(data)['content_size']
        except RuntimeError:
            return 'lz4: not an lz4 frame'
        if stored and stored != usize:
            return f'its lz4 frame holds {stored} bytes, but the chunk declares {usize}'
    return ''


def _bag_file(path):
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
        data = yaml.safe_load(metadata.get('serialized_metadata', '')) or {}
        return {str(k): str(v) for k, v in (data.get('custom_data') or {}).items()}
    except (yaml.YAMLError, RecursionError, AttributeError):
        return {}
