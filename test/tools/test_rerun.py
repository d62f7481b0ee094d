# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Rerun mirror: geometry drawn from the pose alone, and the .rrd read back headless.

The .rrd files are opened with rerun's own reader (rerun.chunk.RrdReader) and checked with
the rerun binary (`rerun rrd verify`), never with project code.
"""

import collections
import math
import os
from pathlib import Path
import subprocess
import sys

from linkage_ros.core.base import carrier_points, matrix_from_quaternion
from linkage_ros.core.model import link_polylines, load_scene
from linkage_ros.core.solve import sweep, travel_range
from linkage_ros.record.rerun_draw import link_points, wheel_circle
from linkage_ros.record.rerun_view import RerunRecorder
from linkage_ros.tools.rerun_convert import main
import numpy as np
import pytest
from rerun.chunk import RrdReader
import yaml

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / 'bags' / 'five_link_sweep.mcap'
RERUN = Path(sys.executable).parent / 'rerun'
SCENES = ('five_link', 'double_wishbone', 'macpherson')
DYNAMIC = {'/suspension/carrier', '/suspension/links', '/plots/travel_mm', '/plots/camber_deg',
           '/plots/toe_deg'}
STATIC = {'/suspension', '/suspension/base_points', '/suspension/labels', '/suspension/carrier',
          '/suspension/carrier/joints', '/suspension/carrier/wheel', '/suspension/links',
          '/plots/travel_mm', '/plots/camber_deg', '/plots/toe_deg'}


def contents(path):
    """{(entity, static): (rows, column names)} of the recording in an .rrd, and its timelines."""
    reader = RrdReader(str(path))
    rows, columns, timelines = collections.Counter(), collections.defaultdict(set), set()
    for chunk in reader.stream(store=reader.recordings()[0]):
        if chunk.entity_path.startswith('/__'):
            continue
        key = (chunk.entity_path, chunk.is_static)
        rows[key] += chunk.num_rows
        columns[key] |= set(chunk.to_record_batch().schema.names)
        timelines |= set(chunk.timeline_names)
    return rows, columns, timelines


def column(path, entity, name):
    """All values of one column of an entity's temporal chunks, in (command) order."""
    reader = RrdReader(str(path))
    pairs = []
    for chunk in reader.stream(store=reader.recordings()[0]):
        if chunk.entity_path == entity and not chunk.is_static:
            batch = chunk.to_record_batch()
            pairs += zip(batch.column('command').to_pylist(), batch.column(name).to_pylist())
    return [value for _, value in sorted(pairs, key=lambda p: p[0])]


@pytest.mark.parametrize('name', SCENES)
def test_carrier_points_from_the_pose_alone_are_the_solved_joints(name):
    scene = load_scene(name)
    result = sweep(scene, travel_range(-40, 40, 5))
    rotation = matrix_from_quaternion(result.quaternion)
    assert np.allclose(rotation, result.rotation, atol=1e-12)
    assert np.allclose(carrier_points(scene.carrier_offsets, result.wheel_center, rotation),
                       result.joints,
                       atol=1e-9)


def test_at_design_the_carrier_points_are_the_scene_points():
    scene = load_scene('double_wishbone')
    points = carrier_points(scene.carrier_offsets, scene.wheel_center, np.eye(3))
    assert np.array_equal(points, np.array([c.carrier for c in scene.constraints]))


@pytest.mark.parametrize('name, shapes', [
    ('five_link', [2, 2, 2, 2, 2]),
    ('double_wishbone', [3, 3, 2]),        # arms: axis[0], carrier point, axis[1]
    ('macpherson', [3, 2, 2]),             # arm, tie rod, strut: top mount to carrier point
])
def test_each_constraint_is_one_line_strip_from_the_body_to_the_carrier(name, shapes):
    scene = load_scene(name)
    joints = np.array([c.carrier for c in scene.constraints])
    strips = link_polylines(scene, joints)
    assert [len(s) for s in strips] == shapes
    for c, strip, joint in zip(scene.constraints, strips, joints):
        assert np.array_equal(strip[0], c.base[0]) and np.array_equal(strip[1], joint)
        if c.type == 'circle':
            assert np.array_equal(strip[2], c.base[1])


@pytest.mark.parametrize('name', SCENES)
def test_batched_link_points_are_the_strips_of_each_pose_end_to_end(name):
    scene = load_scene(name)
    result = sweep(scene, travel_range(-20, 20, 10))
    points = link_points(scene, result.joints)
    for pose, joints in zip(points, result.joints):
        assert np.array_equal(pose, np.vstack(link_polylines(scene, joints)))


