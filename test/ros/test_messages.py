# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""linkage_ros.ros.messages: Solution (mm, rad) -> ROS messages (m, rad), without DDS."""

import math

from builtin_interfaces.msg import Time
from diagnostic_msgs.msg import DiagnosticStatus
from geometry_msgs.msg import PoseStamped
from linkage_ros.answer import cdr
from linkage_ros.answer.cdr import CdrError, float64_of, from_cdr, pose_of, to_cdr
from linkage_ros.answer.health import Health
from linkage_ros.answer.protocol import answer_outputs
from linkage_ros.core.model import load_scene
from linkage_ros.core.solve import Continuation
from linkage_ros.ros import messages
import numpy as np
import pytest
from rclpy.serialization import deserialize_message, serialize_message
from std_msgs.msg import Float64

STAMP = Time(sec=1_700_000_000, nanosec=123_456_789)


@pytest.fixture(scope='module')
def scene():
    return load_scene('five_link')


@pytest.fixture(scope='module')
def solved(scene):
    """five_link solved at 30 mm bump (walked from design in 5 mm substeps)."""
    return Continuation(scene).solve(30.0)


@pytest.fixture(scope='module')
def failed(scene):
    return Continuation(scene).solve(math.nan)


def quaternion_matrix(q):
    """Rotation matrix of a unit quaternion (x, y, z, w): the identity to check against."""
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def answer(solution, stamp, frame_id):
    """[(output name, CDR bytes)] of protocol.answer_outputs: what the node publishes."""
    return [(name, data) for name, _, data in answer_outputs(solution, stamp, frame_id)]


def answered(solution, frame_id='base_link'):
    """{output name: message} of the answer, read back by rclpy's own deserializer."""
    return {name: deserialize_message(data, PoseStamped if name == 'wheel_carrier_pose'
                                      else Float64)
            for name, data in answer(solution, (STAMP.sec, STAMP.nanosec), frame_id)}


def test_the_answer_is_pose_camber_and_toe_in_that_order(solved):
    assert [(name, kind) for name, kind, _ in answer_outputs(solved, (0, 0), 'f')] == [
        ('wheel_carrier_pose', 'geometry_msgs/msg/PoseStamped'),
        ('camber', 'std_msgs/msg/Float64'), ('toe', 'std_msgs/msg/Float64')]


def test_pose_position_is_the_wheel_centre_in_metres(solved):
    position = answered(solved)['wheel_carrier_pose'].pose.position
    assert [position.x, position.y, position.z] == pytest.approx(
        solved.wheel_center / 1000.0, abs=1e-15)


def test_pose_position_moves_up_by_the_commanded_travel(scene, solved):
    # The travel is imposed on the wheel-centre z (scene design z + 30 mm).
    position = answered(solved)['wheel_carrier_pose'].pose.position
    assert position.z == pytest.approx((scene.wheel_center[2] + 30.0) / 1000.0, abs=1e-12)


def test_pose_orientation_is_the_carrier_rotation_relative_to_design(solved):
    q = answered(solved)['wheel_carrier_pose'].pose.orientation
    quaternion = [q.x, q.y, q.z, q.w]
    assert np.linalg.norm(quaternion) == pytest.approx(1.0, abs=1e-12)
    assert quaternion_matrix(quaternion) == pytest.approx(solved.rotation, abs=1e-12)


def test_design_position_has_the_identity_orientation(scene):
    design = Continuation(scene).solve(0.0)
    pose = answered(design)['wheel_carrier_pose'].pose
    assert [pose.orientation.x, pose.orientation.y, pose.orientation.z,
            abs(pose.orientation.w)] == pytest.approx([0.0, 0.0, 0.0, 1.0], abs=1e-12)
    assert [pose.position.x, pose.position.y, pose.position.z] == pytest.approx(
        scene.wheel_center / 1000.0, abs=1e-12)


@pytest.mark.parametrize('frame_id', ['', 'f', 'chassis', 'base_link', 'a_frame_of_16_ch'])
def test_pose_header_carries_stamp_and_frame_of_any_length(solved, frame_id):
    # The frame name's length moves the pose's alignment padding: every length mod 8 here.
    message = answered(solved, frame_id)['wheel_carrier_pose']
    stamp = message.header.stamp
    assert (stamp.sec, stamp.nanosec) == (1_700_000_000, 123_456_789)
    assert message.header.frame_id == frame_id
    assert message.pose.position.x == solved.wheel_center[0] / 1000.0


def test_the_answer_bytes_are_what_rclpy_serializes(solved):
    # Padding aside (rclpy leaves it uninitialised), the bytes read back the same.
    for name, data in answer(solved, (STAMP.sec, STAMP.nanosec), 'base_link'):
        kind = PoseStamped if name == 'wheel_carrier_pose' else Float64
        again = serialize_message(deserialize_message(data, kind))
        assert len(again) == len(data)


def test_camber_and_toe_are_the_solution_angles_in_radians(solved):
    answer = answered(solved)
    assert answer['camber'].data == solved.camber and answer['toe'].data == solved.toe
    assert math.isfinite(solved.camber) and solved.camber != 0.0


def test_a_command_in_metres_becomes_millimetres():
    assert messages.command_mm(serialize_message(Float64(data=0.025))) == pytest.approx(25.0)
    assert messages.command_mm(serialize_message(Float64(data=-0.08))) == pytest.approx(-80.0)


