"""MCAP recording in the layout rosbag2's MCAP storage plugin writes (Jazzy), and reading back.

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
from dataclasses import dataclass, field
import json
import os
from pathlib import Path
import re
import sys
import threading

from mcap.records import Channel, Header, Message, Metadata, Schema
from mcap.stream_reader import StreamReader
from mcap.writer import CompressionType, Writer
import yaml

from ..core.errors import LinkageError
from ..ros.messages import to_cdr

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
        raise RecordingError(f'type {type_name!r}', "expected a ROS 2 message type like "
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
    """Full 'ros2msg' schema text of a type: its .msg text, then each dependency (depth first,
    once each) after a line of 80 '=' and a line 'MSG: pkg/Type'."""
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
    """The 'RIHS01_...' type description hash of a type, from its installed .json ('' if none)."""
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
    """A QoS profile as rosbag2 (metadata version 9) writes it; profile: an rclpy QoSProfile.

    Durations of 0 (rclpy's 'default') are written as rosbag2 records the DDS defaults: infinite.
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
    """Unbuffered file for mcap's Writer: every finished chunk reaches the OS at once, so a
    hard kill loses only the chunk being built (mcap wraps RawIOBase in a buffer, so this is
    deliberately not one)."""

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
    """Writes ROS 2 messages to an MCAP file that rosbag2, Foxglove and rosbags read.

    Thread-safe; a context manager; close() is idempotent. Times are ns since the epoch.
    qos: {topic: rclpy QoSProfile} offered by the publishers (DEFAULT_QOS for others).
    custom_data: {str: str} stored in the bag metadata (e.g. scene name, solver method).
    """

    def __init__(self, path, *, qos=None, custom_data=None, chunk_size=CHUNK_SIZE,
                 flush_period=FLUSH_PERIOD):
        self.path = Path(path)
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._file = _RawFile(self.path)
        except OSError as exc:
            raise RecordingError(path, f'cannot write ({exc.strerror or exc})') from None
        self._qos = {qualified(k): qos_profile_dict(v) for k, v in (qos or {}).items()}
        self._custom = {str(k): str(v) for k, v in (custom_data or {}).items()}
        self._writer = Writer(self._file, chunk_size=chunk_size,
                              compression=CompressionType.ZSTD)
        self._writer.start(profile=PROFILE, library=_library())
        self._schemas = {}
        self._topics = {}
        self._times = [None, None]     # first, last log time
        self._pending = 0
        self._lock = threading.Lock()
        self._closed = False
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
        """Write a message on topic with its ROS 2 type name: data is CDR bytes (as the node
        publishes them, or a raw subscription receives them) or an rclpy message."""
        data = to_cdr(data)
        with self._lock:
            if self._closed:
                raise RecordingError(self.path, 'recording is closed')
            entry = self._topics.get(topic) or self._add_topic(topic, type_name)
            if entry.type_name != type_name:
                raise RecordingError(self.path, f'topic {entry.name} is recorded as '
                                     f'{entry.type_name}, got a {type_name}')
            entry.count += 1
            self._writer.add_message(entry.channel_id, log_time=int(receive_ns), data=data,
                                     publish_time=int(publish_ns), sequence=entry.count)
            first, last = self._times
            self._times = [receive_ns if first is None else min(first, receive_ns),
                           receive_ns if last is None else max(last, receive_ns)]
            self._pending += 1

    def flush(self):
        """Write the chunk being built now (the node need not call this; a thread does)."""
        with self._lock:
            if not self._closed and self._pending:
                self._writer.flush()
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
            self._writer.add_metadata('rosbag2', {'serialized_metadata': _dump(
                self.bag_metadata())})
            self._writer.finish()
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
                data=message_definition(type_name).encode())
        qos = self._qos.get(name, dict(DEFAULT_QOS))
        digest = type_hash(type_name)
        channel_id = self._writer.register_channel(
            topic=name, message_encoding=MESSAGE_ENCODING, schema_id=self._schemas[type_name],
            metadata={'offered_qos_profiles': _dump([qos]), 'topic_type_hash': digest})
        self._topics[topic] = entry = _Topic(name, type_name, channel_id, qos, digest)
        return entry

    def _flush_loop(self, period):
        while not self._stop.wait(period):
            self.flush()


