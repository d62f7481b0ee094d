# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node's parameters changed while it runs, through rcl_interfaces SetParameters.

In process (the probe's own SetParameters client, over DDS in one Context) and from another
process. Expected answers come from the kinematics core for the same scene and travels.
"""

import math

from diagnostic_msgs.msg import DiagnosticStatus
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import sweep
from linkage_ros.ros.messages import status_values
from linkage_ros.ros.testing import connect, live_tf_topics, ParameterClient, Probe, spin_until
import numpy as np
import pytest
from rclpy.parameter import Parameter

NODE = '/suspension_kinematics'


def assert_answers(probe, scene_name, travels_m, method='fast'):
    """Send travels; check that the answers are the core's sweep of scene_name for them."""
    before = len(probe.poses)
    probe.send(*travels_m)
    assert spin_until(probe.executor, lambda: min(len(probe.poses), len(probe.cambers))
                      >= before + len(travels_m), 20.0)
    expected = sweep(load_scene(scene_name), np.asarray(travels_m) * 1000.0, method=method)
    got = [[p.pose.position.x, p.pose.position.y, p.pose.position.z]
           for p in probe.poses[-len(travels_m):]]
    assert np.array(got) == pytest.approx(expected.wheel_center / 1000.0, abs=1e-9)
    assert probe.cambers[-len(travels_m):] == pytest.approx(list(expected.camber), abs=1e-9)


@pytest.fixture
def client(probe):
    return ParameterClient(probe)


def test_max_step_mm_is_accepted_and_the_next_jump_takes_its_substeps(suspension_node, probe,
                                                                      client):
    node = suspension_node(diagnostic_period=3600.0)
    assert client.set(max_step_mm=2.0) == [(True, '')]
    assert node.get_parameter('max_step_mm').value == 2.0
    assert node.corners[''].solver.settings.max_step == 2.0
    probe.ask(0.06)                              # 60 mm from design in steps of at most 2 mm
    assert node.corners[''].health.last.substeps >= 30


def test_a_value_out_of_range_is_refused_with_the_reason_and_the_old_value_kept(
        suspension_node, probe, client):
    node = suspension_node()
    ((ok, reason),) = client.set(max_step_mm=-1.0)
    assert not ok
    assert reason == ('Parameter max_step_mm out of range Min: 0.001, Max: 1000.0, '
                      'value: -1.0')
    assert node.get_parameter('max_step_mm').value == 5.0
    assert node.corners[''].solver.settings.max_step == 5.0
    assert_answers(probe, 'five_link', [0.01, 0.03])      # answers continue


@pytest.mark.parametrize('name,value,reason', [
    ('method', 'newton', "method: unknown value 'newton' (expected one of: paper, fast)"),
    ('max_step_mm', 'big', "max_step_mm: expected a number, got 'big'"),
    ('tf', 1, 'Wrong parameter type'),
])
def test_a_bad_value_is_refused_with_the_reason(suspension_node, client, name, value, reason):
    node = suspension_node()
    before = node.get_parameter(name).value
    ((ok, said),) = client.set(**{name: value})
    assert not ok and said.startswith(reason)
    assert node.get_parameter(name).value == before


@pytest.mark.parametrize('name,value,why', [
    ('vehicle', 'demo_vehicle', 'the corners and their topics are made at start from the '
                                'vehicle file'),
    ('record_mcap', 'run.mcap', 'a recording is one file from start to stop'),
    ('rerun_rrd', 'run.rrd', 'a Rerun mirror is one file from start to stop'),
    ('frame_id', 'chassis', 'every published pose and frame names it from the start'),
])
def test_a_parameter_fixed_at_start_refuses_a_change_and_says_why(suspension_node, client,
                                                                  name, value, why):
    node = suspension_node()
    before = node.get_parameter(name).value
    ((ok, reason),) = client.set(**{name: value})
    assert not ok
    assert reason == (f'{name}: cannot change while the node runs: {why}; restart the node '
                      'with the new value')
    assert node.get_parameter(name).value == before


def test_a_new_scene_restarts_from_its_design_position_says_so_and_answers_as_it(
        suspension_node, probe, client):
    suspension_node()
    assert_answers(probe, 'five_link', [0.03, 0.05])
    assert client.set(scene='macpherson') == [(True, '')]
    assert spin_until(probe.executor, lambda: probe.statuses and 'scene changed to macpherson'
                      in probe.statuses[-1].message)
    status = probe.statuses[-1]
    assert status.level == DiagnosticStatus.OK and status.hardware_id == 'macpherson'
    assert status.message.endswith(': continuation restarts from its design position')
    assert status_values(status)['travel_m'] == '0'
    # the core's sweep of the new scene from ITS design position, for the same travels
    assert_answers(probe, 'macpherson', [0.03, -0.04])


def test_a_scene_that_does_not_load_is_refused_with_the_loaders_line(suspension_node, probe,
                                                                     client, tmp_path):
    node = suspension_node()
    bad = tmp_path / 'bad.yaml'
    bad.write_text('name: bad\nunits: mm\nside: left\ncarrier: {wheel_centre: [0, 1, 2]}\n')
    ((ok, reason),) = client.set(scene=str(bad))
    assert not ok
    assert reason.startswith(f'{bad}: carrier.wheel_centre: unknown key (did you mean '
                             'wheel_center?)')
    assert node.get_parameter('scene').value == 'five_link'
    assert_answers(probe, 'five_link', [0.02])


def test_method_changes_at_the_pose_held_and_answers_as_the_papers_method(suspension_node,
                                                                          probe, client):
    node = suspension_node()
    assert_answers(probe, 'five_link', [0.04])
    assert client.set(method='paper') == [(True, '')]
    assert node.corners[''].solver.settings.method == 'paper'
    assert node.corners[''].solver.travel == pytest.approx(40.0)    # the pose it held
    assert_answers(probe, 'five_link', [0.045, 0.05], method='paper')


def test_condition_warn_and_diagnostic_period_apply_at_once(suspension_node, probe, client):
    node = suspension_node(diagnostic_period=3600.0)
    probe.ask(0.02)
    assert client.set(condition_warn=1.0, diagnostic_period=0.05) == [(True, ''), (True, '')]
    probe.ask(0.03)                # every pose is above condition number 1: WARN at once
    assert spin_until(probe.executor, lambda: len(probe.statuses) >= 4)   # reports again
    assert probe.statuses[-1].level == DiagnosticStatus.WARN
    assert node.timer.timer_period_ns == 50_000_000


def test_the_output_switches_make_and_remove_their_topics(suspension_node, probe, client):
    from std_msgs.msg import Float64MultiArray
    node = suspension_node()
    arrays = []
    probe.node.create_subscription(Float64MultiArray, 'alignment', arrays.append, 10)

    def topics():
        return {p.topic_name for p in node.publishers}

    tf = live_tf_topics()       # none without tf2_msgs: the frames are recorded only
    assert '/alignment' not in topics() and tf <= topics()
    assert client.set(alignment=True, markers=True, tf=False) == [(True, '')] * 3
    assert {'/alignment', '/markers'} <= topics()
    assert not {'/tf', '/tf_static', '/robot_description'} & topics()
    assert node.corners[''].frames is None
    probe.ask(0.02)
    assert spin_until(probe.executor, lambda: arrays)
    assert client.set(alignment=False, tf=True) == [(True, '')] * 2
    assert '/alignment' not in topics() and tf <= topics()


def test_a_recording_goes_on_across_a_scene_change_and_records_it(suspension_node, probe,
                                                                  client, tmp_path):
    from linkage_ros.ros.testing import read_mcap_ros2
    path = tmp_path / 'run.mcap'
    node = suspension_node(record_mcap=str(path))
    assert_answers(probe, 'five_link', [0.02])
    assert client.set(scene='double_wishbone') == [(True, '')]
    assert_answers(probe, 'double_wishbone', [0.02])
    node.destroy_node()
    topics = read_mcap_ros2(path)
    assert len(topics['/wheel_carrier_pose']) == 2
    (event,) = topics['/parameter_events']
    assert event.node == NODE
    assert [(p.name, p.value.string_value) for p in event.changed_parameters] == [
        ('scene', 'double_wishbone')]
    names = [msg.data.split('name="', 2)[1].split('"')[0] for msg in topics['/robot_description']]
    assert names == ['five_link', 'double_wishbone']     # each scene's URDF, in turn
    assert [t.child_frame_id for t in topics['/tf'][-1].transforms] == [
        'wheel_carrier', 'upper_arm', 'lower_arm', 'tie_rod']
    assert any('scene changed to double_wishbone' in s.message
               for m in topics['/diagnostics'] for s in m.status)


def test_scene_cannot_change_on_a_vehicle_node(ros_context, executor):
    from linkage_ros.ros.testing import start_suspension_node
    node = start_suspension_node(ros_context, executor, vehicle='demo_vehicle')
    result = node.set_parameters([Parameter('scene', value='macpherson')])[0]
    assert not result.successful
    assert result.reason.startswith('scene: not used by a node of vehicle demo_vehicle')


def test_from_another_process_max_step_mm_scene_and_a_refusal(node_process, localhost_context,
                                                              localhost_executor):
    process = node_process()
    probe = Probe(localhost_context, localhost_executor)
    client = ParameterClient(probe)
    connect(localhost_executor, probe)
    assert client.set(max_step_mm=1.5) == [(True, '')]
    ((ok, reason),) = client.set(max_step_mm=-1.0)
    assert not ok and 'out of range' in reason
    assert_answers(probe, 'five_link', [0.02, 0.04])        # answers continue
    assert client.set(scene='double_wishbone') == [(True, '')]
    assert_answers(probe, 'double_wishbone', [0.01, -0.03, 0.035])
    code, _, err = process.stop()
    assert code == 0, err
    assert 'scene double_wishbone' in err and 'Traceback' not in err
    assert not math.isnan(probe.poses[-1].pose.position.z)


def test_a_new_scene_keeps_the_elements_topic_and_publishes_its_own_elements(
        suspension_node, probe, client):
    # five_link's damper and spring, then macpherson's strut, on the one elements publisher
    # (its subscribers stay matched across the change)
    from linkage_ros.core.measure import element_values
    from sensor_msgs.msg import JointState
    node = suspension_node()
    got = []
    probe.node.create_subscription(JointState, '/elements', got.append, 100)
    corner = node.corners['']
    before = corner.publishers['elements']
    assert client.set(scene='macpherson') == [(True, '')]
    assert corner.publishers['elements'] is before
    assert_answers(probe, 'macpherson', [0.03])
    assert spin_until(probe.executor, lambda: got)
    scene = load_scene('macpherson')
    result = sweep(scene, [30.0])
    lengths = element_values(scene, result.wheel_center, result.rotation).length[0]
    assert list(got[-1].name) == ['strut']
    assert list(got[-1].position) == pytest.approx(list(lengths / 1000.0), abs=1e-12)
