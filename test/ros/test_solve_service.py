# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The <corner>/solve service of suspension_node (linkage_ros_interfaces/srv/Solve).

From another process over DDS: a node answering by topic and a node answering by service,
both five_link from design and given the same 1000 commands at 1 kHz, give equal answers,
bit for bit (one code path, the corner's Responder, on the same inputs), and each service
answer equals the pose the serving node published for it. A bad request gets a status that is
not OK and no pose, never an exception. Without the interface package (no compiler to build
it) the node serves no solve service and says why, once.
"""

import math
from pathlib import Path
import subprocess
import sys
import time

from geometry_msgs.msg import PoseStamped
from linkage_ros.core.base import Status
from linkage_ros.ros import solve_service
from linkage_ros.ros.testing import spin_until
import pytest
from rclpy.qos import QoSProfile, ReliabilityPolicy
from std_msgs.msg import Float64

Solve = solve_service.solve_type()
needs_interfaces = pytest.mark.skipif(Solve is None, reason=(
    'linkage_ros_interfaces is not built here (linkage-tf2-msgs builds it where a C/C++ '
    'compiler and the Python headers are)'))
WAIT = 20.0
CALLS = 1000
PERIOD = 0.001     # s: 1 kHz
QOS = QoSProfile(depth=CALLS, reliability=ReliabilityPolicy.RELIABLE)


def pose_tuple(pose):
    p, q = pose.position, pose.orientation
    return (p.x, p.y, p.z, q.x, q.y, q.z, q.w)


class Lockstep:
    """Topic commands to /by_topic, service calls to /by_service; keeps every answer."""

    def __init__(self, context, executor):
        import rclpy
        self.node = rclpy.create_node('lockstep', context=context, enable_rosout=False,
                                      start_parameter_services=False)
        self.executor = executor
        self.topic_poses, self.served_poses = [], []
        self.travel = self.node.create_publisher(Float64, '/by_topic/wheel_travel', QOS)
        self.subs = [self.node.create_subscription(PoseStamped, f'/{ns}/wheel_carrier_pose',
                                                   poses.append, QOS)
                     for ns, poses in (('by_topic', self.topic_poses),
                                       ('by_service', self.served_poses))]
        self.client = self.node.create_client(Solve, '/by_service/solve', qos_profile=QOS)
        executor.add_node(self.node)

    def ready(self):
        return (self.travel.get_subscription_count() > 0 and self.client.service_is_ready()
                and all(s.get_publisher_count() > 0 for s in self.subs))

    def call(self, **request):
        future = self.client.call_async(Solve.Request(**request))
        assert spin_until(self.executor, future.done, WAIT)
        return future.result()


@needs_interfaces
def test_service_answers_equal_topic_answers_for_1000_calls_at_1_khz(
        node_process, localhost_context, localhost_executor):
    nodes = [node_process('-r', f'__ns:=/{ns}', '-p', 'tf:=false') for ns in
             ('by_topic', 'by_service')]
    lockstep = Lockstep(localhost_context, localhost_executor)
    assert spin_until(localhost_executor, lockstep.ready, 60.0)
    travels = [0.06 * math.sin(2 * math.pi * i / 250) for i in range(CALLS)]
    futures, start = [], time.monotonic()
    for i, travel in enumerate(travels):
        while time.monotonic() < start + i * PERIOD:   # paced at 1 kHz, answers taken meanwhile
            localhost_executor.spin_once(timeout_sec=0.0002)
        lockstep.travel.publish(Float64(data=travel))
        futures.append(lockstep.client.call_async(Solve.Request(travel=travel)))
    spin_until(localhost_executor, lambda: all(f.done() for f in futures) and len(
        lockstep.topic_poses) == len(lockstep.served_poses) == CALLS, 60.0)
    assert (sum(f.done() for f in futures), len(lockstep.topic_poses),
            len(lockstep.served_poses)) == (CALLS, CALLS, CALLS)
    answers = [f.result() for f in futures]
    assert [a.status for a in answers] == [Status.OK] * CALLS
    assert [pose_tuple(a.pose) for a in answers] == [
        pose_tuple(m.pose) for m in lockstep.topic_poses]
    assert [pose_tuple(a.pose) for a in answers] == [
        pose_tuple(m.pose) for m in lockstep.served_poses]
    # the travel is the wheel centre's z change (m), from design
    design_z = answers[0].pose.position.z - travels[0]
    assert max(abs(a.pose.position.z - design_z - t) for a, t in zip(answers, travels)) < 1e-12
    for node in nodes:
        assert node.stop()[0] == 0


@needs_interfaces
@pytest.mark.parametrize('request_fields,status,says', [
    ({'corner': 'front_left', 'travel': 0.01}, 255, "REFUSED: no corner 'front_left' here"),
    ({'travel': math.nan}, Status.NOT_FINITE, 'NOT_FINITE: '),
    ({'travel': math.inf}, Status.NOT_FINITE, 'NOT_FINITE: '),
    ({'travel': 5.0}, Status.OUT_OF_REACH, 'OUT_OF_REACH: '),
    ({'travel': 0.01, 'rack': 0.002}, Status.NO_RACK, 'NO_RACK: '),
    ({'travel': 0.01, 'use_wrench': True}, 255,
     'REFUSED: scene five_link has no bushings and parameter statics is false'),
])
def test_a_bad_request_gets_an_error_status_and_no_pose(
        ros_context, executor, suspension_node, request_fields, status, says):
    suspension_node()
    lockstep = Lockstep.__new__(Lockstep)
    import rclpy
    lockstep.node = rclpy.create_node('client', context=ros_context)
    lockstep.executor = executor
    lockstep.client = lockstep.node.create_client(Solve, 'solve')
    executor.add_node(lockstep.node)
    assert spin_until(executor, lockstep.client.service_is_ready, WAIT)
    answer = lockstep.call(**request_fields)
    assert (answer.status, answer.status_text.startswith(says)) == (status, True)
    assert all(math.isnan(v) for v in (*pose_tuple(answer.pose), answer.camber, answer.toe))
    assert lockstep.call(travel=0.01).status == Status.OK     # still answering


def test_without_the_interface_package_the_node_serves_no_solve_and_says_why_once(
        suspension_node, monkeypatch, capfd):
    monkeypatch.setattr(solve_service, 'solve_type', lambda: None)
    node = suspension_node(vehicle='demo_vehicle', tf=False)
    assert not [s for s in node.services if s.srv_name.endswith('solve')]
    said = [line for line in capfd.readouterr().err.splitlines() if 'solve' in line]
    assert len(said) == 1 and said[0].endswith(solve_service.MISSING)


@needs_interfaces
def test_node_bench_quick_run_prints_the_service_and_lifecycle_tables(domain_id):
    # A smoke run of the two sections: the tables' structure, not their (machine) timings.
    result = subprocess.run(
        [str(Path(sys.executable).parent / 'linkage-bench'), 'node', '--quick', '--starts',
         '1', '--only', 'service,lifecycle'], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    tables = {}
    for block in result.stdout.strip().split('\n\n'):
        rows = [line.split(',') for line in block.splitlines()]
        tables[rows[0][0]] = rows
    assert list(tables) == ['service', 'lifecycle']
    assert [(r[0], r[1]) for r in tables['service'][1:]] == [('topic', '48'), ('service', '48')]
    assert [(r[0], r[1]) for r in tables['lifecycle'][1:]] == [('configure first', '1'),
                                                               ('configure again', '3')]


@needs_interfaces
def test_a_vehicle_serves_each_corner_which_refuses_another_corner_s_request(
        ros_context, executor, suspension_node):
    import rclpy
    node = suspension_node(vehicle='demo_vehicle', tf=False)
    assert sorted(s.srv_name for s in node.services if s.srv_name.endswith('/solve')) == [
        f'{corner}/solve' for corner in sorted(node.corners)]
    client_node = rclpy.create_node('client', context=ros_context)
    executor.add_node(client_node)
    client = client_node.create_client(Solve, '/front_left/solve')
    assert spin_until(executor, client.service_is_ready, WAIT)
    answers = []
    for corner in ('front_left', 'rear_right'):
        future = client.call_async(Solve.Request(corner=corner, travel=0.02))
        assert spin_until(executor, future.done, WAIT)
        answers.append(future.result())
    assert [a.status for a in answers] == [Status.OK, Solve.Response.REFUSED]
    assert answers[1].status_text == ("REFUSED: no corner 'rear_right' here: this is the solve "
                                      "service of 'front_left'")


@needs_interfaces
def test_a_request_with_a_wrench_answers_the_loaded_pose_the_core_gives(
        ros_context, executor, suspension_node):
    # five_link_bushings: statics on. The response is solve_loaded's pose at that travel and
    # wrench (continued from the corner's kinematic pose, as the node's answers are), in SI,
    # to round-off; a later request without use_wrench keeps the wrench, as the topic does.
    from geometry_msgs.msg import Wrench
    from linkage_ros.core.base import quaternion_from_matrix
    from linkage_ros.core.model import load_scene
    from linkage_ros.core.solve import Continuation
    from linkage_ros.core.statics import Load, solve_loaded
    import rclpy
    suspension_node(scene='five_link_bushings')
    client_node = rclpy.create_node('client', context=ros_context)
    client = client_node.create_client(Solve, 'solve')
    executor.add_node(client_node)
    assert spin_until(executor, client.service_is_ready, WAIT)
    scene = load_scene('five_link_bushings')
    continuation = Continuation(scene)
    wrench = Wrench()
    wrench.force.y, wrench.force.x, wrench.torque.z = 3000.0, -1500.0, 40.0
    for travel_m, use in ((0.02, True), (0.01, False)):
        future = client.call_async(Solve.Request(travel=travel_m, wrench=wrench,
                                                 use_wrench=use))
        assert spin_until(executor, future.done, WAIT)
        answer = future.result()
        assert answer.status == Status.OK, answer.status_text
        assert continuation.solve(travel_m * 1000.0).success
        loaded = solve_loaded(scene, travel_mm=travel_m * 1000.0, rack_mm=0.0,
                              load=Load((-1500.0, 3000.0, 0.0), 'cp', (0.0, 0.0, 40.0)),
                              continuation=continuation)
        p, q = answer.pose.position, answer.pose.orientation
        assert [p.x, p.y, p.z] == pytest.approx((loaded.wheel_center_mm * 1e-3).tolist(),
                                                rel=0, abs=1e-12)
        assert [q.x, q.y, q.z, q.w] == pytest.approx(
            quaternion_from_matrix(loaded.rotation).tolist(), rel=0, abs=1e-12)
        assert answer.toe == pytest.approx(math.radians(loaded.toe_deg), rel=0, abs=1e-12)


def test_the_srv_comment_names_every_status_the_service_answers():
    # Solve.srv's comment is the interface's documentation: every Status value, by number
    # and name (7 NOT_CARRIED was missing), and REFUSED's every reason
    text = (Path(__file__).resolve().parents[2] / 'config' / 'interfaces' /
            'linkage_ros_interfaces' / 'srv' / 'Solve.srv').read_text()
    comment = ' '.join(line.lstrip('# ') for line in text.split('---')[1].splitlines()
                       if line.startswith('#'))
    for status in Status:
        assert f'{status.value} {status.name}' in comment, status
    for reason in ('corner', 'not active', 'wrench', 'overloaded'):
        assert reason in comment.split('REFUSED', 1)[1], reason


@needs_interfaces
def test_with_angles_off_the_service_still_answers_camber_and_toe(
        ros_context, executor, suspension_node):
    # angles:=false publishes no camber or toe; the response's are the solution's own floats,
    # which a Float64's CDR would hold unchanged: the core's Continuation, fed the same
    # command from design, gives the same bits
    from linkage_ros.core.model import load_scene
    from linkage_ros.core.solve import Continuation
    import rclpy
    node = suspension_node(angles=False, tf=False)
    assert node.corners[''].sends.keys() == {'wheel_carrier_pose', 'elements'}
    client_node = rclpy.create_node('client', context=ros_context)
    client = client_node.create_client(Solve, 'solve')
    executor.add_node(client_node)
    assert spin_until(executor, client.service_is_ready, WAIT)
    future = client.call_async(Solve.Request(travel=0.02))
    assert spin_until(executor, future.done, WAIT)
    answer = future.result()
    assert answer.status == Status.OK, answer.status_text
    want = Continuation(load_scene('five_link')).solve(0.02 * 1000.0)
    assert (answer.camber, answer.toe) == (want.camber, want.toe)
    assert answer.pose.position.z == want.wheel_center[2] * 1e-3
