# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
ROS messages of solved positions: pure functions, testable without DDS.

The core works in mm (vehicle frame: x forward, y left, z up); ROS messages are in SI, so the
conversion happens here and only here:

    command_mm(Float64 CDR, m)                         -> float mm (travel + = bump, rack
                                                          + = to the left); CdrError for
                                                          bytes that are not a Float64
    joint_travel_mm(JointState, joint)                 -> float mm of that joint, or None
                                                          (cdr.JointStateRead or rclpy's)
    status_name(node, corner)                          -> a corner's status name
    health_status(health, name, hardware_id, method)   -> DiagnosticStatus of a corner
    diagnostics(statuses, stamp)                       -> DiagnosticArray
    alignment_array(alignment)                         -> Float64MultiArray: ALIGNMENT_FIELDS
                                                          in SI, named by the layout's labels
    alignment_builder(scene, mech, frame_id)           -> build(solution, stamp): the
                                                          alignment output (protocol.OUTPUTS)
    BUILDERS                                           -> the makers of the alignment and
                                                          markers outputs, for a Responder

The answer to a solved command (pose, camber, toe as CDR bytes) is built by
linkage_ros.answer.protocol.answer_outputs, which the node and linkage-replay share; a failed
Solution has no pose and gets none, so no NaN can reach a pose topic; its Health says ERROR
with the reason.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from std_msgs.msg import Float64MultiArray, MultiArrayDimension, MultiArrayLayout

from ..answer.cdr import float64_of
from ..core.base import M_PER_MM, MM_PER_M
from ..core.measure import quantity, TOPICS

if TYPE_CHECKING:
    from collections.abc import Iterable

    from builtin_interfaces.msg import Time
    from sensor_msgs.msg import JointState

    from ..answer.cdr import JointStateRead
    from ..answer.health import Health
    from ..core.measure import Alignment


def command_mm(data: bytes) -> float:
    """
    Read a Float64 command in CDR bytes (wheel travel or steering rack, m) in mm (core unit).

    Bytes that do not hold a Float64 (too short, not CDR) raise linkage_ros.answer.cdr.CdrError.
    """
    return float64_of(data) * MM_PER_M


def joint_travel_mm(msg: JointStateRead | JointState, joint: str) -> float | None:
    """
    Return the wheel travel (mm, + = bump) of a sensor_msgs/JointState.

    msg: as answer/cdr.joint_state_of reads it (the node's), or an rclpy JointState.

    That is the position (m) of the joint named joint. None if the message has no such joint
    or no position for it (not an error: joint_states carries many joints, often in separate
    messages).
    """
    try:
        index = msg.name.index(joint)     # a tuple's or a list's
    except ValueError:
        return None
    if index >= len(msg.position):
        return None
    return float(msg.position[index]) * MM_PER_M


# The alignment message's fields are the registry's
# (core/measure/quantities.TOPICS['alignment']), in that order: table name -> (Alignment
# attribute, column or None).
_ATTRIBUTES = {
    'camber_gain_deg_per_mm': ('camber_gain', None),
    'bump_steer_deg_per_mm': ('bump_steer', None),
    'caster_deg': ('caster', None),
    'kingpin_inclination_deg': ('kingpin_inclination', None),
    'scrub_radius_mm': ('scrub_radius', None),
    'mechanical_trail_mm': ('mechanical_trail', None),
    'track_change_mm': ('track_change', None),
    'wheelbase_change_mm': ('wheelbase_change', None),
    'wheel_center_lateral_shift_mm': ('lateral_shift', None),
    'wheel_center_longitudinal_shift_mm': ('longitudinal_shift', None),
    'svic_x_mm': ('side_view_ic', 0),
    'svic_z_mm': ('side_view_ic', 1),
    'fvic_y_mm': ('front_view_ic', 0),
    'fvic_z_mm': ('front_view_ic', 1),
}
# label (the quantity's SI name): (Alignment attribute, column or None, factor from the core's
# unit to SI). The order is the order of the data in the alignment message.
ALIGNMENT_FIELDS = {quantity(name).si_name: (*_ATTRIBUTES[name], quantity(name).core_factor)
                    for name in TOPICS['alignment']}


def alignment_array(alignment: Alignment) -> Float64MultiArray:
    """
    Return the alignment set of one solved position as a Float64MultiArray in SI.

    alignment is a linkage_ros.core.measure.alignment.Alignment with n = 1. data[i] is the field
    named by layout.dim[i].label (one dimension of size 1 per field, labels and order of
    ALIGNMENT_FIELDS). NaN where a field is undefined (no steer axis without a steer: rack
    link, no contact patch without a wheel radius).
    """
    data = []
    for attribute, column, factor in ALIGNMENT_FIELDS.values():
        value = getattr(alignment, attribute)[0]
        data.append(float(value if column is None else value[column]) * factor)
    layout = MultiArrayLayout(dim=[MultiArrayDimension(label=label, size=1, stride=1)
                                   for label in ALIGNMENT_FIELDS])
    return Float64MultiArray(layout=layout, data=data)


def alignment_builder(scene, mech, frame_id):
    """Return build(solution, stamp) -> alignment_array of a corner's solved position."""
    from ..core.measure import alignment

    def build(solution, stamp):
        return alignment_array(alignment(scene, mech, solution.wheel_center, solution.rotation,
                                         solution.rack))

    return build


def _markers_builder(responder):
    from .markers import markers_builder    # visualization_msgs: only once markers are on
    return markers_builder(responder.scene, responder.frame_id)


# The outputs of a corner whose messages are rclpy's, handed to the ROS-free Responder
# (answer/protocol.py): {output name: make(responder) -> build(solution, stamp)}.
BUILDERS = {
    'alignment': lambda responder: alignment_builder(responder.scene, responder.solver.mech,
                                                     responder.frame_id),
    'markers': _markers_builder,
}


def alignment_values(msg: Float64MultiArray) -> dict[str, float]:
    """Return {label: value} of an alignment message, for its readers."""
    return {dim.label: value for dim, value in zip(msg.layout.dim, msg.data)}


# The answer to a command is sent as CDR bytes built directly (linkage_ros.answer.cdr): rclpy's
# message classes cost about 20 us to build a PoseStamped and 10 more to serialize it, most
# of the node's callback.
def status_name(node: str, corner: str) -> str:
    """
    Return the name of a corner's DiagnosticStatus: '/suspension_kinematics: five_link'.

    node: the node's fully qualified name, so that namespaced nodes report apart; corner: the
    scene's name, or the corner's in a vehicle.
    """
    return f'{node}: {corner}'


def health_status(health: Health, name: str, hardware_id: str,
                  method: str) -> DiagnosticStatus:
    """
    Return a corner's Health (linkage_ros.answer.health) as a DiagnosticStatus.

    Values are in SI and the keys name their units.

    Level and message: ERROR with the reason (a failed last command, a fault such as a
    recording that stopped), WARN near a singular position, OK. Keys about the period since
    the last periodic report: commands, failures, residual_max_m (largest constraint
    violation), condition_max (Jacobian), iterations_max (Newton, last step of a command),
    substeps_max (continuation steps for one command), lost (inputs lost before the node took
    them: a queue that overflowed in a flood, counted by the publishers' sequence numbers,
    ros/inbox.py), refused (solve requests answered REFUSED). Since start: commands_total,
    failures_total, lost_total, refused_total. About the last command: travel_m (commanded),
    rack_m (+ = to the left; 0 without a steer: rack link), reachable_min_m, reachable_max_m
    (travel range explored so far). And method.
    """
    last = health.last
    travel, rack, (low, high) = ((last.travel, last.rack, last.reachable) if last is not None
                                 else (0.0, 0.0, (0.0, 0.0)))
    values = {
        'commands': str(health.commands),
        'failures': str(health.failures),
        'commands_total': str(health.commands_total),
        'failures_total': str(health.failures_total),
        'lost': str(health.lost),
        'lost_total': str(health.lost_total),
        'refused': str(health.refused_requests),
        'refused_total': str(health.refused_total),
        'residual_max_m': _number(health.residual_max * M_PER_MM),
        'condition_max': _number(health.condition_max),
        'iterations_max': str(health.iterations_max),
        'substeps_max': str(health.substeps_max),
        'travel_m': _number(_as_float(travel) * M_PER_MM),
        'rack_m': _number(rack * M_PER_MM),
        'reachable_min_m': _number(low * M_PER_MM),
        'reachable_max_m': _number(high * M_PER_MM),
        'method': method,
    }
    return DiagnosticStatus(level=bytes([health.level]), name=name, message=health.message,
                            hardware_id=hardware_id,
                            values=[KeyValue(key=k, value=v) for k, v in values.items()])


def diagnostics(statuses: Iterable[DiagnosticStatus], stamp: Time) -> DiagnosticArray:
    """Return a DiagnosticArray of DiagnosticStatus messages, stamped."""
    msg = DiagnosticArray(status=list(statuses))
    msg.header.stamp = stamp
    return msg


def status_values(status: DiagnosticStatus) -> dict[str, str]:
    """Return {key: value} of a DiagnosticStatus, for readers of the diagnostics."""
    return {kv.key: kv.value for kv in status.values}


def _number(value):
    # Nine significant digits: nanometres at a metre of travel; 'nan' for a NaN command.
    return f'{float(value):.9g}'


def _as_float(value):
    """Return a commanded travel as a float (NaN if not a number: a bad command may not be)."""
    try:
        return float(value)
    except (TypeError, ValueError):
        return float('nan')
