# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
suspension_node over real rclpy and DDS: in-process (one executor) and cross-process.

Expected values come from the kinematics core (sweep) for the same travels; the node must
publish exactly those, in SI units.
"""

import math
import os
from pathlib import Path
import signal
import subprocess
import sys
from typing import NamedTuple

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from geometry_msgs.msg import PoseStamped
from linkage_ros.core.base import Status
from linkage_ros.core.model import load_scene, SceneError
from linkage_ros.core.solve import Continuation, sweep
from linkage_ros.ros.messages import status_values
from linkage_ros.ros.node import PARAMETERS, QOS, QOS_DEPTH, SuspensionNode
from linkage_ros.ros.testing import connect, live_tf_topics, node_warnings, Probe, spin_until, \
    stamp_ns
import numpy as np
import pytest
from rclpy.parameter import Parameter
from rclpy.serialization import deserialize_message
from std_msgs.msg import Float64
import yaml

PARAMS_FILE = Path(__file__).resolve().parents[2] / 'config' / 'suspension.yaml'   # bundled
TRAVELS_M = [0.02, 0.045, -0.03, -0.0625, 0.0, 0.07]     # jumps up to 132 mm between commands
BAD_COMMANDS_M = {'nan': math.nan, 'inf': math.inf, '-inf': -math.inf,
                  'beyond bump': 1.0, 'beyond rebound': -1.0}
BAD_KIND = {'nan': Status.NOT_FINITE, 'inf': Status.NOT_FINITE, '-inf': Status.NOT_FINITE,
            'beyond bump': Status.OUT_OF_REACH, 'beyond rebound': Status.OUT_OF_REACH}


def core(scene_name, travels_m, method='fast'):
    """Return the core's answer (Sweep, mm and rad) for travels given in metres, in order."""
    return sweep(load_scene(scene_name), np.asarray(travels_m) * 1000.0, method=method)


def burst_travels(count=1000):
    """Travels (m) of a burst: two +-60 mm sine periods, 0.8 mm apart at most."""
    return list(0.06 * np.sin(np.linspace(0.0, 4 * np.pi, count)) + 1e-3)


def assert_counts(probe, n):
    """Exactly n of each output: nothing lost, nothing extra (in-process: no pings)."""
    assert [len(probe.poses), len(probe.cambers), len(probe.toes)] == [n] * 3


def assert_outputs_equal_core(probe, expected, frame_id='base_link'):
    """
    Check that the probe's outputs equal the core's sweep expected.

    The last len(expected) poses, cambers and toes: positions to 1 nm, angles and quaternions
    to 1e-9. One lost message shifts the tail of its topic, so this also checks that none of
    the commands was lost.
    """
    n = len(expected.travel)
    poses = probe.poses[-n:]
    positions = [[p.pose.position.x, p.pose.position.y, p.pose.position.z] for p in poses]
    quaternions = [[p.pose.orientation.x, p.pose.orientation.y, p.pose.orientation.z,
                    p.pose.orientation.w] for p in poses]
    assert np.array(positions) == pytest.approx(expected.wheel_center / 1000.0, abs=1e-9)
    assert np.array(quaternions) == pytest.approx(expected.quaternion, abs=1e-9)
    assert probe.cambers[-n:] == pytest.approx(list(expected.camber), abs=1e-9)
    assert probe.toes[-n:] == pytest.approx(list(expected.toe), abs=1e-9)
    assert {p.header.frame_id for p in poses} == {frame_id}


def report_after(probe, commands):
    """Wait for a status whose running count has reached commands; return its values."""
    def counted():
        return probe.statuses and int(
            status_values(probe.statuses[-1])['commands_total']) >= commands
    assert spin_until(probe.executor, counted)
    return status_values(probe.statuses[-1])


class Record(NamedTuple):
    """One message a sink was given: CDR bytes of type_name on topic, and its times (ns)."""

    topic: str
    type_name: str
    data: bytes
    receive_ns: int
    publish_ns: int


class ListSink:
    """A sink that keeps what it is given, as Records."""

    def __init__(self):
        self.records, self.closed = [], 0

    def record(self, topic, type_name, data, receive_ns, publish_ns):
        self.records.append(Record(topic, type_name, data, receive_ns, publish_ns))

    def close(self):
        self.closed += 1