def test_the_wheel_is_a_circle_of_the_scene_radius_square_to_the_spin_axis():
    scene = load_scene('five_link')
    circle = wheel_circle(scene)
    axis = scene.wheel_center - scene.spin_axis_point
    assert np.allclose(np.linalg.norm(circle, axis=1), scene.wheel_radius)
    assert np.allclose(circle @ axis, 0.0, atol=1e-9)
    assert np.allclose(circle[0], circle[-1])


def test_a_scene_without_wheel_radius_has_no_wheel(tmp_path):
    data = yaml.safe_load((ROOT / 'config' / 'scenes' / 'five_link.yaml').read_text())
    del data['wheel_radius']
    path = tmp_path / 'bare.yaml'
    path.write_text(yaml.safe_dump(data))
    scene = load_scene(path)
    assert wheel_circle(scene) is None
    out = tmp_path / 'bare.rrd'
    assert main([str(EXAMPLE), '--scene', str(path), '-o', str(out)]) == 0
    rows, _, _ = contents(out)
    assert not any(entity == '/suspension/carrier/wheel' for entity, _ in rows)


@pytest.fixture(scope='module')
def example_rrd(tmp_path_factory):
    out = tmp_path_factory.mktemp('rrd') / 'five_link_sweep.rrd'
    assert main([str(EXAMPLE), '-o', str(out)]) == 0
    return out


def test_converted_bag_has_the_scene_entities_and_one_sample_per_message(example_rrd):
    rows, columns, timelines = contents(example_rrd)
    assert {e for e, static in rows if not static} == DYNAMIC
    assert {e for e, static in rows if static} == STATIC
    assert all(rows[(entity, False)] == 161 for entity in DYNAMIC)   # 161 commands in the bag
    assert timelines == {'ros_time', 'command'}
    assert {'Transform3D:translation', 'Transform3D:quaternion'} <= columns[
        ('/suspension/carrier', False)]
    assert 'TransformAxes3D:axis_length' in columns[('/suspension/carrier', True)]
    assert 'LineStrips3D:strips' in columns[('/suspension/links', False)]
    assert 'LineStrips3D:strips' in columns[('/suspension/carrier/wheel', True)]
    assert 'Scalars:scalars' in columns[('/plots/camber_deg', False)]


def test_converted_plots_hold_the_bag_values_in_mm_and_deg(example_rrd):
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory
    with open(EXAMPLE, 'rb') as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        bag = collections.defaultdict(list)
        for _, channel, _, msg in reader.iter_decoded_messages(log_time_order=False):
            bag[channel.topic].append(msg)
    travel = np.ravel(column(example_rrd, '/plots/travel_mm', 'Scalars:scalars'))
    camber = np.ravel(column(example_rrd, '/plots/camber_deg', 'Scalars:scalars'))
    assert travel == pytest.approx([1000.0 * m.data for m in bag['/wheel_travel']])
    assert camber == pytest.approx([math.degrees(m.data) for m in bag['/camber']])
    translation = np.array(column(example_rrd, '/suspension/carrier',
                                  'Transform3D:translation')).reshape(-1, 3)
    assert translation[-1] == pytest.approx(1000.0 * np.array([
        bag['/wheel_carrier_pose'][-1].pose.position.x,
        bag['/wheel_carrier_pose'][-1].pose.position.y,
        bag['/wheel_carrier_pose'][-1].pose.position.z]), abs=1e-3)   # stored as float32


def test_blueprint_opens_on_a_3d_view_beside_three_plots(example_rrd):
    reader = RrdReader(str(example_rrd))
    views, root = [], None
    for chunk in reader.stream(store=reader.blueprints()[0]):
        batch = chunk.to_record_batch()
        if 'ViewBlueprint:class_identifier' in batch.schema.names:
            views += [v[0] for v in batch.column('ViewBlueprint:class_identifier').to_pylist()]
        if 'ContainerBlueprint:col_shares' in batch.schema.names:
            root = [v[0] for v in batch.column('ContainerBlueprint:container_kind').to_pylist()]
    assert sorted(views) == ['3D', 'TimeSeries', 'TimeSeries', 'TimeSeries']
    assert root == [2]     # ContainerKind.Horizontal (the root, the only one with shares)


