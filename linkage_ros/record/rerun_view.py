# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Rerun mirror of a run: RerunRecorder, the sink that writes what the node does to a .rrd file.

The drawing (entities, geometry, blueprint) is rerun_draw's; this module feeds it messages,
batches rows into columns, and watches the file: Rerun's own writer cannot recover from a
failed write, so the mirror stops, whole, short of a size limit or a full disk.
"""

from __future__ import annotations

import collections
import math
import os
import resource
import struct
import time
from typing import Any, TYPE_CHECKING

import numpy as np
import rerun as rr

from .errors import RecordingError
from .output_file import claim, whereabouts
from .rerun_draw import contact_patches, log_forces, new_recording, send_hidden, \
    send_poses, send_values
from ..answer.cdr import CdrError, float64_of, pose_of, to_cdr, wrench_of
from ..core.base import MM_PER_M

if TYPE_CHECKING:
    from os import PathLike

    from ..core.model import Scene


def topic_role(topic: str) -> str | None:
    """
    Return what a topic carries, from its last name (and a pickup's, its folder).

    'travel', 'rack', 'pose', 'camber', 'toe', 'wrench' (contact_wrench), 'pickup'
    (pickup/<name>), or None for a topic that is not drawn.
    """
    parts = topic.rstrip('/').rsplit('/', 2)
    if len(parts) > 1 and parts[-2] == PICKUP:
        return 'pickup'
    return ROLES.get(parts[-1])


ROLES = {'wheel_travel': 'travel', 'steering_rack': 'rack', 'wheel_carrier_pose': 'pose',
         'camber': 'camber', 'toe': 'toe', 'contact_wrench': 'wrench'}
PICKUP = 'pickup'
FLOAT64 = 'std_msgs/msg/Float64'
WRENCH = 'geometry_msgs/msg/WrenchStamped'
ROLE_TYPES = {'travel': FLOAT64, 'rack': FLOAT64, 'camber': FLOAT64, 'toe': FLOAT64,
              'pose': 'geometry_msgs/msg/PoseStamped', 'wrench': WRENCH,
              'pickup': WRENCH}   # the type each role is drawn from


def role_reader(role: str):
    """Return the function that reads a message of role in place (cdr: pose_of, ...)."""
    return {'pose': pose_of, 'wrench': wrench_of, 'pickup': wrench_of}.get(role, float64_of)


PLOTS = {'travel': 'travel_mm', 'rack': 'rack_mm', 'camber': 'camber_deg', 'toe': 'toe_deg'}
BATCH_ROWS = 256       # rows buffered before they are sent as columns
BATCH_DELAY = 0.5      # s (wall clock): or once the oldest buffered row is this old
FLUSH_TIMEOUT = 2.0    # s: a flush of the .rrd that takes longer means its writer stopped
ROOM = 256 * 1024       # bytes: a recording stops, whole, this far from a limit or a full disk
_ABANDONED = []          # streams whose writer failed: never ended (see _broken)


class _LeftAlone(rr.RecordingStream):
    """A stream whose writer failed: its finalizer would wait forever on it (see _broken)."""

    def __del__(self) -> None:
        pass


def cut_to_whole_messages(path):
    """
    Cut a .rrd whose writing failed after its last whole message, so that readers read it.

    The file is a 12-byte header (b'RRF2', version, options) and messages, each a 16-byte
    header (kind, length: two little-endian uint64) and its payload; a write that failed
    leaves a message cut short at the end, which Rerun's readers refuse whole. A file that
    ends with its footer (b'RRF2FOOT' and a version, after the end message) is whole: kept.
    """
    try:
        with open(path, 'r+b') as stream:
            size = os.fstat(stream.fileno()).st_size
            stream.seek(max(size - 12, 0))
            if stream.read(8) == b'RRF2FOOT':
                return
            end = 12
            stream.seek(end)
            while end + 16 <= size:
                _, length = struct.unpack('<QQ', stream.read(16))
                if end + 16 + length > size:
                    break
                end += 16 + length
                stream.seek(end)
            stream.truncate(min(end, size))
    except OSError:
        pass   # nothing more can be done: the failure is reported already


def lack_of_room(path, room=ROOM):
    """
    Say why path cannot take room more bytes, or '' if it can.

    The file gone (removed while written), a file-size limit (ulimit -f) or a full file
    system within room bytes.
    """
    try:
        size = os.path.getsize(path)
    except OSError:
        return f'{path} is gone (removed while recording)'
    limit = resource.getrlimit(resource.RLIMIT_FSIZE)[0]
    if limit != resource.RLIM_INFINITY and size + room >= limit:
        return f'file size limit reached ({size} of {limit} bytes, ulimit -f)'
    space = os.statvfs(os.path.dirname(os.path.abspath(path)))
    free = space.f_bavail * space.f_frsize
    if free < room:
        return f'file system full ({free} bytes free)'
    return ''


class RerunRecorder:
    """
    A sink that mirrors the node's messages to a .rrd file (same calls as McapRecorder).

    scene: the one scene drawn, fed its topics from any namespace; or corners: {corner name:
    Scene} of a vehicle, all in this one file, each corner under its name and fed the topics
    of its namespace (/front_left/camber; other corners' topics are not drawn).

    Commands (wheel_travel) advance the 'command' sequence; the rack (steering_rack), pose,
    camber and toe are logged at the current command, each pose with the last rack. Forces
    are arrows (rerun_draw.log_forces, FORCE_SCALE mm per N): the last contact_wrench's
    force at the contact patch of each pose that follows it, and each pickup/<name> force
    at its pickup (the scene's point, a rack link's moved with the rack); other
    topics (diagnostics) are not drawn, nor a message of another type than its topic's role
    (ROLE_TYPES), nor one whose bytes do not decode (cdr.CdrError): a hostile sample must not
    stop the mirror. Those are counted in skipped ({topic: count}). Rows are buffered and
    sent as columns (rr.send_columns) every batch_rows rows or batch_delay s, and at close:
    logging row by row costs about 10 times more per command.

    rack: give the view a rack plot if a scene steers (False for a recording known to have
    no rack command).

    The file is claimed as McapRecorder's is (output_file.claim: a second recorder of it is
    refused), and watched: removed or replaced, the recording stops and error says so.
    """

    def __init__(self, path: str | PathLike, scene: Scene | None = None,
                 recording_id: str | None = None, batch_rows: int = BATCH_ROWS,
                 batch_delay: float = BATCH_DELAY,
                 corners: dict[str, Scene] | None = None, rack: bool = True) -> None:
        if (scene is None) == (not corners):
            raise ValueError('RerunRecorder: give either scene or corners, exactly one')
        self.scenes = {'': scene} if scene is not None else dict(corners)
        self.path = str(path)
        self._where = os.path.abspath(path)
        self.sequence = 0
        self.batch_rows = batch_rows
        self.batch_delay = batch_delay
        self.skipped = collections.Counter()
        self._fd = claim(path)   # held until the end: the lock, and the file watched
        try:
            self._rec = new_recording(path, self.scenes, recording_id, rack)
        except BaseException as exc:
            os.close(self._fd)
            if not isinstance(exc, (OSError, RuntimeError)):   # RuntimeError: rerun-sdk's
                raise
            reason = getattr(exc, 'strerror', None) or exc
            raise RecordingError(path, f'cannot write ({reason})') from None
        self._racks = dict.fromkeys(self.scenes, 0.0)   # root: last rack (mm)
        self._wrenches = dict.fromkeys(self.scenes)     # root: last contact force (N)
        self._pickups = {}     # root: {pickup name: (point (3,) mm, moves with the rack)}
        self._styled = set()   # (root, force) whose arrows' colour and width are logged
        self._rows = {}        # (root, role): [(receive_ns, sequence, value)]
        self._buffered = 0
        self._oldest = None
        self._closed = False
        self._error = None

    def record(self, topic: str, type_name: str, msg: Any, receive_ns: int,
               publish_ns: int) -> None:
        """Buffer one message (CDR bytes or an rclpy message) by its topic's role; times in ns."""
        role, root = topic_role(topic), self._root(topic)
        if role is None or root is None or self._closed:
            return
        if type_name != ROLE_TYPES[role]:
            self.skipped[topic] += 1
            return
        if not isinstance(msg, bytes):
            msg = to_cdr(msg)
        try:
            if role == 'pose':
                (x, y, z), q = pose_of(msg)
                value = (x * MM_PER_M, y * MM_PER_M, z * MM_PER_M, *q, self._racks[root])
            elif role in ('wrench', 'pickup'):
                value = wrench_of(msg)[1]
            elif role in ('travel', 'rack'):
                value = MM_PER_M * float64_of(msg)
            else:
                value = math.degrees(float64_of(msg))
        except CdrError:
            self.skipped[topic] += 1
            return
        if role == 'travel':
            self.sequence += 1
        elif role == 'rack':
            self._racks[root] = value
        elif role == 'wrench':    # drawn with the poses that answer with it
            self._wrenches[root] = value
            return
        elif role == 'pickup':
            role, value = self._pickup(root, topic, value)
            if role is None:
                self.skipped[topic] += 1
                return
        if role == 'pose' and self._wrenches[root] is not None:
            self._add(root, 'contact', receive_ns, (*value[:7], *self._wrenches[root]))
        self._add(root, role, receive_ns, value)

    def _pickup(self, root, topic, force):
        """Return the row key and value (point mm, force N) of a pickup's force, or None."""
        if root not in self._pickups:   # where each is at rack 0, and how the rack moves it
            from ..answer.pickups import pickup_points
            scene = self.scenes[root]
            at_zero = pickup_points(scene)
            at_one = pickup_points(scene, rack_mm=1.0) if scene.steered else at_zero
            self._pickups[root] = {name: (point, at_one[name] - point)
                                   for name, point in at_zero.items()}
        name = topic.rstrip('/').rsplit('/', 1)[-1]
        if name not in self._pickups[root]:
            return None, None
        point, per_mm = self._pickups[root][name]
        return f'pickup/{name}', (*(point + self._racks[root] * per_mm), *force)

    def _add(self, root, role, receive_ns, value):
        """Buffer one row of root's role; flush the rows when the batch is full or old."""
        self._rows.setdefault((root, role), []).append((receive_ns, self.sequence, value))
        self._buffered += 1
        now = time.monotonic()
        if self._oldest is None:
            self._oldest = now
        if self._buffered >= self.batch_rows or now - self._oldest >= self.batch_delay:
            self.flush()

    def _root(self, topic):
        """
        Return the root a topic (/.../corner/name) is drawn under.

        '' for the single scene; else the corner it belongs to, or None if it is no corner of
        this recording.
        """
        if '' in self.scenes:
            return ''
        if topic_role(topic) == 'pickup':    # /front_left/pickup/<name>
            topic = topic.rstrip('/').rsplit('/', 1)[0]
        parts = topic.rstrip('/').rsplit('/', 2)
        return parts[1] if len(parts) == 3 and parts[1] in self.scenes else None

    def flush(self) -> None:
        """
        Send the buffered rows as columns.

        Rerun's file writer hangs for good on a failed write (rerun-sdk 0.41), so a batch is
        sent only while the file has room for it; else the recording stops, and the file
        is ended whole while it still can be.
        """
        if self._closed:
            return
        gone = whereabouts(self._fd, self._where)
        if gone:                  # what is written reaches no one: stop, touch nothing at path
            self._error = f'{gone}; the .rrd ends there'
            self._closed = True
            self._end()
            return
        problem = lack_of_room(self.path)
        if problem:
            self._error = f'{problem}; the .rrd ends there'
            self._closed = True
            self._end()
            cut_to_whole_messages(self.path)   # in case the end did not fit any more
            return
        for (root, role), rows in self._rows.items():
            if not rows:
                continue
            times, sequence, values = zip(*rows)
            if role == 'pose':
                values = np.array(values)
                send_poses(self._rec, self.scenes[root], times, sequence, values[:, :3],
                           values[:, 3:7], root, values[:, 7])
            elif role == 'contact' or role.startswith('pickup/'):
                values, styled = np.array(values), (root, role) in self._styled
                origins = values[:, :3] if role != 'contact' else contact_patches(
                    self.scenes[root], values[:, :3], values[:, 3:7])
                log_forces(self._rec, self.scenes[root], role, times, sequence, origins,
                           values[:, -3:], root, style=not styled)
                self._styled.add((root, role))
            else:
                send_values(self._rec, PLOTS[role], times, sequence, values, root)
            rows.clear()
        self._buffered = 0
        self._oldest = None

    def hide(self, root: str, time_ns: int) -> None:
        """
        Draw root's carrier and links no more from time_ns on (rerun_draw.send_hidden).

        For a part of a run that ended (linkage-rerun draws each part under its own root):
        from the next command on, the next part shows alone but for the base points.
        """
        self.flush()
        if not self._closed:
            send_hidden(self._rec, time_ns, self.sequence + 1, root)

    @property
    def error(self) -> str | None:
        """
        Say why the .rrd is no longer written, or None while it is.

        The recording stops itself before a file-size limit or a full disk (see flush). Any
        other write error shows only as a flush that cannot complete: checked on each call
        (the node asks once a diagnostic period).
        """
        if self._error is None and not self._closed:
            gone = whereabouts(self._fd, self._where)
            if gone:
                self._error = f'{gone}; the .rrd ends there'
                self._closed = True
                self._end()
                return self._error
            try:
                self._rec.flush(timeout_sec=FLUSH_TIMEOUT)
            except RuntimeError:
                self._broken()
        return self._error

    def close(self) -> None:
        """Send what is buffered and end the file. Idempotent."""
        self.flush()
        if not self._closed:
            self._closed = True
            self._end()

    def _end(self):
        """Write what is sent and end the file, or leave a broken writer alone."""
        if self._rec not in _ABANDONED:
            try:
                self._rec.flush(timeout_sec=FLUSH_TIMEOUT)
            except RuntimeError:
                self._broken()
        if self._rec not in _ABANDONED:
            self._rec.disconnect()
        self._release()

    def _release(self):
        """Close the claimed file descriptor (and so its lock), once."""
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None

    def _broken(self):
        """
        Give up a stream whose writer failed: keep the file's whole messages.

        rerun-sdk 0.41's disconnect(), its shutdown at exit and the stream's finalizer can
        wait forever on such a writer, so the stream is kept referenced and never ended.
        """
        self._error = self._error or ('the .rrd writer stopped: '
                                      f'{lack_of_room(self.path) or "a write failed"}')
        self._closed = True
        self._rec.__class__ = _LeftAlone
        _ABANDONED.append(self._rec)
        rr.unregister_shutdown()
        if self._fd is not None and not whereabouts(self._fd, self._where):
            cut_to_whole_messages(self.path)   # never a file put in its place
        self._release()

    def __enter__(self) -> RerunRecorder:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