# --- in process: the node and a probe node in one EventsExecutor ---------------------------
# Tests that count statuses set a diagnostic_period of an hour: then every status they see
# is one the node published at once (a bad command, a change of level).

HOUR = 3600.0


def test_answers_equal_the_core_sweep_for_the_same_travels(suspension_node, executor, probe):
    suspension_node()
    expected = core('five_link', TRAVELS_M)
    probe.send(*TRAVELS_M)
    assert spin_until(executor, lambda: probe.answered(expected))
    assert_counts(probe, len(TRAVELS_M))
    assert_outputs_equal_core(probe, expected)


def test_each_pose_carries_the_time_its_command_was_received(suspension_node, executor,
                                                             probe):
    sink = ListSink()
    suspension_node(sinks=[sink])
    expected = core('five_link', [0.01, 0.02])
    probe.send(0.01, 0.02)
    assert spin_until(executor, lambda: probe.answered(expected))
    received = [r.receive_ns for r in sink.records if r.topic == '/wheel_travel']
    pose_stamps = [stamp_ns(p.header.stamp) for p in probe.poses]
    assert pose_stamps == received and pose_stamps[0] < pose_stamps[1]


@pytest.mark.parametrize('max_step_mm, substeps', [(5.0, 10), (20, 3)])
def test_a_large_jump_is_walked_in_substeps_of_max_step_mm(suspension_node, executor, probe,
                                                           max_step_mm, substeps):
    suspension_node(max_step_mm=max_step_mm, diagnostic_period=0.05)   # 20: a number too
    probe.send(0.05)                      # 50 mm from the design position
    assert int(report_after(probe, 1)['substeps_max']) == substeps
    assert probe.poses[0].pose.position.z == pytest.approx(
        core('five_link', [0.05]).wheel_center[0, 2] / 1000.0, abs=1e-9)


@pytest.mark.parametrize('bad', list(BAD_COMMANDS_M))
def test_bad_command_publishes_no_pose_and_an_error_saying_why_at_once(
        suspension_node, executor, probe, bad):
    sink = ListSink()
    node = suspension_node(diagnostic_period=HOUR, sinks=[sink])
    kinds = []          # the Status of each command the node answered, in order
    health = node.corners[''].health
    add = health.add
    health.add = lambda solution, *args: kinds.append(solution.status) or add(solution, *args)
    expected = core('five_link', [0.02, 0.03])
    probe.send(0.02, BAD_COMMANDS_M[bad], 0.03)
    # At once: the ERROR of the bad command, then OK again with the good one that follows.
    assert spin_until(executor, lambda: len(probe.statuses) == 2 and probe.answered(expected))
    error, after = probe.statuses
    assert (error.level, after.level) == (DiagnosticStatus.ERROR, DiagnosticStatus.OK)
    assert kinds == [Status.OK, BAD_KIND[bad], Status.OK]     # the kind, by its code
    assert error.message                                       # and why, for people
    assert status_values(error)['failures'] == '1'
    # Each pose carries its command's stamp: the two poses are those of the good commands.
    received = [r.receive_ns for r in sink.records if r.topic == '/wheel_travel']
    assert [stamp_ns(p.header.stamp) for p in probe.poses] == [received[0], received[2]]
    assert [len(probe.poses), len(probe.cambers), len(probe.toes)] == [2, 2, 2]
    assert_outputs_equal_core(probe, expected)


@pytest.mark.parametrize('bad', list(BAD_COMMANDS_M))
def test_bad_command_keeps_the_last_good_state(suspension_node, executor, probe, bad):
    suspension_node(diagnostic_period=HOUR)
    probe.send(0.02, BAD_COMMANDS_M[bad], 0.02)
    assert spin_until(executor, lambda: len(probe.statuses) == 2 and len(probe.poses) == 2)
    assert probe.statuses[0].level == DiagnosticStatus.ERROR
    # Back at the last good travel: the very same pose, and nothing walked to get there.
    assert probe.poses[1].pose == probe.poses[0].pose


