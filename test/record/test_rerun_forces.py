# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The Rerun mirror draws the statics topics as arrows: contact_wrench and pickup/<name>.

An arrow is FORCE_SCALE mm per N (0.1: 1 kN is 100 mm) in the vehicle frame: the contact
force at the contact patch of each pose answered after it (the wheel's lowest point in that
pose), each pickup's force at its pickup (the scene's body point). Read back from the .rrd.
"""

import math

from linkage_ros.answer.cdr import float64_cdr, pose_stamped_cdr, wrench_stamped_cdr
from linkage_ros.core.model import load_scene
from linkage_ros.record.rerun_draw import FORCE_SCALE
from linkage_ros.record.rerun_view import RerunRecorder, topic_role
import numpy as np
import pytest
from rerun.chunk import RrdReader

WRENCH = 'geometry_msgs/msg/WrenchStamped'


def arrows(path, entity):
    """Return [(command, origin (3,), vector (3,))] of an entity's temporal Arrows3D rows."""
    reader = RrdReader(str(path))
    rows = []
    for chunk in reader.stream(store=reader.recordings()[0]):
        if chunk.entity_path == entity and not chunk.is_static:
            batch = chunk.to_record_batch()
            rows += zip(batch.column('command').to_pylist(),
                        batch.column('Arrows3D:origins').to_pylist(),
                        batch.column('Arrows3D:vectors').to_pylist())
    return [(c, np.array(o[0]), np.array(v[0])) for c, o, v in sorted(rows, key=lambda r: r[0])]


def test_the_statics_topics_have_their_roles_in_any_namespace():
    assert topic_role('/contact_wrench') == 'wrench'
    assert topic_role('/front_left/contact_wrench') == 'wrench'
    assert topic_role('/front_left/pickup/lower_arm_axis0') == 'pickup'
    assert topic_role('/pickup/tie_rod') == 'pickup'
    assert topic_role('/pickup') is None


def test_forces_are_arrows_to_scale_at_the_contact_patch_and_at_the_pickups(tmp_path):
    scene = load_scene('double_wishbone')
    path = tmp_path / 'run.rrd'
    tilt = math.radians(2.0)      # a pose turned 2 deg about x: the patch moves with the wheel
    quaternion = (math.sin(tilt / 2), 0.0, 0.0, math.cos(tilt / 2))
    with RerunRecorder(path, scene) as recorder:
        recorder.record('/contact_wrench', WRENCH, wrench_stamped_cdr(
            (0, 0), 'base_link', (100.0, 2000.0, 4000.0), (0.0, 0.0, 30.0)), 5, 5)
        for i, travel in enumerate((0.0, 0.02)):
            t = 10 * (i + 1)
            recorder.record('/wheel_travel', 'std_msgs/msg/Float64', float64_cdr(travel), t, t)
            recorder.record('/wheel_carrier_pose', 'geometry_msgs/msg/PoseStamped',
                            pose_stamped_cdr((0, t), 'base_link', (0.0, 0.76, 0.3 + travel),
                                             quaternion), t + 1, t + 1)
            recorder.record('/pickup/lower_arm_axis1', WRENCH, wrench_stamped_cdr(
                (0, t), 'pickup/lower_arm_axis1', (-300.0 * (i + 1), 50.0, 900.0), (0, 0, 0)),
                t + 2, t + 2)
    contact = arrows(path, '/suspension/forces/contact')
    assert [c for c, _, _ in contact] == [1, 2]
    for (_, origin, vector), z in zip(contact, (300.0, 320.0)):
        # the lowest point of a wheel of 330 mm at (0, 760, z) whose spin axis (0, 1, 0) is
        # turned 2 deg about x: the radius square to the axis, in the plane of the axis and
        # z, points along (0, sin, -cos) of 2 deg
        expected = [0.0, 760.0 + 330.0 * math.sin(tilt), z - 330.0 * math.cos(tilt)]
        assert origin == pytest.approx(expected, abs=1e-3)   # float32 in the .rrd
        assert vector == pytest.approx(np.array([100.0, 2000.0, 4000.0]) * FORCE_SCALE)
    pickup = arrows(path, '/suspension/forces/pickup/lower_arm_axis1')
    assert len(pickup) == 2
    for i, (_, origin, vector) in enumerate(pickup):
        assert origin == pytest.approx([-150.0, 250.0, 185.0])     # the scene's axis[1]
        assert vector == pytest.approx([-30.0 * (i + 1), 5.0, 90.0])
    assert FORCE_SCALE == 0.1    # mm per N, as doc/node.md and linkage-rerun --help say


def test_a_pickup_the_scene_does_not_have_is_skipped(tmp_path):
    path = tmp_path / 'run.rrd'
    with RerunRecorder(path, load_scene('double_wishbone')) as recorder:
        recorder.record('/pickup/no_such_pickup', WRENCH, wrench_stamped_cdr(
            (0, 0), 'base_link', (1.0, 2.0, 3.0), (0, 0, 0)), 1, 1)
        recorder.record('/pickup/tie_rod_base', WRENCH, b'\x00\x01\x00\x00\x01', 2, 2)
    assert recorder.skipped == {'/pickup/no_such_pickup': 1, '/pickup/tie_rod_base': 1}
