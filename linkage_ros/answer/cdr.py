# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
ROS 2 messages as CDR bytes, the form in which DDS carries them and MCAP stores them.

Pure functions, usable without DDS: the recorders, the replay and the node share them.

    float64_cdr(value), float64_of(CDR), pose_of(CDR)  -> built or read in place, no rclpy
    pose_stamped_cdr(stamp, frame_id, position, q)     -> geometry_msgs/PoseStamped, no rclpy
    point_stamped_cdr(stamp, frame_id, point)          -> geometry_msgs/PointStamped, no rclpy
    wrench_stamped_cdr(stamp, frame_id, force, torque) -> geometry_msgs/WrenchStamped, no rclpy
    wrench_of(CDR)                                     -> (frame_id, force, torque), in place
    joint_state_of(CDR)                                -> JointStateRead (stamp, name,
                                                          position) of a JointState, in place
    solve_request_of(CDR)                              -> a Solve request's fields, in place
    joint_state_cdr(stamp, frame_id, names, position)  -> sensor_msgs/JointState, no rclpy
    tf_message_cdr(stamp, parents, children, translations, quaternions)
                                                       -> tf2_msgs/TFMessage, no tf2_msgs
    transforms_of(CDR)                                 -> the TransformStampeds of a TFMessage
    string_cdr(text), string_of(CDR)                   -> std_msgs/String, no rclpy
    CdrError                                           bytes that do not hold the message
    from_cdr(type_name, data), to_cdr(msg)             -> rclpy message <-> CDR bytes
    message_class(type_name), type_name(message)       -> 'pkg/msg/Type' <-> rclpy class

