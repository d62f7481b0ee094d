"""
Rerun mirror of a run: the scene in 3D and the travel, camber and toe plots, in a .rrd file.

Shows what the scene has and nothing else: base points, one line strip per constraint (a
link or strut: base to carrier point; an arm: axis[0], carrier point, axis[1]), the wheel
carrier frame with its joints, and the wheel as a circle of scene.wheel_radius about the spin
axis at the wheel centre (none if the radius is 0). 3D in mm, vehicle frame (ISO 8855: x
forward, y left, z up); plots in mm and deg.

Entities: suspension/base_points, suspension/links, suspension/carrier (Transform3D),
suspension/carrier/joints, suspension/carrier/wheel, plots/travel_mm, plots/camber_deg,
plots/toe_deg. A vehicle (several corners in one recording) has each corner's entities under
its name: front_left/suspension/links, plots/front_left/camber_deg, ...; its blueprint has one
3D view of all corners and one plot per quantity with a line per corner. Timelines: 'ros_time'
(timestamp: the message's receive time, the MCAP log time) and 'command' (sequence: number of
wheel-travel commands received so far, all corners together).

Pure geometry functions first (no rerun import needed), then one log_* function per visual
concept, the blueprint, and RerunRecorder: the node's sink that logs message by message.
"""

from __future__ import annotations

import math
import os
import resource
import struct
import time
from typing import Any, TYPE_CHECKING

import numpy as np
import pyarrow as pa
import rerun as rr
import rerun.blueprint as rrb
from rerun.components import LineStrip3DBatch
from rerun.encodings import Vec3DBatch

from ..cdr import float64_of, pose_of, to_cdr
from ..core.errors import LinkageError
from ..core.geometry import carrier_points, MM_PER_M, perpendicular, unit
from ..core.kinematics import sweep, travel_range
from ..core.scene import link_polylines

if TYPE_CHECKING:
    from collections.abc import Sequence
    from os import PathLike

    from numpy.typing import ArrayLike

    from ..core.scene import Scene

APP_ID = 'linkage_ros'
TIME = 'ros_time'
SEQUENCE = 'command'
SERIES = {'travel_mm': 'travel (mm)', 'camber_deg': 'camber (deg)', 'toe_deg': 'toe (deg)'}
WHEEL_SEGMENTS = 72
# Drawing sizes (mm): thin enough not to hide the joints of a 1 m wide corner.
LINK_RADIUS = 4.0
POINT_RADIUS = 10.0
WHEEL_LINE_RADIUS = 3.0
AXES_LENGTH = 100.0
COLORS = {'sphere': (70, 130, 220), 'circle': (230, 140, 40), 'line': (60, 170, 90),
          'base': (150, 150, 150), 'joint': (220, 70, 70), 'wheel': (190, 190, 190)}
# Camera: from the front, outboard and above the corner (x forward, y outboard, z up).
EYE_DIRECTION = (1.0, 0.8, 0.55)
EYE_DISTANCE = 1.7      # times the size of the scene's bounding box


# --- geometry (pure) -----------------------------------------------------------------------

def rotation_from_quaternion(q: ArrayLike) -> np.ndarray:
    """Return the rotation matrices (..., 3, 3) of unit quaternions (..., 4) as (x, y, z, w)."""
    q = np.asarray(q, dtype=float)
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    x, y, z, w = np.moveaxis(q, -1, 0)
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
    ], -2)


def link_points(scene: Scene, joints: ArrayLike) -> np.ndarray:
    """
    Return the link polylines (core.scene.link_polylines) of many poses as one array.

    joints (n, m, 3) mm -> (n, sum of polyline lengths, 3) mm, polylines one after another
    in constraint order.
    """
    return np.concatenate(link_polylines(scene, joints), axis=-2)


def strip_lengths(scene: Scene) -> np.ndarray:
    """Return the points per constraint polyline: 3 for an arm (circle), 2 for a link or strut."""
    return np.array([3 if c.type == 'circle' else 2 for c in scene.constraints])


def wheel_circle(scene: Scene, segments: int = WHEEL_SEGMENTS) -> np.ndarray | None:
    """
    Return the wheel as a closed circle (segments + 1, 3) mm of radius scene.wheel_radius.

    The circle is about the spin axis, relative to the wheel centre at design (carrier
    frame); None if the scene has no radius.
    """
    if scene.wheel_radius <= 0:
        return None
    axis = unit(scene.wheel_center - scene.spin_axis_point)
    e1 = perpendicular(axis)
    e2 = np.cross(axis, e1)
    angle = np.linspace(0.0, 2.0 * math.pi, segments + 1)
    return scene.wheel_radius * (np.cos(angle)[:, None] * e1 + np.sin(angle)[:, None] * e2)


