# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-rerun on what users and attackers hand it, and what the view shows of a steered run.

Bags are written with the mcap library's own Writer; the .rrd files are read with Rerun's own
reader (rerun.chunk.RrdReader). Label boxes are checked with a pinhole projection written
here, from the camera the blueprint opens on.
"""

import collections
import math
from pathlib import Path
import struct

from linkage_ros.answer import cdr
from linkage_ros.cli import safe_name
from linkage_ros.core.model import load_scene, load_vehicle
from linkage_ros.record import label_layout
from linkage_ros.record.rerun_draw import eye, labelled_points
from linkage_ros.record.rerun_view import RerunRecorder
from linkage_ros.tools import replay, rerun_convert
from mcap.writer import CompressionType, Writer
import numpy as np
import pytest
from rerun.chunk import RrdReader

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / 'bags' / 'five_link_sweep.mcap'
FLOAT64 = ('std_msgs/msg/Float64', 'ros2msg', 'float64 data\n')
STRING = ('std_msgs/msg/String', 'ros2msg', 'string data\n')
POSE = 'geometry_msgs/msg/PoseStamped'


def write(path, channels, messages, metadata=None):
    """
    Write an MCAP (profile ros2) with mcap's Writer.

    channels: {topic: (schema name, encoding, text)}; messages: [(topic, bytes)], 10 ms
    apart; metadata: {record name: {key: value}}.
    """
    with open(path, 'wb') as stream:
        writer = Writer(stream, compression=CompressionType.ZSTD)
        writer.start(profile='ros2', library='test')
        ids = {}
        for topic, (name, encoding, text) in channels.items():
            schema = writer.register_schema(name=name, encoding=encoding, data=text.encode())
            ids[topic] = writer.register_channel(topic=topic, message_encoding='cdr',
                                                 schema_id=schema)
        for i, (topic, data) in enumerate(messages):
            t = 1_700_000_000_000_000_000 + 10**7 * i
            writer.add_message(ids[topic], log_time=t, data=data, publish_time=t)
        for name, values in (metadata or {}).items():
            writer.add_metadata(name, values)
        writer.finish()
    return path


def pose_cdr(x, y, z):
    return cdr.pose_stamped_cdr((0, 0), 'base_link', (x, y, z), (0.0, 0.0, 0.0, 1.0))


def rows(path):
    """{(entity, static): rows} of the recording in an .rrd (Rerun's reader)."""
    reader = RrdReader(str(path))
    found = collections.Counter()
    for chunk in reader.stream(store=reader.recordings()[0]):
        found[(chunk.entity_path, chunk.is_static)] += chunk.num_rows
    return found


def column(path, entity, name, static=False):
    """Every value of one column of an entity's chunks (static or not), in file order."""
    reader = RrdReader(str(path))
    values = []
    for chunk in reader.stream(store=reader.recordings()[0]):
        if chunk.entity_path == entity and chunk.is_static == static:
            values += chunk.to_record_batch().column(name).to_pylist()
    return values


# --- malformed messages, topics of another type --------------------------------------------

def test_messages_that_do_not_decode_are_named_and_lost_and_a_string_topic_skipped(
        tmp_path, capsys):
    frame_too_long = bytearray(pose_cdr(0.0, 0.76, 0.3))
    frame_too_long[12:16] = struct.pack('<I', 2**32 - 1)        # frame_id length 2^32 - 1
    bag = write(tmp_path / 'hostile.mcap', {
        '/wheel_travel': FLOAT64, '/camber': FLOAT64, '/wheel_carrier_pose': (POSE, 'ros2msg',
                                                                              'x'),
        '/toe': STRING}, [
        ('/wheel_travel', cdr.float64_cdr(0.01)), ('/camber', cdr.float64_cdr(-0.01)),
        ('/wheel_carrier_pose', pose_cdr(0.0, 0.76, 0.31)),
        ('/toe', cdr.CDR_LE + struct.pack('<I', 4) + b'abc\0'),   # a String on /toe
        ('/wheel_travel', cdr.float64_cdr(0.02)),
        ('/camber', cdr.CDR_LE + b'\x00'),                         # a 5-byte Float64
        ('/wheel_carrier_pose', pose_cdr(0.0, 0.76, 0.32)[:30]),   # a short PoseStamped
        ('/wheel_carrier_pose', bytes(frame_too_long)),
        ('/wheel_travel', cdr.float64_cdr(0.03)), ('/camber', cdr.float64_cdr(-0.03))])
    out = tmp_path / 'hostile.rrd'
    assert rerun_convert.main([str(bag), '-o', str(out)]) == 1
    err = capsys.readouterr().err
    assert (f'linkage-rerun: {bag}: /toe skipped: it carries std_msgs/msg/String in cdr, not '
            'what is drawn from it\n') in err
    assert (f'linkage-rerun: warning: {bag}: 1 message on /camber does not decode, left out '
            '(the first: std_msgs/Float64 of 5 bytes: too short: it needs 12 bytes)\n') in err
    assert (f'linkage-rerun: warning: {bag}: 2 messages on /wheel_carrier_pose do not decode, '
            'left out (the first: geometry_msgs/PoseStamped of 30 bytes: too short: it needs '
            '84 bytes)\n') in err
    found = rows(out)
    assert found[('/plots/travel_mm', False)] == 3 and found[('/plots/camber_deg', False)] == 2
    assert found[('/suspension/carrier', False)] == 1
    assert ('/plots/toe_deg', False) not in found         # nothing drawn from the String
    assert np.ravel(column(out, '/plots/camber_deg', 'Scalars:scalars')) == pytest.approx(
        [math.degrees(-0.01), math.degrees(-0.03)])


def test_a_live_mirror_skips_a_sample_that_does_not_decode_and_goes_on(tmp_path):
    out = tmp_path / 'live.rrd'
    with RerunRecorder(out, load_scene('five_link')) as mirror:
        mirror.record('/wheel_travel', FLOAT64[0], b'\x00\x01\x00\x00\x01\x02', 1, 1)
        mirror.record('/wheel_travel', FLOAT64[0], cdr.float64_cdr(0.02), 2, 2)
        mirror.record('/camber', STRING[0], cdr.float64_cdr(0.02), 3, 3)
        assert mirror.error is None
        assert mirror.skipped == {'/wheel_travel': 1, '/camber': 1}
    assert np.ravel(column(out, '/plots/travel_mm', 'Scalars:scalars')) == pytest.approx([20.0])


def test_a_damaged_bag_that_yields_nothing_is_status_1_naming_the_damage(tmp_path, capsys):
    cut = tmp_path / 'cut.mcap'
    cut.write_bytes(EXAMPLE.read_bytes()[:60])          # the header record, cut inside
    out = tmp_path / 'cut.rrd'
    assert rerun_convert.main([str(cut), '-o', str(out)]) == 1
    err = capsys.readouterr().err
    assert f'linkage-rerun: warning: {cut}: bag truncated after 0 messages (cut at byte 60' \
        in err
    assert err.endswith(f'linkage-rerun: wrote {out}: nothing but the scene\n')
    found = rows(out)
    assert found[('/suspension/base_points', True)] == 1
    assert not any(not static for _, static in found)


# --- outputs -------------------------------------------------------------------------------

def test_an_output_that_is_the_mcap_inside_an_input_bag_folder_is_refused(tmp_path, capsys):
    folder = tmp_path / 'bagdir'
    folder.mkdir()
    inside = folder / 'run.mcap'
    inside.write_bytes(EXAMPLE.read_bytes())
    (tmp_path / 'alias.mcap').symlink_to(inside)
    for program, out in ((rerun_convert.main, inside),
                         (lambda argv: replay.main(['solve', *argv]), inside),
                         (rerun_convert.main, tmp_path / 'alias.mcap'),
                         (rerun_convert.main, folder / '..' / 'bagdir' / 'run.mcap')):
        assert program([str(folder), '-o', str(out)]) == 2
        err = capsys.readouterr().err
        assert err.count('\n') == 1 and err.endswith(
            f'-o: {out} is {inside}, in the input {folder}; give another file name\n'), err
    assert inside.read_bytes() == EXAMPLE.read_bytes()


def test_the_default_output_of_a_bag_folder_is_its_name_in_the_current_folder(
        tmp_path, monkeypatch):
    folder = tmp_path / 'bagdir'
    folder.mkdir()
    (folder / 'run.mcap').write_bytes(EXAMPLE.read_bytes())
    work = tmp_path / 'work'
    work.mkdir()
    monkeypatch.chdir(work)
    assert rerun_convert.main([str(folder) + '/']) == 0
    assert [p.name for p in work.iterdir()] == ['bagdir.rrd']


@pytest.mark.parametrize('text, name', [('../escaped', 'escaped'), ('/tmp/x', 'tmp_x'),
                                        ('..', 'output'), ('a b', 'a_b'),
                                        ('five_link', 'five_link'), ('-rf', 'rf')])
def test_default_file_names_are_sanitised_to_stay_in_the_current_folder(text, name):
    assert safe_name(text) == name


# --- the scene stored in the recording ------------------------------------------------------

def test_the_scene_stored_in_the_recording_is_drawn_without_its_file(tmp_path, monkeypatch):
    text = (ROOT / 'config' / 'scenes' / 'double_wishbone.yaml').read_text().replace(
        'name: double_wishbone', 'name: my_corner')
    assert 'name: my_corner' in text
    bag = write(tmp_path / 'stored.mcap', {'/wheel_travel': FLOAT64},
                [('/wheel_travel', cdr.float64_cdr(0.01))],
                metadata={'linkage_ros': {'scene_yaml': text}})
    work = tmp_path / 'elsewhere'
    work.mkdir()
    monkeypatch.chdir(work)          # no file of the scene here: only the bag holds it
    assert rerun_convert.main([str(bag), '-o', 'out.rrd']) == 0
    expected = load_scene(ROOT / 'config' / 'scenes' / 'double_wishbone.yaml')
    points = np.array(column(work / 'out.rrd', '/suspension/base_points',
                             'Points3D:positions', static=True)[0])
    assert points == pytest.approx(np.vstack([c.base for c in expected.constraints]))
    assert 'my_corner (mm)' in blueprint_names(work / 'out.rrd')


def test_the_vehicle_stored_in_the_recording_draws_every_corner(tmp_path):
    text = (ROOT / 'config' / 'vehicles' / 'demo_vehicle.yaml').read_text()
    bag = write(tmp_path / 'vehicle.mcap', {'/front_left/wheel_travel': FLOAT64},
                [('/front_left/wheel_travel', cdr.float64_cdr(0.01))],
                metadata={'linkage_ros': {'vehicle_yaml': text}})
    out = tmp_path / 'vehicle.rrd'
    assert rerun_convert.main([str(bag), '-o', str(out)]) == 0
    found = rows(out)
    assert set(load_vehicle('demo_vehicle').corners) == {
        entity.split('/')[1] for entity, static in found
        if static and entity.endswith('/suspension/base_points')}
    assert found[('/plots/front_left/travel_mm', False)] == 1


def blueprint_names(path):
    """Return the names of the views in an .rrd's blueprint."""
    reader = RrdReader(str(path))
    names = []
    for chunk in reader.stream(store=reader.blueprints()[0]):
        batch = chunk.to_record_batch()
        if 'ViewBlueprint:display_name' in batch.schema.names:
            names += [v[0] for v in batch.column('ViewBlueprint:display_name').to_pylist()]
    return names


# --- labels and the rack -------------------------------------------------------------------

def projected_boxes(anchors, labels, position, target):
    """
    Return the label boxes (left, bottom, right, top) px of labels at anchors.

    A pinhole camera built here from a look-at rotation (rows: right, up, back), focal length
    from Rerun's 55 deg vertical field of view over label_layout.VIEW_PX; each box the size
    label_layout says, under its anchor.
    """
    back = np.asarray(position, float) - target
    back /= np.linalg.norm(back)
    right = np.cross([0.0, 0.0, 1.0], back)
    right /= np.linalg.norm(right)
    view = np.array([right, np.cross(back, right), back])
    camera = (np.asarray(anchors, float) - position) @ view.T
    focal = label_layout.VIEW_PX / 2 / math.tan(math.radians(55.0) / 2)
    xy = focal * camera[:, :2] / -camera[:, 2:]
    boxes = []
    for (x, y), label in zip(xy, labels):
        half = (label_layout.CHAR_PX * len(label) + label_layout.PAD_PX) / 2
        top = y - label_layout.GAP_PX
        boxes.append((x - half, top - label_layout.LABEL_PX, x + half, top))
    return boxes


def overlapping(boxes):
    return [(i, j) for i in range(len(boxes)) for j in range(i) if boxes[i][0] < boxes[j][2]
            and boxes[j][0] < boxes[i][2] and boxes[i][1] < boxes[j][3]
            and boxes[j][1] < boxes[i][3]]


@pytest.mark.parametrize('name', sorted(p.stem for p in (ROOT / 'config' / 'scenes').glob(
    '*.yaml')) + ['demo_vehicle'])
def test_every_label_of_the_opening_view_is_shown_and_none_covers_another(name):
    scenes = ({'': load_scene(name)} if name != 'demo_vehicle'
              else load_vehicle(name).corners)
    found = labelled_points(scenes)
    position, target = eye(list(scenes.values()))
    points, labels = [p for _, p, _ in found], [text for _, _, text in found]
    anchors, kept = label_layout.place_labels(points, labels, position, target)
    assert kept == list(range(len(labels)))                  # none had to be left out
    assert overlapping(projected_boxes(anchors, labels, position, target)) == []
    # Each label stays by its point: within three label heights on screen.
    moved = np.array(projected_boxes(anchors, labels, position, target)) - np.array(
        projected_boxes(points, labels, position, target))
    assert np.abs(moved).max() <= 3 * (label_layout.LABEL_PX + label_layout.GAP_PX)


def test_the_rack_is_plotted_in_mm_and_moves_the_steered_link(tmp_path):
    scene = load_scene('double_wishbone')
    steered = [i for i, c in enumerate(scene.constraints) if c.steer == 'rack']
    assert steered
    out = tmp_path / 'rack.rrd'
    with RerunRecorder(out, scene) as mirror:
        for i, rack_m in enumerate((0.0, 0.012)):
            t = 10 + 10 * i
            mirror.record('/steering_rack', FLOAT64[0], cdr.float64_cdr(rack_m), t, t)
            x, y, z = (scene.wheel_center / 1000.0).tolist()
            mirror.record('/wheel_carrier_pose', POSE, pose_cdr(x, y, z), t + 1, t + 1)
    assert np.ravel(column(out, '/plots/rack_mm', 'Scalars:scalars')) == pytest.approx(
        [0.0, 12.0])
    strips = column(out, '/suspension/links', 'LineStrips3D:strips')
    assert len(strips) == 2
    for pose, rack_mm in zip(strips, (0.0, 12.0)):
        for j, c in enumerate(scene.constraints):
            body_end = np.array(pose[j][0])
            shift = [0.0, rack_mm, 0.0] if j in steered else [0.0, 0.0, 0.0]
            assert body_end == pytest.approx(c.base[0] + shift, abs=1e-3)   # float32


def test_a_singular_scene_is_drawn_with_its_warning_and_no_traceback(tmp_path, capsys):
    # five_link_singular solves nothing but its design position: the plots' frames, taken
    # from a sweep of the scene, once failed on that empty sweep (min() of nothing).
    singular = ROOT / 'test' / 'data' / 'five_link_singular.yaml'
    out = tmp_path / 'singular.rrd'
    assert rerun_convert.main([str(EXAMPLE), '--scene', str(singular), '-o', str(out)]) == 0
    warning = f'linkage-rerun: warning: {load_scene(singular).warnings[0]}\n'
    assert capsys.readouterr().err.count(warning) == 1
    assert rows(out)[('/suspension/carrier', False)] == 161     # every recorded pose


TF_SCHEMA = ('tf2_msgs/msg/TFMessage', 'ros2msg', 'geometry_msgs/TransformStamped[] transforms\n')
URDF = ('<robot name="{name}"><link name="base_link"/><link name="{child}"/>'
        '<joint name="j" type="floating"><parent link="base_link"/><child link="{child}"/>'
        '</joint></robot>')


@pytest.mark.parametrize('name, child', [
    ('bad\x01name', 'carrier'),           # a control character: no XML holds it
    ('five_link', 'carrier\x00cut'),      # NUL: cuts a C string, and no XML holds it
])
def test_a_recorded_urdf_or_frame_with_a_control_character_is_one_line_not_a_traceback(
        tmp_path, capsys, name, child):
    # issue 27 item 6: such names cannot be loaded any more, but a bag made elsewhere, or by
    # an older version, may hold them; linkage-rerun --tf names the problem (status 2)
    bag = write(tmp_path / 'run.mcap',
                {'/robot_description': STRING, '/tf': TF_SCHEMA},
                [('/robot_description', cdr.string_cdr(URDF.format(name=name, child=child))),
                 ('/tf', cdr.tf_message_cdr((0, 1), ['base_link'], [child],
                                            [[0.0, 0.0, 0.1]], [[0.0, 0.0, 0.0, 1.0]]))])
    status = rerun_convert.main([str(bag), '--tf', '-o', str(tmp_path / 'run.rrd')])
    err = capsys.readouterr().err
    assert status == 2, err
    assert len(err.strip().splitlines()) == 1 and 'Traceback' not in err
    assert 'U+000' in err and 'control' in err   # the character, by its code point