The layout is XCDR1 as rmw_fastrtps writes it: a 4-byte encapsulation header (CDR_LE for
little-endian), then every field aligned to its size, counted from the header's end.
"""

from __future__ import annotations

import functools
import importlib
import struct
from typing import Any, NamedTuple, TYPE_CHECKING

from ..core.base import LinkageError

if TYPE_CHECKING:
    from collections.abc import Sequence

CDR_LE = b'\x00\x01\x00\x00'
_FLOAT64 = struct.Struct('<4sd')
_ENCAPSULATIONS = (b'\x00\x00', b'\x00\x01')   # CDR big-endian, little-endian (XCDR1)


class CdrError(LinkageError):
    """Bytes that do not hold the message they should: too short, or not CDR at all."""

    def __init__(self, what: str, data: bytes, problem: str) -> None:
        super().__init__(f'{what} of {len(data)} bytes', problem)
        self.size = len(data)


def _order(what: str, data: bytes, needed: int) -> str:
    """Return the struct byte order of CDR bytes holding at least needed bytes; else CdrError."""
    if bytes(data[:2]) not in _ENCAPSULATIONS:
        raise CdrError(what, data, f'not CDR (encapsulation {bytes(data[:4])!r})')
    if len(data) < needed:
        raise CdrError(what, data, f'too short: it needs {needed} bytes')
    return '<' if data[1] else '>'


def float64_cdr(value: float) -> bytes:
    """Return a std_msgs/Float64 (CDR bytes) holding value."""
    return _FLOAT64.pack(CDR_LE, value)


def float64_of(data: bytes) -> float:
    """Read the value of a std_msgs/Float64 in CDR bytes (either byte order); else CdrError."""
    return struct.unpack_from(_order('std_msgs/Float64', data, 12) + 'd', data, 4)[0]


def pose_stamped_cdr(stamp: tuple[int, int], frame_id: str, position: Sequence[float],
                     quaternion: Sequence[float]) -> bytes:
    """
    Return a geometry_msgs/PoseStamped (CDR bytes, little-endian).

    stamp: (sec, nanosec); position (x, y, z) in m in frame_id; quaternion (x, y, z, w).
    Built from a cached struct layout per frame_id: about 1 us, against about 30 for rclpy's
    message class and serializer (this is on the node's path for every command).
    """
    layout, frame = _stamped_layout(frame_id, 7)
    return layout.pack(CDR_LE, stamp[0], stamp[1], len(frame), frame, *position, *quaternion)


def point_stamped_cdr(stamp: tuple[int, int], frame_id: str, point: Sequence[float]) -> bytes:
    """Return a geometry_msgs/PointStamped (CDR bytes, little-endian): point (x, y, z) in m."""
    layout, frame = _stamped_layout(frame_id, 3)
    return layout.pack(CDR_LE, stamp[0], stamp[1], len(frame), frame, *point)


def wrench_stamped_cdr(stamp: tuple[int, int], frame_id: str, force: Sequence[float],
                       torque: Sequence[float]) -> bytes:
    """Return a geometry_msgs/WrenchStamped (CDR bytes, little-endian): force N, torque N m."""
    layout, frame = _stamped_layout(frame_id, 6)
    return layout.pack(CDR_LE, stamp[0], stamp[1], len(frame), frame, *force, *torque)


@functools.lru_cache(maxsize=256)
def _stamped_layout(frame_id, doubles):
    # header: stamp (int32 sec, uint32 nanosec), frame_id (uint32 length with the NUL, bytes,
    # NUL); then the doubles float64 (a pose's 7, a point's 3), aligned to 8.
    frame = frame_id.encode() + b'\0'
    pad = -(12 + len(frame)) % 8
    return struct.Struct(f'<4siII{len(frame)}s{pad}x{doubles}d'), frame


def joint_state_cdr(stamp: tuple[int, int], frame_id: str, names: Sequence[str],
                    position: Sequence[float], velocity: Sequence[float] = (),
                    effort: Sequence[float] = ()) -> bytes:
    """
    Return a sensor_msgs/JointState (CDR bytes, little-endian).

    stamp: (sec, nanosec); names: the joints; position (m or rad), velocity, effort: one
    value per joint or none. The layout is cached per frame_id, names and counts (a few us).
    """
    layout, strings = _joint_state_layout(frame_id, tuple(names), len(position), len(velocity),
                                          len(effort))
    return layout.pack(CDR_LE, stamp[0], stamp[1], strings, len(position), *position,
                       len(velocity), *velocity, len(effort), *effort)


@functools.lru_cache(maxsize=16)
def _joint_state_layout(frame_id, names, positions, velocities, efforts):
    # header: stamp, frame_id; name: sequence<string> (uint32 count, then each string as a
    # uint32 length with the NUL, its bytes and the NUL, aligned to 4); position, velocity,
    # effort: sequence<double> (uint32 count aligned to 4, the values aligned to 8). The
    # strings are the same for every message of these names: packed once, here.
    strings = bytearray()

    def put(data):
        strings.extend(bytes(-(8 + len(strings)) % 4) + data)   # 8: the stamp before

    def string(text):
        raw = text.encode() + b'\0'
        return struct.pack('<I', len(raw)) + raw

    put(string(frame_id))
    put(struct.pack('<I', len(names)))
    for name in names:
        put(string(name))
    fmt, offset = f'<4siI{len(strings)}s', 8 + len(strings)
    for count in (positions, velocities, efforts):
        pad = -offset % 4
        fmt, offset = fmt + f'{pad}xI', offset + pad + 4
        if count:
            pad = -offset % 8
            fmt, offset = fmt + f'{pad}x{count}d', offset + pad + 8 * count
    return struct.Struct(fmt), bytes(strings)


def tf_message_cdr(stamp: tuple[int, int], parents: Sequence[str], children: Sequence[str],
                   translations: Sequence[Sequence[float]],
                   quaternions: Sequence[Sequence[float]] | None = None) -> bytes:
    """
    Return a tf2_msgs/TFMessage (CDR bytes, little-endian) of one TransformStamped per child.

    stamp: (sec, nanosec) of every transform; parents, children: frame names (header.frame_id,
    child_frame_id); translations (k, 3) in m and quaternions (k, 4) (x, y, z, w), or, with
    quaternions None, translations (k, 7): each row the translation then the quaternion.
    Built without tf2_msgs (which has no wheel on the package index), from a struct layout
    cached per frame names: a few us for a corner's frames.
    """
    layout, names = _tf_layout(tuple(parents), tuple(children))
    args = [CDR_LE, len(names)]
    sec, nanosec = stamp
    rows = translations if quaternions is None else (
        (*t, *q) for t, q in zip(translations, quaternions))
    for strings, row in zip(names, rows):
        args += (sec, nanosec, strings)
        args += row
    return layout.pack(*args)


@functools.lru_cache(maxsize=64)
def _tf_layout(parents, children):
    # TFMessage: sequence<TransformStamped> (uint32 count); each: header (stamp: int32 sec,
    # uint32 nanosec; frame_id: uint32 length with the NUL, bytes, NUL), child_frame_id (the
    # same, aligned to 4), transform (translation 3 float64, rotation 4 float64, aligned to 8).
    # The two strings of a transform, with the padding between them, are packed once here.
    if len(parents) != len(children):
        raise ValueError(f'{len(parents)} parents for {len(children)} children')
    fmt, offset, names = '<4sI', 4, []
    for parent, child in zip(parents, children):
        offset += 8                     # the stamp (every element starts 4-aligned: no pad)
        strings = bytearray()
        for name in (parent, child):
            raw = name.encode() + b'\0'
            strings += bytes(-(offset + len(strings)) % 4) + struct.pack('<I', len(raw)) + raw
        pad = -(offset + len(strings)) % 8
        fmt += f'iI{len(strings)}s{pad}x7d'
        offset += len(strings) + pad + 56
        names.append(bytes(strings))
    return struct.Struct(fmt), tuple(names)


def transforms_of(data: bytes) -> list[tuple[tuple[int, int], str, str, tuple, tuple]]:
    """
    Read the transforms of a tf2_msgs/TFMessage in CDR bytes (either byte order).

    Returns [(stamp (sec, nanosec), parent, child, translation (3,) m, rotation (x, y, z, w))];
    CdrError if the bytes are too short for what they declare.
    """
    what = 'tf2_msgs/TFMessage'
    order = _order(what, data, 8)
    reader = _Reader(what, data, order)
    transforms = []
    for _ in range(reader.unpack('I', 4)[0]):
        stamp = reader.unpack('iI', 4)
        parent, child = reader.string(), reader.string()
        values = reader.unpack('7d', 8)
        transforms.append((stamp, parent, child, values[:3], values[3:]))
    return transforms


def string_cdr(text: str) -> bytes:
    """Return a std_msgs/String (CDR bytes, little-endian) holding text."""
    raw = text.encode() + b'\0'
    return CDR_LE + struct.pack('<I', len(raw)) + raw


def string_of(data: bytes) -> str:
    """Read the text of a std_msgs/String in CDR bytes (either byte order); else CdrError."""
    return _Reader('std_msgs/String', data, _order('std_msgs/String', data, 8)).string()


@functools.lru_cache(maxsize=256)
def _layout(fmt):
    # struct.Struct(fmt) compiles fmt anew at each call: a few hundred ns per field read
    return struct.Struct(fmt)


class _Reader:
    """Read CDR fields in turn, each aligned to its size counted from the header's end."""

    def __init__(self, what, data, order):
        self.what, self.data, self.order, self.at = what, data, order, 4
        self.size = len(data)
        self._count = _layout(order + 'I').unpack_from    # a sequence's or string's length

    def unpack(self, fmt, align):
        self.at += -(self.at - 4) % align
        layout = _layout(self.order + fmt)
        end = self.at + layout.size
        if end > self.size:
            raise CdrError(self.what, self.data, f'too short: it needs at least {end} bytes')
        values = layout.unpack_from(self.data, self.at)
        self.at = end
        return values

    def count(self):
        """Read a uint32 (a sequence's or a string's length): unpack('I', 4)[0], inline."""
        at = self.at + -(self.at - 4) % 4
        self.at = at + 4
        if self.at > self.size:
            raise CdrError(self.what, self.data, f'too short: it needs at least {self.at} '
                           'bytes')
        return self._count(self.data, at)[0]

    def doubles(self, keep=True):
        """Read a sequence<double> (a tuple; () if keep is False: only checked, skipped)."""
        count = self.count()
        if not count:      # no values, no alignment: the next field follows the count
            return ()
        self.at += -(self.at - 4) % 8
        end = self.at + 8 * count
        if end > self.size:
            raise CdrError(self.what, self.data, f'too short: {count} doubles at byte '
                           f'{self.at} need {end} bytes')
        values = struct.unpack_from(f'{self.order}{count}d', self.data, self.at) if keep else ()
        self.at = end
        return values

    def string(self):
        length = self.count()
        at = self.at
        if length == 0 or at + length > self.size:
            raise CdrError(self.what, self.data, f'a string of {length} bytes at byte '
                           f'{at} does not fit')
        self.at = at + length
        return str(self.data[at:at + length - 1], 'utf-8', 'replace')


def pose_of(data: bytes) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """
    Read (position (x, y, z), orientation (x, y, z, w)) of a geometry_msgs/PoseStamped.

    From CDR bytes (either byte order), in place, skipping the header's frame_id; CdrError
    if the bytes are too short for the frame_id they declare and the pose after it.
    """
    what = 'geometry_msgs/PoseStamped'
    order = _order(what, data, 16)
    frame_length = struct.unpack_from(order + 'I', data, 12)[0]
    start = 4 + 12 + frame_length
    start += -(start - 4) % 8
    _order(what, data, start + 56)
    values = struct.unpack_from(order + '7d', data, start)
    return values[:3], values[3:]


def wrench_of(data: bytes) -> tuple[str, tuple[float, ...], tuple[float, ...]]:
    """
    Read (frame_id, force (x, y, z), torque (x, y, z)) of a geometry_msgs/WrenchStamped.

    From CDR bytes (either byte order), in place; CdrError if the bytes are too short for
    the frame_id they declare and the wrench after it.
    """
    what = 'geometry_msgs/WrenchStamped'
    reader = _Reader(what, data, _order(what, data, 16))
    reader.unpack('iI', 4)
    frame_id = reader.string()
    values = reader.unpack('6d', 8)
    return frame_id, values[:3], values[3:]


class JointStateRead(NamedTuple):
    """The fields of a sensor_msgs/JointState that a command needs, read in place."""

    stamp: tuple[int, int]           # header.stamp: (sec, nanosec)
    name: tuple[str, ...]            # the joints
    position: tuple[float, ...]      # one per joint, or fewer (m or rad, as sent)


JOINT_STATE = 'sensor_msgs/msg/JointState'


def joint_state_of(data: bytes) -> JointStateRead:
    """
    Read the stamp, names and positions of a sensor_msgs/JointState, in place.

    From CDR bytes (either byte order), without rclpy's message class: a few us, against
    about 15 for rclpy's deserializer and JointState (the node's joint_states step). The
    whole message is checked (frame_id, velocity and effort are read past, not kept):
    CdrError if the bytes are not CDR or too short for what they declare. A name is read
    as rclpy reads it, UTF-8 (bytes that are not: replaced, U+FFFD).
    """
    reader = _Reader(JOINT_STATE, data, _order(JOINT_STATE, data, 16))
    stamp = reader.unpack('iI', 4)
    reader.string()                                    # header.frame_id
    name = tuple(reader.string() for _ in range(reader.count()))
    position = reader.doubles()
    reader.doubles(keep=False)                         # velocity
    reader.doubles(keep=False)                         # effort
    return JointStateRead(stamp, name, position)


SOLVE_REQUEST = 'linkage_ros_interfaces/srv/Solve_Request'


def solve_request_of(data: bytes) -> tuple[str, float, float, tuple, tuple, bool]:
    """
    Read (corner, travel m, rack m, force N, torque N m, use_wrench) of a Solve request.

    linkage_ros_interfaces/srv/Solve's request as the node records it (ros/solve_service.py),
    from CDR bytes in place, without the interface package; CdrError if too short.
    """
    reader = _Reader(SOLVE_REQUEST, data, _order(SOLVE_REQUEST, data, 8))
    corner = reader.string()
    travel, rack, *wrench = reader.unpack('8d', 8)
    (use_wrench,) = reader.unpack('B', 1)
    return corner, travel, rack, tuple(wrench[:3]), tuple(wrench[3:]), bool(use_wrench)


def from_cdr(type_name: str, data: bytes) -> Any:
    """Return the rclpy message of type_name ('pkg/msg/Type') held in CDR bytes; else CdrError."""
    from rclpy.serialization import deserialize_message
    kind = message_class(type_name)
    _order(type_name, data, 4)
    try:
        return deserialize_message(bytes(data), kind)
    except Exception as exc:  # rclpy's _rclpy.RCLError, whose module is private
        reason = str(exc).split(', at /')[0].replace('failed to deserialize ROS message: ', '')
        raise CdrError(type_name, data, f'does not decode ({reason})') from None


def to_cdr(msg: Any) -> bytes:
    """Return the CDR bytes of an rclpy message (bytes are passed through)."""
    if isinstance(msg, bytes):
        return msg
    from rclpy.serialization import serialize_message
    return serialize_message(msg)


def message_class(type_name: str) -> type:
    """Return the rclpy message class of 'pkg/msg/Type'; LinkageError if none is installed."""
    package, _, name = type_name.partition('/msg/')
    try:
        return getattr(importlib.import_module(f'{package}.msg'), name)
    except (ImportError, AttributeError, ValueError):
        raise LinkageError(f'type {type_name!r}', f'no Python message class '
                           f'{package}.msg.{name} is installed') from None


def type_name(message: object) -> str:
    """Return the ROS type name of a message class or instance: 'geometry_msgs/msg/PoseStamped'."""
    kind = message if isinstance(message, type) else type(message)
    return f"{kind.__module__.split('.')[0]}/msg/{kind.__name__}"