def test_a_burst_of_1000_commands_is_answered_in_order_none_lost(suspension_node, executor, probe):
    # All 1000 are published before the executor runs once: the node's subscription queue
    # must hold them all (QoS keep-last QOS_DEPTH, reliable).
    assert QOS_DEPTH >= 1000
    suspension_node()
    travels = burst_travels(1000)
    expected = core('five_link', travels)
    probe.send(*travels)
    assert spin_until(executor, lambda: probe.answered(expected), 30.0)
    assert_counts(probe, 1000)
    assert_outputs_equal_core(probe, expected)


def test_parameters_come_from_a_params_file(ros_context, executor, probe, tmp_path):
    params = tmp_path / 'params.yaml'
    params.write_text(yaml.safe_dump({'/**': {'ros__parameters': {
        'scene': 'double_wishbone', 'frame_id': 'chassis', 'method': 'paper',
        'max_step_mm': 20.0, 'diagnostic_period': 0.05}}}))
    node = SuspensionNode(context=ros_context,
                          cli_args=['--ros-args', '--params-file', str(params)])
    executor.add_node(node)
    expected = core('double_wishbone', [-0.04])
    probe.send(-0.04)
    assert spin_until(executor, lambda: probe.answered(expected))
    assert_outputs_equal_core(probe, expected, frame_id='chassis')
    values = report_after(probe, 1)
    assert probe.statuses[-1].hardware_id == 'double_wishbone'
    assert values['method'] == 'paper' and values['substeps_max'] == '2'


def test_bundled_params_file_holds_the_node_defaults(ros_context):
    node = SuspensionNode(context=ros_context,
                          cli_args=['--ros-args', '--params-file', str(PARAMS_FILE)])
    try:
        assert {name: node.get_parameter(name).value for name in PARAMETERS} == {
            name: spec.default for name, spec in PARAMETERS.items()}
    finally:
        node.destroy_node()


def test_reports_come_every_diagnostic_period_and_summarise_it(suspension_node, executor,
                                                               probe):
    suspension_node(diagnostic_period=0.2)
    travels = [0.0, 0.02, 0.04, 0.06, 0.08]      # all OK: no status is sent at once
    probe.send(*travels)
    report_after(probe, 5)
    assert spin_until(executor, lambda: len(probe.statuses) >= 3)
    values = [status_values(s) for s in probe.statuses]
    # Every command counted in exactly one period, with the worst values of its period.
    assert sum(int(v['commands']) for v in values) == 5
    assert {v['failures'] for v in values} == {'0'}
    expected = [Continuation(load_scene('five_link')).solve(t * 1000.0) for t in travels]
    assert max(float(v['condition_max']) for v in values) == pytest.approx(
        max(e.condition for e in expected), rel=1e-8)
    assert max(float(v['residual_max_m']) for v in values) <= 1e-13       # m: tol 1e-10 mm
    assert max(int(v['iterations_max']) for v in values) >= 1
    # Periodic, not per command: reports a period (0.2 s, timer jitter aside) apart.
    gaps = np.diff(probe.status_stamps) / 1e9
    assert all(0.1 <= gap <= 1.0 for gap in gaps)


def test_condition_warn_parameter_turns_a_well_conditioned_pose_into_a_warning_at_once(
        suspension_node, executor, probe):
    suspension_node(condition_warn=100.0, diagnostic_period=HOUR)   # five_link's is about 600
    probe.send(0.01)
    assert spin_until(executor, lambda: probe.statuses and probe.poses)
    assert probe.statuses[0].level == DiagnosticStatus.WARN
    assert 'condition number' in probe.statuses[0].message


def test_default_condition_warn_leaves_the_scene_travel_range_ok(suspension_node, executor, probe):
    suspension_node(diagnostic_period=0.05)
    probe.send(-0.08, 0.08)            # five_link's declared travel range
    report_after(probe, 2)
    assert {s.level for s in probe.statuses} == {DiagnosticStatus.OK}


@pytest.mark.parametrize('params, error', [
    ({'scene': 'no_such_scene'}, 'not a bundled scene'),
    ({'method': 'slow'}, "method: unknown value 'slow'"),
    ({'max_step_mm': 0.0}, 'max_step_mm: must be from 0.001 to 1000 mm, got 0.0'),
])
def test_bad_parameter_raises_a_clear_error(ros_context, params, error):
    overrides = [Parameter(k, value=v) for k, v in params.items()]
    with pytest.raises(ValueError, match=error) as raised:
        SuspensionNode(context=ros_context, parameter_overrides=overrides)
    assert isinstance(raised.value, SceneError) == ('scene' in params)


