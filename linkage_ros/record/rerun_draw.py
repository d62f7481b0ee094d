# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
How a suspension is drawn in Rerun: the scene in 3D, the plots, the blueprint, the columns.

Shows what the scene has and nothing else: base points, one line strip per constraint (a
link or strut: base to carrier point; an arm: axis[0], carrier point, axis[1]), the wheel
carrier frame with its joints, and the wheel as a circle of scene.wheel_radius about the spin
axis at the wheel centre (none if the radius is 0). 3D in mm, vehicle frame (ISO 8855: x
forward, y left, z up); plots in mm and deg.

Entities: suspension/base_points, suspension/labels, suspension/links, suspension/carrier
(Transform3D), suspension/carrier/joints, suspension/carrier/wheel, with statics
suspension/forces/contact and suspension/forces/pickup/<name> (Arrows3D, FORCE_SCALE mm per
N: the contact wrench's force at the contact patch, each pickup's force on the body at its
pickup), plots/travel_mm,
plots/camber_deg, plots/toe_deg, and plots/rack_mm for a scene with a steer: rack link (whose
links' body ends move with the rack). Labels are laid out not to cover each other in the
opening view (label_layout): the link names at their body-side points for one corner, the
corner names for a vehicle. A vehicle (several corners in one recording) has each corner's
entities under its name: front_left/suspension/links, plots/front_left/camber_deg, ...; its
blueprint has one 3D view of all corners and one plot per quantity with a line per corner.
Timelines: 'ros_time' (timestamp: the message's receive time, the MCAP log time) and
'command' (sequence: number of wheel-travel commands received so far, all corners together).

Pure geometry functions first (no recording needed), then one log_* or send_* function per
visual concept and the blueprint. rerun_view.RerunRecorder, the sink, calls them.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import pyarrow as pa
import rerun as rr
import rerun.blueprint as rrb
from rerun.components import LineStrip3DBatch
from rerun.encodings import Vec3DBatch

from .label_layout import place_labels
from ..core.base import camber_toe, carrier_points, matrix_from_quaternion, perpendicular, unit
from ..core.measure import contact_patch, title
from ..core.model import link_polylines
from ..core.solve import sweep, travel_range

if TYPE_CHECKING:
    from collections.abc import Sequence
    from os import PathLike

    from numpy.typing import ArrayLike

    from ..core.model import Scene

APP_ID = 'linkage_ros'
TIME = 'ros_time'
SEQUENCE = 'command'
# plot name (a registry quantity, core/measure/quantities.py): its title, 'camber (deg)'
SERIES = {name: title(name) for name in ('travel_mm', 'camber_deg', 'toe_deg', 'rack_mm')}
WHEEL_SEGMENTS = 72
# Drawing sizes (mm): thin enough not to hide the joints of a 1 m wide corner.
LINK_RADIUS = 4.0
POINT_RADIUS = 10.0
ANCHOR_RADIUS = 0.01     # a label's anchor: a point too small to see
WHEEL_LINE_RADIUS = 3.0
AXES_LENGTH = 100.0
HIDDEN_SCALE = 1e-6      # the carrier of a part of a run that ended: a 500 mm body, 0.5 um
# Force arrows: 0.1 mm per N, a 1 kN force 100 mm long (a corner's pickups carry 0.1 to
# 10 kN, drawn 10 mm to 1 m beside a suspension about 700 mm wide).
FORCE_SCALE = 0.1
ARROW_RADIUS = 3.0
COLORS = {'sphere': (70, 130, 220), 'circle': (230, 140, 40), 'line': (60, 170, 90),
          'base': (150, 150, 150), 'joint': (220, 70, 70), 'wheel': (190, 190, 190),
          'contact': (200, 40, 200), 'pickup': (240, 200, 30)}
# Camera: from the front, outboard and above the corner (x forward, y outboard, z up).
EYE_DIRECTION = (1.0, 0.8, 0.55)
EYE_DISTANCE = 1.7      # times the size of the scene's bounding box


# --- geometry (pure) -----------------------------------------------------------------------

def link_points(scene: Scene, joints: ArrayLike) -> np.ndarray:
    """
    Return the link polylines (core.model.scene.link_polylines) of many poses as one array.

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


def contact_patches(scene: Scene, centers: ArrayLike, quaternions: ArrayLike) -> np.ndarray:
    """
    Return the contact patch (n, 3) mm of each pose: the wheel's lowest point in that pose.

    centers (n, 3) mm, quaternions (n, 4) (x, y, z, w) of the carrier relative to design
    (core.measure.contact_patch of the spin axis turned by each). The statics core holds the
    unloaded pose's patch fixed in the carrier; under load the two differ by the loaded
    rotation times the radius, a fraction of a mm in a drawing.
    """
    axis = unit(scene.wheel_center - scene.spin_axis_point)
    axes = matrix_from_quaternion(np.asarray(quaternions, dtype=float)) @ axis
    return contact_patch(np.asarray(centers, dtype=float), axes, scene.wheel_radius)


def series(scene: Scene) -> list[str]:
    """Return the plots (names of SERIES) a scene has: the rack only with a steer: rack link."""
    return [name for name in SERIES if name != 'rack_mm' or scene.steered]


def rack_points(scene: Scene) -> np.ndarray:
    """
    Return the indexes, in link_points' rows, of the body-side ends that move with the rack.

    Those of steer: rack links (ends along +y by the rack travel).
    """
    starts = np.concatenate([[0], np.cumsum(strip_lengths(scene))[:-1]])
    return np.array([i for c, start in zip(scene.constraints, starts) if c.steer == 'rack'
                     for i in ((start, start + 2) if c.type == 'circle' else (start,))],
                    dtype=int)


def labelled_points(scenes: dict[str, Scene]) -> list[tuple[str, np.ndarray, str]]:
    """
    Return what the 3D view labels: [(root, point (3,) mm, label)], most important first.

    One corner: each link by its name at its (first) body-side point. A vehicle: each corner
    by its name, over its wheel (links' names would crowd a view of four corners).
    """
    if '' in scenes:
        return [('', c.base[0], c.name) for c in scenes[''].constraints]
    return [(root, scene.wheel_center + [0.0, 0.0, max(scene.wheel_radius, 1.0)], root)
            for root, scene in scenes.items()]


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
                  recording_id: str | None = None, rack: bool = True) -> rr.RecordingStream:
    """
    Open a RecordingStream that writes to path (file sink, no viewer) with the blueprint.

    scenes: {root: Scene}, root '' for the single scene or a corner name for each corner.
    rack: give the blueprint a rack plot, if a scene steers (see blueprint).
    """
    rec = rr.RecordingStream(APP_ID, recording_id=recording_id)
    rec.save(str(path), default_blueprint=blueprint(scenes, rack))
    rec.set_log_time_enabled(False)   # only the ROS time and the command count index data
    rec.set_log_tick_enabled(False)
    if '' not in scenes:   # the vehicle view's origin is the root
        rec.log('/', rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
    for root, scene in scenes.items():
        log_scene(rec, scene, root)
    log_labels(rec, scenes)
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

    {series name: (low, high)}: the travel block (mm) and the camber and toe (deg) over it
    and at design, framed so that the plots open on the whole motion with readable ticks. A
    sweep that ends early (a singular scene solves nothing) frames what it solved.
    """
    travel, camber, toe = [], [], []
    for scene in scenes:
        low, high, step = scene.travel
        result = sweep(scene, travel_range(low, high, max(step, (high - low) / 64)))
        design = camber_toe(unit(scene.wheel_center - scene.spin_axis_point), scene.side_sign)
        travel += [low, high]
        camber += [math.degrees(design[0]), *np.degrees(result.camber)]
        toe += [math.degrees(design[1]), *np.degrees(result.toe)]
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


def blueprint(scenes: dict[str, Scene], rack: bool = True) -> rrb.Blueprint:
    """
    Return the blueprint: a 3D view of the scenes ({root: Scene}) beside the plots.

    The travel, camber and toe plots, and the rack's if a scene steers and rack is true (a
    recording known to hold no rack command has none), have one line per corner, on the
    ROS time.
    """
    position, target = eye(list(scenes.values()))
    ranges = plot_ranges(list(scenes.values()))
    shown = [name for name in SERIES if any(name in series(s) for s in scenes.values())
             and (rack or name != 'rack_mm')]

    def axis(name):   # the rack has no range in the scene: Rerun frames its values
        return rrb.ScalarAxis(range=ranges[name]) if name in ranges else None

    if '' in scenes:
        plots = [rrb.TimeSeriesView(origin=f'/plots/{name}', name=SERIES[name],
                                    axis_y=axis(name)) for name in shown]
        origin, contents, name = '/suspension', '$origin/**', scenes[''].name
    else:
        plots = [rrb.TimeSeriesView(origin='/plots', name=SERIES[name], axis_y=axis(name),
                                    contents=[f'/{plot(root, name)}' for root in scenes])
                 for name in shown]
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

    That is the axes convention, the base points (named when hovered; log_labels shows the
    names), and the carrier joints and wheel in the carrier frame.
    """
    rec.log(entity(root, 'suspension'), rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
    points, labels = base_points(scene)
    rec.log(entity(root, 'suspension/base_points'),
            rr.Points3D(points, labels=labels, radii=POINT_RADIUS, colors=COLORS['base'],
                        show_labels=False),
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
    for name in series(scene):
        title = SERIES[name]
        rec.log(plot(root, name), rr.SeriesLines(names=f'{root} {title}' if root else title),
                static=True)


def log_labels(rec: rr.RecordingStream, scenes: dict[str, Scene]) -> None:
    """
    Log the labels of labelled_points where they cover nothing in the opening view.

    Each root's labels go to root/suspension/labels: anchors too small to see, placed by
    label_layout.place_labels for the blueprint's eye; a label with no room is left out.
    """
    found = labelled_points(scenes)
    anchors, kept = place_labels([p for _, p, _ in found], [text for _, _, text in found],
                                 *eye(list(scenes.values())))
    for root in scenes:
        mine = [(anchor, found[i][2]) for anchor, i in zip(anchors, kept)
                if found[i][0] == root]
        if mine:
            rec.log(entity(root, 'suspension/labels'), rr.Points3D(
                [a for a, _ in mine], labels=[t for _, t in mine], radii=ANCHOR_RADIUS,
                colors=COLORS['base'], show_labels=True), static=True)


def send_poses(rec: rr.RecordingStream, scene: Scene, times_ns: Sequence[int],
               sequence: Sequence[int], centers: ArrayLike, quaternions: ArrayLike,
               root: str = '', racks: ArrayLike | None = None) -> None:
    """
    Send poses as columns, under root.

    times_ns (n,), sequence (n,), centers (n, 3) mm, quaternions (n, 4) as (x, y, z, w),
    racks (n,) mm: the rack travel at each pose (None: 0), which moves the body-side ends
    of steer: rack links along +y.
    """
    if len(times_ns) == 0:
        return
    indexes = _indexes(times_ns, sequence)
    rec.send_columns(entity(root, 'suspension/carrier'), indexes=indexes,
                     columns=rr.Transform3D.columns(translation=centers,
                                                    quaternion=quaternions))
    joints = carrier_points(scene.carrier_offsets, np.asarray(centers),
                            matrix_from_quaternion(quaternions))
    points = link_points(scene, joints)
    if racks is not None:
        points[:, rack_points(scene), 1] += np.asarray(racks, dtype=float)[:, None]
    rec.send_columns(entity(root, 'suspension/links'), indexes=indexes,
                     columns=rr.LineStrips3D.columns(
                         strips=_strips_array(scene, points)).partition(
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


def log_forces(rec: rr.RecordingStream, scene: Scene, name: str, times_ns: Sequence[int],
               sequence: Sequence[int], origins: ArrayLike, forces_n: ArrayLike,
               root: str = '', style: bool = True) -> None:
    """
    Log one force over time as an arrow of FORCE_SCALE mm per N under suspension/forces/name.

    name: 'contact' (the tyre's force at the contact patch) or 'pickup/<name>' (the force on
    the body at that pickup); origins (n, 3) mm where it acts, forces_n (n, 3) N, vehicle
    frame; times_ns (n,), sequence (n,). style: also log its colour and width (static: once
    per entity is enough).
    """
    if len(times_ns) == 0:
        return
    path = entity(root, f'suspension/forces/{name}')
    if style:
        rec.log(path, rr.Arrows3D.from_fields(
            radii=ARROW_RADIUS, colors=COLORS['contact' if name == 'contact' else 'pickup']),
            static=True)
    rec.send_columns(path, indexes=_indexes(times_ns, sequence), columns=rr.Arrows3D.columns(
        origins=np.asarray(origins, dtype=float),
        vectors=FORCE_SCALE * np.asarray(forces_n, dtype=float)))


def send_hidden(rec: rr.RecordingStream, time_ns: int, sequence: int, root: str) -> None:
    """
    Draw root's moving bodies no more from time_ns and command sequence on.

    The carrier (its joints and wheel) is scaled to a speck (HIDDEN_SCALE: a scale of 0 is
    not invertible, which Rerun refuses) and the links are cleared; the base points, logged
    static, stay.
    """
    indexes = _indexes([time_ns], [sequence])
    rec.send_columns(entity(root, 'suspension/carrier'), indexes=indexes,
                     columns=rr.Transform3D.columns(scale=[[HIDDEN_SCALE] * 3]))
    rec.send_columns(entity(root, 'suspension/links'), indexes=indexes,
                     columns=rr.Clear.columns(is_recursive=[False]))


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
