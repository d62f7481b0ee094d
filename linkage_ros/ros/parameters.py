# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The parameters of suspension_node: their table, their declaration and their checks.

Every parameter is declared with its description and, for numbers, its range
(rcl_interfaces FloatingPointRange / IntegerRange), so that `ros2 param describe` shows it;
values are checked here first, so that a bad one is one line naming the parameter, the range
and the value. A number parameter takes integers too (a YAML 5 means 5.0).

RUNTIME parameters can be changed while the node runs (rcl_interfaces SetParameters, `ros2
param set`; ros/runtime.py applies them); the others are FIXED, and a change is refused with
the reason (their descriptors are not read_only, so that the refusal can say why: rclpy's
own refusal of a read-only parameter does not).

The node is built with automatically_declare_parameters_from_overrides: every parameter given
to it (-p, a params file, parameter_overrides) is then declared by rclpy, and one that is
neither the node's nor rclpy's own is a misspelling, refused with the closest name. (rclpy
would otherwise ignore an override that nobody declares, and keeps the overrides only in a
private attribute.)
"""

from __future__ import annotations

import difflib
import textwrap
from typing import Any, NamedTuple, TYPE_CHECKING

from rcl_interfaces.msg import FloatingPointRange, IntegerRange, ParameterDescriptor
from rclpy.parameter import Parameter

from .qos import check_overrides, MAX_DEPTH, QOS_DEPTH
from ..core.base import LinkageError
from ..core.model import name_problem
from ..core.solve import METHODS

if TYPE_CHECKING:
    from rclpy.node import Node


class Spec(NamedTuple):
    """One parameter: its default (which gives its type), what it means, its range."""

    default: Any
    text: str
    low: float | None = None    # inclusive bounds of a number
    high: float | None = None
    unit: str = ''

    def range_text(self) -> str:
        """Say the range: '0.001 to 1000 mm', or '' for a parameter that is not a number."""
        if self.low is None:
            return ''
        return f'{self.low:g} to {self.high:g}' + (f' {self.unit}' if self.unit else '')


PARAMETERS = {
    'scene': Spec('five_link', 'bundled scene name or path to a scene YAML file'),
    'frame_id': Spec('base_link', "frame of wheel_carrier_pose (the scene's vehicle frame)"),
    'method': Spec('fast', 'solver: fast (pose Newton) or paper (Gauss-Jordan, Alexandru 2018)'),
    # A substep below a micrometre serves no scene (the submillimetre stress scene is solved
    # with 0.001); above a metre no suspension moves.
    'max_step_mm': Spec(5.0, 'longest continuation substep', 0.001, 1000.0, 'mm'),
    # A condition number is at least 1; beyond 1e15 float64 cannot tell the Jacobian singular.
    'condition_warn': Spec(1e4, 'Jacobian condition number above which diagnostics say WARN',
                           1.0, 1e15),
    # 100 reports a second at most; at least one a day.
    'diagnostic_period': Spec(1.0, 'time between /diagnostics reports, on the node clock',
                              0.01, 86400.0, 's'),
    'record_mcap': Spec('', 'path of an MCAP file recording commands and outputs; empty = off'),
    'rerun_rrd': Spec('', 'path of a Rerun .rrd file mirroring the poses; empty = off'),
    'travel_joint': Spec('', 'joint of sensor_msgs/JointState on joint_states whose position '
                         'is the wheel travel (m, + = bump); empty = joint_states not '
                         'subscribed'),
    'alignment': Spec(False, 'publish the alignment set (std_msgs/Float64MultiArray) per '
                      'answer'),
    'tf': Spec(True, 'publish the frames of the carrier, wheel, links and arms on /tf per '
               'answer and /tf_static, and the URDF on robot_description; false: none of '
               'them, no cost'),
    'markers': Spec(False, 'publish links and joints (visualization_msgs/MarkerArray) per '
                    'answer'),
    'statics': Spec(False, 'take contact_wrench (geometry_msgs/WrenchStamped) and answer the '
                    "loaded pose at the last one, with each pickup's force on pickup/<name>; "
                    'on anyway for a scene with bushings'),
    'pickups': Spec(True, "with statics, publish each body pickup's force on pickup/<name> per "
                    'answer; false: no pickup topics, and the forces are neither read nor '
                    'built (a simulator that needs only the loaded pose)'),
    'angles': Spec(True, 'publish camber and toe (std_msgs/Float64, rad) per answer; false: '
                   'neither topic, the pose alone (a simulator that needs only the loaded '
                   'pose)'),
    'elements': Spec(True, 'for a scene with elements, publish their lengths and motion ratios '
                     '(sensor_msgs/JointState) on elements per answer; false: no elements '
                     'topic, nothing of them computed'),
    'roll_centres': Spec(True, "with a vehicle file that has axles, publish each axle's roll "
                         'centre on <axle>/roll_centre; false: no roll-centre topics, none '
                         'computed'),
    'vehicle': Spec('', 'vehicle file (bundled name or path): one corner per wheel, topics '
                    'under the corner name; empty = the single scene of parameter scene'),
    # Each subscription holds at most this many samples: memory up to depth times the largest
    # message (1000 JointStates of 10^5 joints: 2.8 GB), so lower it for large messages.
    'qos_depth': Spec(QOS_DEPTH, 'keep-last depth of every topic: a burst this long is not '
                      'lost; each input holds at most this many messages', 1, MAX_DEPTH,
                      'messages'),
}

# The parameters a SetParameters request may change while the node runs (ros/runtime.py).
RUNTIME = ('scene', 'method', 'max_step_mm', 'condition_warn', 'diagnostic_period',
           'alignment', 'markers', 'tf', 'pickups', 'angles', 'elements', 'roll_centres')
# Why each other parameter is fixed once the node runs (the reason a change is refused with).
FIXED = {
    'frame_id': 'every published pose and frame names it from the start',
    'record_mcap': 'a recording is one file from start to stop',
    'rerun_rrd': 'a Rerun mirror is one file from start to stop',
    'travel_joint': "the corner's joint_states subscription is made at start",
    'vehicle': 'the corners and their topics are made at start from the vehicle file',
    'qos_depth': 'every topic is made at start with its QoS',
    'statics': 'the contact_wrench subscriptions and pickup topics are made at start',
    'use_sim_time': "the node's clock and its /clock subscription are set up at start",
}

# The parameters rclpy declares on every node (test_node pins that there are no others), and
# the prefix of its QoS overrides.
ROS_PARAMETERS = ('use_sim_time', 'start_type_description_service')
ROS_PREFIXES = ('qos_overrides.',)


def declare(node: Node) -> dict[str, Any]:
    """
    Declare the parameters on node and return {name: value}, checked; else LinkageError.

    node must be built with automatically_declare_parameters_from_overrides=True: the
    parameters it was given are then declared already, and any other than the node's or
    rclpy's is refused as a misspelling.
    """
    given = node.list_parameters([], 0).names
    for name in given:
        if name not in PARAMETERS and name not in ROS_PARAMETERS \
                and not name.startswith(ROS_PREFIXES):
            raise LinkageError(f'parameter {name}', unknown_parameter(name))
    sim_time = node.get_parameter('use_sim_time').value
    if not isinstance(sim_time, bool):
        raise LinkageError('use_sim_time', f'expected true or false, got {sim_time!r}')
    check_overrides({name: node.get_parameter(name).value for name in given})
    values = {}
    for name, spec in PARAMETERS.items():
        if node.has_parameter(name):     # given: check it, then describe it
            values[name] = checked(name, node.get_parameter(name).value)
            node.set_descriptor(name, descriptor(name))
        else:
            values[name] = node.declare_parameter(name, spec.default, descriptor(name)).value
    return values


def checked(name: str, value: Any) -> Any:
    """Return a parameter's value in its type (a number as a float), or raise LinkageError."""
    spec = PARAMETERS[name]
    kind = type(spec.default)
    if kind is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise LinkageError(name, f'expected a number, got {value!r}')
        value = float(value)
    elif not isinstance(value, kind) or isinstance(value, bool) != (kind is bool):
        expected = {str: 'a text', bool: 'true or false', int: 'an integer'}[kind]
        raise LinkageError(name, f'expected {expected}, got {value!r}')
    if spec.low is not None and not (spec.low <= value <= spec.high):   # NaN is refused too
        raise LinkageError(name, f'must be from {spec.range_text()}, got {value!r}')
    if name == 'frame_id' and name_problem(value):   # it names every frame and the URDF root
        raise LinkageError(name, name_problem(value))
    if name == 'method' and value not in METHODS:
        raise LinkageError(name, f'unknown value {value!r} (expected one of: '
                           f'{", ".join(METHODS)})')
    return value


