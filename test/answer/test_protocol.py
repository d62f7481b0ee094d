# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
protocol.Responder answers as suspension_node does: same answers, same reports, same times.

The reference is the node itself: a SuspensionNode in process (the plugin's suspension_node
and probe fixtures, real DDS), driven on simulated time (/clock) through a stream with bad
commands (out of reach, NaN, infinite) and changes of level, on a clock that passes each
period end. What the probe receives is compared with what a Responder builds for the same
stream, and with what linkage-replay writes for a recording of the same commands (read back
by mcap + mcap_ros2, not project code).
"""

import math
import subprocess
import sys

from builtin_interfaces.msg import Time
from linkage_ros.answer.cdr import float64_of, from_cdr
from linkage_ros.answer.protocol import Responder
from linkage_ros.core.base import Status
from linkage_ros.core.model import load_scene
from linkage_ros.record.mcap_writer import McapRecorder
from linkage_ros.ros import messages
from linkage_ros.ros.testing import spin_until, stamp_ns
from linkage_ros.tools import replay
from linkage_ros.tools.replay_solve import status_name
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
from rclpy.qos import QoSProfile
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Float64

S = 10**9   # ns per s
# (simulated time ns, wheel travel m, or None: the clock moves alone), from 0, where the
# node's diagnostic periods start (its timer's start on simulated time). five_link reaches
# [-146, 387] mm; its Jacobian condition number rises from 546 at -80 mm to 617 at +80 mm,
# so with condition_warn 600 a travel above about +30 mm is WARN.
STREAM = [(0, 0.0), (S // 2, 0.04), (3 * S // 4, 0.5), (S, None),
          (5 * S // 4, math.nan), (3 * S // 2, 0.01), (7 * S // 4, 0.02), (2 * S, None),
          (9 * S // 4, 0.05), (3 * S, None), (13 * S // 4, -0.03), (7 * S // 2, math.inf)]
# What the node, started with its default name, calls the corner (replay names it the same).
NAME = status_name(load_scene('five_link'))


def pose_key(msg):
    """Return what a PoseStamped says: (stamp ns, frame_id, x, y, z, qx, qy, qz, qw), m."""
    p, q = msg.pose.position, msg.pose.orientation
    return (stamp_ns(msg.header.stamp), msg.header.frame_id, p.x, p.y, p.z, q.x, q.y, q.z, q.w)


def report_key(stamp, status):
    """Return what a report says: (stamp ns, level (0 OK, 1 WARN, 2 ERROR), name, ...)."""
    level = status.level if isinstance(status.level, int) else status.level[0]   # rclpy: bytes
    return (stamp, level, status.name, status.message, status.hardware_id,
            tuple((kv.key, kv.value) for kv in status.values))


def responder_run(condition_warn, stream=STREAM):
    """
    Return what a Responder builds for stream: ([(pose, camber, toe)], [reports]).

    The pose is pose_key of the bytes decoded by rclpy; camber and toe rad.
    """
    scene = load_scene('five_link')
    responder = Responder(scene, method='fast', max_step_mm=5.0, condition_warn=condition_warn,
                          frame_id='base_link', status_name=NAME, period_ns=S, start_ns=0)
    answers, reports = [], []

    def report(stamp):
        reports.append(report_key(stamp, messages.health_status(
            responder.health, NAME, scene.name, 'fast')))

    for t, travel in stream:
        due = responder.due(t)
        if due is not None:
            report(due)
            responder.health.reset_period()
        if travel is None:
            continue
        reply = responder.answer(travel * 1000.0, None, divmod(t, S),
                                 f'/wheel_travel {travel!r} m')
        if reply.outputs:
            # five_link has elements: the node publishes them after pose, camber and toe
            assert [(n, kind) for n, kind, _ in reply.outputs] == [
                ('wheel_carrier_pose', 'geometry_msgs/msg/PoseStamped'),
                ('camber', 'std_msgs/msg/Float64'), ('toe', 'std_msgs/msg/Float64'),
                ('elements', 'sensor_msgs/msg/JointState')]
            pose, camber, toe = (data for _, _, data in reply.outputs[:3])
            answers.append((pose_key(from_cdr('geometry_msgs/msg/PoseStamped', pose)),
                            float64_of(camber), float64_of(toe)))
        if reply.report:
            report(t)
    return answers, reports


def node_run(suspension_node, executor, probe, stream=STREAM, **params):
    """
    Drive an in-process node (use_sim_time) through stream; return what the probe received.

    ([(pose, camber, toe)], [reports]) as responder_run gives them. Each step waits until the
    node's clock
    reads the time, then for the answer (pose, camber, toe) or the ERROR, and for every
    report the Responder says the step gives (counts of what arrives, never fixed sleeps).
    """
    node = suspension_node(use_sim_time=True, diagnostic_period=1.0, **params)
    clock = probe.node.create_publisher(Clock, '/clock', QoSProfile(depth=10))
    assert spin_until(executor, probe.matched)
    _, reports = responder_run(params.get('condition_warn', 1e4), stream)
    answered = 0
    for t, travel in stream:
        clock.publish(Clock(clock=Time(sec=t // S, nanosec=t % S)))
        assert spin_until(executor, lambda: node.get_clock().now().nanoseconds == t)
        if travel is not None:
            probe.send(travel)
            answered += math.isfinite(travel) and abs(travel) < 0.1
        reported = sum(1 for r in reports if r[0] <= t)
        assert spin_until(executor, lambda: len(probe.statuses) >= reported
                          and len(probe.toes) >= answered), (t, travel)
    spin_until(executor, lambda: False, 0.2)   # anything more would arrive now
    answers = list(zip(map(pose_key, probe.poses), probe.cambers, probe.toes))
    received = [report_key(stamp, status)
                for stamp, status in zip(probe.status_stamps, probe.statuses)]
    return answers, received


def test_a_responder_answers_and_reports_as_the_node_does(suspension_node, executor, probe):
    node_answers, node_reports = node_run(suspension_node, executor, probe,
                                          condition_warn=600.0)
    answers, reports = responder_run(600.0)
    assert len(answers) == 6                    # every command but 0.5 m, NaN and inf
    assert node_answers == answers              # the same values at the same stamps
    levels = [(stamp, level) for stamp, level, *_ in reports]
    # At once: WARN at 0.04 m, ERROR at 0.5 m, NaN and inf, OK at 0.01 and -0.03 m, WARN at
    # 0.05 m; periodic at 1, 2 and 3 s (the level then held).
    assert levels == [(S // 2, 1), (3 * S // 4, 2), (S, 2),
                      (5 * S // 4, 2), (3 * S // 2, 0), (2 * S, 0),
                      (9 * S // 4, 1), (3 * S, 1), (13 * S // 4, 0),
                      (7 * S // 2, 2)]
    assert node_reports == reports              # same times, levels, messages and values
    assert reports[1][3].startswith('/wheel_travel 0.5 m: travel 500 mm is out of reach')


def decoded(path):
    """[(topic, log time, decoded message)] in file order, by mcap + mcap_ros2."""
    with open(path, 'rb') as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        return [(c.topic, m.log_time, d) for _, c, m, d in reader.iter_decoded_messages(
            log_time_order=False)]


def test_replay_answers_a_recording_as_the_node_answered_it(suspension_node, executor, probe,
                                                            tmp_path):
    node_answers, node_reports = node_run(suspension_node, executor, probe)
    bag, out = tmp_path / 'run.mcap', tmp_path / 'solved.mcap'
    with McapRecorder(bag) as recorder:
        for t, travel in STREAM:
            if travel is not None:
                recorder.record('/wheel_travel', 'std_msgs/msg/Float64', Float64(data=travel),
                                t, t)
    # Replay counts the periods from the first command, at 0 as the node's timer.
    assert replay.main(['solve', str(bag), '-o', str(out)]) == 0
    messages_out = decoded(out)
    poses = [pose_key(m) for topic, _, m in messages_out if topic == '/wheel_carrier_pose']
    assert poses == [pose for pose, _, _ in node_answers]
    assert [m.data for topic, _, m in messages_out if topic == '/camber'] == [
        camber for _, camber, _ in node_answers]
    reports = [report_key(t, m.status[0]) for topic, t, m in messages_out
               if topic == '/diagnostics']
    assert [r[:2] for r in node_reports] == [
        (3 * S // 4, 2), (S, 2), (5 * S // 4, 2), (3 * S // 2, 0),
        (2 * S, 0), (3 * S, 0), (7 * S // 2, 2)]
    assert reports[:-1] == node_reports
    assert reports[-1][0] == STREAM[-1][0]               # and one after the last command


def test_due_gives_each_period_end_once_and_one_report_for_a_gap():
    responder = Responder(load_scene('five_link'), method='fast', max_step_mm=5.0,
                          condition_warn=1e4, frame_id='base_link', status_name=NAME,
                          period_ns=S)
    assert responder.due(100 * S) is None                   # the first call starts the clock
    assert [responder.due(t) for t in (100 * S + S // 2, 101 * S, 101 * S)] == [
        None, 101 * S, None]
    assert responder.due(105 * S + 1) == 102 * S            # a gap: the first end it passed
    assert responder.due(105 * S + 2) is None and responder.due(106 * S) == 106 * S


def test_the_answer_reads_back_by_rclpy_as_the_solution_at_every_frame_id_padding():
    # An independent reader: rclpy's deserializer, for every padding of the frame_id.
    from geometry_msgs.msg import PoseStamped
    from rclpy.serialization import deserialize_message
    from std_msgs.msg import Float64
    scene = load_scene('double_wishbone')
    for frame_id in ('', 'a', 'base_link', 'odom_1234567'):
        responder = Responder(scene, method='fast', max_step_mm=5.0, condition_warn=1e4,
                              frame_id=frame_id, status_name=NAME, period_ns=S)
        for travel in (-40.0, 0.0, 12.5, 40.0):
            reply = responder.answer(travel, None, (1_700_000_000, 123))
            # then double_wishbone's elements (test_outputs.py)
            (_, _, pose), (_, _, camber), (_, _, toe) = reply.outputs[:3]
            pose = deserialize_message(pose, PoseStamped)
            assert (pose.header.stamp.sec, pose.header.stamp.nanosec) == (1_700_000_000, 123)
            assert pose.header.frame_id == frame_id
            p, q = pose.pose.position, pose.pose.orientation
            assert [p.x, p.y, p.z] == (reply.solution.wheel_center * 1e-3).tolist()   # M_PER_MM
            assert [q.x, q.y, q.z, q.w] == reply.solution.quaternion.tolist()
            assert deserialize_message(camber, Float64).data == reply.solution.camber
            assert deserialize_message(toe, Float64).data == reply.solution.toe


def loaded_by(imports, wanted):
    """Return the sorted modules that `import imports` loads in a new Python, of those wanted."""
    code = (f'import sys, {imports}; print(sorted(m for m in sys.modules if {wanted}))')
    result = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                            timeout=120, check=True)
    return result.stdout


def test_importing_the_protocol_loads_neither_rclpy_nor_a_message_package():
    assert loaded_by('linkage_ros.answer.protocol', 'm.split(".")[0] in {"rclpy", "std_msgs", '
                     '"geometry_msgs", "diagnostic_msgs", "builtin_interfaces", '
                     '"rosidl_parser", "mcap"} and "." not in m') == '[]\n'


def test_the_protocol_and_health_import_nothing_of_the_ros_adapter():
    # health.py was in ros/ while ROS-free, and the protocol imported it from there: the
    # layers import downwards only (ros uses the protocol, never the other way).
    assert loaded_by('linkage_ros.answer.protocol, linkage_ros.answer.health', 'm.startswith(('
                     '"linkage_ros.ros", "linkage_ros.record", "linkage_ros.tools"))'
                     ) == '[]\n'


def test_a_rack_command_to_a_scene_without_a_rack_link_is_refused_with_no_pose():
    # five_link has no steer: rack link: the node and linkage-replay refuse alike (Responder)
    responder = Responder(load_scene('five_link'), method='fast', max_step_mm=5.0,
                          condition_warn=1e4, frame_id='base_link', status_name='s',
                          period_ns=10**9)
    responder.answer(20.0, None, (0, 0))
    reply = responder.answer(None, 5.0, (0, 1), '/steering_rack 0.005 m')
    assert (reply.solution.success, reply.solution.status) == (False, Status.NO_RACK)
    assert reply.outputs == [] and reply.report
    assert reply.sent == '/steering_rack 0.005 m'
    assert responder.health.level == 2   # ERROR (diagnostic_msgs), as for undecodable bytes
    assert responder.solver.travel == 20.0 and responder.solver.rack == 0.0   # the pose kept