def test_qos_is_reliable_keep_last_1000():
    assert (QOS.reliability.name, QOS.history.name, QOS.depth) == ('RELIABLE', 'KEEP_LAST',
                                                                   1000)


# --- sinks: recorders and viewers ------------------------------------------------------------

def test_every_command_and_published_message_reaches_each_sink(suspension_node, executor, probe):
    sinks = [ListSink(), ListSink()]
    suspension_node(sinks=sinks, diagnostic_period=HOUR)
    probe.send(0.02, math.nan)
    assert spin_until(executor, lambda: len(probe.statuses) == 1)
    # At start the design-fixed frames and the URDF (TF is on by default), then per answer
    # the pose, camber, toe and the frames of the bodies.
    expected = [('/tf_static', 'tf2_msgs/msg/TFMessage'),
                ('/robot_description', 'std_msgs/msg/String'),
                ('/wheel_travel', 'std_msgs/msg/Float64'),
                ('/wheel_carrier_pose', 'geometry_msgs/msg/PoseStamped'),
                ('/camber', 'std_msgs/msg/Float64'), ('/toe', 'std_msgs/msg/Float64'),
                ('/elements', 'sensor_msgs/msg/JointState'),   # five_link has elements
                ('/tf', 'tf2_msgs/msg/TFMessage'),
                ('/wheel_travel', 'std_msgs/msg/Float64'),
                ('/diagnostics', 'diagnostic_msgs/msg/DiagnosticArray')]
    for sink in sinks:
        assert [(r.topic, r.type_name) for r in sink.records] == expected
    # Sinks get CDR bytes; rclpy's own deserializer reads them back.
    command, pose = sinks[0].records[2:4]
    assert deserialize_message(command.data, Float64).data == 0.02     # the bits sent
    pose_msg = deserialize_message(pose.data, PoseStamped)
    assert pose_msg.pose.position == probe.poses[0].pose.position     # the same message
    stamp = pose_msg.header.stamp
    assert command.receive_ns == stamp.sec * 10**9 + stamp.nanosec     # received at the stamp
    assert all(r.receive_ns <= r.publish_ns for r in sinks[0].records)   # received, published


def test_destroying_the_node_closes_its_sinks_once(suspension_node, executor):
    sink = ListSink()
    node = suspension_node(sinks=[sink])
    executor.remove_node(node)
    node.destroy_node()
    node.close_sinks()
    assert sink.closed == 1


def test_record_mcap_parameter_writes_a_recording_readable_by_mcap(suspension_node, executor,
                                                                   probe, tmp_path):
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory
    path = tmp_path / 'run.mcap'
    node = suspension_node(record_mcap=str(path), diagnostic_period=HOUR)
    probe.send(0.02, 0.03, math.nan)
    assert spin_until(executor, lambda: len(probe.statuses) == 1 and len(probe.poses) == 2)
    executor.remove_node(node)
    node.destroy_node()
    with open(path, 'rb') as stream:
        decoded = [(channel.topic, msg) for _, channel, _, msg in make_reader(
            stream, decoder_factories=[DecoderFactory()]).iter_decoded_messages()]
    topics = [topic for topic, _ in decoded]
    assert topics.count('/wheel_travel') == 3 and topics.count('/wheel_carrier_pose') == 2
    assert topics.count('/diagnostics') == 1 and topics.count('/camber') == 2
    assert [m.data for t, m in decoded if t == '/wheel_travel'][:2] == [0.02, 0.03]


