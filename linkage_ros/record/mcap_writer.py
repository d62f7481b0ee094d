# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
MCAP recording in the layout rosbag2's MCAP storage plugin writes (Jazzy).

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
mcap_reader.read_bag() (used by linkage-replay and linkage-rerun) recovers it.
"""

import atexit
from dataclasses import dataclass
import os
from pathlib import Path
import threading

from mcap.writer import CompressionType, Writer

from .errors import RecordingError
from .interfaces import (DEFAULT_QOS, dump, message_definition, MESSAGE_ENCODING,
                         METADATA_VERSION, PROFILE, qos_profile_dict, qualified,
                         SCHEMA_ENCODING, type_hash)
from .output_file import claim, whereabouts
from ..answer.cdr import to_cdr

CHUNK_SIZE = 64 * 1024         # bytes of uncompressed messages per chunk
FLUSH_PERIOD = 1.0             # s: longest a message waits in memory before its chunk is written


class _RawFile:
    """
    Unbuffered file for mcap's Writer.

    Every finished chunk reaches the OS at once, so a hard kill loses only the chunk being
    built (mcap wraps RawIOBase in a buffer, so this is deliberately not one).
    """

    def __init__(self, fd):
        self._file = open(fd, 'wb', buffering=0)

    def write(self, data):
        view = memoryview(data)
        while view:
            view = view[self._file.write(view):]

    def tell(self):
        return self._file.tell()

    def flush(self):
        pass

    def fileno(self):
        return self._file.fileno()

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
    metadata: {record name: {str: str}} written as MCAP metadata records at once, after the
    header, so that a file cut by a hard kill keeps them (Bag.metadata reads them back; e.g.
    'linkage_ros': {'scene_yaml': the scene file's content}, which linkage-rerun draws).

    The file is claimed (output_file.claim): a second recorder of the same file, in this
    process or another, is refused with RecordingError, and the file is left alone.

    A write error (disk full, file-size limit) or the file removed or replaced stops the
    recording: error says why from then on, whichever thread met it, and record() raises
    RecordingError. Removal is seen by the flush thread (every flush_period) and whenever
    error is read (the node reads it every diagnostic period). The file keeps every chunk
    written before; close() does not raise for the lost end.
    """

    def __init__(self, path, *, qos=None, custom_data=None, chunk_size=CHUNK_SIZE,
                 flush_period=FLUSH_PERIOD, definitions=None, metadata=None):
        self.path = Path(path)
        self._where = os.path.abspath(path)    # what whereabouts checks, whatever the cwd
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise RecordingError(path, f'cannot write ({exc.strerror or exc})') from None
        self._file = _RawFile(claim(self.path))
        try:
            self._writer = Writer(self._file, chunk_size=chunk_size,
                                  compression=CompressionType.ZSTD)
            self._writer.start(profile=PROFILE, library=_library())
            for name, values in (metadata or {}).items():
                self._writer.add_metadata(str(name), {str(k): str(v) for k, v in
                                                      values.items()})
        except OSError as exc:
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
        self._error = ''          # why the recording stopped; '' while it records
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

    @property
    def error(self):
        """Say why the recording stopped ('' while it records); checks that the file is there."""
        if not self._error and not self._closed:
            self._watch()
        return self._error

    def record(self, topic, type_name, data, receive_ns, publish_ns, schema=None):
        """
        Write a message on topic with its ROS 2 type name.

        data is CDR bytes (as the node publishes them, or a raw subscription receives them)
        or an rclpy message. schema: (name, encoding, data) of a schema to store as it is,
        for a type whose definition is not installed or not a .msg (rosbag2 writes
        'ros2idl' schemas for IDL types); by default the 'ros2msg' definition of type_name.
        A topic keeps its first type (RecordingError for another), except with schemas
        given: a copy keeps each channel of a topic that a bag holds in several types.
        """
        data = to_cdr(data)
        key = topic if schema is None else (topic, _schema_key(schema))
        with self._lock:
            if self._closed:
                raise RecordingError(self.path, 'recording is closed')
            if self._error:
                raise RecordingError(self.path, self._error)
            entry = self._topics.get(key) or self._add_topic(key, topic, type_name, schema)
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
            if not self._closed and self._pending and not self._error:
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
            if not self._error:
                self._writer.add_metadata('rosbag2', {'serialized_metadata': dump(
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

    def _add_topic(self, key, topic, type_name, schema=None):
        name = qualified(topic)
        kind = type_name if schema is None else _schema_key(schema)
        if kind not in self._schemas:
            if schema is None:
                schema = (type_name, SCHEMA_ENCODING, (self._definitions.get(type_name)
                                                       or message_definition(type_name)))
            self._schemas[kind] = self._writer.register_schema(*_schema_key(schema))
        qos = self._qos.get(name, dict(DEFAULT_QOS))
        digest = type_hash(type_name)
        channel_id = self._writer.register_channel(
            topic=name, message_encoding=MESSAGE_ENCODING, schema_id=self._schemas[kind],
            metadata={'offered_qos_profiles': dump([qos]), 'topic_type_hash': digest})
        self._topics[key] = entry = _Topic(name, type_name, channel_id, qos, digest)
        return entry

    def _flush_loop(self, period):
        while not self._stop.wait(period) and not self._error:
            self._watch()
            try:
                self.flush()
            except RecordingError:
                return          # self.error says why; the node reports it

    def _watch(self):
        """Stop the recording if its file was removed or replaced (output_file.whereabouts)."""
        try:
            problem = whereabouts(self._file.fileno(), self._where)
        except (OSError, ValueError):   # closed meanwhile by another thread
            return
        if problem:
            with self._lock:
                self._error = self._error or problem

    def _failed(self, exc):
        """Remember the first write error as the reason the recording stopped; return it."""
        self._error = self._error or f'cannot write ({exc.strerror or exc})'
        return self._error


def _schema_key(schema):
    """Return a schema (name, encoding, data: str or bytes) as (name, encoding, bytes)."""
    name, encoding, data = schema
    return name, encoding, data.encode() if isinstance(data, str) else bytes(data)


def _library():
    from importlib.metadata import version, PackageNotFoundError
    try:
        return f'linkage_ros {version("linkage_ros")}, mcap-python {version("mcap")}'
    except PackageNotFoundError:
        return 'linkage_ros'
