# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-rerun of a run that is not one scene's travel commands.

A run whose scene changed while the node ran (plain: each part drawn with its own scene;
--tf: each part's URDF, hidden out of its part), and a vehicle run commanded by joint_states
(its travel plotted). The changed run is the node's protocol replaying a recorded change
(linkage-replay solve, tested against the node in test_replay_runtime.py). The .rrd is read
back with Rerun's RrdReader.
"""

from linkage_ros.core.model import load_scene
from linkage_ros.record.mcap_writer import McapRecorder
from linkage_ros.record.rerun_draw import HIDDEN_SCALE
from linkage_ros.record.rerun_tf import HIDDEN
from linkage_ros.tools.replay import main as replay
from linkage_ros.tools.rerun_convert import main
import numpy as np
import pytest
from rcl_interfaces.msg import ParameterEvent
from rclpy.parameter import Parameter
from rerun.chunk import RrdReader
from std_msgs.msg import Float64
from test_replay import by_topic, decoded, T0
from test_rerun import column, contents

FIRST, THEN = [0.01, 0.03, 0.05, 0.02], [0.01, 0.03, -0.05, 0.02, 0.04]


@pytest.fixture
def changed_run(tmp_path):
    """Return a five_link run switched to double_wishbone, solved as the node does."""
    commands = tmp_path / 'commands.mcap'
    with McapRecorder(commands) as rec:
        t = T0
        for value in FIRST:
            t += 10**8
            rec.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=value), t, t)
        t += 10**8
        event = ParameterEvent(node='/suspension_kinematics', changed_parameters=[
            Parameter('scene', value='double_wishbone').to_parameter_msg()])
        rec.record('/parameter_events', 'rcl_interfaces/msg/ParameterEvent', event, t, t)
        for value in THEN:
            t += 10**8
            rec.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=value), t, t)
    run = tmp_path / 'run.mcap'
    assert replay(['solve', str(commands), '-o', str(run), '--scene', 'five_link']) == 0
    return run


def test_each_part_of_a_changed_run_is_drawn_with_its_own_scene(changed_run, tmp_path):
    out = tmp_path / 'run.rrd'
    assert main([str(changed_run), '-o', str(out)]) == 0
    rows, _, _ = contents(out)
    assert rows[('/five_link/suspension/links', False)] == len(FIRST) + 1   # + its Clear
    assert rows[('/double_wishbone/suspension/links', False)] == len(THEN)
    # each pose's strips are its own scene's constraints, from its own carrier points
    strips = column(out, '/double_wishbone/suspension/links', 'LineStrips3D:strips')
    assert len(strips[-1]) == len(load_scene('double_wishbone').constraints)
    centre = np.array(column(out, '/double_wishbone/suspension/carrier',
                             'Transform3D:translation')).reshape(-1, 3)[-1]
    pose = by_topic(decoded(changed_run), '/wheel_carrier_pose')[-1].pose.position
    assert centre == pytest.approx([1000.0 * pose.x, 1000.0 * pose.y, 1000.0 * pose.z],
                                   abs=1e-3)    # stored as float32
    # the first part's carrier and links no more from the second part's first command on
    (hidden,) = scaled(out, '/five_link/suspension/carrier')
    first_then = min(transforms_times(out, '/double_wishbone/suspension/carrier'))
    assert hidden == (first_then, pytest.approx(HIDDEN_SCALE, rel=1e-7))


def scaled(path, entity):
    """Return [(ns, scale)] of the rows of an entity that set a Transform3D scale."""
    got = []
    for chunk in RrdReader(str(path)).stream():
        batch = chunk.to_record_batch()
        if chunk.entity_path == entity and 'Transform3D:scale' in batch.schema.names:
            got += zip(batch.column('ros_time').cast('int64').to_pylist(),
                       [s[0][0] for s in batch.column('Transform3D:scale').to_pylist()])
    return got


def transforms_times(path, entity):
    """Return the times (ns) of an entity's temporal rows."""
    return [t for chunk in RrdReader(str(path)).stream()
            if chunk.entity_path == entity and not chunk.is_static
            for t in chunk.to_record_batch().column('ros_time').cast('int64').to_pylist()]


def transforms(path, entity):
    """Return [(ns, scale)] of an entity's temporal Transform3D rows."""
    got = []
    for chunk in RrdReader(str(path)).stream():
        if chunk.entity_path == entity and not chunk.is_static:
            batch = chunk.to_record_batch()
            times = batch.column('ros_time').cast('int64').to_pylist()
            got += zip(times, [s[0][0] for s in batch.column('Transform3D:scale').to_pylist()])
    return sorted(got)


def test_the_tf_view_of_a_changed_run_draws_each_urdf_only_in_its_part(changed_run, tmp_path):
    out = tmp_path / 'run_tf.rrd'
    assert main([str(changed_run), '--tf', '-o', str(out)]) == 0
    rows, _, _ = contents(out)
    static = {entity for entity, is_static in rows if is_static}
    assert '/robot_part1/five_link' in static and '/robot_part2/double_wishbone' in static
    first = transforms(out, '/tf/part1/wheel_carrier')
    then = transforms(out, '/tf/part2/wheel_carrier')
    switch = then[1][0]        # the first stamp of the second part
    # drawn while its part runs, scaled to nothing outside it
    # (scales are stored as float32: 1e-6 to 7 digits)
    assert [scale for _, scale in first] == pytest.approx([1.0] * len(FIRST) + [HIDDEN],
                                                          rel=1e-7)
    assert first[-1][0] == switch
    assert then[0] == (first[0][0], pytest.approx(HIDDEN, rel=1e-7))
    assert [scale for _, scale in then[1:]] == [1.0] * len(THEN)


def test_a_vehicle_run_commanded_by_joint_states_plots_each_corners_travel(tmp_path):
    from sensor_msgs.msg import JointState
    bag = tmp_path / 'vehicle.mcap'
    travels = [0.01, -0.02, 0.03]
    with McapRecorder(bag, custom_data={'vehicle': 'demo_vehicle'}) as rec:
        for i, travel in enumerate(travels):
            msg = JointState(name=['front_left_travel', 'rear_right_travel', 'steering_rack'],
                             position=[travel, -travel, 0.001 * i])
            rec.record('/joint_states', 'sensor_msgs/msg/JointState', msg, T0 + i, T0 + i)
            rec.record('/front_left/camber', 'std_msgs/msg/Float64', Float64(data=0.01),
                       T0 + i, T0 + i)
    out = tmp_path / 'vehicle.rrd'
    assert main([str(bag), '-o', str(out)]) == 0
    front = np.ravel(column(out, '/plots/front_left/travel_mm', 'Scalars:scalars'))
    rear = np.ravel(column(out, '/plots/rear_right/travel_mm', 'Scalars:scalars'))
    rack = np.ravel(column(out, '/plots/front_right/rack_mm', 'Scalars:scalars'))
    assert front == pytest.approx([1000.0 * t for t in travels], abs=1e-9)
    assert rear == pytest.approx([-1000.0 * t for t in travels], abs=1e-9)
    assert rack == pytest.approx([0.0, 1.0, 2.0], abs=1e-9)