def test_pose_and_float64_are_read_back_in_place_from_any_cdr(solved):
    pose = PoseStamped()
    pose.header.frame_id = 'abc'
    pose.pose.position.x, pose.pose.orientation.w = 1.25, -0.5
    assert cdr.pose_of(serialize_message(pose)) == ((1.25, 0.0, 0.0), (0.0, 0.0, 0.0, -0.5))
    assert cdr.float64_of(serialize_message(Float64(data=-2.5))) == -2.5


def test_failed_solution_has_no_answer(failed):
    with pytest.raises(ValueError, match='not a finite number'):
        answer_outputs(failed, (0, 0), 'base_link')


def health_of(*solutions, condition_warn=1e4):
    health = Health(condition_warn)
    for solution in solutions:
        health.add(solution)
    return health


def test_status_of_good_solves_is_ok_with_the_period_in_si(solved):
    second = solved._replace(residual=solved.residual * 3, condition=solved.condition / 2,
                             iterations=solved.iterations + 4, substeps=1, travel=12.5)
    status = messages.health_status(health_of(solved, second),
                                    'suspension_kinematics: five_link', 'five_link', 'fast')
    values = messages.status_values(status)
    assert status.level == DiagnosticStatus.OK
    assert (status.name, status.hardware_id, status.message) == (
        'suspension_kinematics: five_link', 'five_link', 'ok')
    assert list(values) == ['commands', 'failures', 'commands_total', 'failures_total',
                            'lost', 'lost_total', 'refused', 'refused_total',
                            'residual_max_m', 'condition_max', 'iterations_max',
                            'substeps_max', 'travel_m', 'rack_m', 'reachable_min_m',
                            'reachable_max_m', 'method']
    assert (values['commands'], values['failures']) == ('2', '0')
    assert [values[k] for k in ('lost', 'lost_total', 'refused', 'refused_total')] == ['0'] * 4
    # The worst of the period: residual and iterations of the second, condition and
    # substeps (6: 30 mm from design in steps of max_step 5 mm) of the first.
    assert float(values['residual_max_m']) == pytest.approx(3 * solved.residual / 1000.0,
                                                            rel=1e-8)
    assert float(values['condition_max']) == pytest.approx(solved.condition, rel=1e-8)
    assert int(values['iterations_max']) == solved.iterations + 4
    assert int(values['substeps_max']) == 6
    assert float(values['travel_m']) == pytest.approx(0.0125, abs=1e-12)   # the last command
    assert float(values['reachable_min_m']) == pytest.approx(solved.reachable[0] / 1000.0)
    assert float(values['reachable_max_m']) == pytest.approx(solved.reachable[1] / 1000.0)
    assert values['method'] == 'fast'


def test_status_warns_when_the_jacobian_condition_exceeds_the_threshold(solved):
    status = messages.health_status(health_of(solved, condition_warn=solved.condition / 2),
                                    'n', 'five_link', 'fast')
    assert status.level == DiagnosticStatus.WARN
    assert 'condition number' in status.message and f'{solved.condition:.3g}' in status.message


def test_status_of_a_failed_solve_is_an_error_saying_why(solved, failed):
    status = messages.health_status(health_of(solved, failed), 'n', 'five_link', 'fast')
    values = messages.status_values(status)
    assert status.level == DiagnosticStatus.ERROR
    assert status.message == failed.message == 'travel nan mm is not a finite number'
    assert (values['travel_m'], values['commands'], values['failures']) == ('nan', '2', '1')


def test_error_outranks_an_ill_conditioned_jacobian(failed):
    bad = failed._replace(condition=1e12)
    assert health_of(bad).level == DiagnosticStatus.ERROR[0]


def test_diagnostic_array_is_stamped_and_holds_the_statuses(solved):
    statuses = [messages.health_status(health_of(solved), name, 'five_link', 'paper')
                for name in ('a', 'b')]
    array = messages.diagnostics(statuses, STAMP)
    assert (array.header.stamp.sec, array.header.stamp.nanosec) == (1_700_000_000, 123_456_789)
    assert [s.name for s in array.status] == ['a', 'b']
    assert messages.status_values(array.status[0])['method'] == 'paper'


@pytest.mark.parametrize('message, expected', [
    (PoseStamped(), 'geometry_msgs/msg/PoseStamped'), (Float64, 'std_msgs/msg/Float64'),
    (messages.diagnostics([], STAMP), 'diagnostic_msgs/msg/DiagnosticArray'),
])
def test_type_name_is_the_ros_interface_name_of_a_message_or_its_class(message, expected):
    assert cdr.type_name(message) == expected


@pytest.mark.parametrize('data, problem', [
    (b'\x00\x01\x00\x00\x01\x02', 'std_msgs/Float64 of 6 bytes: too short: it needs 12 bytes'),
    (b'', 'std_msgs/Float64 of 0 bytes: not CDR'),
    (b'\x07\x07\x00\x00' + bytes(8), 'std_msgs/Float64 of 12 bytes: not CDR'),
])
def test_a_float64_that_does_not_decode_is_a_cdr_error_naming_its_size(data, problem):
    with pytest.raises(CdrError) as raised:
        float64_of(data)
    assert str(raised.value).startswith(problem)


def test_a_pose_whose_frame_id_runs_past_its_end_is_a_cdr_error():
    data = bytearray(to_cdr(PoseStamped()))
    data[12:16] = (2**32 - 1).to_bytes(4, 'little')    # frame_id length 2^32 - 1
    with pytest.raises(CdrError, match='too short: it needs 4294967'):
        pose_of(bytes(data))
    with pytest.raises(CdrError, match='does not decode'):
        from_cdr('geometry_msgs/msg/PoseStamped', bytes(data))