def test_without_sinks_neither_mcap_nor_rerun_is_imported(domain_id):
    script = (
        'import sys, rclpy\n'
        'from linkage_ros.ros.node import SuspensionNode\n'
        f'ctx = rclpy.context.Context(); rclpy.init(context=ctx, domain_id={domain_id})\n'
        'SuspensionNode(context=ctx).destroy_node(); rclpy.try_shutdown(context=ctx)\n'
        "names = ('mcap', 'rerun', 'linkage_ros.record.mcap_writer', "
        "'linkage_ros.record.rerun_view')\n"
        'print(sorted(n for n in names if n in sys.modules))\n')
    result = subprocess.run([sys.executable, '-c', script], capture_output=True, text=True,
                            timeout=60, env={**os.environ,
                                             'ROS_AUTOMATIC_DISCOVERY_RANGE': 'OFF'})
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == '[]'


# --- across processes: the console script in a subprocess ----------------------------------

def test_node_process_answers_like_the_core_and_exits_cleanly_on_sigint(
        node_process, localhost_context, localhost_executor):
    process = node_process('--params-file', str(PARAMS_FILE))
    probe = Probe(localhost_context, localhost_executor)
    connect(localhost_executor, probe)
    expected = core('five_link', TRAVELS_M)
    probe.send(*TRAVELS_M)
    assert spin_until(localhost_executor, lambda: probe.answered(expected))
    assert_outputs_equal_core(probe, expected)
    code, _, err = process.stop(signal.SIGINT)
    assert code == 0, err
    assert 'Traceback' not in err


def test_node_process_exits_cleanly_on_sigterm_with_its_recording_closed(
        node_process, localhost_context, localhost_executor, tmp_path):
    from mcap.reader import make_reader
    path = tmp_path / 'run.mcap'
    process = node_process('-p', f'record_mcap:={path}')
    probe = Probe(localhost_context, localhost_executor)
    connect(localhost_executor, probe)
    code, _, err = process.stop(signal.SIGTERM)
    assert code == 0, err
    with open(path, 'rb') as stream:
        summary = make_reader(stream).get_summary()     # written only by a finished file
    assert summary is not None
    assert summary.statistics.message_count >= 4       # at least one answered command


def test_node_process_answers_a_burst_of_1000_in_order(node_process, localhost_context,
                                                       localhost_executor):
    process = node_process()
    probe = Probe(localhost_context, localhost_executor)
    connect(localhost_executor, probe)
    travels = burst_travels(1000)
    expected = core('five_link', travels)    # the pings leave the node at 0, as the core
    probe.send(*travels)
    assert spin_until(localhost_executor, lambda: probe.answered(expected), 30.0)
    # Replies to the connection pings come first; the last 1000 of each are the burst's.
    assert_outputs_equal_core(probe, expected)
    assert process.stop(signal.SIGINT)[0] == 0


@pytest.mark.parametrize('scene, error', [
    ('no_such_scene', 'no_such_scene: scene: no such file, and not a bundled scene'),
    ('{tmp}/broken.yaml', "broken.yaml: units: unknown value 'furlong'"),
])
def test_bad_scene_exits_non_zero_with_the_loader_message(node_process, tmp_path, scene,
                                                          error):
    (tmp_path / 'broken.yaml').write_text('units: furlong\nside: left\n')
    process = node_process('-p', f'scene:={scene.format(tmp=tmp_path)}')
    code, _, err = process.finish()
    assert code == 2
    assert err.strip().splitlines() == [err.strip()]            # one line, no traceback
    assert err.startswith('suspension_node: ') and error in err