def _library():
    from importlib.metadata import version, PackageNotFoundError
    try:
        return f'linkage_ros {version("linkage_ros")}, mcap-python {version("mcap")}'
    except PackageNotFoundError:
        return 'linkage_ros'


# --- reader --------------------------------------------------------------------------------

@dataclass(frozen=True)
class BagMessage:
    """One message as stored: topic, type name, CDR bytes, log (receive) and publish time (ns)."""

    topic: str
    type_name: str
    data: bytes
    log_time: int
    publish_time: int


@dataclass
class Bag:
    """What read_bag() found. truncated: the file ends early or is damaged after `messages`."""

    path: str
    profile: str = ''
    topics: dict = field(default_factory=dict)    # topic -> type name
    encodings: dict = field(default_factory=dict)  # topic -> message encoding ('cdr')
    qos: dict = field(default_factory=dict)       # topic -> first offered QoS profile (dict)
    custom_data: dict = field(default_factory=dict)   # from the 'rosbag2' metadata record
    messages: list = field(default_factory=list)  # BagMessage, in file order
    truncated: bool = False
    problem: str = ''                             # why reading stopped early


def read_bag(path, topics=None):
    """Read every readable message of an MCAP file (ROS 2 profile), tolerating truncation.

    path: an .mcap file, or a rosbag2 bag folder holding one.

    A complete file is read to its end. A file cut short (hard kill) or damaged is read up to
    the last intact chunk; Bag.truncated and Bag.problem say so. topics: keep only these.
    Raises RecordingError if the file cannot be opened or is not MCAP at all.
    """
    path = str(_bag_file(Path(path)))
    try:
        stream = open(path, 'rb')
    except OSError as exc:
        raise RecordingError(path, f'cannot read ({exc.strerror or exc})') from None
    bag = Bag(path)
    schemas, channels = {}, {}
    wanted = None if topics is None else {qualified(t) for t in topics}
    with stream:
        if stream.read(len(MCAP_MAGIC)) != MCAP_MAGIC:
            raise RecordingError(path, 'not an MCAP file (it does not start with the MCAP '
                                 'magic bytes)')
        stream.seek(0)
        records = StreamReader(stream, validate_crcs=True).records
        try:
            for record in records:
                if isinstance(record, Header):
                    bag.profile = record.profile
                elif isinstance(record, Schema):
                    schemas[record.id] = record
                elif isinstance(record, Channel):
                    channels[record.id] = record
                    schema = schemas.get(record.schema_id)
                    bag.topics.setdefault(record.topic, schema.name if schema else '')
                    bag.encodings.setdefault(record.topic, record.message_encoding)
                    qos = _offered_qos(record.metadata.get('offered_qos_profiles', ''))
                    if qos:
                        bag.qos.setdefault(record.topic, qos)
                elif isinstance(record, Message):
                    channel = channels[record.channel_id]
                    if wanted is not None and channel.topic not in wanted:
                        continue
                    bag.messages.append(BagMessage(channel.topic, bag.topics[channel.topic],
                                                   bytes(record.data), record.log_time,
                                                   record.publish_time))
                elif isinstance(record, Metadata) and record.name == 'rosbag2':
                    bag.custom_data = _custom_data(record.metadata)
        except Exception as exc:  # truncated or damaged: keep what was read
            bag.truncated = True
            bag.problem = _describe(exc)
    return bag


def _bag_file(path):
    """The .mcap of a rosbag2 bag folder (metadata.yaml beside one .mcap), or path itself."""
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
    except yaml.YAMLError:
        return None
    return profiles[0] if isinstance(profiles, list) and profiles else None


def _custom_data(metadata):
    try:
        data = yaml.safe_load(metadata.get('serialized_metadata', '')) or {}
        return {str(k): str(v) for k, v in (data.get('custom_data') or {}).items()}
    except (yaml.YAMLError, AttributeError):
        return {}


def _describe(exc):
    if type(exc).__name__ in ('EndOfFile', 'error'):   # mcap's EndOfFile, struct.error
        return 'the file ends in the middle of a record'
    return f'{type(exc).__name__}: {exc}'