def test_a_vehicle_recording_shows_every_corner_in_one_3d_view_beside_the_plots(tmp_path):
    from std_msgs.msg import Float64
    from linkage_ros.core.model import load_vehicle
    corners = load_vehicle('demo_vehicle').corners
    out = tmp_path / 'vehicle.rrd'
    with RerunRecorder(out, corners=corners) as viewer:
        viewer.record('/front_left/camber', 'std_msgs/msg/Float64', Float64(data=0.01), 1, 1)
        viewer.record('/no_corner/camber', 'std_msgs/msg/Float64', Float64(data=0.02), 2, 2)
    reader = RrdReader(str(out))
    views = {}    # view entity: (kind, origin, contents)
    for chunk in reader.stream(store=reader.blueprints()[0]):
        batch = chunk.to_record_batch()
        path = chunk.entity_path.removesuffix('/ViewContents')
        if 'ViewBlueprint:class_identifier' in batch.schema.names:
            views[path] = (batch.column('ViewBlueprint:class_identifier').to_pylist()[0][0],
                           batch.column('ViewBlueprint:space_origin').to_pylist()[0][0],
                           views.get(path, (None, None, None))[2])
        if 'ViewContents:query' in batch.schema.names:
            kind, origin, _ = views.get(path, (None, None, None))
            views[path] = (kind, origin, batch.column('ViewContents:query').to_pylist()[0])
    assert sorted((kind, origin) for kind, origin, _ in views.values()) == [   # its front
        ('3D', '/'), ('TimeSeries', '/plots'), ('TimeSeries', '/plots'),      # steers: travel,
        ('TimeSeries', '/plots'), ('TimeSeries', '/plots')]                   # camber, toe, rack
    for _, _, query in views.values():     # every corner in every view
        assert len(query) == len(corners) and all(
            any(f'/{c}/' in q for q in query) for c in corners)
    rows, _, _ = contents(out)
    assert [e for e, static in rows if not static] == ['/plots/front_left/camber_deg']


def test_the_rerun_binary_verifies_the_file(example_rrd):
    env = dict(os.environ, RERUN_ANALYTICS='0')
    result = subprocess.run([str(RERUN), 'rrd', 'verify', str(example_rrd)], env=env,
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    assert '1 file verified without error' in result.stdout + result.stderr


def test_live_sink_counts_commands_on_the_sequence_timeline_and_batches_rows(tmp_path):
    from geometry_msgs.msg import PoseStamped
    from std_msgs.msg import Float64
    scene = load_scene('five_link')
    out = tmp_path / 'live.rrd'
    t0 = 1_700_000_000_000_000_000
    with RerunRecorder(out, scene, batch_rows=7) as viewer:   # several batches and a remainder
        for i in range(10):
            t = t0 + i * 10**7
            viewer.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=i / 1000.0), t,
                          t)
            pose = PoseStamped()
            pose.pose.position.y, pose.pose.position.z = 0.76, 0.3 + i / 1000.0
            pose.pose.orientation.w = 1.0
            viewer.record('/wheel_carrier_pose', 'geometry_msgs/msg/PoseStamped', pose, t, t)
            viewer.record('/diagnostics', 'diagnostic_msgs/msg/DiagnosticArray', None, t, t)
    rows, _, _ = contents(out)
    assert rows[('/plots/travel_mm', False)] == 10 and rows[('/suspension/carrier', False)] == 10
    assert ('/plots/camber_deg', False) not in rows      # nothing published, nothing drawn
    assert np.ravel(column(out, '/plots/travel_mm', 'Scalars:scalars')) == pytest.approx(
        np.arange(10.0))
    reader = RrdReader(str(out))
    commands = sorted(v for chunk in reader.stream(store=reader.recordings()[0])
                      if chunk.entity_path == '/suspension/carrier' and not chunk.is_static
                      for v in chunk.to_record_batch().column('command').to_pylist())
    assert commands == list(range(1, 11))


def test_a_truncated_bag_is_converted_up_to_the_cut_with_a_warning(tmp_path, capsys):
    data = EXAMPLE.read_bytes()
    cut = tmp_path / 'cut.mcap'
    cut.write_bytes(data[:-200])          # summary and footer lost, the chunk is intact
    out = tmp_path / 'cut.rrd'
    assert main([str(cut), '-o', str(out)]) == 1
    # 161 x 6 (command, pose, camber, toe, elements, /tf) + 4 /diagnostics + /tf_static and
    # the URDF
    assert 'bag truncated after 972 messages' in capsys.readouterr().err
    rows, _, _ = contents(out)
    assert rows[('/plots/toe_deg', False)] == 161


def test_recording_and_viewing_modules_import_only_their_own_library():
    code = ('import sys, linkage_ros.record.mcap_writer; a = "rerun" in sys.modules; '
            'import linkage_ros.record.rerun_view; b = "mcap" in sys.modules; print(a, b)')
    fresh = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                           timeout=60)
    assert fresh.stdout.split() == ['False', 'True']   # mcap was imported by recording
    code = 'import sys, linkage_ros.record.rerun_view; print("mcap" in sys.modules)'
    fresh = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                           timeout=60)
    assert fresh.stdout.split() == ['False']