def descriptor(name: str) -> ParameterDescriptor:
    """
    Return the ParameterDescriptor of a parameter, with its range and whether it is fixed.

    Not read_only even where fixed: the node refuses a change of a FIXED parameter itself,
    saying why (ros/runtime.py); the description ends with '(fixed while the node runs)'.
    """
    spec = PARAMETERS[name]
    text = spec.text + (f', {spec.range_text()}' if spec.low is not None else '')
    text += '' if name in RUNTIME else ' (fixed while the node runs)'
    numeric = isinstance(spec.default, float)
    desc = ParameterDescriptor(description=text, read_only=False, dynamic_typing=numeric)
    if not numeric:   # rclpy's declare_parameter sets the type; set_descriptor needs it given
        desc.type = Parameter.Type.from_parameter_value(spec.default).value
    if isinstance(spec.default, float):
        desc.floating_point_range = [FloatingPointRange(from_value=float(spec.low),
                                                        to_value=float(spec.high), step=0.0)]
    elif isinstance(spec.default, int) and not isinstance(spec.default, bool):
        desc.integer_range = [IntegerRange(from_value=int(spec.low), to_value=int(spec.high),
                                           step=1)]
    return desc


def unknown_parameter(name: str) -> str:
    """Say that a parameter name is unknown, suggest the closest, list the known ones."""
    close = difflib.get_close_matches(name, PARAMETERS, n=1)
    guess = f'did you mean {close[0]}? ' if close else ''
    return f'not a parameter of suspension_node ({guess}known: {", ".join(PARAMETERS)})'


def help_lines(width: int = 92) -> list[str]:
    """Return the lines of --help that list the parameters: name, default, meaning, range."""
    lines = []
    for name, spec in PARAMETERS.items():
        text = spec.text + (f' ({spec.range_text()})' if spec.low is not None else '')
        lines += textwrap.wrap(f'{name:<18} {spec.default!r:<12} {text}', width,
                               initial_indent='  ', subsequent_indent=' ' * 34)
    return lines