def test_node_bench_quick_run_prints_every_section_with_nothing_lost(domain_id):
    # A smoke run of linkage-bench node: the tables' structure, not their (machine) timings.
    result = subprocess.run(
        [str(Path(sys.executable).parent / 'linkage-bench'), 'node', '--quick',
         '--only', 'core,sweep,latency,vehicle,callback'],
        capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    assert f'ROS domain {domain_id},' in result.stderr      # the user's, not one of its own
    tables = {}
    for block in result.stdout.strip().split('\n\n'):
        rows = [line.split(',') for line in block.splitlines()]
        tables[rows[0][0]] = rows
    assert list(tables) == ['core', 'sweep', 'latency', 'rate', 'vehicle', 'callback']
    assert [r[0] for r in tables['core'][1:]][:1] == ['linkage_ros']
    assert [r[0] for r in tables['latency'][1:]] == ['node', 'echo'] * 2
    assert {r[4] for r in tables['rate'][1:]} == {'0'}            # nothing lost
    # then demo_vehicle_bushings: a contact wrench per corner and a JointState per step
    assert [(r[0], r[1], r[4]) for r in tables['vehicle'][1:]] == [
        ('node', 'float64_per_corner', '0'), ('echo', 'float64_per_corner', '0'),
        ('node', 'joint_states', '0'), ('echo', 'joint_states', '0'),
        *((name, 'joint_states+contact_wrench', '0')
          for name in ('node_lean', 'node_defaults', 'node_all', 'echo'))]
    # each row ends with the load average after its run, then the ratio to the echo's
    assert tables['vehicle'][0][-2:] == ['load_average', 'ratio_to_echo']
    assert [r[0] for r in tables['callback'][1:]][:4] == ['plain', 'elements', 'tf',
                                                          'alignment']


# --- parameters, names, QoS ----------------------------------------------------------------

def test_every_parameter_says_if_it_is_fixed_and_a_number_carries_its_range(ros_context):
    # Not read_only: a change of a fixed one is refused by the node, saying why
    # (test_params_runtime.py); its description says it is fixed.
    from linkage_ros.ros.parameters import RUNTIME
    node = SuspensionNode(context=ros_context, parameter_overrides=[
        Parameter('max_step_mm', value=2), Parameter('scene', value='double_wishbone')])
    try:
        for name, spec in PARAMETERS.items():     # given (max_step_mm, scene) or not
            descriptor = node.describe_parameter(name)
            assert not descriptor.read_only, name
            assert descriptor.description.endswith('(fixed while the node runs)') == (
                name not in RUNTIME), name
            if isinstance(spec.default, float):
                (bounds,) = descriptor.floating_point_range
                assert (bounds.from_value, bounds.to_value) == (spec.low, spec.high), name
        assert node.describe_parameter('qos_depth').integer_range[0].to_value == 100000
        assert node.get_parameter('max_step_mm').value == 2        # an integer is a number
    finally:
        node.destroy_node()


def test_a_parameter_the_node_does_not_know_is_refused_with_the_closest_name(ros_context):
    with pytest.raises(ValueError, match='parameter max_stepmm: not a parameter of '
                                         r'suspension_node \(did you mean max_step_mm\?'):
        SuspensionNode(context=ros_context,
                       parameter_overrides=[Parameter('max_stepmm', value=1.0)])


def test_rclpy_declares_no_parameter_of_its_own_that_the_node_would_call_unknown(ros_context):
    # The node refuses every parameter it is given that is neither its own nor rclpy's;
    # rclpy's are named in parameters.ROS_PARAMETERS, which this pins for the installed rclpy.
    import rclpy
    from linkage_ros.ros.parameters import ROS_PARAMETERS
    bare = rclpy.create_node('bare', context=ros_context, enable_rosout=False,
                             start_parameter_services=False)
    try:
        assert set(bare.list_parameters([], 0).names) <= set(ROS_PARAMETERS)
    finally:
        bare.destroy_node()


def test_qos_depth_is_the_depth_of_every_topic_of_the_node(suspension_node):
    node = suspension_node(scene='double_wishbone', travel_joint='wheel', alignment=True,
                           qos_depth=7)
    own = [e for e in [*node.subscriptions, *node.publishers]
           if e.topic_name not in ('/parameter_events', '/rosout')]
    assert sorted(e.topic_name for e in own) == sorted({
        '/alignment', '/camber', '/diagnostics', '/elements', '/joint_states',
        '/robot_description', '/steering_rack', '/toe', '/wheel_carrier_pose',
        '/wheel_travel'} | live_tf_topics())
    latched = ('/robot_description', '/tf_static')     # transient local, the last one only
    assert {e.qos_profile.depth for e in own if e.topic_name not in latched} == {7}
    assert {e.qos_profile.depth for e in own if e.topic_name in latched} == {1}


def test_namespaced_nodes_name_their_statuses_with_their_full_names(ros_context, executor,
                                                                    probe):
    # Eight namespaced nodes once all reported 'suspension_kinematics: five_link'.
    for namespace in ('car1', 'car2'):
        executor.add_node(SuspensionNode(context=ros_context, namespace=namespace,
                                         parameter_overrides=[
                                             Parameter('diagnostic_period', value=0.05)]))
    statuses = []
    probe.node.create_subscription(DiagnosticArray, '/diagnostics',
                                   lambda m: statuses.extend(m.status), QOS)
    assert spin_until(executor, lambda: {s.name for s in statuses} == {
        '/car1/suspension_kinematics: five_link', '/car2/suspension_kinematics: five_link'})


@pytest.mark.parametrize('params, says', [
    ({'travel_joint': 'wheel'}, 'listening on /wheel_travel (m), /joint_states (joint wheel, m)'),
    ({'scene': 'double_wishbone'}, 'listening on /wheel_travel (m), /steering_rack (m)'),
    ({'vehicle': 'demo_vehicle'}, 'listening on /front_left/wheel_travel (m), '
     '/front_left/steering_rack (m), /joint_states (joints front_left_travel, steering_rack, m)'),
])
def test_the_start_up_line_names_every_input_the_node_listens_to(ros_context, capfd, params,
                                                                 says):
    node = SuspensionNode(context=ros_context, parameter_overrides=[
        Parameter(k, value=v) for k, v in params.items()])
    node.destroy_node()
    assert says in capfd.readouterr().err


def test_a_scene_s_warnings_are_logged_once_at_start_as_warnings(ros_context, capfd):
    # five_link_singular: two links alike, a singular design position (Scene.warnings).
    singular = Path(__file__).resolve().parents[1] / 'data' / 'five_link_singular.yaml'
    scene = load_scene(singular)
    assert len(scene.warnings) == 1
    node = SuspensionNode(context=ros_context, parameter_overrides=[
        Parameter('scene', value=str(singular))])
    node.destroy_node()
    warned = node_warnings(capfd.readouterr().err)
    assert len(warned) == 1
    assert warned[0].endswith(f'[suspension_kinematics]: {scene.warnings[0]}')


def test_a_sound_scene_logs_no_warning(ros_context, capfd):
    SuspensionNode(context=ros_context).destroy_node()
    assert node_warnings(capfd.readouterr().err) == []


def recording_custom_data(path):
    """
    Return what an MCAP says of its run, read with mcap and yaml.

    That is the custom_data of its rosbag2 metadata record (the parameters) and its
    linkage_ros metadata record (the files' content), in one dict.
    """
    from mcap.reader import make_reader
    with open(path, 'rb') as stream:
        records = {m.name: m.metadata for m in make_reader(stream).iter_metadata()}
    custom = yaml.safe_load(records['rosbag2']['serialized_metadata'])['custom_data']
    assert not set(custom) & set(records['linkage_ros'])
    return {**custom, **records['linkage_ros']}


def test_a_recording_holds_the_text_of_its_scene_file(ros_context, tmp_path, monkeypatch):
    # A user's scene is named by the path as typed: from another folder that path is gone.
    source = Path(load_scene('macpherson').source).read_text()
    (tmp_path / 'mine.yaml').write_text(source)
    monkeypatch.chdir(tmp_path)
    node = SuspensionNode(context=ros_context, parameter_overrides=[
        Parameter('scene', value='mine.yaml'), Parameter('record_mcap', value='run.mcap')])
    node.destroy_node()
    custom = recording_custom_data(tmp_path / 'run.mcap')
    assert (custom['scene'], custom['scene_yaml']) == ('mine.yaml', source)


def test_a_vehicle_recording_holds_the_vehicle_file_and_each_corners_scene(ros_context,
                                                                           tmp_path):
    from linkage_ros.core.model import load_vehicle
    node = SuspensionNode(context=ros_context, parameter_overrides=[
        Parameter('vehicle', value='demo_vehicle'),
        Parameter('record_mcap', value=str(tmp_path / 'run.mcap'))])
    node.destroy_node()
    custom = recording_custom_data(tmp_path / 'run.mcap')
    vehicle = load_vehicle('demo_vehicle')
    assert custom['vehicle_yaml'] == Path(vehicle.source).read_text()
    assert custom['scene_yaml/front_left'] == Path(
        load_scene('double_wishbone').source).read_text()
    assert custom['scene_yaml/rear_right'] == Path(load_scene('five_link').source).read_text()
    assert 'scene_yaml' not in custom
