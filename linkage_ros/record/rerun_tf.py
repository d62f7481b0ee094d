"""
A Rerun view of a recording drawn from what any ROS viewer draws: its URDF and its TF.

    counts = convert_tf(bag, 'run_tf.rrd')     linkage-rerun BAG --tf

No scene file is read: the bodies are the URDF of /robot_description (the last one), loaded
by Rerun's own URDF loader (its visual geometry, without its joints' transforms), and they
are placed by the transforms of /tf (at their stamps, on the ros_time timeline) and
/tf_static, each logged with its parent and child frame, as RViz and Foxglove place a robot
model. Beside the 3D view: travel (mm), camber and toe (deg) of every corner, from their
topics. What the package's own drawing (rerun_draw) shows from the scene, this shows from the
bag alone: a check that the recording carries a robot that third-party viewers can draw.
"""

from __future__ import annotations

import math
from pathlib import Path
import tempfile
from typing import TYPE_CHECKING

import numpy as np
import rerun as rr
import rerun.blueprint as rrb

from .rerun_draw import APP_ID, EYE_DIRECTION, EYE_DISTANCE, framed, TIME
from ..cdr import CdrError, float64_of, string_of, transforms_of
from ..core.base import LinkageError, unit

if TYPE_CHECKING:
    from .mcap_reader import Bag

STRING, TF = 'std_msgs/msg/String', 'tf2_msgs/msg/TFMessage'
FLOAT64 = 'std_msgs/msg/Float64'
# the plots: topic's last name -> (plot, factor from the message's SI value)
PLOTS = {'wheel_travel': ('travel (mm)', 1000.0), 'camber': ('camber (deg)', 180 / math.pi),
         'toe': ('toe (deg)', 180 / math.pi)}
ROBOT = 'robot'


def convert_tf(bag: Bag, output: str | Path, recording_id: str | None = None) -> dict:
    """
    Write the view of a Bag's URDF and TF into output (.rrd); return {what: count}.

    LinkageError if the bag holds no /robot_description or no /tf (a recording made with the
    node's tf off, or by an older version).
    """
    description, dynamic, static, plots = _read(bag)
    if description is None or not dynamic:
        raise LinkageError(str(bag.path), 'no /robot_description and /tf to draw from (the '
                           'node records them with its parameter tf on, its default; so does '
                           'linkage-replay)')
    rec = rr.RecordingStream(APP_ID, recording_id=recording_id)
    rec.save(str(output), default_blueprint=_blueprint(dynamic, plots))
    rec.set_log_time_enabled(False)
    rec.set_log_tick_enabled(False)
    rec.log('/', rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / 'robot.urdf'
        path.write_text(description)
        tree = rr.urdf.UrdfTree.from_file_path(path, ROBOT)
        rec.send_chunks(tree.stream(include_joint_transforms=False))
    for child, (parent, t, q) in static.items():
        rec.log(f'tf_static/{child}', rr.Transform3D(
            translation=t, quaternion=rr.Quaternion(xyzw=q), parent_frame=parent,
            child_frame=child), static=True)
    for child, rows in dynamic.items():
        times = np.array([r[0] for r in rows], dtype='int64').astype('datetime64[ns]')
        rec.send_columns(f'tf/{child}', indexes=[rr.TimeColumn(TIME, timestamp=times)],
                         columns=rr.Transform3D.columns(
                             translation=[r[2] for r in rows],
                             quaternion=[r[3] for r in rows],
                             parent_frame=[r[1] for r in rows],
                             child_frame=[child] * len(rows)))
    for entity, rows in plots.items():
        times = np.array([r[0] for r in rows], dtype='int64').astype('datetime64[ns]')
        rec.send_columns(entity, indexes=[rr.TimeColumn(TIME, timestamp=times)],
                         columns=rr.Scalars.columns(scalars=[r[1] for r in rows]))
    rec.flush()
    rec.disconnect()
    return {'frames': len(dynamic) + len(static),
            'transforms': sum(len(rows) for rows in dynamic.values()),
            'plotted values': sum(len(rows) for rows in plots.values())}


def _read(bag):
    """Return the URDF, {child: [(ns, parent, t, q)]}, {child: (parent, t, q)}, the plots."""
    description, dynamic, static, plots = None, {}, {}, {}
    for m in bag.messages:
        try:
            if m.topic.endswith('/robot_description') and m.carries(STRING):
                description = string_of(m.data)
            elif m.topic in ('/tf', '/tf_static') and m.carries(TF):
                for stamp, parent, child, t, q in transforms_of(m.data):
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
    return description, dynamic, static, plots


def _blueprint(dynamic, plots):
    """Return the 3D view of the robot, looked at from the front left, beside the plots."""
    points = np.array([r[2] for rows in dynamic.values() for r in rows])
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
    view = rrb.Spatial3DView(origin='/', contents=[f'/{ROBOT}/**', '/tf/**', '/tf_static/**'],
                             name='URDF placed by /tf (m)',
                             eye_controls=rrb.EyeControls3D(position=position,
                                                            look_target=target,
                                                            eye_up=[0.0, 0.0, 1.0]))
    return rrb.Blueprint(rrb.Horizontal(view, rrb.Vertical(*views), column_shares=[3, 2]),
                         rrb.TimePanel(timeline=TIME, state='collapsed'),
                         collapse_panels=True)
