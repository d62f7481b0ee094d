"""linkage_ros.messages: Solution (mm, rad) -> ROS messages (m, rad), without DDS."""

import math

from builtin_interfaces.msg import Time
from diagnostic_msgs.msg import DiagnosticStatus
import numpy as np
import pytest
from std_msgs.msg import Float64

from linkage_ros import messages
from linkage_ros.kinematics import Continuation
from linkage_ros.scene import load_scene

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


def test_travel_command_in_metres_becomes_millimetres():
    assert messages.travel_mm(Float64(data=0.025)) == pytest.approx(25.0, abs=1e-12)
    assert messages.travel_mm(Float64(data=-0.08)) == pytest.approx(-80.0, abs=1e-12)


def test_pose_position_is_the_wheel_centre_in_metres(solved):
    position = messages.pose_stamped(solved, STAMP, 'base_link').pose.position
    assert [position.x, position.y, position.z] == pytest.approx(
        solved.wheel_center / 1000.0, abs=1e-15)


def test_pose_position_moves_up_by_the_commanded_travel(scene, solved):
    # The travel is imposed on the wheel-centre z (scene design z + 30 mm).
    position = messages.pose_stamped(solved, STAMP, 'base_link').pose.position
    assert position.z == pytest.approx((scene.wheel_center[2] + 30.0) / 1000.0, abs=1e-12)


def test_pose_orientation_is_the_carrier_rotation_relative_to_design(solved):
    q = messages.pose_stamped(solved, STAMP, 'base_link').pose.orientation
    quaternion = [q.x, q.y, q.z, q.w]
    assert np.linalg.norm(quaternion) == pytest.approx(1.0, abs=1e-12)
    assert quaternion_matrix(quaternion) == pytest.approx(solved.rotation, abs=1e-12)


def test_design_position_has_the_identity_orientation(scene):
    design = Continuation(scene).solve(0.0)
    pose = messages.pose_stamped(design, STAMP, 'base_link').pose
    assert [pose.orientation.x, pose.orientation.y, pose.orientation.z,
            abs(pose.orientation.w)] == pytest.approx([0.0, 0.0, 0.0, 1.0], abs=1e-12)
    assert [pose.position.x, pose.position.y, pose.position.z] == pytest.approx(
        scene.wheel_center / 1000.0, abs=1e-12)


def test_pose_header_carries_stamp_and_frame(solved):
    header = messages.pose_stamped(solved, STAMP, 'chassis').header
    assert (header.stamp.sec, header.stamp.nanosec) == (1_700_000_000, 123_456_789)
    assert header.frame_id == 'chassis'


def test_camber_and_toe_are_the_solution_angles_in_radians(solved):
    assert messages.camber(solved).data == solved.camber
    assert messages.toe(solved).data == solved.toe
    assert math.isfinite(solved.camber) and solved.camber != 0.0


@pytest.mark.parametrize('build', [
    lambda s: messages.pose_stamped(s, STAMP, 'base_link'),
    messages.camber,
    messages.toe,
])
def test_failed_solution_has_no_pose_message(failed, build):
    with pytest.raises(ValueError, match='not a finite number'):
        build(failed)


def test_diagnostic_of_a_good_solve_is_ok_with_its_numbers_in_si(solved):
    status = messages.diagnostic_status(solved, 'suspension_kinematics: five_link', 'five_link',
                                        'fast', 1e4)
    values = messages.status_values(status)
    assert status.level == DiagnosticStatus.OK
    assert (status.name, status.hardware_id, status.message) == (
        'suspension_kinematics: five_link', 'five_link', 'ok')
    assert list(values) == ['travel_m', 'iterations', 'residual_m', 'substeps', 'condition',
                            'reachable_min_m', 'reachable_max_m', 'method', 'rack_m']
    assert float(values['travel_m']) == pytest.approx(0.030, abs=1e-12)
    assert int(values['iterations']) == solved.iterations
    assert float(values['residual_m']) == pytest.approx(solved.residual / 1000.0, rel=1e-8)
    assert int(values['substeps']) == 6     # 30 mm from design in steps of max_step 5 mm
    assert float(values['condition']) == pytest.approx(solved.condition, rel=1e-8)
    assert float(values['reachable_min_m']) == pytest.approx(solved.reachable[0] / 1000.0)
    assert float(values['reachable_max_m']) == pytest.approx(solved.reachable[1] / 1000.0)
    assert values['method'] == 'fast'


def test_diagnostic_warns_when_the_jacobian_condition_exceeds_the_threshold(solved):
    level, message = messages.health(solved, condition_warn=solved.condition / 2)
    assert level == DiagnosticStatus.WARN
    assert 'condition number' in message and f'{solved.condition:.3g}' in message


def test_diagnostic_of_a_failed_solve_is_an_error_saying_why(failed):
    status = messages.diagnostic_status(failed, 'n', 'five_link', 'fast', 1e4)
    assert status.level == DiagnosticStatus.ERROR
    assert status.message == failed.message == 'travel nan is not a finite number'
    assert messages.status_values(status)['travel_m'] == 'nan'


def test_error_outranks_an_ill_conditioned_jacobian(failed):
    bad = failed._replace(condition=1e12)
    assert messages.health(bad, condition_warn=1e4)[0] == DiagnosticStatus.ERROR


def test_diagnostic_array_is_stamped_and_holds_one_status(solved):
    array = messages.diagnostics(solved, STAMP, 'n', 'five_link', 'paper', 1e4)
    assert (array.header.stamp.sec, array.header.stamp.nanosec) == (1_700_000_000, 123_456_789)
    assert len(array.status) == 1
    assert messages.status_values(array.status[0])['method'] == 'paper'


@pytest.mark.parametrize('build, expected', [
    (lambda s: messages.pose_stamped(s, STAMP, 'f'), 'geometry_msgs/msg/PoseStamped'),
    (messages.camber, 'std_msgs/msg/Float64'),
    (lambda s: messages.diagnostics(s, STAMP, 'n', 'h', 'fast', 1e4),
     'diagnostic_msgs/msg/DiagnosticArray'),
])
def test_type_name_is_the_ros_interface_name(solved, build, expected):
    assert messages.type_name(build(solved)) == expected
