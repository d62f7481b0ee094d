"""ROS messages of one solved position: pure functions, testable without DDS.

The core works in mm (vehicle frame: x forward, y left, z up); ROS messages are in SI, so the
conversion happens here and only here:

    travel_mm(Float64 m)                               -> float mm (+ = bump)
    pose_stamped(solution, stamp, frame_id)            -> PoseStamped: wheel centre (m) and
                                                          carrier rotation relative to design
    camber(solution), toe(solution)                    -> Float64 (rad)
    diagnostics(solution, stamp, name, hardware_id, method, condition_warn)
                                                       -> DiagnosticArray (one status)

A failed Solution (NaN, inf or out-of-reach command) has no pose: pose_stamped, camber and toe
refuse it, so no NaN can reach a pose topic; diagnostics turns it into an ERROR status.
"""

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from geometry_msgs.msg import PoseStamped
from std_msgs.msg import Float64

M_PER_MM = 1e-3
MM_PER_M = 1e3


def travel_mm(msg):
    """Commanded wheel travel of a Float64 (m, + = bump) in mm, the core's unit."""
    return msg.data * MM_PER_M


def pose_stamped(solution, stamp, frame_id):
    """Wheel-centre position (m, in frame_id) and carrier orientation of a solved position.

    The orientation is the carrier's rotation relative to its design position, as a unit
    quaternion, so the design position reads (0, 0, 0, 1). stamp is a builtin_interfaces/Time.
    """
    _require_pose(solution)
    msg = PoseStamped()
    msg.header.stamp = stamp
    msg.header.frame_id = frame_id
    position = msg.pose.position
    position.x, position.y, position.z = (float(v) * M_PER_MM for v in solution.wheel_center)
    orientation = msg.pose.orientation
    orientation.x, orientation.y, orientation.z, orientation.w = (
        float(v) for v in solution.quaternion)
    return msg


def camber(solution):
    """Camber angle (rad, + = top of the wheel outboard) of a solved position."""
    _require_pose(solution)
    return Float64(data=float(solution.camber))


def toe(solution):
    """Toe angle (rad, + = toe-in) of a solved position."""
    _require_pose(solution)
    return Float64(data=float(solution.toe))


def health(solution, condition_warn):
    """(level, message) of a solve: ERROR if it failed, WARN if the Jacobian is ill-conditioned.

    A condition number above condition_warn means the mechanism is near a singular position
    (a turning point at the end of travel): the pose is right but sensitive to hardpoint error.
    """
    if not solution.success:
        return DiagnosticStatus.ERROR, solution.message
    if solution.condition > condition_warn:
        return DiagnosticStatus.WARN, (f'near a singular position: Jacobian condition number '
                                       f'{solution.condition:.3g} above {condition_warn:.3g}')
    return DiagnosticStatus.OK, 'ok'


def diagnostic_status(solution, name, hardware_id, method, condition_warn):
    """Solver health of one command as a DiagnosticStatus; values in m (SI), keys name units.

    Keys: travel_m (commanded), iterations (Newton, last step), residual_m (largest
    constraint violation), substeps (continuation steps walked), condition (Jacobian),
    reachable_min_m and reachable_max_m (travel range explored so far), method.
    """
    level, message = health(solution, condition_warn)
    low, high = solution.reachable
    values = {
        'travel_m': _number(solution.travel * M_PER_MM),
        'iterations': str(int(solution.iterations)),
        'residual_m': _number(solution.residual * M_PER_MM),
        'substeps': str(int(solution.substeps)),
        'condition': _number(solution.condition),
        'reachable_min_m': _number(low * M_PER_MM),
        'reachable_max_m': _number(high * M_PER_MM),
        'method': method,
    }
    return DiagnosticStatus(level=level, name=name, message=message, hardware_id=hardware_id,
                            values=[KeyValue(key=k, value=v) for k, v in values.items()])


def diagnostics(solution, stamp, name, hardware_id, method, condition_warn):
    """A DiagnosticArray holding the one status of diagnostic_status, stamped."""
    msg = DiagnosticArray(status=[diagnostic_status(solution, name, hardware_id, method,
                                                    condition_warn)])
    msg.header.stamp = stamp
    return msg


def type_name(msg):
    """ROS type name of a message instance, e.g. 'geometry_msgs/msg/PoseStamped'."""
    return f"{type(msg).__module__.split('.')[0]}/msg/{type(msg).__name__}"


def status_values(status):
    """{key: value} of a DiagnosticStatus, for readers of the diagnostics."""
    return {kv.key: kv.value for kv in status.values}


def _number(value):
    # Nine significant digits: nanometres at a metre of travel; 'nan' for a NaN command.
    return f'{float(value):.9g}'


def _require_pose(solution):
    if not solution.success:
        raise ValueError(f'no pose for travel {solution.travel!r} mm: {solution.message}')
