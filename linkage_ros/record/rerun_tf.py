# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
A Rerun view of a recording drawn from what any ROS viewer draws: its URDF and its TF.

    counts = convert_tf(bag, 'run_tf.rrd')     linkage-rerun BAG --tf

No scene file is read: the bodies are the URDF of /robot_description, loaded by Rerun's own
URDF loader (its visual geometry, without its joints' transforms), and they are placed by the
transforms of /tf (at their stamps, on the ros_time timeline) and /tf_static, each logged with
its parent and child frame, as RViz and Foxglove place a robot model.

A run whose scene changed while the node ran holds a /robot_description per scene (the node
sends the new one, and /tf_static, at the change): each starts a part of the run. The
parts are drawn each with its own URDF, under robot_part<k>, its frames prefixed part<k>/
(Rerun's frame_prefix) and hung from the one root frame, placed by the /tf and /tf_static
received during the part; out of its part a URDF's frames are scaled down by HIDDEN (a scale
of 0 is not invertible, and Rerun then draws no frame of the view at all), so that one robot
shows at a time.

Beside the 3D view: travel (mm), camber and toe (deg) of every corner, from their topics.
What the package's own drawing (rerun_draw) shows from the scene, this shows from the bag
alone: a check that the recording carries a robot that third-party viewers can draw.
"""

from __future__ import annotations

import bisect
import math
from pathlib import Path
import tempfile
from typing import TYPE_CHECKING
import unicodedata
from xml.etree import ElementTree

import numpy as np
import rerun as rr
import rerun.blueprint as rrb

from .rerun_draw import APP_ID, EYE_DIRECTION, EYE_DISTANCE, framed, TIME
from ..answer.cdr import CdrError, float64_of, string_of, transforms_of
from ..core.base import LinkageError, unit
from ..core.model import name_problem

if TYPE_CHECKING:
    from .mcap_reader import Bag

STRING, TF = 'std_msgs/msg/String', 'tf2_msgs/msg/TFMessage'
FLOAT64 = 'std_msgs/msg/Float64'
# the plots: topic's last name -> (plot, factor from the message's SI value)
PLOTS = {'wheel_travel': ('travel (mm)', 1000.0), 'camber': ('camber (deg)', 180 / math.pi),
         'toe': ('toe (deg)', 180 / math.pi)}
ROBOT = 'robot'
HIDDEN = 1e-6     # the scale of a URDF out of its part: a 1 m body shows as 1 um


def convert_tf(bag: Bag, output: str | Path, recording_id: str | None = None) -> dict:
    """
    Write the view of a Bag's URDF and TF into output (.rrd); return {what: count}.

    LinkageError if the bag holds no /robot_description or no /tf (a recording made with the
    node's tf off, or by an older version).
    """
    descriptions, dynamic, static, plots = _read(bag)
    if not descriptions or not dynamic:
        raise LinkageError(str(bag.path), 'no /robot_description and /tf to draw from (the '
                           'node records them with its parameter tf on, its default; so does '
                           'linkage-replay)')
    for when, description in descriptions:   # Rerun's URDF reader would raise
        problem = urdf_problem(description)
        if problem:
            raise LinkageError(str(bag.path), f'the /robot_description recorded at {when} ns '
                               f'{problem}: not drawn')
    for child, rows in [*dynamic.items(), *((c, [r]) for c, r in static.items())]:
        for name in {child, *(r[1] if len(r) > 3 else r[0] for r in rows)}:
            problem = name_problem(name)
            if problem:
                raise LinkageError(str(bag.path), f'a frame of its /tf: {problem}: not drawn')
    parts = len(descriptions) > 1
    if parts:
        dynamic = _hidden_out_of_part(dynamic)
    rec = rr.RecordingStream(APP_ID, recording_id=recording_id)
    rec.save(str(output), default_blueprint=_blueprint(dynamic, plots, len(descriptions)))
    rec.set_log_time_enabled(False)
    rec.set_log_tick_enabled(False)
    rec.log('/', rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
    with tempfile.TemporaryDirectory() as folder:
        for k, (_, description) in enumerate(descriptions):
            path = Path(folder) / f'robot{k}.urdf'
            path.write_text(description)
            tree = (rr.urdf.UrdfTree.from_file_path(path, _robot(k, parts),
                                                    frame_prefix=_prefix(k, parts))
                    if parts else rr.urdf.UrdfTree.from_file_path(path, ROBOT))
            rec.send_chunks(tree.stream(include_joint_transforms=False))
            if parts:   # every part's root hangs from the one root frame of the view
                root = tree.root_link().name.removeprefix(_prefix(k, parts))
                rec.log(f'tf_static/{_prefix(k, parts)}{root}', rr.Transform3D(
                    parent_frame=root, child_frame=_prefix(k, parts) + root), static=True)
    for child, (parent, t, q) in static.items():
        rec.log(f'tf_static/{child}', rr.Transform3D(
            translation=t, quaternion=rr.Quaternion(xyzw=q), parent_frame=parent,
            child_frame=child), static=True)
    for child, rows in dynamic.items():
        rows = sorted(rows, key=lambda r: r[0])
        times = np.array([r[0] for r in rows], dtype='int64').astype('datetime64[ns]')
        rec.send_columns(f'tf/{child}', indexes=[rr.TimeColumn(TIME, timestamp=times)],
                         columns=rr.Transform3D.columns(
                             translation=[r[2] for r in rows],
                             quaternion=[r[3] for r in rows],
                             parent_frame=[r[1] for r in rows],
                             child_frame=[child] * len(rows),
                             **({'scale': [[r[4] if len(r) > 4 else 1.0] * 3 for r in rows]}
                                if parts else {})))
    for entity, rows in plots.items():
        times = np.array([r[0] for r in rows], dtype='int64').astype('datetime64[ns]')
        rec.send_columns(entity, indexes=[rr.TimeColumn(TIME, timestamp=times)],
                         columns=rr.Scalars.columns(scalars=[r[1] for r in rows]))
    rec.flush()
    rec.disconnect()
    return {**({'URDFs': len(descriptions)} if parts else {}),
            'frames': len(dynamic) + len(static),
            'transforms': sum(1 for rows in dynamic.values() for r in rows if len(r) == 4),
            'plotted values': sum(len(rows) for rows in plots.values())}


def urdf_problem(text: str) -> str:
    """Say why text cannot be drawn as a URDF (its characters, or not XML); '' if it can."""
    bad = sorted({c for c in text if unicodedata.category(c)[0] == 'C' and c not in '\t\n\r'})
    if bad:
        return (f"holds {', '.join(f'U+{ord(c):04X}' for c in bad)}: control or unassigned "
                'characters, which no URDF (XML) holds')
    try:
        ElementTree.fromstring(text)
    except ElementTree.ParseError as exc:
        return f'is not XML ({exc})'
    return ''


def _robot(k, parts):
    """Return the entity the URDF of part k (from 0) is drawn under: robot, or robot_part1..."""
    return f'{ROBOT}_part{k + 1}' if parts else ROBOT


def _prefix(k, parts):
    """Return the frame prefix of part k (from 0): 'part1/', ...; '' for a run of one part."""
    return f'part{k + 1}/' if parts else ''


def _hidden_out_of_part(dynamic):
    """
    Add to each frame's rows a transform scaled by HIDDEN where its part does not run.

    dynamic: {prefixed child: [(ns, parent, t, q)]}. A part runs from its frames' first
    stamp to the first stamp of the next part; before and after, its frames are scaled to
    a speck (rows (ns, parent, t, q, HIDDEN)), so that its URDF does not show.
    """
    first = {}
    for child, rows in dynamic.items():
        part = child.split('/', 1)[0]
        first[part] = min(first.get(part, rows[0][0]), min(r[0] for r in rows))
    order = sorted(first, key=first.get)
    start = min(first.values())
    hidden = {}
    for child, rows in dynamic.items():
        part = child.split('/', 1)[0]
        parent, t, q = rows[0][1:4]
        extra = [] if first[part] == start else [(start, parent, t, q, HIDDEN)]
        index = order.index(part)
        if index + 1 < len(order):
            extra.append((first[order[index + 1]], parent, t, q, HIDDEN))
        hidden[child] = rows + extra
    return hidden


def _read(bag):
    """
    Return the URDFs [(log ns, text)], the transforms and the plots of a bag.

    Transforms: {child: [(ns, parent, t, q)]} of /tf at their stamps, {child: (parent, t, q)}
    of /tf_static; with more than one URDF, each message belongs to the part of the last
    URDF received before it, and its frames carry the part's prefix.
    """
    descriptions, dynamic, static, plots = [], {}, {}, {}
    for m in bag.messages:
        if m.topic.endswith('/robot_description') and m.carries(STRING):
            try:
                descriptions.append((m.log_time, string_of(m.data)))
            except CdrError:
                continue
    descriptions.sort(key=lambda d: d[0])
    starts = [t for t, _ in descriptions[1:]]
    parts = len(descriptions) > 1
    for m in bag.messages:
        try:
            if m.topic in ('/tf', '/tf_static') and m.carries(TF):
                prefix = _prefix(bisect.bisect_right(starts, m.log_time), parts)
                for stamp, parent, child, t, q in transforms_of(m.data):
                    parent, child = prefix + parent, prefix + child
                    if m.topic == '/tf_static':
                        static[child] = (parent, t, q)
                    else:
                        dynamic.setdefault(child, []).append(
                            (stamp[0] * 10**9 + stamp[1], parent, t, q))
            elif m.topic.rsplit('/', 1)[-1] in PLOTS and m.carries(FLOAT64):
                name, factor = PLOTS[m.topic.rsplit('/', 1)[-1]]
                corner = m.topic.rsplit('/', 1)[0].strip('/')
                entity = f'plots/{name.split(" ")[0]}' + (f'/{corner}' if corner else '')
                plots.setdefault(entity, []).append((m.log_time, float64_of(m.data) * factor))
        except CdrError:
            continue       # a message that does not decode is not drawn (the reader names it)
    return descriptions, dynamic, static, plots


def _blueprint(dynamic, plots, urdfs=1):
    """Return the 3D view of the robot, looked at from the front left, beside the plots."""
    points = np.array([r[2] for rows in dynamic.values() for r in rows if len(r) == 4])
    low, high = points.min(axis=0), points.max(axis=0)
    target = (low + high) / 2
    position = target + EYE_DISTANCE * 1.15 * float(np.max(high - low)) * unit(
        np.array(EYE_DIRECTION))
    views = []
    for name, _ in PLOTS.values():
        short = name.split(' ')[0]
        values = [r[1] for entity, rows in plots.items() if entity.startswith(f'plots/{short}')
                  for r in rows]
        if values:
            views.append(rrb.TimeSeriesView(origin=f'/plots/{short}', name=name,
                                            axis_y=rrb.ScalarAxis(range=framed(values))))
    robots = [f'/{_robot(k, urdfs > 1)}/**' for k in range(urdfs)]
    view = rrb.Spatial3DView(origin='/', contents=[*robots, '/tf/**', '/tf_static/**'],
                             name='URDF placed by /tf (m)',
                             eye_controls=rrb.EyeControls3D(position=position,
                                                            look_target=target,
                                                            eye_up=[0.0, 0.0, 1.0]))
    return rrb.Blueprint(rrb.Horizontal(view, rrb.Vertical(*views), column_shares=[3, 2]),
                         rrb.TimePanel(timeline=TIME, state='collapsed'),
                         collapse_panels=True)