def base_points(scene: Scene) -> tuple[np.ndarray, list[str]]:
    """Return (points (k, 3) mm, labels) of every body-side point of the scene."""
    points, labels = [], []
    for c in scene.constraints:
        for i, b in enumerate(c.base):
            points.append(b)
            labels.append(f'{c.name}[{i}]' if len(c.base) > 1 else c.name)
    return np.array(points), labels


# --- logging -------------------------------------------------------------------------------

def new_recording(path: str | PathLike, scenes: dict[str, Scene],
                  recording_id: str | None = None) -> rr.RecordingStream:
    """
    Open a RecordingStream that writes to path (file sink, no viewer) with the blueprint.

    scenes: {root: Scene}, root '' for the single scene or a corner name for each corner.
    """
    rec = rr.RecordingStream(APP_ID, recording_id=recording_id)
    rec.save(str(path), default_blueprint=blueprint(scenes))
    rec.set_log_time_enabled(False)   # only the ROS time and the command count index data
    rec.set_log_tick_enabled(False)
    if '' not in scenes:   # the vehicle view's origin is the root
        rec.log('/', rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
    for root, scene in scenes.items():
        log_scene(rec, scene, root)
    return rec


def entity(root: str, path: str) -> str:
    """Return the entity path of path (like 'suspension/links') under root ('' = none)."""
    return f'{root}/{path}' if root else path


def plot(root: str, name: str) -> str:
    """Return the entity path of the plot of name (in SERIES): plots/name or plots/root/name."""
    return f'plots/{root}/{name}' if root else f'plots/{name}'


def eye(scenes: Sequence[Scene]) -> tuple[np.ndarray, np.ndarray]:
    """Return (position, look target) in mm of a camera that shows every scene (corner) given."""
    points = np.vstack([p for scene in scenes for p in (
        base_points(scene)[0], scene.carrier_offsets + scene.wheel_center,
        scene.wheel_center - [0.0, 0.0, scene.wheel_radius],
        scene.wheel_center + [0.0, 0.0, scene.wheel_radius])])
    low, high = points.min(axis=0), points.max(axis=0)
    target = (low + high) / 2
    side = scenes[0].side_sign if len(scenes) == 1 else 1.0   # a vehicle: from its left
    direction = unit(np.array(EYE_DIRECTION) * [1.0, side, 1.0])
    return target + EYE_DISTANCE * float(np.max(high - low)) * direction, target


def plot_ranges(scenes: list[Scene]) -> dict[str, tuple[float, float]]:
    """
    Frame each plot on the scenes' travel blocks.

    {series name: (low, high)}: the travel block (mm) and the camber and toe (deg) over it,
    framed so that the plots open on the whole motion with readable ticks.
    """
    travel, camber, toe = [], [], []
    for scene in scenes:
        low, high, step = scene.travel
        result = sweep(scene, travel_range(low, high, max(step, (high - low) / 64)))
        travel += [low, high]
        camber += list(np.degrees(result.camber))
        toe += list(np.degrees(result.toe))
    return {'travel_mm': framed(travel), 'camber_deg': framed(camber), 'toe_deg': framed(toe)}


def framed(values: list[float]) -> tuple[float, float]:
    """
    Frame values for a plot with at least three labelled ticks.

    The plot labels round steps (1, 2 or 5 times a power of ten) only where they fall inside
    its range: the range is widened to the round step beyond each end, plus a little.
    """
    low, high = min(values), max(values)
    span = high - low or 1.0
    step = 10.0 ** math.floor(math.log10(span / 2))
    step *= next((f for f in (1, 2, 5) if span / (f * step) <= 4), 10)
    low, high = math.floor(low / step) * step, math.ceil(high / step) * step
    return (low - 0.1 * step, high + 0.1 * step)


def blueprint(scenes: dict[str, Scene]) -> rrb.Blueprint:
    """
    Return the blueprint: a 3D view of the scenes ({root: Scene}) beside the plots.

    The travel, camber and toe plots have one line per corner, on the ROS time.
    """
    position, target = eye(list(scenes.values()))
    ranges = plot_ranges(list(scenes.values()))
    if '' in scenes:
        plots = [rrb.TimeSeriesView(origin=f'/plots/{name}', name=title,
                                    axis_y=rrb.ScalarAxis(range=ranges[name]))
                 for name, title in SERIES.items()]
        origin, contents, name = '/suspension', '$origin/**', scenes[''].name
    else:
        plots = [rrb.TimeSeriesView(origin='/plots', name=title,
                                    contents=[f'/{plot(root, name)}' for root in scenes],
                                    axis_y=rrb.ScalarAxis(range=ranges[name]))
                 for name, title in SERIES.items()]
        origin, contents = '/', [f'/{entity(root, "suspension")}/**' for root in scenes]
        name = 'vehicle'
    view = rrb.Spatial3DView(origin=origin, contents=contents, name=f'{name} (mm)',
                             eye_controls=rrb.EyeControls3D(position=position,
                                                            look_target=target,
                                                            eye_up=[0.0, 0.0, 1.0]))
    return rrb.Blueprint(
        rrb.Horizontal(view, rrb.Vertical(*plots), column_shares=[3, 2]),
        rrb.TimePanel(timeline=TIME, state='collapsed'),
        collapse_panels=True)


def log_scene(rec: rr.RecordingStream, scene: Scene, root: str = '') -> None:
    """
    Log what does not move, under root ('' or a corner name).

    That is the axes convention, the base points, and the carrier joints and wheel in the
    carrier frame.
    """
    rec.log(entity(root, 'suspension'), rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
    points, labels = base_points(scene)
    rec.log(entity(root, 'suspension/base_points'),
            rr.Points3D(points, labels=labels, radii=POINT_RADIUS, colors=COLORS['base'],
                        show_labels=True),
            static=True)
    rec.log(entity(root, 'suspension/carrier'), rr.TransformAxes3D(AXES_LENGTH), static=True)
    rec.log(entity(root, 'suspension/carrier/joints'),
            rr.Points3D(scene.carrier_offsets, labels=[c.name for c in scene.constraints],
                        radii=POINT_RADIUS, colors=COLORS['joint'], show_labels=False),
            static=True)
    circle = wheel_circle(scene)
    if circle is not None:
        rec.log(entity(root, 'suspension/carrier/wheel'),
                rr.LineStrips3D([circle], radii=WHEEL_LINE_RADIUS, colors=COLORS['wheel']),
                static=True)
    # Labelled at the body-side points, which lie apart; at the links' middles they overlap.
    rec.log(entity(root, 'suspension/links'), rr.LineStrips3D.from_fields(
        radii=LINK_RADIUS, colors=[COLORS[c.type] for c in scene.constraints],
        labels=[c.name for c in scene.constraints], show_labels=False), static=True)
    for name, title in SERIES.items():
        rec.log(plot(root, name), rr.SeriesLines(names=f'{root} {title}' if root else title),
                static=True)


def send_poses(rec: rr.RecordingStream, scene: Scene, times_ns: Sequence[int],
               sequence: Sequence[int], centers: ArrayLike, quaternions: ArrayLike,
               root: str = '') -> None:
    """
    Send poses as columns, under root.

    times_ns (n,), sequence (n,), centers (n, 3) mm, quaternions (n, 4) as (x, y, z, w).
    """
    if len(times_ns) == 0:
        return
    indexes = _indexes(times_ns, sequence)
    rec.send_columns(entity(root, 'suspension/carrier'), indexes=indexes,
                     columns=rr.Transform3D.columns(translation=centers,
                                                    quaternion=quaternions))
    joints = carrier_points(scene.carrier_offsets, np.asarray(centers),
                            rotation_from_quaternion(quaternions))
    rec.send_columns(entity(root, 'suspension/links'), indexes=indexes,
                     columns=rr.LineStrips3D.columns(
                         strips=_strips_array(scene, link_points(scene, joints))).partition(
                             [len(scene.constraints)] * len(times_ns)))


def _strips_array(scene, points):
    """
    Return the Arrow array of the strips of link_points (n poses).

    Built from one numpy array and offsets: about 10 times faster than from a list of
    per-strip arrays.
    """
    lengths = np.tile(strip_lengths(scene), len(points))
    offsets = np.concatenate([[0], np.cumsum(lengths)]).astype(np.int32)
    inner = Vec3DBatch(points.reshape(-1, 3).astype(np.float32)).as_arrow_array()
    return pa.ListArray.from_arrays(offsets, inner, type=LineStrip3DBatch._ARROW_DATATYPE)


def send_values(rec: rr.RecordingStream, name: str, times_ns: Sequence[int],
                sequence: Sequence[int], values: ArrayLike, root: str = '') -> None:
    """Send the columns of one plot: times_ns (n,), sequence (n,), values (n,)."""
    if len(times_ns) == 0:
        return
    rec.send_columns(plot(root, name), indexes=_indexes(times_ns, sequence),
                     columns=rr.Scalars.columns(scalars=np.asarray(values, dtype=float)))


def _indexes(times_ns, sequence):
    return [rr.TimeColumn(TIME, timestamp=np.asarray(times_ns, dtype='int64').astype(
        'datetime64[ns]')), rr.TimeColumn(SEQUENCE, sequence=np.asarray(sequence, dtype='int64'))]


# --- the node's sink -----------------------------------------------------------------------

def topic_role(topic: str) -> str | None:
    """Return what a topic carries, from its last name: 'travel', 'pose', 'camber', 'toe', None."""
    return ROLES.get(topic.rstrip('/').rsplit('/', 1)[-1])


ROLES = {'wheel_travel': 'travel', 'wheel_carrier_pose': 'pose', 'camber': 'camber',
         'toe': 'toe'}
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


def probe_write(path):
    """
    Create path and write a byte to it, or raise OSError (/dev/full, no permission, no room).

    rerun-sdk would fail too, but only after a warning of its own on stderr; the file is
    written anew by the recording.
    """
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o666)
    try:
        os.write(fd, b'\0')
    finally:
        os.close(fd)


class RerunRecorder:
    """
    A sink that mirrors the node's messages to a .rrd file (same calls as McapRecorder).

    scene: the one scene drawn, fed its topics from any namespace; or corners: {corner name:
    Scene} of a vehicle, all in this one file, each corner under its name and fed the topics
    of its namespace (/front_left/camber; other corners' topics are not drawn).

    Commands (wheel_travel) advance the 'command' sequence; pose, camber and toe are logged at
    the current command; other topics (diagnostics) are not drawn. Rows are buffered and sent
    as columns (rr.send_columns) every batch_rows rows or batch_delay s, and at close: logging
    row by row costs about 10 times more per command.
    """

    def __init__(self, path: str | PathLike, scene: Scene | None = None,
                 recording_id: str | None = None, batch_rows: int = BATCH_ROWS,
                 batch_delay: float = BATCH_DELAY,
                 corners: dict[str, Scene] | None = None) -> None:
        if (scene is None) == (not corners):
            raise ValueError('RerunRecorder: give either scene or corners, exactly one')
        self.scenes = {'': scene} if scene is not None else dict(corners)
        self.path = str(path)
        self.sequence = 0
        self.batch_rows = batch_rows
        self.batch_delay = batch_delay
        try:
            probe_write(path)
            self._rec = new_recording(path, self.scenes, recording_id)
        except OSError as exc:
            raise LinkageError(path, f'cannot write ({exc.strerror or exc})') from None
        except RuntimeError as exc:   # how rerun-sdk says a failed write
            raise LinkageError(path, f'cannot write ({exc})') from None
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
        if not isinstance(msg, bytes):
            msg = to_cdr(msg)
        if role == 'pose':
            (x, y, z), q = pose_of(msg)
            value = (x * MM_PER_M, y * MM_PER_M, z * MM_PER_M, *q)
        elif role == 'travel':
            self.sequence += 1
            value = MM_PER_M * float64_of(msg)
        else:
            value = math.degrees(float64_of(msg))
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
                           values[:, 3:], root)
            else:
                name = 'travel_mm' if role == 'travel' else f'{role}_deg'
                send_values(self._rec, name, times, sequence, values, root)
            rows.clear()
        self._buffered = 0
        self._oldest = None

    @property
    def error(self) -> str | None:
        """
        Say why the .rrd is no longer written, or None while it is.

        The recording stops itself before a file-size limit or a full disk (see flush). Any
        other write error shows only as a flush that cannot complete: checked on each call
        (the node asks once a diagnostic period).
        """
        if self._error is None and not self._closed:
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
        cut_to_whole_messages(self.path)

    def __enter__(self) -> RerunRecorder:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
